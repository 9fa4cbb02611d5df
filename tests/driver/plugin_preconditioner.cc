// A preconditioner in a library of its own, loaded through 'Additional
// shared libraries' (shared_libraries.sh): point Jacobi scaled by a factor
// read from its own subsection, 'Linear solver/test scaled jacobi/Scale'.
// CG is invariant under a positive scaling of the preconditioner, so it must
// take the iterations of the built-in 'Jacobi' and reach the same solution.

#include <perideal/base/exceptions.h>
#include <perideal/solvers/preconditioner.h>

namespace
{
  using namespace dealii;
  using PeriDEAL::Solvers::OperatorForm;
  using PeriDEAL::Solvers::PreconditionerSetup;

  class ScaledJacobi : public PeriDEAL::Solvers::Preconditioner
  {
  public:
    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Scale",
                        "1",
                        Patterns::Double(),
                        "The factor s of P^{-1} = s D^{-1}; > 0.");
    }

    void
    parse_parameters(ParameterHandler &prm) override
    {
      scale = prm.get_double("Scale");
      AssertThrow(
        scale > 0,
        PeriDEAL::ExcInvalidInput("Linear solver/test scaled jacobi/Scale",
                                  prm.get("Scale"),
                                  "give a factor > 0"));
    }

    bool
    supports(const OperatorForm form) const override
    {
      return form == OperatorForm::matrix_free;
    }

    void
    initialize(const OperatorForm, const PreconditionerSetup &setup) override
    {
      inverse_diagonal = *setup.inverse_diagonal;
      inverse_diagonal *= scale;
    }

    void
    vmult(VectorType &dst, const VectorType &src) const override
    {
      dst = src;
      dst.scale(inverse_diagonal);
    }

    void
    clear() override
    {
      inverse_diagonal.reinit(0);
    }

  private:
    double     scale = 1;
    VectorType inverse_diagonal;
  };
} // namespace

PERIDEAL_REGISTER_PRECONDITIONER(ScaledJacobi,
                                 "test scaled jacobi",
                                 "Point Jacobi times 'Scale' (a test plugin).")
