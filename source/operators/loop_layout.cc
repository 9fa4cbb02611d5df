#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/loop_layout.h>

#include <algorithm>
#include <array>
#include <map>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    LoopLayout<dim>::reinit(const Discretization::NodeSet<dim>      &nodes_,
                            const Discretization::NeighborList<dim> &lists_,
                            const Discretization::BondState<dim>    *state_,
                            const bool         one_value_per_node,
                            const unsigned int n_passes,
                            const std::string &user)
    {
      nodes                = &nodes_;
      lists                = &lists_;
      bond_state           = state_;
      const unsigned int n = nodes->size();
      // Checks that may fail on one process only are reduced over all of
      // them before anyone throws.
      const MPI_Comm comm        = nodes->get_communicator();
      bool           consecutive = true;
      vector_index.resize(n);
      if (one_value_per_node)
        {
          // The global index dofs[0] / dim of the FE_DGQ(0)^dim numbering
          // (the dim DoFs of a cell are consecutive).
          for (unsigned int i = 0; i < n && consecutive; ++i)
            {
              const auto &dofs = (*nodes)[i].dofs;
              consecutive      = dofs[0] % dim == 0;
              for (unsigned int c = 1; c < dim; ++c)
                consecutive = consecutive && dofs[c] == dofs[0] + c;
            }
          AssertThrow(Utilities::MPI::min(consecutive ? 1 : 0, comm) == 1,
                      ExcMessage(user +
                                 " needs the dim DoFs of a node "
                                 "numbered consecutively from a multiple of "
                                 "dim (FESystem of FE_DGQ(0) without "
                                 "renumbering)."));
          partitioner = nodes->node_partitioner();
          for (unsigned int i = 0; i < n; ++i)
            vector_index[i] =
              partitioner->global_to_local((*nodes)[i].dofs[0] / dim);
        }
      else
        {
          // Owned DoFs, then every other node of the set as a ghost.
          std::vector<types::global_dof_index> dofs;
          for (unsigned int i = 0; i < nodes->n_owned(); ++i)
            dofs.insert(dofs.end(),
                        (*nodes)[i].dofs.begin(),
                        (*nodes)[i].dofs.end());
          std::sort(dofs.begin(), dofs.end());
          IndexSet owned(nodes->relevant_dofs().size());
          owned.add_indices(dofs.begin(), dofs.end());
          owned.compress();
          partitioner = std::make_shared<Utilities::MPI::Partitioner>(
            owned,
            nodes->relevant_dofs(),
            comm);
          for (unsigned int i = 0; i < n; ++i)
            {
              vector_index[i] =
                partitioner->global_to_local((*nodes)[i].dofs[0]);
              for (unsigned int c = 1; c < dim; ++c)
                consecutive =
                  consecutive && partitioner->global_to_local(
                                   (*nodes)[i].dofs[c]) == vector_index[i] + c;
            }
          AssertThrow(Utilities::MPI::min(consecutive ? 1 : 0, comm) == 1,
                      ExcMessage(user + " needs the dim DoFs of a node "
                                        "numbered consecutively (FESystem of "
                                        "FE_DGQ(0) without renumbering)."));
        }

      // The lattice's dense box on a uniform grid with a shared stencil,
      // unless that box is much larger than the node set (a scattered
      // partition: more than 8 n + 4096 slots); node indices otherwise.
      const auto &lattice = lists->lattice();
      use_lattice         = lattice.is_uniform() && !lists->stencil().empty() &&
                    lattice.n_slots() <= 8 * static_cast<std::size_t>(n) + 4096;
      n_slots = use_lattice ? lattice.n_slots() : n;
      slot.resize(n);
      for (unsigned int i = 0; i < n; ++i)
        slot[i] = use_lattice ? lattice.slot(i) : i;
      // The nodes by increasing slot (slots are distinct), so that
      // make_chunks() needs no sort.
      nodes_by_slot.resize(n);
      for (unsigned int i = 0; i < n; ++i)
        nodes_by_slot[i] = i;
      if (use_lattice)
        std::sort(nodes_by_slot.begin(),
                  nodes_by_slot.end(),
                  [&](const unsigned int a, const unsigned int b) {
                    return slot[a] < slot[b];
                  });
      stencil_offset.clear();
      if (use_lattice)
        for (const auto &o : lists->stencil())
          stencil_offset.push_back(lattice.slot_offset(o.offset));

      // Owned nodes that are ghosts on another process, and every ghost.
      {
        std::vector<char> imported(partitioner->locally_owned_size(), 0);
        for (const auto &range : partitioner->import_indices())
          std::fill(imported.begin() + range.first,
                    imported.begin() + range.second,
                    1);
        on_partition_boundary.assign(n, 1);
        for (unsigned int i = 0; i < nodes->n_owned(); ++i)
          on_partition_boundary[i] = imported[vector_index[i]];
      }

      pass.assign(n_passes, Pass());
      list_first.clear();
      list_end.clear();
      is_listed.clear();
      list_stencil_index.clear();
      bond_stencil_index.clear();
      bond_stencil_first.clear();
      bond_in_stencil_order.clear();
      run_eligible.assign(n, 0);
      eligible_stencil_index.clear();
      eligible_first.clear();
      stencil_opposite.clear();
      member_row.clear();
      member_words.clear();
      member_row_words = 0;
      block_mask_first.clear();
      mask_words.clear();
      n_owned_stencil = 0;
      bond_visits     = 0;
    }


    template <int dim>
    void
    LoopLayout<dim>::index_list_bonds()
    {
      const unsigned int n = nodes->size();
      if (use_lattice)
        AssertThrow(lists->stencil().size() < 65536,
                    ExcMessage("The stencil has more than 65535 offsets: "
                               "use a smaller m-ratio."));
      // Stencil indices of the bonds of stored lists on the lattice, in
      // bond order (looked up once), and the same bonds' numbers k in
      // increasing stencil index: lists are written in this order, fixed
      // by the bonds (the neighbour search's order may depend on the
      // partition, and a node's sum must not). Threaded: each node writes
      // its own range; the order by placing each k at its stencil index
      // (distinct within a node), no sort.
      bond_stencil_first.assign(use_lattice ? n + 1 : 0, 0);
      if (use_lattice)
        for (unsigned int i = 0; i < n; ++i)
          bond_stencil_first[i + 1] =
            bond_stencil_first[i] +
            (lists->has_list(i) && !lists->has_full_stencil(i) ?
               lists->n_bonds(i) :
               0);
      const std::size_t n_list_bonds = use_lattice ? bond_stencil_first[n] : 0;
      bond_stencil_index.resize(n_list_bonds);
      bond_in_stencil_order.resize(n_list_bonds);
      if (use_lattice)
        parallel::apply_to_subranges(
          0u,
          n,
          [&](const unsigned int begin, const unsigned int end) {
            std::vector<int> at(lists->stencil().size(), -1);
            for (unsigned int i = begin; i < end; ++i)
              {
                const std::size_t first = bond_stencil_first[i];
                const std::size_t size  = bond_stencil_first[i + 1] - first;
                if (size == 0)
                  continue;
                const auto bonds = lists->bonds(i);
                for (std::size_t k = 0; k < size; ++k)
                  {
                    const int index =
                      lists->stencil_index(i, bonds[k].neighbor);
                    // (Lists on the lattice hold stencil offsets, each
                    // once: an invariant, checked in debug builds.)
                    Assert(index >= 0 && at[index] < 0, ExcInternalError());
                    bond_stencil_index[first + k] =
                      static_cast<std::uint16_t>(index);
                    at[index] = static_cast<int>(k);
                  }
                std::uint16_t *order = bond_in_stencil_order.data() + first;
                std::size_t    m     = 0;
                for (std::size_t index = 0; index < at.size(); ++index)
                  if (at[index] >= 0)
                    {
                      order[m++] = static_cast<std::uint16_t>(at[index]);
                      at[index]  = -1;
                    }
              }
          },
          256);

      run_eligible.assign(n, 0);
      stencil_opposite.clear();
      member_row.clear();
      member_words.clear();
      member_row_words = 0;
      if (!use_lattice)
        return;
      // For every stencil offset o, the index of o - e_0 (-1 if outside).
      const auto                         &offsets = lists->stencil();
      std::map<std::array<int, dim>, int> index_of;
      for (unsigned int k = 0; k < offsets.size(); ++k)
        index_of[offsets[k].offset] = k;
      // The opposite of each offset (the stencil is symmetric).
      stencil_opposite.resize(offsets.size());
      for (unsigned int k = 0; k < offsets.size(); ++k)
        {
          auto opposite = offsets[k].offset;
          for (unsigned int d = 0; d < dim; ++d)
            opposite[d] = -opposite[d];
          const auto it = index_of.find(opposite);
          AssertThrow(it != index_of.end(),
                      ExcMessage("The shared stencil is not symmetric."));
          stencil_opposite[k] = static_cast<std::uint16_t>(it->second);
        }
      // The membership bits of the stored lists (bond_number()).
      member_row_words = (offsets.size() + 63) / 64;
      member_row.assign(n, ~std::uint32_t(0));
      std::uint32_t n_rows = 0;
      for (unsigned int i = 0; i < n; ++i)
        if (bond_stencil_first[i + 1] > bond_stencil_first[i])
          member_row[i] = n_rows++;
      member_words.assign(std::size_t(n_rows) * member_row_words, 0);
      for (unsigned int i = 0; i < n; ++i)
        for (std::size_t b = bond_stencil_first[i];
             b < bond_stencil_first[i + 1];
             ++b)
          member_words[std::size_t(member_row[i]) * member_row_words +
                       bond_stencil_index[b] / 64] |=
            std::uint64_t(1) << (bond_stencil_index[b] % 64);
      std::vector<std::pair<unsigned int, unsigned int>> pairs;
      for (unsigned int k = 0; k < offsets.size(); ++k)
        {
          auto shifted = offsets[k].offset;
          --shifted[0];
          const auto it = index_of.find(shifted);
          if (it != index_of.end())
            pairs.emplace_back(k, it->second);
        }
      // Node i (off the full stencil) is eligible when its neighbourhood
      // is invariant under a shift by one slot wherever both positions are
      // inside its horizon: a node at i + o exists iff one at i + o - e_0
      // does. It uses node i's own (initial) bonds only, so it does not
      // depend on the partition; its neighbours along the slot axis with
      // the same bonds then form runs.
      std::vector<char> present(offsets.size());
      for (unsigned int i = 0; i < n; ++i)
        if (lists->has_list(i) && !lists->has_full_stencil(i))
          {
            std::fill(present.begin(), present.end(), 0);
            for (std::size_t b = bond_stencil_first[i];
                 b < bond_stencil_first[i + 1];
                 ++b)
              present[bond_stencil_index[b]] = 1;
            bool invariant = bond_stencil_first[i + 1] > bond_stencil_first[i];
            for (const auto &[k, k_minus] : pairs)
              invariant = invariant && present[k] == present[k_minus];
            run_eligible[i] = invariant ? 1 : 0;
          }
      // The runs' offsets: each eligible node's initial bonds in
      // increasing stencil order (its membership bits).
      eligible_first.assign(n, 0);
      eligible_stencil_index.clear();
      for (unsigned int i = 0; i < n; ++i)
        if (run_eligible[i])
          {
            eligible_first[i] = eligible_stencil_index.size();
            const std::uint64_t *row =
              member_words.data() +
              std::size_t(member_row[i]) * member_row_words;
            for (unsigned int w = 0; w < member_row_words; ++w)
              for (std::uint64_t v = row[w]; v != 0; v &= v - 1)
                eligible_stencil_index.push_back(
                  static_cast<std::uint16_t>(64 * w + __builtin_ctzll(v)));
          }
    }


    template <int dim>
    std::size_t
    LoopLayout<dim>::write_intact_stencil_indices(const unsigned int i,
                                                  std::size_t        pos)
    {
      // For a full stencil the bond index is the stencil index; for a
      // stored list the index found once (bond_stencil_index) and kept, so
      // that a re-sort after bonds broke costs a bit test per bond, not a
      // lattice look-up.
      const unsigned int n_all = lists->n_bonds(i);
      const bool         full  = lists->has_full_stencil(i);
      if (full && bond_state != nullptr)
        {
          // The intact bits a word at a time.
          bond_state->for_each_intact(i, [&](const unsigned int k) {
            list_stencil_index[pos++] = static_cast<std::uint16_t>(k);
          });
          return pos;
        }
      const std::size_t first = full ? 0 : bond_stencil_first[i];
      if (!full && bond_state != nullptr && n_all > 0 && member_row_words > 0 &&
          member_row_words <= 16)
        {
          // The broken bonds as stencil-index bits, then the membership
          // bits without them, a word at a time (increasing stencil order).
          std::uint64_t        broken[16] = {};
          const std::uint16_t *index      = bond_stencil_index.data() + first;
          bond_state->for_each_broken(i, [&](const unsigned int k) {
            broken[index[k] / 64] |= std::uint64_t(1) << (index[k] % 64);
          });
          const std::uint64_t *row =
            member_words.data() + std::size_t(member_row[i]) * member_row_words;
          for (unsigned int w = 0; w < member_row_words; ++w)
            for (std::uint64_t v = row[w] & ~broken[w]; v != 0; v &= v - 1)
              list_stencil_index[pos++] =
                static_cast<std::uint16_t>(64 * w + __builtin_ctzll(v));
          return pos;
        }
      for (unsigned int q = 0; q < n_all; ++q)
        {
          const unsigned int k = full ? q : bond_in_stencil_order[first + q];
          if (bond_state == nullptr || !bond_state->is_broken(i, k))
            list_stencil_index[pos++] =
              full ? k : bond_stencil_index[first + k];
        }
      return pos;
    }


    template <int dim>
    void
    LoopLayout<dim>::clear_masks()
    {
      block_mask_first.assign(use_lattice ? (n_slots + 63) / 64 : 0, -1);
      mask_words.clear();
    }


    template <int dim>
    void
    LoopLayout<dim>::set_broken_bits(const unsigned int i)
    {
      const std::size_t  s    = slot[i];
      const std::size_t  b    = s / 64;
      const unsigned int lane = s % 64;
      const std::size_t  n_k  = n_offsets();
      if (block_mask_first[b] < 0)
        {
          block_mask_first[b] = mask_words.size();
          mask_words.resize(mask_words.size() + n_k, 0);
        }
      std::uint64_t *words = mask_words.data() + block_mask_first[b];
      // A node of the full stencil numbers its bonds in stencil order; a
      // stored list's bond k has the stencil index found once.
      if (lists->has_full_stencil(i))
        bond_state->for_each_broken(i, [&](const unsigned int k) {
          words[k] |= std::uint64_t(1) << lane;
        });
      else
        {
          const std::uint16_t *index =
            bond_stencil_index.data() + bond_stencil_first[i];
          bond_state->for_each_broken(i, [&](const unsigned int k) {
            words[index[k]] |= std::uint64_t(1) << lane;
          });
        }
    }


    template <int dim>
    void
    LoopLayout<dim>::make_runs(Pass &work) const
    {
      work.runs.clear();
      work.gather_nodes.clear();
      std::vector<std::pair<std::size_t, unsigned int>> candidates;
      for (const unsigned int i : work.list_nodes)
        if (use_lattice && lists->has_full_stencil(i))
          continue; // in the full chunks, its broken bonds masked
        else if (use_lattice && run_eligible[i])
          candidates.emplace_back(slot[i], i); // broken bonds masked
        else
          work.gather_nodes.push_back(i);
      std::sort(candidates.begin(), candidates.end());
      for (std::size_t a = 0; a < candidates.size();)
        {
          // Nodes with the same set of initial offsets have equal
          // membership rows.
          const unsigned int   i = candidates[a].second;
          const std::uint64_t *row =
            member_words.data() + std::size_t(member_row[i]) * member_row_words;
          std::size_t b = a + 1;
          while (b < candidates.size() && b - a < chunk_size &&
                 candidates[b].first == candidates[a].first + (b - a))
            {
              const unsigned int j = candidates[b].second;
              if (!std::equal(row,
                              row + member_row_words,
                              member_words.data() +
                                std::size_t(member_row[j]) * member_row_words))
                break;
              ++b;
            }
          const std::size_t first = eligible_first[i];
          const std::size_t size =
            bond_stencil_first[i + 1] - bond_stencil_first[i];
          work.runs.push_back({candidates[a].first,
                               static_cast<unsigned int>(b - a),
                               first,
                               static_cast<unsigned int>(size)});
          a = b;
        }
    }


    template <int dim>
    std::size_t
    LoopLayout<dim>::count_bond_visits() const
    {
      std::size_t visits = 0;
      for (const Pass &work : pass)
        {
          for (const unsigned int i : work.list_nodes)
            visits += list_end[i] - list_first[i];
          for (const Chunk &chunk : work.chunks)
            visits += chunk.length * n_offsets();
        }
      return visits;
    }


    template <int dim>
    std::size_t
    LoopLayout<dim>::Pass::memory_consumption() const
    {
      return (chunks.capacity() + full_chunks.capacity()) * sizeof(Chunk) +
             (list_nodes.capacity() + gather_nodes.capacity()) *
               sizeof(unsigned int) +
             runs.capacity() * sizeof(Run);
    }


    template <int dim>
    std::size_t
    LoopLayout<dim>::memory_consumption() const
    {
      std::size_t bytes =
        vector_index.capacity() * sizeof(unsigned int) +
        slot.capacity() * sizeof(std::size_t) +
        nodes_by_slot.capacity() * sizeof(unsigned int) +
        stencil_offset.capacity() * sizeof(std::ptrdiff_t) +
        (list_first.capacity() + list_end.capacity() +
         bond_stencil_first.capacity()) *
          sizeof(std::size_t) +
        is_listed.capacity() + run_eligible.capacity() +
        (list_stencil_index.capacity() + bond_stencil_index.capacity() +
         bond_in_stencil_order.capacity() + stencil_opposite.capacity()) *
          sizeof(std::uint16_t) +
        member_row.capacity() * sizeof(std::uint32_t) +
        eligible_stencil_index.capacity() * sizeof(std::uint16_t) +
        eligible_first.capacity() * sizeof(std::size_t) +
        member_words.capacity() * sizeof(std::uint64_t) +
        on_partition_boundary.capacity() +
        block_mask_first.capacity() * sizeof(std::int64_t) +
        mask_words.capacity() * sizeof(std::uint64_t);
      for (const Pass &work : pass)
        bytes += work.memory_consumption();
      return bytes;
    }


    template class LoopLayout<1>;
    template class LoopLayout<2>;
    template class LoopLayout<3>;
  } // namespace Operators
} // namespace PeriDEAL
