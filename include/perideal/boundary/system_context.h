#ifndef perideal_boundary_system_context_h
#define perideal_boundary_system_context_h

/**
 * @file
 * What a discrete system sees of the run (SystemContext), and the two log
 * lines that every system prints after its solve (print_solve(),
 * print_equilibrium()).
 */

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/dofs/dof_handler.h>

#include <perideal/boundary/boundary_conditions.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/run_summary.h>
#include <perideal/models/model.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/quadrature_scheme.h>
#include <perideal/solvers/linear_solver.h>

#include <functional>
#include <string>

namespace PeriDEAL
{
  namespace Boundary
  {
    using namespace dealii;

    /**
     * Everything a DiscreteSystem reads from the run or does to it: the
     * shared set-up (mesh, DoFs, nodes, neighbour lists, model, partial
     * volumes, boundary conditions, linear solver), where it writes (log,
     * timer, run summary), and the few actions that only the owner of the
     * set-up can take, as hooks (build the neighbour lists, the wall time,
     * a progress line).
     *
     * The context is a view: its members refer to objects owned elsewhere
     * (by Problems::Simulator, which fills one in
     * Problems::Simulator::system_context()) and must outlive it. A const
     * context still writes through its references and hooks, so discrete
     * systems take it as `const SystemContext<dim> &`. With it, the
     * `boundary` folder needs nothing from `problems`.
     */
    template <int dim>
    struct SystemContext
    {
      /// The communicator of the run.
      const MPI_Comm communicator;

      /// The log, printed on rank 0.
      ConditionalOStream &pcout;

      /// The phase timer ("operator setup", "assembly", "solve", ...).
      TimerOutput &timer;

      /// The run summary, which the systems fill (sizes, solver report,
      /// equilibrium residual).
      IO::RunSummary &summary;

      /// One DoF per component and node (FE_DGQ(0)^dim).
      const DoFHandler<dim> &dof_handler;

      /// The mesh.
      const parallel::TriangulationBase<dim> &triangulation;

      /// The PD nodes, owned and ghost.
      const Discretization::NodeSet<dim> &nodes;

      /// The neighbour lists; filled by setup_neighbor_lists().
      const Discretization::NeighborList<dim> &neighbor_lists;

      /// The material model.
      const Models::Model<dim> &model;

      /// The partial-volume algorithm.
      const Quadrature::PartialVolume<dim> &partial_volume;

      /// Its name in the input file.
      const std::string &partial_volume_name;

      /// The quadrature scheme ('Quadrature/Scheme') and its name.
      const Quadrature::QuadratureScheme<dim> &quadrature_scheme;

      const std::string &quadrature_scheme_name;

      /// The horizon \f$\delta\f$.
      const double horizon;

      /// Dirichlet layers, body force, tractions.
      const BoundaryConditions<dim> &boundary_conditions;

      /// The name of the boundary treatment in the input file.
      const std::string &treatment_name;

      /// The settings and methods of 'Linear solver'.
      const Solvers::LinearSolver &linear_solver;

      /**
       * Build the neighbour lists into #neighbor_lists and count the bonds
       * into the summary (timer "neighbour search and weights").
       * The argument: also store the lists of nodes whose neighbourhood is
       * the full stencil.
       */
      std::function<void(bool)> setup_neighbor_lists;

      /// Wall time since the run started, in seconds.
      std::function<double()> elapsed;

      /// Print "[ wall time s] text" on rank 0.
      std::function<void(const std::string &)> print_progress;

      /// With the hybrid quadrature scheme: the fixed standard region
      /// (Problems::hybrid_standard_region(), owned and ghost nodes), set by
      /// the problem type before the system's setup().
      const std::vector<bool> *hybrid_standard = nullptr;
    };


    /**
     * Log the linear solve of the run summary: "[ wall time s] solved with
     * " method, iterations, relative residual, and @p note.
     */
    template <int dim>
    void
    print_solve(const SystemContext<dim> &context, const std::string &note);


    /**
     * Log the equilibrium residual of the run summary, computed with
     * @p what.
     */
    template <int dim>
    void
    print_equilibrium(const SystemContext<dim> &context,
                      const std::string        &what);
  } // namespace Boundary
} // namespace PeriDEAL

#endif
