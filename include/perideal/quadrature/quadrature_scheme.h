#ifndef perideal_quadrature_quadrature_scheme_h
#define perideal_quadrature_quadrature_scheme_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <perideal/base/plugin_registry.h>

#include <string>
#include <utility>
#include <vector>

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
      /// The two kinds of collocation rows: the one shared row of the
      /// uniform bulk ('lattice') and the rows fitted node by node where
      /// nodes are irregular ('per node').
      enum class RowKind
      {
        lattice,
        per_node
      };

      /// 'Quadrature/collocation/Stabilisation' (doc/collocation.md
      /// Sect. 7): 'automatic' stabilises the rows that need it (order 4,
      /// and the rows per node of order 2); 'all orders' also the order-2
      /// lattice row of 2D and 3D, which makes it more accurate and gives a
      /// longer explicit time step (Sect. 7.3); 'none' keeps the paper's
      /// rows.
      enum class Stabilisation
      {
        automatic,
        all_orders,
        none
      };
      Stabilisation stabilisation_mode = Stabilisation::automatic;

      /// Whether rows of @p kind are fitted with the wider weight and carry
      /// the stabilisation term (order 6 never is).
      bool
      stabilised(const RowKind kind) const
      {
        if (stabilisation_mode == Stabilisation::none || order > 4)
          return false;
        return order == 4 || kind == RowKind::per_node ||
               stabilisation_mode == Stabilisation::all_orders;
      }

      /// The weight radius of Eq. 36 over the horizon: 1.5 for stabilised
      /// rows, otherwise 1 (the paper's).
      double
      weight_radius_factor(const RowKind kind) const
      {
        return stabilised(kind) ? 1.5 : 1.;
      }

      /// The factor gamma of the stabilisation term
      /// (Quadrature::stabilisation_row()): 1.25 for stabilised rows,
      /// otherwise 0.
      double
      stabilisation(const RowKind kind) const
      {
        return stabilised(kind) ? 1.25 : 0.;
      }

      /// The text to add to an error about growing modes or an indefinite
      /// row when the user turned the stabilisation off.
      std::string
      stabilisation_hint() const
      {
        return stabilisation_mode == Stabilisation::none ?
                 ", or 'Stabilisation = automatic'" :
                 "";
      }
      /// The largest cond_2(A_i) accepted (doc/collocation.md Sect. 7: the
      /// fit then loses at most about sqrt(1e12) eps ~ 1e-10 of its
      /// reproduction accuracy).
      static constexpr double condition_limit = 1e12;
    };


    /**
     * The entries of `Quadrature/hybrid` (hybrid-collocation paper Sect. 4,
     * Eq. 65; doc/collocation.md Sect. 11): which nodes are standard from
     * the start (fixed regions), and whether bonds nearing failure make more
     * of them standard as the run goes (adaptive).
     */
    template <int dim>
    struct HybridSettings
    {
      /// 'Configuration = adaptive': nodes switch to the standard scheme
      /// when one of their bonds reaches the fraction alpha of its critical
      /// stretch; 'fixed': they never switch, and such a bond stops the run.
      bool adaptive = true;
      /// 'Standard boxes': nodes whose centre lies in one are standard.
      std::vector<BoundingBox<dim>> boxes;
      /// 'Standard boundary ids' and 'Standard layer thickness' (in
      /// horizons): nodes closer than that to one of these boundaries are
      /// standard.
      std::vector<types::boundary_id> boundary_ids;
      double                          layer_thickness = 1;
      /// alpha of Eq. 65, in (0, 1).
      double alpha = 0.8;
      /// 'Critical bond detection = every step': scan the bonds of every
      /// collocation node at every step, instead of only when the
      /// displacement bound says a bond may have reached alpha s0 (the two
      /// switch the same nodes at the same steps; the scan is the check).
      bool scan_every_step = false;
      /// The entries as given, for messages.
      std::string boxes_text, boundary_ids_text, layer_thickness_text;
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

      /// The settings of the hybrid scheme; nullptr for the others. A
      /// hybrid scheme also has collocation() (the rows of its collocation
      /// nodes, from the subsection 'collocation').
      virtual const HybridSettings<dim> *
      hybrid() const;

      /// Entries of the scheme's subsections that this input sets to no
      /// effect ('Critical stretch fraction' with 'Configuration = fixed',
      /// say), with the reason, for Simulator::check_unused_entries().
      virtual std::vector<std::pair<std::string, std::string>>
      unused_entries() const;

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
