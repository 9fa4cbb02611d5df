#ifndef perideal_operators_loop_layout_h
#define perideal_operators_loop_layout_h

#include <perideal/discretization/neighbor_list.h>

#include <cstddef>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    /**
     * The loop layout that the matrix-free operators share (BondOperator,
     * DiffusionOperator): how nodes are placed in slot arrays and how the
     * loops over them are cut into pieces for the threads. One place for
     * the choices, so that every operator on the same node set makes the
     * same ones.
     */
    namespace LoopLayout
    {
      /// Lanes of one vectorised chunk: runs of nodes with the shared
      /// stencil are cut into chunks of at most this many consecutive slots.
      constexpr unsigned int chunk_size = 64;
      /// Chunks per task in parallel::apply_to_subranges().
      constexpr unsigned int chunk_grain = 4;
      /// Nodes per task in the loops over single nodes.
      constexpr unsigned int node_grain = 256;

      /**
       * Chooses the slots of the @p n_nodes local nodes (owned and ghost)
       * of @p lists: the lattice's dense box on a uniform grid with a
       * shared stencil, unless that box is much larger than the node set
       * (a scattered partition: more than 8 n + 4096 slots); node indices
       * otherwise. Sets @p use_lattice, @p n_slots and @p slot (node i sits
       * in slot[i]).
       */
      template <int dim>
      void
      choose_slots(const Discretization::NeighborList<dim> &lists,
                   const unsigned int                       n_nodes,
                   bool                                    &use_lattice,
                   std::size_t                             &n_slots,
                   std::vector<std::size_t>                &slot)
      {
        const auto &lattice = lists.lattice();
        use_lattice =
          lattice.is_uniform() && !lists.stencil().empty() &&
          lattice.n_slots() <= 8 * static_cast<std::size_t>(n_nodes) + 4096;
        n_slots = use_lattice ? lattice.n_slots() : n_nodes;
        slot.resize(n_nodes);
        for (unsigned int i = 0; i < n_nodes; ++i)
          slot[i] = use_lattice ? lattice.slot(i) : i;
      }
    } // namespace LoopLayout
  }   // namespace Operators
} // namespace PeriDEAL

#endif
