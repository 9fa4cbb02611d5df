#ifndef perideal_solvers_krylov_h
#define perideal_solvers_krylov_h

#include <deal.II/lac/solver_bicgstab.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>

#include <string>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /// The linear-solver methods of 'Linear solver/Method', parsed once.
    enum class Method
    {
      direct,
      cg,
      gmres,
      bicgstab
    };

    /// The value of @p name ('direct', 'CG', 'GMRES', 'BiCGStab'), as
    /// accepted by the entry's pattern.
    Method
    method_from_name(const std::string &name);

    /// The name of @p method, as written in the input file.
    std::string
    name_of(const Method method);

    /**
     * Run deal.II's Krylov @p method (CG, GMRES or BiCGStab) on @p op with
     * @p precondition: the one Krylov dispatch of the matrix-free solves
     * (PD operator, layer systems, diffusion). @p gmres_data sets the
     * restart length and the side of the preconditioning; right
     * preconditioning makes GMRES's stopping test see the true residual.
     */
    template <typename VectorType,
              typename OperatorType,
              typename PreconditionerType>
    void
    run_krylov(
      const Method                                            method,
      const typename SolverGMRES<VectorType>::AdditionalData &gmres_data,
      SolverControl                                          &control,
      const OperatorType                                     &op,
      VectorType                                             &x,
      const VectorType                                       &b,
      const PreconditionerType                               &precondition)
    {
      switch (method)
        {
          case Method::cg:
            SolverCG<VectorType>(control).solve(op, x, b, precondition);
            break;
          case Method::gmres:
            SolverGMRES<VectorType>(control, gmres_data)
              .solve(op, x, b, precondition);
            break;
          case Method::bicgstab:
            SolverBicgstab<VectorType>(control).solve(op, x, b, precondition);
            break;
          case Method::direct:
            Assert(false, ExcInternalError());
        }
    }
  } // namespace Solvers
} // namespace PeriDEAL

#endif
