#include <deal.II/base/timer.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_control.h>

#include <perideal/base/exceptions.h>
#include <perideal/solvers/krylov.h>
#include <perideal/solvers/linear_solver.h>

#include <cmath>
#include <cstdlib>
#include <sstream>

namespace PeriDEAL
{
  namespace Solvers
  {
    namespace
    {
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// deal.II's GMRES settings of the PD solves: right-preconditioned,
      /// so that its stopping test sees the true residual, not the
      /// preconditioned one.
      template <typename Vector>
      typename SolverGMRES<Vector>::AdditionalData
      gmres_data(const unsigned int restart_length)
      {
        return
          typename SolverGMRES<Vector>::AdditionalData(restart_length, true);
      }


      /// A preconditioner plugin as deal.II's solvers take it.
      template <typename Vector>
      struct PluginPreconditioner
      {
        const Preconditioner &preconditioner;

        void
        vmult(Vector &dst, const Vector &src) const
        {
          preconditioner.vmult(dst, src);
        }
      };


      /**
       * Complete @p report of a converged Krylov solve: its iterations, the
       * relative residual it actually reached, measured with the operator
       * (@p residual holds A x on entry, |b - A x| / |b| is reported), the
       * check of that residual, and the wall time since @p timer started.
       */
      template <typename Vector>
      SolverReport
      finish_report(SolverReport         report,
                    const SolverControl &control,
                    Vector              &residual,
                    const Vector        &rhs,
                    const double         rhs_norm,
                    const Timer         &timer)
      {
        report.iterations = control.last_step();
        residual.sadd(-1., 1., rhs);
        report.relative_residual = residual.l2_norm() / rhs_norm;
        internal::check_solve_result(control.last_check() ==
                                       SolverControl::success,
                                     control.last_value(),
                                     report.relative_residual,
                                     report.method);
        report.seconds = timer.wall_time();
        return report;
      }


      /// Stop on a Krylov solve that did not converge, with @p fix.
      [[noreturn]] void
      throw_no_convergence(const std::string                  &method,
                           const SolverControl::NoConvergence &e,
                           const double                        rhs_norm,
                           const double                        tolerance,
                           const std::string                  &fix)
      {
        std::ostringstream message;
        message << "The linear solver (" << method
                << ") did not converge: after " << e.last_step
                << " iterations the residual is " << e.last_residual / rhs_norm
                << " of |b|, above 'Linear solver/Relative tolerance' = "
                << tolerance << ". " << fix;
        AssertThrow(false, ExcNoConvergence(message.str()));
        std::abort(); // not reached
      }
    } // namespace


    template <int dim>
    SolverReport
    LinearSolver::solve(const Operators::ConstrainedOperator<dim> &op,
                        VectorType                                &solution,
                        const VectorType                          &rhs,
                        const TrilinosWrappers::SparseMatrix      *local_matrix,
                        const std::vector<std::vector<bool>> &constant_modes,
                        const Operators::GridTransfer        *local_transfer,
                        const std::uint64_t local_matrix_version) const
    {
      Timer              timer;
      SolverReport       report;
      const unsigned int coarsening =
        preconditioner_object->local_matrix_coarsening();
      report.method =
        method_name() + " + " + preconditioner_selected +
        (coarsening > 1 ? " (coarsening " + std::to_string(coarsening) + ")" :
                          "") +
        " (matrix-free operator)";
      const double rhs_norm = rhs.l2_norm();
      internal::check_finite_rhs(rhs_norm, report.method);
      if (rhs_norm == 0)
        {
          solution = 0;
          return report;
        }

      // Zero rows (nodes without bonds) make the diagonal preconditioners
      // and the operator singular: say so instead of dividing by zero.
      const VectorType &diagonal = op.diagonal();
      VectorType        inverse_diagonal(diagonal);
      unsigned int      zero_rows = 0;
      for (unsigned int k = 0; k < diagonal.locally_owned_size(); ++k)
        {
          const double d = diagonal.local_element(k);
          if (!(d > 0))
            ++zero_rows;
          inverse_diagonal.local_element(k) = d > 0 ? 1. / d : 1.;
        }
      zero_rows =
        Utilities::MPI::sum(zero_rows, diagonal.get_mpi_communicator());
      AssertThrow(zero_rows == 0,
                  ExcMessage(std::to_string(zero_rows) +
                             " rows of the PD stiffness have no positive "
                             "diagonal entry: nodes without intact bonds. "
                             "Raise the m-ratio or check the mesh."));

      PreconditionerSetup setup;
      setup.inverse_diagonal = &inverse_diagonal;
      setup.apply            = [&op](VectorType &dst, const VectorType &src) {
        op.vmult(dst, src);
      };
      setup.n_rows               = op.m();
      setup.local_matrix         = local_matrix;
      setup.constant_modes       = constant_modes;
      setup.local_transfer       = local_transfer;
      setup.local_matrix_version = local_matrix_version;
      AssertThrow(!preconditioner_object->needs_local_matrix() ||
                    local_matrix != nullptr,
                  ExcInternalError());
      SolverControl control(max_iterations, tolerance * rhs_norm);
      try
        {
          const Preconditioner &preconditioner =
            setup_preconditioner(OperatorForm::matrix_free, std::move(setup));
          const auto krylov = [&](const auto &precondition) {
            run_krylov(method_value,
                       gmres_data<VectorType>(restart_length),
                       control,
                       op,
                       solution,
                       rhs,
                       precondition);
          };
          if (preconditioner.is_identity())
            krylov(PreconditionIdentity());
          else
            krylov(PluginPreconditioner<VectorType>{preconditioner});
        }
      catch (const SolverControl::NoConvergence &e)
        {
          throw_no_convergence(report.method,
                               e,
                               rhs_norm,
                               tolerance,
                               "Raise 'Maximum iterations', use "
                               "'Preconditioner = local elasticity', or check "
                               "that the Dirichlet conditions fix every rigid "
                               "motion.");
        }
      release_preconditioner();
      VectorType residual;
      op.initialize_dof_vector(residual);
      op.vmult(residual, solution);
      return finish_report(report, control, residual, rhs, rhs_norm, timer);
    }


    namespace
    {
      /// A function as the operator of deal.II's solvers.
      struct FunctionOperator
      {
        const LinearSolver::TrilinosMap &map;

        void
        vmult(TrilinosWrappers::MPI::Vector       &dst,
              const TrilinosWrappers::MPI::Vector &src) const
        {
          map(dst, src);
        }
      };
    } // namespace


    SolverReport
    LinearSolver::solve(const TrilinosMap                   &op,
                        const TrilinosMap                   &precondition,
                        TrilinosWrappers::MPI::Vector       &solution,
                        const TrilinosWrappers::MPI::Vector &rhs,
                        const std::string                   &label) const
    {
      using Vector = TrilinosWrappers::MPI::Vector;
      Timer        timer;
      SolverReport report;
      report.method = method_name() + " + " + label + " (matrix-free operator)";
      AssertThrow(method_value == Method::gmres ||
                    method_value == Method::bicgstab,
                  ExcInvalidInput("Linear solver/Method",
                                  method_name(),
                                  "this system is not symmetric and has no "
                                  "matrix; use GMRES or BiCGStab"));
      const double rhs_norm = rhs.l2_norm();
      internal::check_finite_rhs(rhs_norm, report.method);
      solution = 0;
      if (rhs_norm == 0)
        return report;
      const FunctionOperator A{op};
      const FunctionOperator P{precondition};
      SolverControl          control(max_iterations, tolerance * rhs_norm);
      try
        {
          if (precondition)
            run_krylov(method_value,
                       gmres_data<Vector>(restart_length),
                       control,
                       A,
                       solution,
                       rhs,
                       P);
          else
            run_krylov(method_value,
                       gmres_data<Vector>(restart_length),
                       control,
                       A,
                       solution,
                       rhs,
                       PreconditionIdentity());
        }
      catch (const SolverControl::NoConvergence &e)
        {
          throw_no_convergence(report.method,
                               e,
                               rhs_norm,
                               tolerance,
                               "Raise 'Maximum iterations' or 'GMRES restart "
                               "length', use 'Preconditioner = local "
                               "elasticity', or 'Operator = assembled' with a "
                               "direct solver.");
        }
      Vector residual(rhs);
      op(residual, solution);
      return finish_report(report, control, residual, rhs, rhs_norm, timer);
    }


#define PERIDEAL_INSTANTIATE(dim)                 \
  template SolverReport LinearSolver::solve<dim>( \
    const Operators::ConstrainedOperator<dim> &,  \
    VectorType &,                                 \
    const VectorType &,                           \
    const TrilinosWrappers::SparseMatrix *,       \
    const std::vector<std::vector<bool>> &,       \
    const Operators::GridTransfer *,              \
    const std::uint64_t) const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Solvers
} // namespace PeriDEAL
