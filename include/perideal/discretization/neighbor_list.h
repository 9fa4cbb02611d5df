#ifndef perideal_discretization_neighbor_list_h
#define perideal_discretization_neighbor_list_h

#include <deal.II/base/array_view.h>

#include <perideal/discretization/lattice.h>
#include <perideal/discretization/node_set.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <array>
#include <cmath>
#include <cstdint>
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
     * On a uniform grid (Lattice::is_uniform()) the coefficients come from
     * a UniformGridWeights table computed once for the m-ratio; otherwise
     * each candidate cell is passed to the algorithm as a general box.
     *
     * On a uniform grid a node whose neighbourhood holds every offset of
     * the table (stencil()) has a *full stencil*; its list is then the
     * stencil itself, in the stencil's order, and need not be stored
     * (reinit() with @p store_full_lists = false): the bulk of a uniform
     * grid costs no per-bond memory.
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
       * @param[in] store_full_lists Store the lists of nodes with a full
       *   stencil too (false: only their stencil flag).
       */
      void
      reinit(const NodeSet<dim>                   &nodes,
             const double                          horizon,
             const Quadrature::PartialVolume<dim> &algorithm,
             const bool                            with_ghost_lists,
             const bool                            store_full_lists = true);

      /// Whether node @p i has a list (stored, or its full stencil).
      bool
      has_list(const unsigned int i) const;

      /// Whether node @p i has the full stencil as its neighbourhood.
      bool
      has_full_stencil(const unsigned int i) const;

      /// Whether the list of node @p i is stored (bonds() may be called).
      bool
      has_stored_list(const unsigned int i) const;

      /// Number of bonds of node @p i (stored or stencil).
      unsigned int
      n_bonds(const unsigned int i) const;

      /**
       * The stored bonds of node @p i (node i itself excluded), in the
       * order of the neighbours' first DoF. (A node with a full stencil
       * enumerates its bonds in the stencil's order wherever bonds are
       * numbered, e.g. in BondState.)
       */
      ArrayView<const Bond>
      bonds(const unsigned int i) const;

      /**
       * Call f(k, j, w) for every bond of node @p i, in the order bonds are
       * numbered (BondState): its index k, the neighbour j and the weight
       * w = beta V_j. A node with a full stencil enumerates the stencil
       * (needs its lattice neighbours in the node set), any other node its
       * stored list. Not for hot loops (a lattice lookup per bond).
       */
      template <typename Function>
      void
      for_each_bond(const unsigned int i, const Function &f) const;

      /**
       * On a uniform grid: every lattice offset with a non-zero
       * coefficient, in lexicographic order (empty otherwise).
       */
      const std::vector<Quadrature::WeightedOffset<dim>> &
      stencil() const;

      /**
       * On a uniform grid: the index in stencil() of the lattice offset
       * from node @p i to node @p j, or -1 when that offset is not in the
       * stencil (a dense table, built once; not for hot loops).
       */
      int
      stencil_index(const unsigned int i, const unsigned int j) const;

      /// The lattice of the node set (uniformity decided here, once).
      const Lattice<dim> &
      lattice() const;

      /// Total number of bonds of owned nodes.
      std::size_t
      n_owned_bonds() const;

      /// Whether the uniform-grid table was used.
      bool
      used_uniform_grid_table() const;

    private:
      std::vector<std::size_t> offsets; // size n_nodes + 1
      std::vector<Bond>        all_bonds;
      /// Per node, as bytes (the threads of reinit() set them side by
      /// side, which std::vector<bool> forbids).
      std::vector<std::uint8_t>                    listed;
      std::vector<std::uint8_t>                    full;
      std::vector<std::uint8_t>                    stored;
      std::size_t                                  owned_bonds = 0;
      bool                                         uniform     = false;
      Lattice<dim>                                 grid;
      std::vector<Quadrature::WeightedOffset<dim>> full_stencil;
      std::vector<int>                             offset_to_stencil;
      int                                          stencil_bound = 0;
    };


    template <int dim>
    template <typename Function>
    void
    NeighborList<dim>::for_each_bond(const unsigned int i,
                                     const Function    &f) const
    {
      if (has_full_stencil(i))
        {
          const double volume = std::pow(grid.spacing(), dim);
          const auto  &x      = grid.coordinates(i);
          for (unsigned int k = 0; k < full_stencil.size(); ++k)
            {
              std::array<std::int64_t, dim> y = x;
              for (unsigned int d = 0; d < dim; ++d)
                y[d] += full_stencil[k].offset[d];
              f(k,
                static_cast<unsigned int>(grid.node_at(y)),
                full_stencil[k].beta * volume);
            }
        }
      else
        {
          const auto list = bonds(i);
          for (unsigned int k = 0; k < list.size(); ++k)
            f(k, list[k].neighbor, list[k].weight);
        }
    }
  } // namespace Discretization
} // namespace PeriDEAL

#endif
