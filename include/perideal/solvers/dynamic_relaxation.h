#ifndef perideal_solvers_dynamic_relaxation_h
#define perideal_solvers_dynamic_relaxation_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <perideal/solvers/solver_report.h>

#include <string>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * Adaptive dynamic relaxation (Kilic & Madenci 2010, Theor. Appl.
     * Fract. Mech. 53): the equilibrium A x = b as the steady state of the
     * damped pseudo-dynamics D x'' + c D x' + A x = b with the central
     * difference rule at Δt = 1,
     * \f[
     *   v^{n+1/2} = \frac{(2 - c^n) v^{n-1/2} + 2 D^{-1} r^n}{2 + c^n},\quad
     *   x^{n+1} = x^n + v^{n+1/2},\quad r^n = b - A x^n,
     * \f]
     * started with \f$v^{1/2} = D^{-1} r^0 / 2\f$. The damping follows the
     * lowest mode the run excites, \f$c^n = 2\sqrt{(x^T K^n x)/(x^T x)}\f$
     * with the local stiffness \f$K^n_{ii} = -(r^n_i - r^{n-1}_i)/(D_{ii}
     * v^{n-1/2}_i)\f$ (0 where it is negative: no damping). The fictitious
     * density is \f$D = s\,{\rm diag}(A)\f$ with s = 1.25 μ / 4, μ the
     * largest eigenvalue of diag(A)⁻¹A by 50 power iterations, so that the
     * scheme is stable (it needs \f$\lambda_{\max}(D^{-1}A) \le 4\f$; the
     * paper bounds it by the row sums of the assembled stiffness, which the
     * matrix-free operator does not have). Should a mode the estimate
     * missed grow (the residual 1000 times the best so far), the run goes
     * back to the best iterate with twice the density, at most 20 times.
     * A may be nonlinear (finite deformation): the residual is the
     * operator's residual() and the eigenvalue estimate uses its
     * linearisation vmult(); the fictitious density then bounds the
     * tangent as long as it stays near K, and the restarts cover the rest.
     *
     * The test of convergence is the one of the Krylov solvers: the
     * residual \f$\|b - A x\|\f$ at most `Relative tolerance` times
     * \f$\|b\|\f$; more than `Maximum iterations` throws ExcNoConvergence
     * (a load step that can be cut retries). Every sum over the unknowns
     * (norms, the Rayleigh quotients) is reproducible_sum(), and the
     * operator's apply is the same to the last bit on any partition, so the
     * iterates are bitwise the same on 1, 2 or N processes and threads.
     */
    class DynamicRelaxation
    {
    public:
      /// 'Relative tolerance' and 'Maximum iterations' in the current
      /// subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Parse them; @p path ('Subsection/') names them in errors.
      void
      parse_parameters(ParameterHandler &prm, const std::string &path);

      /**
       * Solve A x = b from the start @p x, A @p op (with residual(r, x, b),
       * the linearised vmult() and diagonal() on the owned entries of @p x's
       * layout). Collective.
       */
      template <typename OperatorType, typename VectorType>
      SolverReport
      solve(const OperatorType &op,
            VectorType         &x,
            const VectorType   &b,
            MPI_Comm            comm) const;

      double       tolerance      = 1e-8;
      unsigned int max_iterations = 1000000;
    };
  } // namespace Solvers
} // namespace PeriDEAL

#endif
