#ifndef perideal_solvers_solver_report_h
#define perideal_solvers_solver_report_h

#include <string>

namespace PeriDEAL
{
  /**
   * Linear solvers (direct and Krylov), their preconditioners (plugins, see
   * preconditioner.h) and the one algebraic multigrid set-up (amg.h).
   */
  namespace Solvers
  {
    /**
     * What a linear solve did: the method, the number of iterations (1 for a
     * direct solve), the relative residual \f$|b - Ax|/|b|\f$ measured after
     * the solve (not the solver's own estimate), and the wall time.
     */
    struct SolverReport
    {
      std::string  method;
      unsigned int iterations = 0;
      /// Newton corrections of a nonlinear solve (0: a linear solve).
      unsigned int corrections       = 0;
      double       relative_residual = 0;
      double       seconds           = 0;
    };
  } // namespace Solvers
} // namespace PeriDEAL

#endif
