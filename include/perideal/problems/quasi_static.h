#ifndef perideal_problems_quasi_static_h
#define perideal_problems_quasi_static_h

#include <deal.II/base/bounding_box.h>

#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/discrete_system.h>
#include <perideal/problems/bond_failure.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>
#include <perideal/solvers/dynamic_relaxation.h>

#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * The quasi-static PD problem (problem type `quasi-static`): equilibrium
     * \f$K u = V b\f$ with volumetric Dirichlet layers, body forces and
     * tractions, in one solve or in load steps with bond breaking.
     *
     * run() asks the boundary treatment for its Boundary::DiscreteSystem
     * (Boundary::NodalSystem for `none`: the BondOperator, matrix-free or
     * assembled; Boundary::LayerSystem for `fictitious layer` and `surface
     * nodes`), sets it up and solves with it, then compares with the
     * analytical solution when one is given and writes PVTU output and the
     * per-node CSV. It never branches on the treatment.
     *
     * The functions of 'Boundary conditions' and the analytical solution
     * are functions of the (pseudo-)time t. With 'Load steps = 1' and
     * 'Bond breaking = off' (the defaults) they are evaluated once, at
     * 'End time'. Otherwise the run steps from t = 0 to 'End time'
     * (quasi_static_steps.cc): at each step the equilibrium with the bonds
     * intact so far (warm-started Krylov or direct solve), then the bonds
     * over their critical stretch break ('Bond breaking': all of them, or
     * the most critical ones per sweep) and the same load is solved again
     * until no bond breaks. The step is halved while a bond is further
     * than 'Critical stretch tolerance' past its critical stretch or a
     * solve fails, down to 'Minimum load step', and doubled (up to 'End
     * time' / 'Load steps') after a step without breaking. Bonds that keep
     * breaking at a fixed load are reported as unstable growth, with the
     * critical load; the run stops at complete failure (the reaction below
     * 'Complete failure fraction' of its peak). Rows of the load-displacement
     * CSV, a damage PVD series and a progress line per step.
     */
    template <int dim>
    class QuasiStatic : public ProblemType<dim>
    {
    public:
      /// 'End time', 'Load steps', 'Bond breaking', the step control,
      /// the reactions and the failure entries (BondFailure).
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      check_input(const Simulator<dim> &simulator) const override;

      /// True: the nodal system ('Boundary treatment = none') evaluates
      /// the collocation rows (bond-based models, matrix-free).
      bool
      supports_collocation() const override;

      /// True, with 'Configuration = fixed' (no bond breaks in a static
      /// solve yet, so no node would switch): the standard region of
      /// 'Quadrature/hybrid' and the nodes whose ball is cut are standard,
      /// every other node takes the collocation row.
      bool
      supports_hybrid() const override;

      /// Those of 'Boundary conditions', the failure and inertia entries
      /// of the material model, and the analytical displacement without a
      /// comparison.
      std::vector<UnusedEntry>
      unused_entries(const Simulator<dim> &simulator) const override;

      void
      run(Simulator<dim> &simulator) override;

      /// The records and PVD series of load-stepped runs, the
      /// load-displacement file.
      std::vector<IO::OutputName>
      output_names(const Simulator<dim> &simulator) const override;

    private:
      /// 'Bond breaking'.
      enum class BondBreaking
      {
        off,
        all_beyond_critical,
        most_critical
      };

      /// Whether the run steps the load (more than one step, bond
      /// breaking, dynamic relaxation or finite deformation, which only
      /// solve_step() offers).
      bool
      steps_load() const
      {
        return n_load_steps > 1 || bond_breaking != BondBreaking::off ||
               use_dynamic_relaxation || finite_deformation;
      }

      /// Whether a reaction is written: 'Reaction boundary ids' or
      /// 'Reaction boxes' are given.
      bool
      has_reaction() const
      {
        return !reaction_ids.empty() || !reaction_boxes.empty();
      }

      /// The load-stepped run (quasi_static_steps.cc).
      void
      run_load_steps(Simulator<dim> &simulator);

      /// One sweep of 'Bond breaking' on the last solution: the bonds
      /// over their critical stretch, or the most critical of them.
      /// Returns the number broken. Collective.
      std::size_t
      break_bonds();

      /**
       * The largest ratio of a bond's stretch to its critical stretch in
       * the last solution, to a relative @p precision, by bisection on
       * the count of bonds over a multiple of the critical stretch; 0 when
       * no bond is stretched by more than 2^-40 of it. Collective.
       */
      double
      largest_stretch_ratio(const double precision);

      /// The owned nodes with a prescribed component in the Dirichlet
      /// layers of 'Reaction boundary ids' or in the 'Reaction boxes'
      /// (after the first solve). Collective.
      std::vector<bool>
      reaction_nodes(const Simulator<dim> &simulator) const;

      /// The load-displacement CSV under a temporary name, renamed
      /// (rank 0; collective verdict).
      void
      write_load_displacement(const Simulator<dim> &simulator) const;

      /// A damage record of the PVD series (collective).
      void
      write_step_record(Simulator<dim> &simulator, const double time);

      /// The entries that the collocation scheme needs (check_input()).
      void
      check_collocation_input(const Simulator<dim> &simulator) const;

      /// Errors against the analytical solution, the node data file and
      /// the PVTU record @p index with @p extra fields; returns the
      /// record's name.
      std::string
      postprocess(Simulator<dim>                   &simulator,
                  const std::vector<IO::NodeField> &extra = {},
                  const unsigned int                index = 0);

      /// Gather every node's position, displacement and error to the CSV
      /// named in 'Output/Node data file'.
      void
      write_node_data(Simulator<dim>       &simulator,
                      const Tensor<1, dim> &component_max) const;

      /// The system built by the boundary treatment.
      std::unique_ptr<Boundary::DiscreteSystem<dim>> system;
      TrilinosWrappers::MPI::Vector                  displacement;

      // Input.
      double                          end_time      = 1;
      unsigned int                    n_load_steps  = 1;
      BondBreaking                    bond_breaking = BondBreaking::off;
      std::string                     bond_breaking_name;
      double                          minimum_step       = 0;
      double                          stretch_tolerance  = 0.01;
      unsigned int                    max_bonds_per_step = 0;
      double                          failure_fraction   = 0.01;
      std::vector<types::boundary_id> reaction_ids;
      std::string                     reaction_ids_text;
      std::vector<BoundingBox<dim>>   reaction_boxes;
      std::string                     reaction_boxes_text;
      /// Whether reaction_nodes() has been called (collective, once).
      bool        reaction_nodes_found = false;
      std::string load_displacement_file;
      /// Pre-cracks and no-fail regions.
      BondFailure<dim> failure;
      /// 'Nonlinear solver = dynamic relaxation' and its settings.
      bool                       use_dynamic_relaxation = false;
      Solvers::DynamicRelaxation dynamic_relaxation;
      /// 'Kinematics = finite deformation' and its Newton iteration.
      bool finite_deformation = false;
      typename Boundary::DiscreteSystem<dim>::NewtonControl newton;

      // State of a load-stepped run.
      /// Rows of the load-displacement CSV: step, time, reaction, broken
      /// bonds, iterations.
      std::vector<std::vector<double>> rows;
      /// The PVD series: (time, record).
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
