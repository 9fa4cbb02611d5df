#ifndef perideal_solvers_linear_solver_h
#define perideal_solvers_linear_solver_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/operators/constrained_operator.h>
#include <perideal/solvers/krylov.h>
#include <perideal/solvers/preconditioner.h>
#include <perideal/solvers/solver_report.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * The linear solver of a PD system, chosen in the subsection
     * "Linear solver" of the input file: a sparse direct solver through
     * Trilinos Amesos (MUMPS by default), or a Krylov method (CG, GMRES,
     * BiCGStab) with a preconditioner plugin (Preconditioner: AMG, Jacobi,
     * SSOR, ILU(k), Chebyshev, local elasticity, none, or a user's own).
     * Every selection is parsed once, into Method, OperatorForm and the
     * preconditioner object; callers ask those, never the names.
     *
     * A solve that does not reach its tolerance is an error (the run stops
     * before any output is written), and every solve reports the residual it
     * actually achieved.
     */
    class LinearSolver
    {
    public:
      LinearSolver();
      ~LinearSolver();

      /**
       * Declare the entries of the current subsection, and one subsection
       * per registered preconditioner with its parameters.
       */
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm);

      /**
       * Solve \f$A x = b\f$. @p constant_modes are the rigid translations,
       * one boolean mask over the locally owned DoFs per displacement
       * component, used by the AMG preconditioner; may be empty.
       * @p symmetric says whether @p matrix is symmetric: CG on a
       * non-symmetric matrix is refused.
       */
      SolverReport
      solve(const TrilinosWrappers::SparseMatrix &matrix,
            TrilinosWrappers::MPI::Vector        &solution,
            const TrilinosWrappers::MPI::Vector  &rhs,
            const std::vector<std::vector<bool>> &constant_modes,
            const bool                            symmetric) const;

      /**
       * Solve \f$K x = b\f$ without the PD matrix: a Krylov method of
       * deal.II on the matrix-free @p op with the selected preconditioner,
       * given the inverse of the exact diagonal and the operator's action,
       * and @p local_matrix, the local elasticity operator on the same nodes
       * (Operators::LocalElasticityOperator), where the preconditioner
       * needs_local_matrix() (may be null otherwise). @p constant_modes as
       * for the assembled solve (of the local matrix). @p local_transfer:
       * where the local matrix lives on a coarser lattice
       * (Preconditioner::local_matrix_coarsening() > 1), the transfer to it.
       * @p local_matrix_version: PreconditionerSetup::local_matrix_version.
       */
      template <int dim>
      SolverReport
      solve(const Operators::ConstrainedOperator<dim>        &op,
            LinearAlgebra::distributed::Vector<double>       &solution,
            const LinearAlgebra::distributed::Vector<double> &rhs,
            const TrilinosWrappers::SparseMatrix             *local_matrix,
            const std::vector<std::vector<bool>>             &constant_modes,
            const Operators::GridTransfer *local_transfer       = nullptr,
            const std::uint64_t            local_matrix_version = 0) const;

      /// A linear map between Trilinos vectors: dst = A src.
      using TrilinosMap =
        std::function<void(TrilinosWrappers::MPI::Vector       &dst,
                           const TrilinosWrappers::MPI::Vector &src)>;

      /**
       * Solve \f$A x = b\f$ for a non-symmetric @p op given only by its
       * action (a matrix-free layer system): GMRES or BiCGStab ('Method'),
       * preconditioned by @p precondition (the identity if empty; the
       * caller builds it from setup_preconditioner()), named @p label in
       * reports. CG is refused (not symmetric); a solve that
       * does not converge stops with the method, preconditioner, iterations
       * and residual.
       */
      SolverReport
      solve(const TrilinosMap                   &op,
            const TrilinosMap                   &precondition,
            TrilinosWrappers::MPI::Vector       &solution,
            const TrilinosWrappers::MPI::Vector &rhs,
            const std::string                   &label) const;

      /// 'Method', parsed.
      Method
      method() const;

      /// 'Method' as written in the input file.
      std::string
      method_name() const;

      /// Whether 'Operator = matrix-free'.
      bool
      is_matrix_free() const;

      /// The selected preconditioner (parsed, not yet set up).
      const Preconditioner &
      preconditioner() const;

      /// The preconditioner's name as given.
      const std::string &
      preconditioner_name() const;

      /**
       * Refuse this solver for an operator of @p form whose owner is named
       * @p owner in the message (for instance "the boundary treatment
       * 'surface nodes'"): a Krylov method other than CG where @p symmetric
       * is false, and a preconditioner that does not support @p form. The
       * exception names the entry, its value and what to choose instead.
       */
      void
      check_form(const OperatorForm form,
                 const bool         symmetric,
                 const std::string &owner) const;

      /**
       * The preconditioner set up for one solve of an operator of @p form
       * from @p setup (to which the solver's AMG settings are added);
       * released by the solver after the solve, or by
       * release_preconditioner().
       */
      const Preconditioner &
      setup_preconditioner(const OperatorForm    form,
                           PreconditionerSetup &&setup) const;

      /// Release what setup_preconditioner() built.
      void
      release_preconditioner() const;

    private:
      Method       method_value            = Method::direct;
      std::string  direct_package          = "MUMPS";
      std::string  preconditioner_selected = "AMG";
      bool         matrix_free             = false;
      double       tolerance               = 1e-10;
      unsigned int max_iterations          = 10000;
      unsigned int restart_length          = 200;
      AmgSettings  amg;

      /// The selected preconditioner; set up per solve (hence mutable: a
      /// solve does not change the solver's parameters).
      mutable std::unique_ptr<Preconditioner> preconditioner_object;
    };

    namespace internal
    {
      /**
       * Stop, naming @p method, when the right-hand side (of norm
       * @p rhs_norm) holds NaN or Inf: a Krylov method would stop at once
       * (deal.II's CG even without an error) and a direct one returns NaN.
       * The loads and prescribed values are checked where they are
       * evaluated, so what remains is an overflow of the lifting.
       */
      void
      check_finite_rhs(const double rhs_norm, const std::string &method);

      /**
       * Stop, naming @p method, when the solve did not end in success
       * (@p converged false with the last residual @p last_residual: a
       * solver that stops at its first check returns without an error) or
       * the residual of its solution, @p relative_residual, is not finite.
       */
      void
      check_solve_result(const bool         converged,
                         const double       last_residual,
                         const double       relative_residual,
                         const std::string &method);
    } // namespace internal
  }   // namespace Solvers
} // namespace PeriDEAL

#endif
