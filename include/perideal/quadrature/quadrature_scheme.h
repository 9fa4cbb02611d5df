#ifndef perideal_quadrature_quadrature_scheme_h
#define perideal_quadrature_quadrature_scheme_h

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/plugin_registry.h>

#include <string>

namespace PeriDEAL
{
  namespace Quadrature
  {
    using namespace dealii;

    /**
     * What the collocation quadrature of a node needs from the input
     * ('Quadrature/collocation'): the order of the fit, the requested
     * number of collocation nodes and what to do with an ill-conditioned
     * cloud (doc/collocation.md Sects. 2 and 7).
     */
    struct CollocationSettings
    {
      /// The order k of the fit: 2, 4 or (1D) 6.
      unsigned int order = 2;
      /// The requested number n_c of collocation nodes (0: the default of
      /// the order and dimension, default_collocation_nodes()).
      unsigned int n_collocation = 0;
      /// Whether an ill-conditioned cloud falls back to the standard
      /// scheme (true) or stops the run (false).
      bool fall_back = true;
      /// The largest cond_2(A_i) accepted (doc/collocation.md Sect. 7: the
      /// fit then loses at most about sqrt(1e12) eps ~ 1e-10 of its
      /// reproduction accuracy).
      static constexpr double condition_limit = 1e12;
    };


    /**
     * The quadrature scheme of the nonlocal operators ('Quadrature/Scheme'):
     * which nodes are evaluated with the standard partial-volume quadrature
     * (the weights of 'Partial volumes/Algorithm') and which with the WLS
     * collocation of the hybrid-collocation paper (Sect. 3;
     * doc/collocation.md). Schemes register themselves with
     * PERIDEAL_REGISTER_QUADRATURE_SCHEME and keep their entries in the
     * subsection of 'Quadrature' named after them.
     */
    template <int dim>
    class QuadratureScheme
    {
    public:
      virtual ~QuadratureScheme() = default;

      /// Read the scheme's entries from its own subsection.
      virtual void
      parse_parameters(ParameterHandler &prm);

      /**
       * The collocation settings where the scheme evaluates nodes by
       * collocation; null where every node is standard (the default).
       */
      virtual const CollocationSettings *
      collocation() const;

      /// What the registry calls this family in error messages.
      static std::string
      family_name();
    };

    /// The registry of quadrature schemes of dimension @p dim.
    template <int dim>
    using QuadratureSchemeRegistry = PluginRegistry<QuadratureScheme<dim>>;
  } // namespace Quadrature

  extern template class PluginRegistry<Quadrature::QuadratureScheme<1>>;
  extern template class PluginRegistry<Quadrature::QuadratureScheme<2>>;
  extern template class PluginRegistry<Quadrature::QuadratureScheme<3>>;
} // namespace PeriDEAL

/**
 * Register the quadrature scheme @p Class (a template over dim) for
 * dimension @p dim under @p name.
 */
#define PERIDEAL_REGISTER_QUADRATURE_SCHEME(Class, dim, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Quadrature::QuadratureScheme<dim>,   \
                          Class<dim>,                                      \
                          name,                                            \
                          description)

#endif
