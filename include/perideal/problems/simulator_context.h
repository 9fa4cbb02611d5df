#ifndef perideal_problems_simulator_context_h
#define perideal_problems_simulator_context_h

#include <perideal/problems/simulator.h>

#include <iomanip>
#include <string>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace internal
    {
      /**
       * What the phases of the quasi-static problem read from the
       * simulator, gathered once per phase.
       */
      template <int dim>
      struct Context
      {
        const MPI_Comm                           communicator;
        ConditionalOStream                      &pcout;
        TimerOutput                             &timer;
        IO::RunSummary                          &summary;
        const DoFHandler<dim>                   &dof_handler;
        const parallel::TriangulationBase<dim>  &triangulation;
        const Discretization::NodeSet<dim>      &nodes;
        const Discretization::NeighborList<dim> &neighbor_lists;
        const Models::Model<dim>                &model;
        const double                             horizon;
        const Boundary::BoundaryConditions<dim> &boundary_conditions;
        const Boundary::BoundaryTreatment       &treatment;
        const std::string                       &treatment_name;
        const Solvers::LinearSolver             &linear_solver;
        const Functions::ParsedFunction<dim>    *analytical_solution;
        const IO::SolutionOutput<dim>           &output;
        const std::string                       &node_data_file;
      };

      /// The Context of @p s.
      template <int dim>
      inline Context<dim>
      context_of(Simulator<dim> &s)
      {
        return {s.get_communicator(),
                s.get_pcout(),
                s.get_timer(),
                s.get_summary(),
                s.get_dof_handler(),
                s.get_triangulation(),
                s.get_nodes(),
                s.get_neighbor_lists(),
                s.get_model(),
                s.get_horizon(),
                s.get_boundary_conditions(),
                s.get_boundary_treatment(),
                s.get_boundary_treatment_name(),
                s.get_linear_solver(),
                s.get_analytical_solution(),
                s.get_output(),
                s.get_node_data_file()};
      }

      /// Log the linear solve of the run summary: method, iterations,
      /// residual, and @p note.
      template <int dim>
      inline void
      print_solve(Simulator<dim> &s, const std::string &note)
      {
        const auto &solver = s.get_summary().solver;
        s.get_pcout() << "[" << std::setw(8) << std::fixed
                      << std::setprecision(2) << s.elapsed()
                      << " s] solved with " << solver.method << ": "
                      << solver.iterations
                      << " iteration(s), relative residual " << std::scientific
                      << std::setprecision(2) << solver.relative_residual
                      << std::defaultfloat << note << std::endl;
      }

      /// Log the equilibrium residual of the run summary, computed with
      /// @p what.
      template <int dim>
      inline void
      print_equilibrium(Simulator<dim> &s, const std::string &what)
      {
        s.get_pcout() << "           equilibrium check (" << what
                      << "): |F_int + F_ext| / |F_int| = " << std::scientific
                      << std::setprecision(2)
                      << s.get_summary().equilibrium_residual
                      << std::defaultfloat << std::endl;
      }
    } // namespace internal
  }   // namespace Problems
} // namespace PeriDEAL

#endif
