#include <perideal/boundary/system_context.h>

#include <iomanip>

namespace PeriDEAL
{
  namespace Boundary
  {
    template <int dim>
    void
    print_solve(const SystemContext<dim> &context, const std::string &note)
    {
      const auto &solver = context.summary.solver;
      context.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                    << context.elapsed() << " s] solved with " << solver.method
                    << ": " << solver.iterations
                    << " iteration(s), relative residual " << std::scientific
                    << std::setprecision(2) << solver.relative_residual
                    << std::defaultfloat << note << std::endl;
    }


    template <int dim>
    void
    print_equilibrium(const SystemContext<dim> &context,
                      const std::string        &what)
    {
      context.pcout << "           equilibrium check (" << what
                    << "): |F_int + F_ext| / |F_int| = " << std::scientific
                    << std::setprecision(2)
                    << context.summary.equilibrium_residual << std::defaultfloat
                    << std::endl;
    }


    template void
    print_solve(const SystemContext<2> &, const std::string &);
    template void
    print_solve(const SystemContext<3> &, const std::string &);
    template void
    print_equilibrium(const SystemContext<2> &, const std::string &);
    template void
    print_equilibrium(const SystemContext<3> &, const std::string &);
  } // namespace Boundary
} // namespace PeriDEAL
