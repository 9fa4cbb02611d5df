#ifndef perideal_problems_simulator_h
#define perideal_problems_simulator_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <perideal/boundary/boundary_conditions.h>
#include <perideal/boundary/boundary_treatment.h>
#include <perideal/boundary/system_context.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/run_summary.h>
#include <perideal/io/solution_output.h>
#include <perideal/models/model.h>
#include <perideal/problems/mesh_generator.h>
#include <perideal/problems/problem_type.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/quadrature_scheme.h>
#include <perideal/solvers/linear_solver.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * One PD simulation described entirely by a parameter file: the
     * tutorial-plain driver behind the `perideal` program.
     *
     * The simulator owns what every problem type shares and sets it up in
     * one path: the mesh (a subdivided box or a Cartesian mesh read with
     * GridIn, on a parallel::distributed::Triangulation), one PD node per
     * active cell with the off-process nodes within the coupling range
     * (NodeSet), the model, the partial-volume algorithm, the boundary
     * conditions and treatment, the linear solver settings, the analytical
     * solution for verification, and the output settings. The registered
     * ProblemType chosen with `Problem type` then builds its bonds and
     * operators through the simulator (setup_neighbor_lists()) and runs;
     * run() ends with the phase timings, the peak memory and the summary
     * CSV.
     *
     * All entries are declared with a pattern and a help text; see
     * `perideal --print-parameters`.
     */
    template <int dim>
    class Simulator
    {
    public:
      explicit Simulator(const MPI_Comm communicator);

      /**
       * Declare every entry of the input file (the top-level "Dimension"
       * included, so that a file that sets it parses).
       */
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * Checks of the parameter file @p file (already parsed into @p prm)
       * that ParameterHandler does not make: an entry set twice, a file that
       * sets nothing (scan_input_file()), entries in the subsection of a
       * plugin that the file does not select (a material model, a
       * partial-volume algorithm, a boundary treatment, a problem type), and
       * `Plane model` in 3D. Each would otherwise be ignored silently.
       */
      static void
      check_input_file(const std::string &file, ParameterHandler &prm);

      /**
       * Read and check the entries; errors name the entry, the value and
       * what to do.
       */
      void
      parse_parameters(ParameterHandler &prm);

      /// Run the whole problem and return what it measured.
      IO::RunSummary
      run();

      /// @name The shared set-up, for problem types
      /// @{

      /**
       * Build the neighbour lists (with lists of the off-process
       * neighbours for state-based models). @p store_full_lists: also
       * store the lists of nodes whose neighbourhood is the full stencil.
       */
      void
      setup_neighbor_lists(const bool store_full_lists);

      /// Wall time since run() started, in seconds.
      double
      elapsed() const;

      /// Print "[ wall time s] @p text" on rank 0.
      void
      print_progress(const std::string &text);

      MPI_Comm
      get_communicator() const;

      ConditionalOStream &
      get_pcout();

      TimerOutput &
      get_timer();

      /**
       * The mesh: a parallel::distributed::Triangulation (p4est) in 2D and
       * 3D, a parallel::shared::Triangulation in 1D (p4est has no 1D; every
       * process holds the whole line and owns a contiguous part of it).
       */
      const parallel::TriangulationBase<dim> &
      get_triangulation() const;

      const DoFHandler<dim> &
      get_dof_handler() const;

      const Discretization::NodeSet<dim> &
      get_nodes() const;

      const Discretization::NeighborList<dim> &
      get_neighbor_lists() const;

      const Models::Model<dim> &
      get_model() const;

      const Quadrature::PartialVolume<dim> &
      get_partial_volume() const;

      const std::string &
      get_partial_volume_name() const;

      /// The quadrature scheme ('Quadrature/Scheme').
      const Quadrature::QuadratureScheme<dim> &
      get_quadrature_scheme() const;

      /// 'Quadrature/Scheme' as given.
      const std::string &
      get_quadrature_scheme_name() const;

      /// The horizon \f$\delta\f$.
      double
      get_horizon() const;

      /// 'Geometry/Node perturbation': the largest offset of a node from its
      /// cell's centre, per direction, as a fraction of the cell's side (0:
      /// nodes at the centres).
      double
      get_node_perturbation() const
      {
        return node_perturbation;
      }

      const Boundary::BoundaryConditions<dim> &
      get_boundary_conditions() const;

      /// The boundary conditions, to set their time (dynamics).
      Boundary::BoundaryConditions<dim> &
      get_boundary_conditions();

      const Boundary::BoundaryTreatment &
      get_boundary_treatment() const;

      const std::string &
      get_boundary_treatment_name() const;

      const Solvers::LinearSolver &
      get_linear_solver() const;

      /// The analytical displacement, or null without a comparison.
      const Functions::ParsedFunction<dim> *
      get_analytical_solution() const;

      /**
       * Evaluate the functions of the shared set-up that may depend on
       * time (those of 'Boundary conditions' and the analytical
       * displacement) at time @p t from now on.
       */
      void
      set_time(const double t);

      const IO::SolutionOutput<dim> &
      get_output() const;

      /// The per-node CSV file ('Output/Node data file'); may be empty.
      const std::string &
      get_node_data_file() const;

      /**
       * The entry of the material model that sets its stiffness, as
       * 'Material model/<model>/<entry>', and its value as given; for
       * messages about a stiffness out of the range of doubles.
       */
      std::pair<std::string, std::string>
      get_stiffness_entry() const;

      IO::RunSummary &
      get_summary();

      /**
       * The run as a Boundary::DiscreteSystem sees it: references to the
       * shared set-up, the log, the timer and the summary, and hooks to
       * setup_neighbor_lists(), elapsed() and print_progress(). The
       * references stay valid as long as the simulator; the neighbour lists
       * are those that the hook builds. Needs a material model (as
       * get_model()).
       */
      Boundary::SystemContext<dim>
      system_context();

      /// @}

    private:
      /**
       * Estimate the memory of a run on a mesh of known size @p coarse
       * (before global refinement) before anything is allocated, and refuse
       * it with the estimate when it exceeds what the machines have.
       */
      void
      check_memory_estimate(
        const typename MeshGenerator<dim>::CoarseSize &coarse) const;

      /// The entry that gives the horizon ('Horizon/m-ratio' or
      /// 'Horizon/Length') and its value, for messages.
      std::pair<std::string, std::string>
      horizon_entry() const;

      /// Whether owned nodes couple to nodes two horizons away (the
      /// problem type's answer for this run's material model, if any).
      bool
      couples_two_horizons() const;

      void
      make_mesh();

      void
      setup_nodes();

      /**
       * Refuse a material model whose bond stiffness at this horizon is
       * not a finite number (a modulus such as 1e308 overflows once divided
       * by a power of the horizon), naming the modulus; otherwise every
       * operator, bound and residual turns NaN or Inf and the failure is
       * reported far from its cause.
       */
      void
      check_material_scale() const;

      /**
       * Refuse output names that meet (IO::check_output_names()): the
       * problem type's, the summary and node data files, and the mesh file
       * read. Collective.
       */
      void
      check_output_names() const;

      /**
       * Refuse entries that @p prm sets to a value other than their
       * default where they have no effect on this run (those that the
       * problem type, the material model and the boundary conditions list,
       * and the sections of a model or solver the problem type does not
       * use): each would otherwise be ignored without a word.
       */
      void
      check_unused_entries(const ParameterHandler &prm) const;

      const MPI_Comm     communicator;
      ConditionalOStream pcout;
      TimerOutput        timer;
      Timer              wall_clock;

      // Input.
      std::string problem_name;
      /// The coarse mesh ('Geometry/Mesh').
      std::unique_ptr<MeshGenerator<dim>> mesh_generator;
      unsigned int                        global_refinements = 0;
      /// 'Geometry/Node perturbation' (a fraction of h) and 'Random seed'.
      double        node_perturbation = 0;
      std::uint64_t random_seed       = 1;
      /// 'Horizon/Specification', parsed once.
      enum class HorizonSpecification
      {
        m_ratio,
        length
      };
      HorizonSpecification horizon_specification =
        HorizonSpecification::m_ratio;
      double      m_ratio        = 3;
      double      horizon_length = 0;
      std::string algorithm_name, model_name;
      bool        compare_with_analytical = false;
      std::string summary_file;
      std::string node_data_file;

      std::unique_ptr<ProblemType<dim>>                  problem;
      std::unique_ptr<Quadrature::PartialVolume<dim>>    algorithm;
      std::string                                        quadrature_scheme_name;
      std::unique_ptr<Quadrature::QuadratureScheme<dim>> quadrature_scheme;
      std::unique_ptr<Models::Model<dim>>                model;
      std::string                                        treatment_name;
      std::unique_ptr<Boundary::BoundaryTreatment>       treatment;
      Boundary::BoundaryConditions<dim>                  boundary_conditions;
      std::unique_ptr<Functions::ParsedFunction<dim>>    analytical_solution;
      Solvers::LinearSolver                              linear_solver;
      IO::SolutionOutput<dim>                            output;

      // Discretisation.
      std::unique_ptr<parallel::TriangulationBase<dim>> triangulation;
      FESystem<dim>                                     fe;
      DoFHandler<dim>                                   dof_handler;
      double                                            h       = 0;
      double                                            horizon = 0;
      Discretization::NodeSet<dim>                      nodes;
      Discretization::NeighborList<dim>                 neighbor_lists;

      IO::RunSummary summary;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
