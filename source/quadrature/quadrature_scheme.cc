/**
 * @file
 * The quadrature schemes 'standard' (every node with the partial-volume
 * weights) and 'collocation' (every node whose neighbourhood is a full
 * ball by WLS collocation, doc/collocation.md), and their registry.
 */

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/collocation.h>
#include <perideal/quadrature/quadrature_scheme.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    void
    QuadratureScheme<dim>::parse_parameters(ParameterHandler &)
    {}


    template <int dim>
    const CollocationSettings *
    QuadratureScheme<dim>::collocation() const
    {
      return nullptr;
    }


    template <int dim>
    std::string
    QuadratureScheme<dim>::family_name()
    {
      return "quadrature scheme (" + std::to_string(dim) + "D)";
    }


    namespace
    {
      /// Every node with the partial-volume weights (today's behaviour).
      template <int dim>
      class StandardScheme : public QuadratureScheme<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}
      };


      /**
       * Every node whose neighbourhood is a full ball inside the body and
       * its layers by WLS collocation; the other nodes (a ball cut by the
       * surface) keep the standard scheme, since the moments of a cut ball
       * have no closed form (doc/collocation.md Sect. 10).
       */
      template <int dim>
      class CollocationScheme : public QuadratureScheme<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm)
        {
          prm.declare_entry(
            "Order",
            "2",
            Patterns::Integer(2, 6),
            "Order k of the WLS fit: 2 or 4 (and 6 in 1D). A node's row "
            "applies the PD operator exactly to every field of degree k "
            "(doc/collocation.md).");
          prm.declare_entry(
            "Collocation nodes",
            "0",
            Patterns::Integer(0),
            "Requested number n_c of collocation nodes per node; honoured "
            "through the auxiliary grid whose size is closest (Remark 2 of "
            "the hybrid-collocation paper). 0: the default of the order and "
            "dimension (1D 5/11/13, 2D 29/49, 3D 33/123). At least the "
            "number of monomials of the order.");
          prm.declare_entry(
            "Ill-conditioned clouds",
            "fall back",
            Patterns::Selection("fall back|error"),
            "What a node does whose moment matrix has a condition number "
            "above 1e12: 'fall back' to the standard scheme (counted and "
            "reported) or stop the run ('error').");
        }

        void
        parse_parameters(ParameterHandler &prm) override
        {
          const std::string path = "Quadrature/collocation/";
          settings.order         = prm.get_integer("Order");
          AssertThrow(offers_order(dim, settings.order),
                      ExcInvalidInput(path + "Order",
                                      prm.get("Order"),
                                      std::string("the collocation scheme "
                                                  "offers the orders ") +
                                        (dim == 1 ? "2, 4 and 6" : "2 and 4") +
                                        " in " + std::to_string(dim) +
                                        "D; choose one of them"));
          settings.n_collocation = prm.get_integer("Collocation nodes");
          const unsigned int n_p = n_monomials(dim, settings.order);
          AssertThrow(
            settings.n_collocation == 0 || settings.n_collocation >= n_p,
            ExcInvalidInput(
              path + "Collocation nodes",
              prm.get("Collocation nodes"),
              "a fit of order " + std::to_string(settings.order) + " in " +
                std::to_string(dim) + "D has " + std::to_string(n_p) +
                " monomials and needs at least that many "
                "collocation nodes; give at least " +
                std::to_string(n_p) + ", or 0 for the default (" +
                std::to_string(default_collocation_nodes(dim, settings.order)) +
                ")"));
          settings.fall_back = prm.get("Ill-conditioned clouds") == "fall back";
        }

        const CollocationSettings *
        collocation() const override
        {
          return &settings;
        }

      private:
        CollocationSettings settings;
      };
    } // namespace

    template class QuadratureScheme<1>;
    template class QuadratureScheme<2>;
    template class QuadratureScheme<3>;
  } // namespace Quadrature

  template class PluginRegistry<Quadrature::QuadratureScheme<1>>;
  template class PluginRegistry<Quadrature::QuadratureScheme<2>>;
  template class PluginRegistry<Quadrature::QuadratureScheme<3>>;
} // namespace PeriDEAL

#define PERIDEAL_REGISTER_SCHEMES(dim)                                       \
  PERIDEAL_REGISTER_QUADRATURE_SCHEME(                                       \
    PeriDEAL::Quadrature::StandardScheme,                                    \
    dim,                                                                     \
    "standard",                                                              \
    "Every node with the partial-volume weights of 'Partial "                \
    "volumes/Algorithm'.")                                                   \
  PERIDEAL_REGISTER_QUADRATURE_SCHEME(                                       \
    PeriDEAL::Quadrature::CollocationScheme,                                 \
    dim,                                                                     \
    "collocation",                                                           \
    "Every node whose neighbourhood is a full ball inside the body and its " \
    "layers by the WLS collocation of the hybrid-collocation paper; the "    \
    "others standard.")
PERIDEAL_REGISTER_SCHEMES(1)
PERIDEAL_REGISTER_SCHEMES(2)
PERIDEAL_REGISTER_SCHEMES(3)
#undef PERIDEAL_REGISTER_SCHEMES
