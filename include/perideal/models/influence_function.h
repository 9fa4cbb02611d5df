#ifndef perideal_models_influence_function_h
#define perideal_models_influence_function_h

#include <perideal/base/plugin_registry.h>

#include <string>

namespace PeriDEAL
{
  /**
   * Peridynamic material models and influence functions.
   */
  namespace Models
  {
    using namespace dealii;

    /**
     * A spherical influence function \f$\underline\omega\langle\xi\rangle =
     * \omega(|\xi|/\delta)\f$ that weighs bonds by their length relative to
     * the horizon. Registered classes: "gaussian"
     * \f$e^{-r^2/\delta^2}\f$ (Scabbia et al. 2022, Eq. 10), "constant"
     * \f$1\f$, "conical" \f$1 - r/\delta\f$ and "inverse distance"
     * \f$\delta/r\f$ (the influence function of LAMMPS's `peri/lps`).
     *
     * value() is called from several threads at once (the operator's
     * set-up is threaded): an implementation must not change state.
     */
    class InfluenceFunction
    {
    public:
      virtual ~InfluenceFunction() = default;

      /// \f$\omega\f$ at the scaled bond length @p s = |xi|/delta in [0, 1].
      virtual double
      value(const double s) const = 0;

      /**
       * \f$\int_0^1 \omega(s)\, s^k\, ds\f$, the moments that calibrate
       * material constants (Gauss quadrature, exact for the registered
       * functions to round-off). A function that is singular at s = 0
       * overrides it and throws for the orders whose integral diverges.
       */
      virtual double
      moment(const unsigned int k) const;

      /// No parameters by default.
      virtual void
      parse_parameters(ParameterHandler &prm);

      static std::string
      family_name();
    };

    using InfluenceFunctionRegistry = PluginRegistry<InfluenceFunction>;
  } // namespace Models

  extern template class PluginRegistry<Models::InfluenceFunction>;
} // namespace PeriDEAL

/**
 * Register the influence function @p Class (derived from
 * PeriDEAL::Models::InfluenceFunction) under @p name; it can then be chosen
 * as the "Influence function" of the isotropic material models.
 */
#define PERIDEAL_REGISTER_INFLUENCE_FUNCTION(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::InfluenceFunction,       \
                          Class,                                       \
                          name,                                        \
                          description)

#endif
