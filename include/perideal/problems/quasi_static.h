#ifndef perideal_problems_quasi_static_h
#define perideal_problems_quasi_static_h

#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/discrete_system.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>

#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * The linear quasi-static PD problem \f$K u = V b\f$ with volumetric
     * Dirichlet layers, body forces and tractions (problem type
     * `quasi-static`).
     *
     * run() asks the boundary treatment for its Boundary::DiscreteSystem
     * (Boundary::NodalSystem for `none`: the BondOperator, matrix-free or
     * assembled; Boundary::LayerSystem for `fictitious layer` and `surface
     * nodes`), sets it up and solves with it, then compares with the
     * analytical solution when one is given and writes PVTU output and the
     * per-node CSV. It never branches on the treatment.
     *
     * The functions of 'Boundary conditions' and the analytical solution
     * are evaluated at the time 'quasi-static/Time' (default 1, the end of
     * a unit load ramp), which the run's log states.
     */
    template <int dim>
    class QuasiStatic : public ProblemType<dim>
    {
    public:
      /// 'Time', at which the loads are evaluated.
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

    private:
      /// The entries that the collocation scheme needs (check_input()).
      void
      check_collocation_input(const Simulator<dim> &simulator) const;

      void
      postprocess(Simulator<dim> &simulator);

      /// Gather every node's position, displacement and error to the CSV
      /// named in 'Output/Node data file'.
      void
      write_node_data(Simulator<dim>       &simulator,
                      const Tensor<1, dim> &component_max) const;

      /// The system built by the boundary treatment.
      std::unique_ptr<Boundary::DiscreteSystem<dim>> system;
      TrilinosWrappers::MPI::Vector                  displacement;
      /// 'Time'.
      double load_time = 1;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
