#ifndef perideal_solvers_quasi_static_simulation_h
#define perideal_solvers_quasi_static_simulation_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/boundary_conditions.h>
#include <perideal/boundary/boundary_treatment.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/solution_output.h>
#include <perideal/models/model.h>
#include <perideal/discretization/bond_state.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/constrained_operator.h>
#include <perideal/operators/fictitious_layer_operator.h>
#include <perideal/operators/linear_peridynamic_operator.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/solvers/linear_solver.h>

#include <map>
#include <memory>
#include <string>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * Errors of a computed displacement against an analytical one, over the
     * owned nodes of all processes:
     * \f[
     *   e_{L^2} = \Big(\frac{\sum_i V_i |u_i - u(x_i)|^2}
     *                      {\sum_i V_i |u(x_i)|^2}\Big)^{1/2},\qquad
     *   e_{\max} = \frac{\max_i |u_i - u(x_i)|}{\max_i |u(x_i)|}.
     * \f]
     */
    struct ErrorNorms
    {
      double l2  = 0;
      double max = 0;
      /**
       * Scabbia et al. 2023, Eq. 38: the largest over the nodes of
       * \f$\big(\sum_c ((u_{i,c} - \bar u_c(x_i)) / \max_j |\bar u_c(x_j)|)^2
       * \big)^{1/2}\f$, each component scaled by its own largest analytical
       * magnitude (components that vanish everywhere are left out).
       */
      double max_normalized = 0;
    };

    /**
     * What a run measured: sizes, solver report, errors, the wall time of
     * each phase and the peak memory; written to the summary CSV.
     */
    struct RunSummary
    {
      unsigned int                  n_ranks             = 1;
      types::global_dof_index       n_nodes             = 0;
      types::global_dof_index       n_constrained_nodes = 0;
      double                        h = 0, horizon = 0;
      std::size_t                   n_bonds    = 0;
      std::size_t                   n_nonzeros = 0;
      SolverReport                  solver;
      double                        equilibrium_residual = 0;
      std::string                   treatment            = "none";
      unsigned int                  taylor_order         = 0;
      types::global_dof_index       n_unknowns           = 0;
      unsigned int                  n_surface_nodes      = 0;
      unsigned int                  n_fictitious_nodes   = 0;
      bool                          has_errors           = false;
      ErrorNorms                    errors;
      std::map<std::string, double> seconds;
      double                        peak_memory_mb = 0;
    };

    /**
     * A quasi-static linear PD problem described entirely by a parameter
     * file: the tutorial-plain driver behind the `perideal` program.
     *
     * run() builds the mesh (a subdivided box or a Cartesian mesh read with
     * GridIn) on a parallel::distributed::Triangulation, places one PD node
     * at each active cell's centre (NodeSet), exchanges the off-process
     * nodes within the coupling range, builds the neighbour lists with the
     * selected partial-volume algorithm, assembles the linearised PD
     * stiffness in a Trilinos matrix with the volumetric boundary
     * conditions eliminated, solves with the selected linear solver, checks
     * equilibrium with the matrix-free force evaluation, compares with an
     * analytical solution when one is given, and writes PVTU output and a
     * CSV summary.
     *
     * All entries are declared with a pattern and a help text; see
     * `perideal --print-parameters`.
     */
    template <int dim>
    class QuasiStaticSimulation
    {
    public:
      explicit QuasiStaticSimulation(const MPI_Comm communicator);

      /**
       * Declare every entry of the input file (the top-level "Dimension"
       * included, so that a file that sets it parses).
       */
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * Read and check the entries; errors name the entry, the value and
       * what to do.
       */
      void
      parse_parameters(ParameterHandler &prm);

      /**
       * Run the whole problem and return what it measured.
       */
      RunSummary
      run();

      /**
       * The computed displacement (ghosted over the relevant DoFs).
       */
      const TrilinosWrappers::MPI::Vector &
      solution() const;

    private:
      void
      make_mesh();

      void
      setup_nodes_and_bonds();

      void
      assemble_and_solve();

      /// assemble_and_solve() with a fictitious layer (and surface nodes).
      void
      assemble_and_solve_with_layer();

      /// assemble_and_solve() with 'Operator = matrix-free'.
      void
      solve_matrix_free();

      void
      postprocess();

      /// Gather every node's position, displacement and error to the CSV
      /// named in 'Output/Node data file'.
      void
      write_node_data(const Tensor<1, dim> &component_max) const;

      const MPI_Comm     communicator;
      ConditionalOStream pcout;
      TimerOutput        timer;
      Timer              wall_clock;

      // Input.
      std::string               mesh_kind;
      Point<dim>                lower_corner, upper_corner;
      std::vector<unsigned int> subdivisions;
      unsigned int              global_refinements = 0;
      std::string               mesh_file;
      std::string               horizon_specification;
      double                    m_ratio        = 3;
      double                    horizon_length = 0;
      std::string               algorithm_name, model_name;
      bool                      compare_with_analytical = false;
      std::string               summary_file;
      std::string               node_data_file;

      std::unique_ptr<Quadrature::PartialVolume<dim>> algorithm;
      std::unique_ptr<Models::Model<dim>>             model;
      std::string                                     treatment_name;
      std::unique_ptr<Boundary::BoundaryTreatment>    treatment;
      Boundary::BoundaryConditions<dim>               boundary_conditions;
      std::unique_ptr<Functions::ParsedFunction<dim>> analytical_solution;
      LinearSolver                                    linear_solver;
      IO::SolutionOutput<dim>                         output;

      // Discretisation.
      parallel::distributed::Triangulation<dim> triangulation;
      FESystem<dim>                             fe;
      DoFHandler<dim>                           dof_handler;
      double                                    h       = 0;
      double                                    horizon = 0;
      Discretization::NodeSet<dim>              nodes;
      Discretization::NeighborList<dim>         neighbor_lists;
      Operators::LinearPeridynamicOperator<dim> pd_operator;
      Discretization::BondState<dim>            bond_state;
      Operators::BondOperator<dim>              bond_operator;
      Operators::ConstrainedOperator<dim>       constrained_operator;
      TrilinosWrappers::SparseMatrix            local_matrix;
      Operators::FictitiousLayerOperator<dim>   layer_operator;
      AffineConstraints<double>                 constraints;

      // Linear system.
      TrilinosWrappers::SparseMatrix system_matrix;
      TrilinosWrappers::MPI::Vector  load;
      TrilinosWrappers::MPI::Vector  system_rhs;
      TrilinosWrappers::MPI::Vector  displacement;
      // With surface nodes: their displacements, owned ones, in the order
      // of FictitiousLayerOperator::owned_surface_nodes().
      std::vector<Tensor<1, dim>> surface_displacement;

      RunSummary summary;
    };
  } // namespace Solvers
} // namespace PeriDEAL

#endif
