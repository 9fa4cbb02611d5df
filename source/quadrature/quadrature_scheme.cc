/**
 * @file
 * The quadrature schemes 'standard' (every node with the partial-volume
 * weights) and 'collocation' (every node whose neighbourhood is a full
 * ball by WLS collocation, doc/collocation.md), and their registry.
 */

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/discretization/crack_geometry.h>
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
    const HybridSettings<dim> *
    QuadratureScheme<dim>::hybrid() const
    {
      return nullptr;
    }


    template <int dim>
    std::vector<std::pair<std::string, std::string>>
    QuadratureScheme<dim>::unused_entries() const
    {
      return {};
    }


    template <int dim>
    std::string
    QuadratureScheme<dim>::family_name()
    {
      return "quadrature scheme (" + std::to_string(dim) + "D)";
    }


    namespace
    {
      /// The entries of the subsection 'collocation' (also read by the
      /// hybrid scheme).
      void
      declare_collocation_parameters(ParameterHandler &prm)
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
          "above 1e12 (or, with a row per node, whose stabilised row has a "
          "non-positive diagonal): 'fall back' to the standard scheme "
          "(counted and reported; with a row per node and 'Order = 4' the "
          "node first tries an order-2 row, also counted) or stop the run "
          "('error').");
        prm.declare_entry(
          "Stabilisation",
          "automatic",
          Patterns::Selection("automatic|all orders|none"),
          "'automatic': the order-4 rows, which as the paper gives them have "
          "growing modes (no explicit time stepping, an indefinite static "
          "operator), are fitted with the weight radius 1.5 delta and carry "
          "the consistent stabilisation term gamma T, gamma = 1.25, which "
          "vanishes on every quartic, so the rows stay exact "
          "(doc/collocation.md Sect. 7.1); so are the order-2 rows of "
          "perturbed nodes ('Geometry/Node perturbation', a row per node), "
          "which otherwise have node-local growing modes (Sect. 7.2). The "
          "order-2 row of a uniform grid and order 6 are stable as the paper "
          "gives them and stay unchanged. 'all orders': the order-2 row of a "
          "uniform grid (2D, 3D) is stabilised too; its largest eigenvalue "
          "is up to 4 times smaller, so explicit time steps are up to twice "
          "as long (the choice for explicit dynamics), and it is 1.3-18 times "
          "closer to the PD solution, though 3-4 times farther from the "
          "classical one, whose difference the paper's row partly cancels "
          "(Sect. 7.3; not in 1D, where it has growing modes). "
          "'none': the paper's rows for every order. The state-based (LPS) "
          "rows are not stabilised yet.");
      }


      /// Read them (@p prm in 'Quadrature/collocation') into @p settings,
      /// refusing an order that @p dim does not offer and too few nodes.
      template <int dim>
      void
      parse_collocation_parameters(ParameterHandler    &prm,
                                   CollocationSettings &settings)
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
        const std::string stabilisation = prm.get("Stabilisation");
        settings.stabilisation_mode =
          stabilisation == "none" ?
            CollocationSettings::Stabilisation::none :
            (stabilisation == "all orders" ?
               CollocationSettings::Stabilisation::all_orders :
               CollocationSettings::Stabilisation::automatic);
        AssertThrow(dim > 1 || settings.stabilisation_mode !=
                                 CollocationSettings::Stabilisation::all_orders,
                    ExcInvalidInput(path + "Stabilisation",
                                    stabilisation,
                                    "in 1D the stabilised order-2 row has "
                                    "growing modes (doc/collocation.md "
                                    "Sect. 7.3); use 'automatic'"));
      }


      /// Entries of 'Quadrature/collocation' that @p settings leave
      /// without effect.
      std::vector<std::pair<std::string, std::string>>
      collocation_unused_entries(const CollocationSettings &settings)
      {
        if (settings.order <= 4)
          return {};
        return {{"Quadrature/collocation/Stabilisation",
                 "order 6 is stable as the paper gives it and is not "
                 "stabilised; remove the entry"}};
      }


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
          declare_collocation_parameters(prm);
        }

        void
        parse_parameters(ParameterHandler &prm) override
        {
          parse_collocation_parameters<dim>(prm, settings);
        }

        const CollocationSettings *
        collocation() const override
        {
          return &settings;
        }

        std::vector<std::pair<std::string, std::string>>
        unused_entries() const override
        {
          return collocation_unused_entries(settings);
        }

      private:
        CollocationSettings settings;
      };


      /**
       * The hybrid scheme (hybrid-collocation paper Sect. 4, Eq. 65):
       * collocation (the rows of the subsection 'collocation') except in the
       * standard region: the nodes whose ball is cut by the surface, those
       * in 'Standard boxes' or near 'Standard boundary ids', those next to
       * a pre-crack, and (adaptive) those that a bond nearing failure has
       * switched.
       */
      template <int dim>
      class HybridScheme : public QuadratureScheme<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm)
        {
          prm.declare_entry(
            "Configuration",
            "adaptive",
            Patterns::Selection("fixed|adaptive"),
            "'adaptive': a collocation node becomes standard for good at the "
            "end of the step in which one of its bonds reaches 'Critical "
            "stretch fraction' times its critical stretch (Eq. 65 of the "
            "hybrid-collocation paper); 'fixed': the standard region is the "
            "one given, and a bond of a collocation node that reaches its "
            "critical stretch stops the run (the crack left the region).");
          prm.declare_entry(
            "Standard boxes",
            "",
            Patterns::Anything(),
            "Boxes 'x0, y0[, z0], x1, y1[, z1]' separated by ';' whose nodes "
            "use the standard scheme from the start (where a crack is "
            "expected). Nodes whose ball is cut by the surface and nodes "
            "with a bond cut by a pre-crack are standard anyway.");
          prm.declare_entry(
            "Standard boundary ids",
            "",
            Patterns::List(Patterns::Integer(0, 254)),
            "Nodes closer than 'Standard layer thickness' to a boundary face "
            "with one of these ids use the standard scheme from the start.");
          prm.declare_entry("Standard layer thickness",
                            "1",
                            Patterns::Double(0),
                            "The thickness of the standard layers along "
                            "'Standard boundary ids', in horizons.");
          prm.declare_entry(
            "Critical stretch fraction",
            "0.8",
            Patterns::Double(),
            "alpha of Eq. 65, in (0, 1): with 'Configuration = adaptive', a "
            "bond at alpha times its critical stretch or beyond makes both "
            "its nodes standard.");
          prm.declare_entry(
            "Critical bond detection",
            "displacement bound",
            Patterns::Selection("displacement bound|every step"),
            "When the bonds of the collocation nodes are scanned for Eq. 65: "
            "'displacement bound' only at the steps where the largest "
            "displacement since the last scan could have brought a bond to "
            "the threshold (a stretch changes by at most 2 max|du| / r_min; "
            "the same switches as 'every step', at a fraction of the cost), "
            "'every step' at each step.");
        }

        void
        parse_parameters(ParameterHandler &prm) override
        {
          prm.leave_subsection();
          prm.enter_subsection("collocation");
          parse_collocation_parameters<dim>(prm, collocation_settings);
          prm.leave_subsection();
          prm.enter_subsection("hybrid");
          const std::string path = "Quadrature/hybrid/";
          settings.adaptive      = prm.get("Configuration") == "adaptive";
          settings.boxes_text    = prm.get("Standard boxes");
          settings.boxes =
            Discretization::parse_boxes<dim>(settings.boxes_text,
                                             path + "Standard boxes");
          settings.boundary_ids_text = prm.get("Standard boundary ids");
          settings.boundary_ids =
            Boundary::parse_boundary_ids(settings.boundary_ids_text);
          settings.layer_thickness_text = prm.get("Standard layer thickness");
          settings.layer_thickness = prm.get_double("Standard layer thickness");
          AssertThrow(settings.boundary_ids.empty() ||
                        settings.layer_thickness > 0,
                      ExcInvalidInput(path + "Standard layer thickness",
                                      settings.layer_thickness_text,
                                      "give a thickness > 0 (in horizons), "
                                      "for instance 1"));
          settings.alpha = prm.get_double("Critical stretch fraction");
          AssertThrow(settings.alpha > 0 && settings.alpha < 1,
                      ExcInvalidInput(path + "Critical stretch fraction",
                                      prm.get("Critical stretch fraction"),
                                      "alpha of Eq. 65 lies strictly between "
                                      "0 and 1 (a bond switches its nodes to "
                                      "the standard scheme before it can "
                                      "break); give for instance 0.8"));
          settings.scan_every_step =
            prm.get("Critical bond detection") == "every step";
          unused_fixed = !settings.adaptive;
          unused_layer = settings.boundary_ids.empty();
        }

        const CollocationSettings *
        collocation() const override
        {
          return &collocation_settings;
        }

        const HybridSettings<dim> *
        hybrid() const override
        {
          return &settings;
        }

        std::vector<std::pair<std::string, std::string>>
        unused_entries() const override
        {
          std::vector<std::pair<std::string, std::string>> unused =
            collocation_unused_entries(collocation_settings);
          const std::string path = "Quadrature/hybrid/";
          if (unused_fixed)
            for (const char *entry :
                 {"Critical stretch fraction", "Critical bond detection"})
              unused.emplace_back(path + entry,
                                  "with 'Configuration = fixed' no node "
                                  "switches; set 'Configuration = adaptive', "
                                  "or remove the entry");
          if (unused_layer)
            unused.emplace_back(path + "Standard layer thickness",
                                "it is the thickness of the layers along "
                                "'Standard boundary ids', and none are "
                                "given; give them, or remove the entry");
          return unused;
        }

      private:
        CollocationSettings collocation_settings;
        HybridSettings<dim> settings;
        bool                unused_fixed = false, unused_layer = false;
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

#define PERIDEAL_REGISTER_SCHEMES(dim)                                        \
  PERIDEAL_REGISTER_QUADRATURE_SCHEME(                                        \
    PeriDEAL::Quadrature::StandardScheme,                                     \
    dim,                                                                      \
    "standard",                                                               \
    "Every node with the partial-volume weights of 'Partial "                 \
    "volumes/Algorithm'.")                                                    \
  PERIDEAL_REGISTER_QUADRATURE_SCHEME(                                        \
    PeriDEAL::Quadrature::CollocationScheme,                                  \
    dim,                                                                      \
    "collocation",                                                            \
    "Every node whose neighbourhood is a full ball inside the body and its "  \
    "layers by the WLS collocation of the hybrid-collocation paper; the "     \
    "others standard.")                                                       \
  PERIDEAL_REGISTER_QUADRATURE_SCHEME(                                        \
    PeriDEAL::Quadrature::HybridScheme,                                       \
    dim,                                                                      \
    "hybrid",                                                                 \
    "Collocation outside a standard region that is fixed (boxes, boundary "   \
    "layers, pre-cracks, cut balls) and, adaptively, grows where bonds near " \
    "failure (Eq. 65 of the hybrid-collocation paper).")
PERIDEAL_REGISTER_SCHEMES(1)
PERIDEAL_REGISTER_SCHEMES(2)
PERIDEAL_REGISTER_SCHEMES(3)
#undef PERIDEAL_REGISTER_SCHEMES
