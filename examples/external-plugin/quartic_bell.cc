// A user's own influence function, compiled into a shared library outside
// PeriDEAL's source tree and loaded by the perideal driver at run time
// through the parameter file:
//
//   set Additional shared libraries = ./libquartic_bell.so
//
// The registration below runs when the library is loaded, before perideal
// declares its parameters: "quartic bell" then appears among the allowed
// values of every model's "Influence function" entry, like the built-in
// "constant", "conical" and "gaussian".

#include <deal.II/base/parameter_handler.h>

#include <perideal/models/influence_function.h>

namespace MyPlugins
{
  /**
   * The quartic bell \f$\omega(s) = (1 - s^2)^2\f$, \f$s = |\xi|/\delta\f$:
   * smooth at the horizon (it and its slope vanish there), so bonds fade
   * out instead of being cut off.
   */
  class QuarticBell : public PeriDEAL::Models::InfluenceFunction
  {
  public:
    /// omega at the scaled bond length s in [0, 1]; dimensionless.
    double
    value(const double s) const override
    {
      const double t = 1 - s * s;
      return t * t;
    }

    // moment(k), the integral of omega(s) s^k over [0, 1] that calibrates
    // the bond-based micromodulus and the critical stretch, is inherited:
    // PeriDEAL integrates value() by 30-point Gauss quadrature, exact for
    // this polynomial.

    /// No parameters; the registry calls this when it declares them.
    static void
    declare_parameters(dealii::ParameterHandler &)
    {}
  };
} // namespace MyPlugins

PERIDEAL_REGISTER_INFLUENCE_FUNCTION(MyPlugins::QuarticBell,
                                     "quartic bell",
                                     "(1 - |xi|^2 / delta^2)^2 within the "
                                     "horizon (examples/external-plugin)")
