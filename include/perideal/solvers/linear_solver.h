#ifndef perideal_solvers_linear_solver_h
#define perideal_solvers_linear_solver_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/operators/constrained_operator.h>

#include <functional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  /**
   * Linear solvers, quasi-static drivers and (later) time integrators.
   */
  namespace Solvers
  {
    using namespace dealii;

    /**
     * What a linear solve did: the method, the number of iterations (1 for a
     * direct solve), the relative residual \f$|b - Ax|/|b|\f$ measured after
     * the solve (not the solver's own estimate), and the wall time.
     */
    struct SolverReport
    {
      std::string  method;
      unsigned int iterations        = 0;
      double       relative_residual = 0;
      double       seconds           = 0;
    };

    /**
     * The linear solver of a PD system, chosen in the subsection
     * "Linear solver" of the input file: a sparse direct solver through
     * Trilinos Amesos (MUMPS by default), or a Krylov method (CG, GMRES,
     * BiCGStab) from deal.II's Trilinos wrappers with an algebraic multigrid
     * (ML), Jacobi, SSOR, ILU(k) or no preconditioner.
     *
     * A solve that does not reach its tolerance is an error (the run stops
     * before any output is written), and every solve reports the residual it
     * actually achieved.
     */
    class LinearSolver
    {
    public:
      /**
       * Declare the entries of the current subsection.
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
       * deal.II on the matrix-free @p op, preconditioned by Jacobi or
       * Chebyshev on its exact diagonal, or by algebraic multigrid (ML) on
       * @p local_matrix, the local elasticity operator on the same nodes
       * (Operators::LocalElasticityOperator; may be null for the other
       * preconditioners). @p constant_modes as for the assembled solve.
       */
      template <int dim>
      SolverReport
      solve(const Operators::ConstrainedOperator<dim>        &op,
            LinearAlgebra::distributed::Vector<double>       &solution,
            const LinearAlgebra::distributed::Vector<double> &rhs,
            const TrilinosWrappers::SparseMatrix             *local_matrix,
            const std::vector<std::vector<bool>> &constant_modes) const;

      /// A linear map between Trilinos vectors: dst = A src.
      using TrilinosMap =
        std::function<void(TrilinosWrappers::MPI::Vector       &dst,
                           const TrilinosWrappers::MPI::Vector &src)>;

      /**
       * Solve \f$A x = b\f$ for a non-symmetric @p op given only by its
       * action (a matrix-free layer system): GMRES or BiCGStab ('Method'),
       * preconditioned by @p precondition (the identity if empty), named
       * @p label in reports. CG is refused (not symmetric); a solve that
       * does not converge stops with the method, preconditioner, iterations
       * and residual.
       */
      SolverReport
      solve(const TrilinosMap                   &op,
            const TrilinosMap                   &precondition,
            TrilinosWrappers::MPI::Vector       &solution,
            const TrilinosWrappers::MPI::Vector &rhs,
            const std::string                   &label) const;

      const std::string &
      method() const;

      /// Whether 'Operator = matrix-free'.
      bool
      is_matrix_free() const;

      /// The preconditioner's name as given.
      const std::string &
      preconditioner_name() const;

    private:
      std::string  method_name      = "direct";
      std::string  direct_package   = "MUMPS";
      std::string  preconditioner   = "AMG";
      bool         matrix_free      = false;
      unsigned int chebyshev_degree = 4;
      unsigned int ilu_fill         = 1;
      double       tolerance        = 1e-10;
      unsigned int max_iterations   = 10000;
      unsigned int restart_length   = 200;
      unsigned int smoother_sweeps  = 2;
      double       aggregation      = 1e-4;
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
  } // namespace Solvers
} // namespace PeriDEAL

#endif
