#ifndef perideal_discretization_neighbor_list_h
#define perideal_discretization_neighbor_list_h

#include <deal.II/base/array_view.h>

#include <perideal/discretization/node_set.h>
#include <perideal/quadrature/partial_volume.h>

#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    /**
     * A bond from a node to one of its neighbours.
     */
    struct Bond
    {
      /// Local index (in the NodeSet) of the neighbour.
      unsigned int neighbor;

      /**
       * Quadrature weight of the neighbour in the node's horizon integral:
       * \f$\beta_{ij} V_j\f$, with \f$\beta_{ij}\f$ from the partial-volume
       * algorithm and \f$V_j\f$ the neighbour's cell measure.
       */
      double weight;
    };

    /**
     * The neighbours of PD nodes and their quadrature weights, in
     * compressed-row storage.
     *
     * Lists are built for the owned nodes and, when requested, for every
     * off-process node that is a neighbour of an owned node (state-based
     * models need the weighted volume and dilatation of those). The search
     * uses a bucket grid of bucket size about the horizon: O(N) work for N
     * nodes.
     *
     * On a uniform grid (all cells cubes of one side h, centres on a common
     * lattice) the coefficients come from a UniformGridWeights table computed
     * once for the m-ratio; otherwise each candidate cell is passed to the
     * algorithm as a general box.
     */
    template <int dim>
    class NeighborList
    {
    public:
      /**
       * Build the lists.
       *
       * @param[in] nodes The node set; it must hold every off-process node
       *   within the required range (horizon for owned lists only, twice the
       *   horizon plus two cell diameters with @p with_ghost_lists).
       * @param[in] horizon The horizon \f$\delta\f$ (same for all nodes).
       * @param[in] algorithm The partial-volume algorithm.
       * @param[in] with_ghost_lists Also build lists for off-process
       *   neighbours of owned nodes.
       */
      void
      reinit(const NodeSet<dim>                   &nodes,
             const double                          horizon,
             const Quadrature::PartialVolume<dim> &algorithm,
             const bool                            with_ghost_lists);

      /// Whether node @p i has a list.
      bool
      has_list(const unsigned int i) const;

      /// The bonds of node @p i (node i itself excluded).
      ArrayView<const Bond>
      bonds(const unsigned int i) const;

      /// Total number of bonds of owned nodes.
      std::size_t
      n_owned_bonds() const;

      /// Whether the uniform-grid table was used.
      bool
      used_uniform_grid_table() const;

    private:
      std::vector<std::size_t> offsets; // size n_nodes + 1
      std::vector<Bond>        all_bonds;
      std::vector<bool>        listed;
      std::size_t              owned_bonds = 0;
      bool                     uniform     = false;
    };
  } // namespace Discretization
} // namespace PeriDEAL

#endif
