#ifndef perideal_operators_loop_layout_h
#define perideal_operators_loop_layout_h

#include <deal.II/base/parallel.h>
#include <deal.II/base/partitioner.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * The loop layout that the matrix-free operators share (BondOperator,
     * DiffusionOperator): everything about their loops that is not physics,
     * built once here so that every operator on the same node set makes the
     * same choices.
     *
     * - The vector layout: a partitioner with the owned nodes' values and,
     *   as ghosts, those of every other node of the set, and the index of
     *   node i's first value in such a vector (vector_index).
     * - The slots: node i's values sit in slot[i] of the operators'
     *   structure-of-arrays scratch: its place in the lattice box
     *   (Discretization::Lattice) on a uniform grid with a shared stencil,
     *   its node index otherwise; the shared stencil's slot offsets.
     * - The work of each pass of an operator (Pass): runs of consecutive
     *   stencil slots (Chunk, vectorised over the slots with the offsets
     *   outside), the nodes with lists, their runs with a common set of
     *   stencil offsets (Run) and the rest (gathers).
     * - The list segments: the bonds of list node i are
     *   [list_first[i], list_end[i]) of an operator's bond array or, on the
     *   lattice, of list_stencil_index (the stencil index of each intact
     *   bond, in increasing stencil order).
     * - The broken bonds of full-stencil nodes as bit masks, one bit per
     *   (stencil offset, slot), per block of 64 slots.
     * - The threaded sweeps over chunks, runs and nodes, and the statistics.
     *
     * What a bond contributes (constants, kernels) stays in the operators:
     * they index their per-offset and per-bond constants by the stencil and
     * list indices this class gives. No loop of this class or of its sweeps
     * touches a map, a global index or the allocator per bond; the order of
     * every node's bonds is fixed by the bonds, never by the partition.
     */
    template <int dim>
    class LoopLayout
    {
    public:
      /// Lanes of one vectorised chunk: runs of nodes with the shared
      /// stencil are cut into chunks of at most this many consecutive slots.
      static constexpr unsigned int chunk_size = 64;
      /// Chunks per task in parallel::apply_to_subranges().
      static constexpr unsigned int chunk_grain = 4;
      /// Nodes per task in the loops over single nodes.
      static constexpr unsigned int node_grain = 256;

      /// Consecutive slots of nodes on the shared stencil.
      struct Chunk
      {
        std::size_t  first_slot;
        unsigned int length;
      };

      /**
       * A run of consecutive slots of nodes off the shared stencil (near
       * the surface) whose bonds were initially the same set of stencil
       * offsets, eligible_stencil_index[index_first, index_first +
       * n_index) in increasing order: evaluated like a Chunk, vectorised
       * over the slots, over those offsets only, with the bonds broken
       * since masked as in the full chunks, instead of one gather loop per
       * node. A node of a run sums its bonds in the same order whichever
       * node heads the run (the partition decides that), and stays in its
       * run as its bonds break.
       */
      struct Run
      {
        std::size_t  first_slot;
        unsigned int length;
        std::size_t  index_first;
        unsigned int n_index;
      };

      /**
       * Consecutive slots and the stencil offsets to visit for them
       * (index == nullptr: all of them); with broken bonds, the mask words
       * of the one or two blocks of 64 slots that they span (nullptr: none
       * broken there) and the first slot's place in its block.
       */
      struct Block
      {
        std::size_t          first_slot;
        unsigned int         length;
        const std::uint16_t *index;
        std::size_t          n_index;
        const std::uint64_t *mask_low  = nullptr;
        const std::uint64_t *mask_high = nullptr;
        unsigned int         shift     = 0;

        /// The broken bonds of offset @p k: bit l for the slot first_slot + l.
        std::uint64_t
        broken(const std::size_t k) const
        {
          return (mask_low != nullptr ? mask_low[k] >> shift : 0) |
                 (mask_high != nullptr ? mask_high[k] << (64 - shift) : 0);
        }

        /**
         * broken(k) (0 where the block has no mask), and where it is not 0
         * its bits as @p gone[l] = 0 or 1 for the block's lanes: a test the
         * lane loops vectorise, which a bit test is not.
         */
        std::uint64_t
        broken_lanes(const std::size_t k, double *gone) const
        {
          const bool masked = mask_low != nullptr || mask_high != nullptr;
          const std::uint64_t bits = masked ? broken(k) : 0;
          if (bits != 0)
            for (unsigned int l = 0; l < length; ++l)
              gone[l] = double((bits >> l) & 1);
          return bits;
        }
      };

      /**
       * The work of one pass of an operator over the nodes that need it
       * (BondOperator: the dilatations and the forces; DiffusionOperator:
       * its one pass).
       */
      struct Pass
      {
        /// The nodes on the shared stencil with every bond intact.
        std::vector<Chunk> chunks;
        /// Every node of the full stencil, broken bonds masked (the
        /// nonlinear passes).
        std::vector<Chunk> full_chunks;
        /// The other nodes, in increasing node index.
        std::vector<unsigned int> list_nodes;
        /// Of those, runs (Run) and the rest (gathers), for the nonlinear
        /// passes (make_runs()).
        std::vector<Run>          runs;
        std::vector<unsigned int> gather_nodes;

        /// Bytes held.
        std::size_t
        memory_consumption() const;
      };

      /**
       * Build the vector layout and the slots of the nodes of @p nodes,
       * the shared stencil's slot offsets and @p n_passes empty passes.
       * The vector holds the dim DoFs of each node (which must be numbered
       * consecutively), or with @p one_value_per_node one value per node
       * at global index dofs[0] / dim. @p user names the operator in error
       * messages. Collective. @p nodes, @p lists and @p bond_state (may be
       * null) must stay alive.
       */
      void
      reinit(const Discretization::NodeSet<dim>      &nodes,
             const Discretization::NeighborList<dim> &lists,
             const Discretization::BondState<dim>    *bond_state,
             const bool                               one_value_per_node,
             const unsigned int                       n_passes,
             const std::string                       &user);

      /**
       * On the lattice: look up the stencil index of every bond of the
       * stored lists once (bond_stencil_index, in bond order, and
       * bond_in_stencil_order), and find the list nodes that may join
       * runs (run_eligible). Needed by write_intact_stencil_indices() and
       * make_runs().
       */
      void
      index_list_bonds();

      /// Whether node i is evaluated with the shared stencil (full and
      /// intact).
      bool
      on_stencil(const unsigned int i) const
      {
        return use_lattice && lists->has_full_stencil(i) &&
               !(bond_state != nullptr && bond_state->any_broken(i));
      }

      /// The node in slot @p s.
      unsigned int
      node_of_slot(const std::size_t s) const
      {
        return use_lattice ?
                 static_cast<unsigned int>(lists->lattice().node_at_slot(s)) :
                 static_cast<unsigned int>(s);
      }

      /**
       * Append (node of slot s0 + l, @p k) to @p found for each lane l <
       * @p length with @p failed[l] != 0: the bonds a lane loop over the
       * stencil offset @p k found failed, each named by its node and
       * stencil index (bond_number() and stencil_opposite give both ends'
       * bond numbers without a search).
       */
      template <typename Pair>
      void
      add_failed_lanes(const double      *failed,
                       const std::size_t  s0,
                       const unsigned int length,
                       const std::size_t  k,
                       std::vector<Pair> &found) const
      {
        for (unsigned int l = 0; l < length; ++l)
          if (failed[l] != 0)
            found.emplace_back(node_of_slot(s0 + l), k);
      }

      /**
       * On the lattice: append (i, stencil index) to @p found for each list
       * bond b of node @p i with @p failed[b - list_first[i]] != 0.
       */
      template <typename Pair>
      void
      add_failed_list_bonds(const unsigned int i,
                            const double      *failed,
                            std::vector<Pair> &found) const
      {
        for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
          if (failed[b - list_first[i]] != 0)
            found.emplace_back(i, list_stencil_index[b]);
      }

      /**
       * On the lattice: the number of the bond of node @p i (which has a
       * list) along stencil offset @p k in i's BondState numbering, or -1
       * when i has no bond there. A full stencil numbers its bonds in
       * stencil order; a stored list by the rank of k among the list's
       * stencil indices (a popcount over its membership bits), mapped to
       * the list's order: no search.
       */
      int
      bond_number(const unsigned int i, const unsigned int k) const
      {
        if (lists->has_full_stencil(i))
          return static_cast<int>(k);
        const std::uint64_t *row =
          member_words.data() + std::size_t(member_row[i]) * member_row_words;
        const unsigned int  w   = k / 64;
        const std::uint64_t bit = std::uint64_t(1) << (k % 64);
        if ((row[w] & bit) == 0)
          return -1;
        unsigned int rank = __builtin_popcountll(row[w] & (bit - 1));
        for (unsigned int v = 0; v < w; ++v)
          rank += __builtin_popcountll(row[v]);
        return bond_in_stencil_order[bond_stencil_first[i] + rank];
      }

      /// The shared stencil's number of offsets (0 off the lattice).
      std::size_t
      n_offsets() const
      {
        return stencil_offset.size();
      }

      /**
       * Cut the slots of the nodes i for which @p selected(i) into chunks
       * of at most chunk_size consecutive slots.
       */
      template <typename Predicate>
      void
      make_chunks(const Predicate &selected, std::vector<Chunk> &chunks) const;

      /**
       * Cut @p sorted_slots into chunks of at most chunk_size consecutive
       * slots; a slot joins the last chunk only if @p joins(chunk, slot).
       */
      template <typename Joins>
      static void
      cut_into_chunks(const std::vector<std::size_t> &sorted_slots,
                      const Joins                    &joins,
                      std::vector<Chunk>             &chunks);

      /**
       * Write the stencil indices of node i's intact bonds into
       * list_stencil_index from position @p pos on, in increasing stencil
       * order (the order fixed by the bonds). Returns the position after
       * the last. The room must be there (n_bonds(i) entries).
       */
      std::size_t
      write_intact_stencil_indices(const unsigned int i, std::size_t pos);

      /// Empty masks for every block of slots (on the lattice).
      void
      clear_masks();

      /// Set the mask bits of the broken bonds of node @p i (full stencil,
      /// or a list node eligible for runs).
      void
      set_broken_bits(const unsigned int i);

      /// Whether node @p i's broken bonds are masked (set_broken_bits())
      /// instead of dropped from its list: the nodes of full chunks and
      /// runs.
      bool
      masks_bonds(const unsigned int i) const
      {
        return use_lattice &&
               (lists->has_full_stencil(i) || run_eligible[i] != 0);
      }

      /// Split @p pass's list nodes into runs and gather nodes (after
      /// every change of the lists).
      void
      make_runs(Pass &pass) const;

      /// The bond visits of one sweep of every pass: their list segments
      /// and chunks.
      std::size_t
      count_bond_visits() const;

      /// The Block of a chunk of nodes of the full stencil, with the mask
      /// words of its blocks of 64 slots.
      Block
      masked_block(const Chunk &chunk) const
      {
        return with_masks(
          Block{chunk.first_slot, chunk.length, nullptr, n_offsets()});
      }

      /// @p block with the mask words of the blocks of 64 slots it spans
      /// (masks are indexed by stencil index).
      Block
      with_masks(Block block) const
      {
        const std::size_t b0 = block.first_slot / 64;
        const std::size_t b1 = (block.first_slot + block.length - 1) / 64;
        block.shift          = block.first_slot % 64;
        if (block_mask_first[b0] >= 0)
          block.mask_low = mask_words.data() + block_mask_first[b0];
        // A chunk of at most 64 slots spans a second block only if it does
        // not start at the first slot of a block (shift > 0).
        if (b1 != b0 && block_mask_first[b1] >= 0)
          block.mask_high = mask_words.data() + block_mask_first[b1];
        return block;
      }

      /**
       * Calls @p sweep (a pass's vectorised loop over Blocks: sweep(n,
       * block) with block(c) the c-th Block) for the full chunks of
       * @p pass, with their broken bonds masked, and then for its runs over
       * their common offsets.
       */
      template <typename Sweep>
      void
      sweep_chunks_and_runs(const Pass &pass, const Sweep &sweep) const
      {
        sweep(pass.full_chunks.size(), [&](const std::size_t c) {
          return masked_block(pass.full_chunks[c]);
        });
        sweep(pass.runs.size(), [&](const std::size_t c) {
          const Run &run = pass.runs[c];
          return with_masks(
            Block{run.first_slot,
                  run.length,
                  eligible_stencil_index.data() + run.index_first,
                  run.n_index});
        });
      }

      /// Calls @p f(begin, end) on the thread pool for subranges of the
      /// chunks [0, @p n_chunks).
      template <typename Function>
      static void
      for_chunk_ranges(const std::size_t n_chunks, const Function &f)
      {
        parallel::apply_to_subranges(std::size_t(0), n_chunks, f, chunk_grain);
      }

      /// Calls @p f(i, slot[i]) for every node i of @p work, threaded.
      template <typename Function>
      void
      for_each_node_of(const std::vector<unsigned int> &work,
                       const Function                  &f) const
      {
        parallel::apply_to_subranges(
          std::size_t(0),
          work.size(),
          [&](const std::size_t begin, const std::size_t end) {
            for (std::size_t q = begin; q < end; ++q)
              f(work[q], slot[work[q]]);
          },
          node_grain);
      }

      /// Calls @p f(i) for the nodes i in [0, @p n), threaded.
      template <typename Function>
      static void
      for_each_node(const unsigned int n, const Function &f)
      {
        parallel::apply_to_subranges(
          0u,
          n,
          [&](const unsigned int begin, const unsigned int end) {
            for (unsigned int i = begin; i < end; ++i)
              f(i);
          },
          node_grain);
      }

      /// Calls @p f(k) for the stencil index k of every intact bond of
      /// node i, on the stencil or with a list (on the lattice).
      template <typename Function>
      void
      for_each_stencil_index(const unsigned int i, const Function &f) const
      {
        if (on_stencil(i))
          for (unsigned int k = 0; k < n_offsets(); ++k)
            f(k);
        else
          for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
            f(list_stencil_index[b]);
      }

      /// Bytes held on this process.
      std::size_t
      memory_consumption() const;

      const Discretization::NodeSet<dim>      *nodes      = nullptr;
      const Discretization::NeighborList<dim> *lists      = nullptr;
      const Discretization::BondState<dim>    *bond_state = nullptr;

      /// The vector layout and the index of node i's first value in it.
      std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
      std::vector<unsigned int>                          vector_index;

      /// Whether slots are lattice places, the number of slots, and node
      /// i's slot.
      bool                     use_lattice = false;
      std::size_t              n_slots     = 0;
      std::vector<std::size_t> slot;
      /// The nodes in the order of their slots.
      std::vector<unsigned int> nodes_by_slot;
      /// The shared stencil's slot offsets (on the lattice).
      std::vector<std::ptrdiff_t> stencil_offset;

      /// The work of each pass.
      std::vector<Pass> pass;

      // Segment [list_first[i], list_end[i]) of the bonds of node i in an
      // operator's bond array or list_stencil_index; is_listed[i]: node i
      // has one.
      std::vector<std::size_t> list_first, list_end;
      std::vector<char>        is_listed;
      // On a lattice the bonds of a node off the shared stencil are a
      // subset of the stencil: the stencil index of each (2 bytes a bond).
      std::vector<std::uint16_t> list_stencil_index;
      // Per node with a stored list on the lattice: the stencil index of
      // every bond (broken or not), in bond order, and the bonds' numbers
      // in increasing stencil index (the order lists are written in).
      std::vector<std::uint16_t> bond_stencil_index;
      std::vector<std::size_t>   bond_stencil_first;
      std::vector<std::uint16_t> bond_in_stencil_order;
      // On the lattice: the stencil index of the opposite offset -o of
      // each offset o.
      std::vector<std::uint16_t> stencil_opposite;
      // Per node with a stored list on the lattice: which stencil offsets
      // its bonds take, member_row_words bits-words from row member_row[i]
      // of member_words (bond_number()).
      std::vector<std::uint32_t> member_row;
      std::vector<std::uint64_t> member_words;
      unsigned int               member_row_words = 0;
      // Node i is a ghost here, or an owned node that is a ghost on
      // another process: another process may hold a list for it, so a bond
      // broken at it is sent at BondState::synchronize().
      std::vector<char> on_partition_boundary;
      // run_eligible[i]: node i's neighbourhood looks the same one slot
      // further along the slot axis wherever both are inside its horizon
      // (a node-local test, so every partition treats a node alike); it
      // joins a run, and stays in it as bonds break (masked).
      std::vector<char> run_eligible;
      // The initial bonds' stencil indices of each eligible node, in
      // increasing order, from eligible_first[i] (the runs' offsets).
      std::vector<std::uint16_t> eligible_stencil_index;
      std::vector<std::size_t>   eligible_first;
      // The bonds that broke at nodes of the full stencil: one bit per
      // (stencil offset, slot), stored per block of 64 slots for the blocks
      // that hold a node with a broken bond (block_mask_first[b]: its first
      // word in mask_words, n_offsets() words, or -1).
      std::vector<std::int64_t>  block_mask_first;
      std::vector<std::uint64_t> mask_words;

      /// Owned nodes evaluated with the shared stencil.
      unsigned int n_owned_stencil = 0;
      /// Bond visits of one application on this process.
      std::size_t bond_visits = 0;
    };


    template <int dim>
    template <typename Predicate>
    void
    LoopLayout<dim>::make_chunks(const Predicate    &selected,
                                 std::vector<Chunk> &chunks) const
    {
      // In slot order already: no sort.
      std::vector<std::size_t> slots;
      slots.reserve(nodes_by_slot.size());
      for (const unsigned int i : nodes_by_slot)
        if (selected(i))
          slots.push_back(slot[i]);
      cut_into_chunks(
        slots,
        [](const Chunk &, const std::size_t) { return true; },
        chunks);
    }


    template <int dim>
    template <typename Joins>
    void
    LoopLayout<dim>::cut_into_chunks(
      const std::vector<std::size_t> &sorted_slots,
      const Joins                    &joins,
      std::vector<Chunk>             &chunks)
    {
      chunks.clear();
      for (const std::size_t s : sorted_slots)
        if (!chunks.empty() &&
            chunks.back().first_slot + chunks.back().length == s &&
            chunks.back().length < chunk_size && joins(chunks.back(), s))
          ++chunks.back().length;
        else
          chunks.push_back({s, 1});
    }
  } // namespace Operators
} // namespace PeriDEAL

#endif
