#ifndef perideal_quadrature_partial_volume_h
#define perideal_quadrature_partial_volume_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <perideal/base/plugin_registry.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  /**
   * Quadrature weights of peridynamic nodes: partial areas and volumes.
   */
  namespace Quadrature
  {
    using namespace dealii;

    /**
     * The interface of a partial-volume algorithm: how much of a neighbour's
     * cell a node's horizon ball (a disc in 2D) takes into account.
     *
     * A PD node \f$i\f$ sits at a point \f$\mathbf x_i\f$ with horizon
     * \f$\delta\f$; a neighbour \f$j\f$ owns an axis-aligned cell
     * \f$C_j\f$. The quadrature coefficient is
     * \f[
     *   \beta_{ij} = \frac{|B(\mathbf x_i,\delta) \cap C_j|}{|C_j|}
     *   \in [0, 1],
     * \f]
     * computed exactly or approximately depending on the algorithm
     * (Scabbia, Zaccariotto, Galvanetto 2022, "Accurate computation of
     * partial volumes in 3D peridynamics", Eq. 21). The weight of the
     * neighbour in a nodal sum is \f$\beta_{ij} |C_j|\f$.
     *
     * Implementations register themselves with
     * PERIDEAL_REGISTER_PARTIAL_VOLUME and are created by name through
     * PartialVolumeRegistry.
     */
    template <int dim>
    class PartialVolume
    {
    public:
      virtual ~PartialVolume() = default;

      /**
       * The coefficient \f$\beta\f$ of @p cell for a node at @p node with
       * horizon @p horizon (same length unit as the points), for general
       * cells: any position, any side lengths.
       */
      virtual double
      weight(const Point<dim>       &node,
             const double            horizon,
             const BoundingBox<dim> &cell) const = 0;

      /**
       * The coefficient \f$\beta\f$ on a uniform grid in scaled units (grid
       * spacing 1, node at the origin): the neighbour's unit cell is centred
       * at the integer @p offset and the horizon is the m-ratio
       * \f$\bar m = \delta/h\f$. The default implementation calls weight();
       * algorithms defined only on uniform grids override it.
       */
      virtual double
      uniform_grid_weight(const std::array<int, dim> &offset,
                          const double                m_ratio) const;

      /**
       * uniform_grid_weight() for many offsets at once: the coefficients of
       * the cells centred at @p offsets, in that order. The default
       * implementation calls uniform_grid_weight() for each; algorithms that
       * can share work between neighbouring cells override it.
       */
      virtual std::vector<double>
      uniform_grid_weights(const std::vector<std::array<int, dim>> &offsets,
                           const double m_ratio) const;

      /**
       * Read this algorithm's parameters from the subsection it declared.
       * The default implementation reads nothing.
       */
      virtual void
      parse_parameters(ParameterHandler &prm);

      /// What the registry calls this family in error messages.
      static std::string
      family_name();
    };

    /**
     * The registry of partial-volume algorithms for dimension @p dim.
     */
    template <int dim>
    using PartialVolumeRegistry = PluginRegistry<PartialVolume<dim>>;

    /**
     * The unit cell \f$[\mathbf o - \tfrac12, \mathbf o + \tfrac12]^{dim}\f$
     * centred at the integer @p offset.
     */
    template <int dim>
    BoundingBox<dim>
    unit_cell(const std::array<int, dim> &offset);
  } // namespace Quadrature
} // namespace PeriDEAL

namespace PeriDEAL
{
  extern template class PluginRegistry<Quadrature::PartialVolume<1>>;
  extern template class PluginRegistry<Quadrature::PartialVolume<2>>;
  extern template class PluginRegistry<Quadrature::PartialVolume<3>>;
} // namespace PeriDEAL

/**
 * Register the partial-volume algorithm @p Class (a template over dim) for
 * dimension @p dim under @p name.
 */
#define PERIDEAL_REGISTER_PARTIAL_VOLUME(Class, dim, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Quadrature::PartialVolume<dim>,   \
                          Class<dim>,                                   \
                          name,                                         \
                          description)

#endif
