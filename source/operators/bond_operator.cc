#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>

#include <algorithm>
#include <array>
#include <map>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      // Work items per task of the thread pool: runs of the stencil loop
      // and nodes of the list loop.
      using LoopLayout::chunk_grain;
      using LoopLayout::node_grain;

      template <int dim>
      double
      cell_measure(const double h)
      {
        return std::pow(h, dim);
      }
    } // namespace


    template <int dim>
    void
    BondOperator<dim>::reinit(const Discretization::NodeSet<dim>      &nodes_,
                              const Discretization::NeighborList<dim> &lists_,
                              const Models::Model<dim>                &model_,
                              const double                             horizon_,
                              const Discretization::BondState<dim>    *state_)
    {
      nodes                = &nodes_;
      lists                = &lists_;
      model                = &model_;
      horizon              = horizon_;
      bond_state           = state_;
      state_based          = model->is_state_based();
      const unsigned int n = nodes->size();

      // The vector layout: owned DoFs, then every other node of the set as
      // a ghost.
      {
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
          nodes->get_communicator());
      }
      // Checks that may fail on one process only are reduced over all of
      // them before anyone throws.
      const MPI_Comm comm        = nodes->get_communicator();
      bool           consecutive = true;
      vector_index.resize(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          vector_index[i] = partitioner->global_to_local((*nodes)[i].dofs[0]);
          for (unsigned int c = 1; c < dim; ++c)
            consecutive = consecutive &&
                          partitioner->global_to_local((*nodes)[i].dofs[c]) ==
                            vector_index[i] + c;
        }
      AssertThrow(Utilities::MPI::min(consecutive ? 1 : 0, comm) == 1,
                  ExcMessage("BondOperator needs the dim DoFs of a node "
                             "numbered consecutively (FESystem of "
                             "FE_DGQ(0) without renumbering)."));

      LoopLayout::choose_slots(*lists, n, use_lattice, n_slots, slot);
      const auto &lattice = lists->lattice();

      // Reference weighted volumes (every bond, broken or not).
      const double h  = lattice.spacing();
      double       m0 = 0;
      for (const auto &o : lists->stencil())
        {
          double r2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            r2 += double(o.offset[d]) * o.offset[d];
          const double r = std::sqrt(r2) * h;
          m0 += model->influence(r, horizon) * r * r * o.beta *
                cell_measure<dim>(h);
        }
      stencil_weighted_volume = m0;
      m.assign(n, 0.);
      std::vector<std::pair<std::array<double, dim>, double>> terms;
      for (unsigned int i = 0; i < n; ++i)
        if (lists->has_full_stencil(i))
          m[i] = m0;
        else if (lists->has_list(i))
          {
            // Summed in the order of the bond vectors (lexicographic): the
            // neighbour search's order may depend on the partition, and
            // m_i must not, to the last bit.
            terms.clear();
            for (const auto &bond : lists->bonds(i))
              {
                const Tensor<1, dim> xi =
                  (*nodes)[bond.neighbor].location - (*nodes)[i].location;
                const double            r = xi.norm();
                std::array<double, dim> key;
                for (unsigned int d = 0; d < dim; ++d)
                  key[d] = xi[d];
                terms.emplace_back(key,
                                   model->influence(r, horizon) * r * r *
                                     bond.weight);
              }
            std::sort(terms.begin(), terms.end());
            for (const auto &term : terms)
              m[i] += term.second;
          }

      // The shared stencil: slot offsets and per-offset constants.
      stencil = Stencil();
      if (use_lattice)
        {
          const double volume = cell_measure<dim>(h);
          stencil.node_factor = model->node_factor(m0);
          for (const auto &o : lists->stencil())
            {
              Tensor<1, dim> xi;
              for (unsigned int d = 0; d < dim; ++d)
                xi[d] = o.offset[d] * h;
              const double r = xi.norm();
              const double w = o.beta * volume;
              stencil.slot_offset.push_back(lattice.slot_offset(o.offset));
              for (unsigned int d = 0; d < dim; ++d)
                {
                  stencil.n[d].push_back(xi[d] / r);
                  stencil.xi[d].push_back(xi[d]);
                }
              stencil.r.push_back(r);
              stencil.inv_r.push_back(1. / r);
              stencil.g.push_back(
                state_based ? dim / m0 * model->influence(r, horizon) * r * w :
                              0.);
              stencil.a.push_back(volume * w *
                                  model->dilatation_constant(r, horizon));
              stencil.b.push_back(volume * w *
                                  model->extension_constant(r, horizon));
            }
        }

      if (use_lattice)
        AssertThrow(lists->stencil().size() < 65536,
                    ExcMessage("The stencil has more than 65535 offsets: "
                               "use a smaller m-ratio."));

      for (unsigned int c = 0; c < dim; ++c)
        {
          u_slot[c].resize_fast(n_slots);
          f_slot[c].resize_fast(n_slots);
          std::fill(u_slot[c].begin(), u_slot[c].end(), 0.);
          std::fill(f_slot[c].begin(), f_slot[c].end(), 0.);
        }
      t_slot.resize_fast(n_slots);
      s_slot.resize_fast(n_slots);
      std::fill(t_slot.begin(), t_slot.end(), 0.);
      std::fill(s_slot.begin(), s_slot.end(), 0.);
      for (unsigned int i = 0; i < n; ++i)
        if (lists->has_list(i))
          s_slot[slot[i]] = model->node_factor(m[i]);
        else if (!state_based)
          s_slot[slot[i]] = model->node_factor(0.);

      // No failure until set_kinematics() says otherwise.
      finite       = false;
      with_failure = false;
      critical_stretch.clear();
      s0_slot.resize_fast(0);

      // State-based forces need every neighbour's dilatation.
      if (state_based)
        {
          bool complete = true;
          for (unsigned int i = 0; i < nodes->n_owned() && complete; ++i)
            for_each_intact_bond(i, [&](const unsigned int j, const double) {
              complete = complete && lists->has_list(j);
            });
          AssertThrow(Utilities::MPI::min(complete ? 1 : 0, comm) == 1,
                      ExcMessage("A state-based model needs neighbour lists "
                                 "of the off-process neighbours of owned "
                                 "nodes: build the NeighborList with "
                                 "with_ghost_lists = true, and the NodeSet "
                                 "with a coupling range of at least twice "
                                 "the horizon plus two cell diameters."));
        }

      // Stencil indices of the bonds of stored lists on the lattice, in
      // bond order (looked up once).
      bond_stencil_first.assign(use_lattice ? n + 1 : 0, 0);
      bond_stencil_index.clear();
      if (use_lattice)
        for (unsigned int i = 0; i < n; ++i)
          {
            if (lists->has_list(i) && !lists->has_full_stencil(i))
              for (const auto &bond : lists->bonds(i))
                bond_stencil_index.push_back(
                  lists->stencil_index(i, bond.neighbor));
            bond_stencil_first[i + 1] = bond_stencil_index.size();
          }
      // The same bonds' numbers k in increasing stencil index: lists are
      // written in this order, fixed by the bonds (the neighbour search's
      // order may depend on the partition, and a node's sum must not).
      bond_in_stencil_order.resize(bond_stencil_index.size());
      if (use_lattice)
        for (unsigned int i = 0; i < n; ++i)
          {
            const std::size_t first = bond_stencil_first[i];
            const std::size_t size  = bond_stencil_first[i + 1] - first;
            std::uint16_t    *order = bond_in_stencil_order.data() + first;
            for (std::size_t k = 0; k < size; ++k)
              order[k] = static_cast<std::uint16_t>(k);
            std::sort(order, order + size, [&](const auto a, const auto b) {
              return bond_stencil_index[first + a] <
                     bond_stencil_index[first + b];
            });
          }

      find_run_eligible_nodes();
      build_work_lists();
    }


    template <int dim>
    void
    BondOperator<dim>::find_run_eligible_nodes()
    {
      const unsigned int n = nodes->size();
      run_eligible.assign(n, 0);
      if (!use_lattice)
        return;
      // For every stencil offset o, the index of o - e_0 (-1 if outside).
      const auto                         &offsets = lists->stencil();
      std::map<std::array<int, dim>, int> index_of;
      for (unsigned int k = 0; k < offsets.size(); ++k)
        index_of[offsets[k].offset] = k;
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
    }


    template <int dim>
    void
    BondOperator<dim>::set_broken_bits(const unsigned int i)
    {
      const std::size_t  s    = slot[i];
      const std::size_t  b    = s / 64;
      const unsigned int lane = s % 64;
      const std::size_t  n_k  = stencil.slot_offset.size();
      if (block_mask_first[b] < 0)
        {
          block_mask_first[b] = mask_words.size();
          mask_words.resize(mask_words.size() + n_k, 0);
        }
      std::uint64_t *words = mask_words.data() + block_mask_first[b];
      // A node of the full stencil numbers its bonds in stencil order.
      for (std::size_t k = 0; k < n_k; ++k)
        if (bond_state->is_broken(i, k))
          words[k] |= std::uint64_t(1) << lane;
    }


    template <int dim>
    void
    BondOperator<dim>::make_runs()
    {
      const auto split = [&](const std::vector<unsigned int> &work,
                             std::vector<Run>                &runs,
                             std::vector<unsigned int>       &gather) {
        runs.clear();
        gather.clear();
        std::vector<std::pair<std::size_t, unsigned int>> candidates;
        for (const unsigned int i : work)
          if (use_lattice && lists->has_full_stencil(i))
            continue; // in the full chunks, its broken bonds masked
          else if (use_lattice && run_eligible[i] &&
                   list_end[i] > list_first[i] &&
                   !(bond_state != nullptr && bond_state->any_broken(i)))
            candidates.emplace_back(slot[i], i);
          else
            gather.push_back(i);
        std::sort(candidates.begin(), candidates.end());
        const std::uint16_t *index = list_stencil_index.data();
        for (std::size_t a = 0; a < candidates.size();)
          {
            // Lists are written in increasing stencil order, so nodes
            // with the same set of offsets have equal segments.
            const unsigned int i     = candidates[a].second;
            const std::size_t  first = list_first[i];
            const std::size_t  size  = list_end[i] - first;
            std::size_t        b     = a + 1;
            while (b < candidates.size() && b - a < chunk_size &&
                   candidates[b].first == candidates[a].first + (b - a))
              {
                const unsigned int j = candidates[b].second;
                if (list_end[j] - list_first[j] != size ||
                    !std::equal(index + first,
                                index + first + size,
                                index + list_first[j]))
                  break;
                ++b;
              }
            runs.push_back({candidates[a].first,
                            static_cast<unsigned int>(b - a),
                            first,
                            static_cast<unsigned int>(size)});
            a = b;
          }
      };
      split(theta_list_nodes, theta_runs, theta_gather_nodes);
      split(force_list_nodes, force_runs, force_gather_nodes);
    }


    template <int dim>
    void
    BondOperator<dim>::update_bond_state()
    {
      build_work_lists();
    }


    template <int dim>
    bool
    BondOperator<dim>::on_stencil(const unsigned int i) const
    {
      return use_lattice && lists->has_full_stencil(i) &&
             !(bond_state != nullptr && bond_state->any_broken(i));
    }


    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_intact_bond(const unsigned int i,
                                            const Function    &f) const
    {
      if (lists->has_full_stencil(i))
        {
          const auto  &lattice = lists->lattice();
          const double volume  = cell_measure<dim>(lattice.spacing());
          const auto  &x       = lattice.coordinates(i);
          const auto  &offsets = lists->stencil();
          for (unsigned int k = 0; k < offsets.size(); ++k)
            if (bond_state == nullptr || !bond_state->is_broken(i, k))
              {
                std::array<std::int64_t, dim> y = x;
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] += offsets[k].offset[d];
                f(static_cast<unsigned int>(lattice.node_at(y)),
                  offsets[k].beta * volume);
              }
        }
      else
        {
          const auto bonds = lists->bonds(i);
          for (unsigned int k = 0; k < bonds.size(); ++k)
            if (bond_state == nullptr || !bond_state->is_broken(i, k))
              f(bonds[k].neighbor, bonds[k].weight);
        }
    }


    template <int dim>
    void
    BondOperator<dim>::build_work_lists()
    {
      const unsigned int n = nodes->size();
      std::vector<bool>  needs_theta(n, false), needs_force(n, false);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        needs_force[i] = true;
      if (state_based)
        for (unsigned int i = 0; i < n; ++i)
          needs_theta[i] = lists->has_list(i);

      make_chunks(true, theta_chunks);
      make_chunks(false, force_chunks);
      full_theta_chunks.clear();
      full_force_chunks.clear();
      block_mask_first.clear();
      mask_words.clear();
      if (use_lattice)
        {
          make_chunks(true, full_theta_chunks, true);
          make_chunks(false, full_force_chunks, true);
          block_mask_first.assign((n_slots + 63) / 64, -1);
          if (bond_state != nullptr)
            for (unsigned int i = 0; i < n; ++i)
              if (lists->has_full_stencil(i) && bond_state->any_broken(i))
                set_broken_bits(i);
        }

      theta_list_nodes.clear();
      force_list_nodes.clear();
      list_first.assign(n + 1, 0);
      list_bonds.clear();
      list_stencil_index.clear();
      list_theta_scale.assign(use_lattice ? n : 0, 0.);
      const double m0 = stencil_weighted_volume;
      n_owned_stencil = 0;
      bond_visits     = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          if ((needs_theta[i] || needs_force[i]) && !on_stencil(i))
            {
              if (needs_theta[i])
                theta_list_nodes.push_back(i);
              if (needs_force[i])
                force_list_nodes.push_back(i);
              const Point<dim> &x      = (*nodes)[i].location;
              const double      volume = (*nodes)[i].volume();
              if (use_lattice)
                {
                  // The stencil's constants hold for every node of the
                  // lattice; only the dilatation factor d / m_i differs.
                  list_theta_scale[i] = m[i] > 0 ? m0 / m[i] : 0.;
                  // The stencil index of each intact bond: for a full
                  // stencil the bond index itself; for a stored list the
                  // index found once (bond_stencil_index) and kept, so
                  // that a re-sort after bonds broke costs a bit test per
                  // bond, not a lattice look-up.
                  // In increasing stencil order (bond_in_stencil_order; a
                  // node of the full stencil numbers its bonds so).
                  const unsigned int n_all = lists->n_bonds(i);
                  const bool         full  = lists->has_full_stencil(i);
                  const std::size_t  first = bond_stencil_first[i];
                  for (unsigned int q = 0; q < n_all; ++q)
                    {
                      const unsigned int k =
                        full ? q : bond_in_stencil_order[first + q];
                      if (bond_state == nullptr || !bond_state->is_broken(i, k))
                        list_stencil_index.push_back(
                          full ? k : bond_stencil_index[first + k]);
                    }
                  const std::size_t n_bonds =
                    list_stencil_index.size() - list_first[i];
                  bond_visits += (needs_theta[i] ? n_bonds : 0) +
                                 (needs_force[i] ? n_bonds : 0);
                  list_first[i + 1] = list_stencil_index.size();
                  continue;
                }
              for_each_intact_bond(
                i,
                [&](const unsigned int j, const double w) {
                  const Tensor<1, dim> xi = (*nodes)[j].location - x;
                  const double         r  = xi.norm();
                  ListBond             bond;
                  bond.neighbor_slot = slot[j];
                  bond.r             = r;
                  for (unsigned int d = 0; d < dim; ++d)
                    bond.n[d] = xi[d] / r;
                  bond.g = state_based ?
                             dim / m[i] * model->influence(r, horizon) * r * w :
                             0.;
                  bond.a = volume * w * model->dilatation_constant(r, horizon);
                  bond.b = volume * w * model->extension_constant(r, horizon);
                  list_bonds.push_back(bond);
                });
              // In the order of the bond vectors, not the neighbour
              // search's (which may depend on the partition).
              std::sort(list_bonds.begin() + list_first[i],
                        list_bonds.end(),
                        [](const ListBond &a, const ListBond &b) {
                          for (unsigned int d = 0; d < dim; ++d)
                            if (a.n[d] * a.r != b.n[d] * b.r)
                              return a.n[d] * a.r < b.n[d] * b.r;
                          return false;
                        });
              const std::size_t n_bonds = list_bonds.size() - list_first[i];
              bond_visits +=
                (needs_theta[i] ? n_bonds : 0) + (needs_force[i] ? n_bonds : 0);
            }
          else if (needs_force[i] && on_stencil(i))
            ++n_owned_stencil;
          list_first[i + 1] =
            use_lattice ? list_stencil_index.size() : list_bonds.size();
        }
      list_end.assign(list_first.begin() + 1, list_first.end());
      is_listed.assign(n, 0);
      for (const auto *work : {&theta_list_nodes, &force_list_nodes})
        for (const unsigned int i : *work)
          is_listed[i] = 1;
      const std::size_t stencil_size = stencil.slot_offset.size();
      for (const auto &chunk : theta_chunks)
        bond_visits += chunk.length * stencil_size;
      for (const auto &chunk : force_chunks)
        bond_visits += chunk.length * stencil_size;
      if (use_lattice && state_based)
        {
          theta_run_factor.resize_fast(n_slots);
          for (const unsigned int i : theta_list_nodes)
            theta_run_factor[slot[i]] = s_slot[slot[i]] * list_theta_scale[i];
        }
      make_runs();
    }


    template <int dim>
    void
    BondOperator<dim>::make_chunks(const bool          for_theta,
                                   std::vector<Chunk> &chunks,
                                   const bool          with_broken) const
    {
      // Runs of consecutive slots of the nodes on the shared stencil that
      // need the pass: every owned node for the forces, every node with a
      // list for the dilatations of a state-based model.
      const unsigned int       n = nodes->size();
      std::vector<std::size_t> slots;
      for (unsigned int i = 0; i < n; ++i)
        if ((for_theta ? state_based && lists->has_list(i) :
                         i < nodes->n_owned()) &&
            (with_broken ? use_lattice && lists->has_full_stencil(i) :
                           on_stencil(i)))
          slots.push_back(slot[i]);
      std::sort(slots.begin(), slots.end());
      chunks.clear();
      for (std::size_t k = 0; k < slots.size(); ++k)
        if (!chunks.empty() &&
            chunks.back().first_slot + chunks.back().length == slots[k] &&
            chunks.back().length < chunk_size)
          ++chunks.back().length;
        else
          chunks.push_back({slots[k], 1});
    }


    template <int dim>
    void
    BondOperator<dim>::update_work_lists(
      const std::vector<unsigned int> &changed)
    {
      if (!use_lattice)
        {
          build_work_lists();
          return;
        }
      for (const unsigned int i : changed)
        if (lists->has_full_stencil(i))
          set_broken_bits(i);
      const unsigned int n_owned     = nodes->n_owned();
      const auto         needs_theta = [&](const unsigned int i) {
        return state_based && lists->has_list(i);
      };
      std::vector<unsigned int> listed, newcomers;
      for (const unsigned int i : changed)
        if (needs_theta(i) || i < n_owned)
          (is_listed[i] ? listed : newcomers).push_back(i);

      // The intact bonds of node i as stencil indices, from position pos.
      // (In increasing stencil order, as in build_work_lists().)
      const auto write_intact = [&](const unsigned int i, std::size_t pos) {
        const unsigned int n_all = lists->n_bonds(i);
        const bool         full  = lists->has_full_stencil(i);
        const std::size_t  first = bond_stencil_first[i];
        for (unsigned int q = 0; q < n_all; ++q)
          {
            const unsigned int k = full ? q : bond_in_stencil_order[first + q];
            if (!bond_state->is_broken(i, k))
              list_stencil_index[pos++] =
                full ? k : bond_stencil_index[first + k];
          }
        return pos;
      };
      // Nodes already on lists lost bonds: their segments shrink in place
      // (bonds only break), independently, on the thread pool.
      parallel::apply_to_subranges(
        std::size_t(0),
        listed.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t q = begin; q < end; ++q)
            list_end[listed[q]] =
              write_intact(listed[q], list_first[listed[q]]);
        },
        64);
      if (!newcomers.empty())
        {
          // Nodes that leave the shared stencil get a segment at the end.
          std::sort(newcomers.begin(), newcomers.end());
          const double m0            = stencil_weighted_volume;
          const auto   sorted_insert = [&](std::vector<unsigned int> &work,
                                         const bool needed_theta) {
            const std::size_t old_size = work.size();
            for (const unsigned int i : newcomers)
              if (needed_theta ? needs_theta(i) : i < n_owned)
                work.push_back(i);
            std::inplace_merge(work.begin(),
                               work.begin() + old_size,
                               work.end());
          };
          for (const unsigned int i : newcomers)
            {
              list_first[i] = list_stencil_index.size();
              list_stencil_index.resize(list_first[i] + lists->n_bonds(i));
              list_end[i] = write_intact(i, list_first[i]);
              list_stencil_index.resize(list_end[i]);
              list_theta_scale[i] = m[i] > 0 ? m0 / m[i] : 0.;
              if (state_based)
                theta_run_factor[slot[i]] =
                  s_slot[slot[i]] * list_theta_scale[i];
              is_listed[i] = 1;
              if (i < n_owned && lists->has_full_stencil(i))
                --n_owned_stencil;
            }
          if (state_based)
            sorted_insert(theta_list_nodes, true);
          sorted_insert(force_list_nodes, false);
          make_chunks(true, theta_chunks);
          make_chunks(false, force_chunks);
        }

      // Bond visits of one apply().
      bond_visits = 0;
      for (const unsigned int i : theta_list_nodes)
        bond_visits += list_end[i] - list_first[i];
      for (const unsigned int i : force_list_nodes)
        bond_visits += list_end[i] - list_first[i];
      const std::size_t stencil_size = stencil.slot_offset.size();
      for (const auto *chunks : {&theta_chunks, &force_chunks})
        for (const auto &chunk : *chunks)
          bond_visits += chunk.length * stencil_size;
      make_runs();
    }


    template <int dim>
    void
    BondOperator<dim>::copy_in(const VectorType &displacement) const
    {
      const double *values = displacement.begin();
      parallel::apply_to_subranges(
        0u,
        static_cast<unsigned int>(nodes->size()),
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int i = begin; i < end; ++i)
            for (unsigned int c = 0; c < dim; ++c)
              u_slot[c][slot[i]] = values[vector_index[i] + c];
        },
        node_grain);
    }


    template <int dim>
    void
    BondOperator<dim>::dilatation_pass() const
    {
      const std::size_t n_offsets = stencil.slot_offset.size();
      // The uniform bulk: theta_i = sum_k g_k n_k . (u_{i+k} - u_i),
      // vectorised over a run of consecutive slots.
      parallel::apply_to_subranges(
        std::size_t(0),
        theta_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double theta[chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = theta_chunks[c].first_slot;
              const unsigned int len = theta_chunks[c].length;
              for (unsigned int l = 0; l < len; ++l)
                theta[l] = 0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = stencil.slot_offset[k];
                  double               gn[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    gn[d] = stencil.g[k] * stencil.n[d][k];
                  const double *ui[dim], *uj[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      ui[d] = u_slot[d].data() + s0;
                      uj[d] = ui[d] + o;
                    }
#pragma omp simd
                  for (unsigned int l = 0; l < len; ++l)
                    {
                      // g e with g folded into the direction.
                      theta[l] += BondKernel::linear_extension_of_lane<dim>(gn,
                                                                            uj,
                                                                            ui,
                                                                            l);
                    }
                }
              const double s = stencil.node_factor;
              for (unsigned int l = 0; l < len; ++l)
                t_slot[s0 + l] = s * theta[l];
            }
        },
        chunk_grain);

      parallel::apply_to_subranges(
        std::size_t(0),
        theta_list_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t q = begin; q < end; ++q)
            {
              const unsigned int i     = theta_list_nodes[q];
              const std::size_t  si    = slot[i];
              double             theta = 0;
              if (use_lattice)
                {
                  for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                    {
                      const unsigned int k  = list_stencil_index[b];
                      const std::size_t  sj = si + stencil.slot_offset[k];
                      const double       e  = BondKernel::linear_extension<dim>(
                        [&](const unsigned int d) { return stencil.n[d][k]; },
                        [&](const unsigned int d) {
                          return u_slot[d][sj] - u_slot[d][si];
                        });
                      theta += stencil.g[k] * e;
                    }
                  theta *= list_theta_scale[i];
                }
              else
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const ListBond   &bond = list_bonds[b];
                    const std::size_t sj   = bond.neighbor_slot;
                    const double      e    = BondKernel::linear_extension<dim>(
                      bond.n,
                      [&](const unsigned int d) {
                        return u_slot[d][sj] - u_slot[d][si];
                      });
                    theta += bond.g * e;
                  }
              t_slot[si] = s_slot[si] * theta;
            }
        },
        node_grain);
    }


    template <int dim>
    void
    BondOperator<dim>::force_pass() const
    {
      const std::size_t n_offsets = stencil.slot_offset.size();
      const bool        sb        = state_based;
      parallel::apply_to_subranges(
        std::size_t(0),
        force_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double force[dim][chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = force_chunks[c].first_slot;
              const unsigned int len = force_chunks[c].length;
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int l = 0; l < len; ++l)
                  force[d][l] = 0;
              const double *ui[dim];
              for (unsigned int d = 0; d < dim; ++d)
                ui[d] = u_slot[d].data() + s0;
              const double *ti = t_slot.data() + s0;
              const double *si = s_slot.data() + s0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = stencil.slot_offset[k];
                  const double         a = stencil.a[k], b = stencil.b[k];
                  double               nk[dim];
                  const double        *uj[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      nk[d] = stencil.n[d][k];
                      uj[d] = ui[d] + o;
                    }
                  if (sb)
                    {
                      const double *tj = ti + o, *sj = si + o;
#pragma omp simd
                      for (unsigned int l = 0; l < len; ++l)
                        {
                          const double e =
                            BondKernel::linear_extension_of_lane<dim>(nk,
                                                                      uj,
                                                                      ui,
                                                                      l);
                          const double t = BondKernel::pair_force(a,
                                                                  ti[l],
                                                                  tj[l],
                                                                  b,
                                                                  si[l],
                                                                  sj[l],
                                                                  e);
                          for (unsigned int d = 0; d < dim; ++d)
                            force[d][l] += t * nk[d];
                        }
                    }
                  else
                    {
                    // Bond-based: s = 1 at every node.
#pragma omp simd
                      for (unsigned int l = 0; l < len; ++l)
                        {
                          const double e =
                            BondKernel::linear_extension_of_lane<dim>(nk,
                                                                      uj,
                                                                      ui,
                                                                      l);
                          const double t =
                            BondKernel::bond_based_pair_force(b, e);
                          for (unsigned int d = 0; d < dim; ++d)
                            force[d][l] += t * nk[d];
                        }
                    }
                }
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int l = 0; l < len; ++l)
                  f_slot[d][s0 + l] = force[d][l];
            }
        },
        chunk_grain);

      parallel::apply_to_subranges(
        std::size_t(0),
        force_list_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t q = begin; q < end; ++q)
            {
              const unsigned int i      = force_list_nodes[q];
              const std::size_t  si     = slot[i];
              double             f[dim] = {};
              if (use_lattice)
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const unsigned int k  = list_stencil_index[b];
                    const std::size_t  sj = si + stencil.slot_offset[k];
                    const double       e  = BondKernel::linear_extension<dim>(
                      [&](const unsigned int d) { return stencil.n[d][k]; },
                      [&](const unsigned int d) {
                        return u_slot[d][sj] - u_slot[d][si];
                      });
                    const double t = BondKernel::pair_force(stencil.a[k],
                                                            t_slot[si],
                                                            t_slot[sj],
                                                            stencil.b[k],
                                                            s_slot[si],
                                                            s_slot[sj],
                                                            e);
                    for (unsigned int d = 0; d < dim; ++d)
                      f[d] += t * stencil.n[d][k];
                  }
              else
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const ListBond   &bond = list_bonds[b];
                    const std::size_t sj   = bond.neighbor_slot;
                    const double      e    = BondKernel::linear_extension<dim>(
                      bond.n,
                      [&](const unsigned int d) {
                        return u_slot[d][sj] - u_slot[d][si];
                      });
                    const double t = BondKernel::pair_force(bond.a,
                                                            t_slot[si],
                                                            t_slot[sj],
                                                            bond.b,
                                                            s_slot[si],
                                                            s_slot[sj],
                                                            e);
                    for (unsigned int d = 0; d < dim; ++d)
                      f[d] += t * bond.n[d];
                  }
              for (unsigned int d = 0; d < dim; ++d)
                f_slot[d][si] = f[d];
            }
        },
        node_grain);
    }


    template <int dim>
    void
    BondOperator<dim>::apply(const VectorType &displacement,
                             VectorType       &force) const
    {
      apply_passes<false>(displacement, force);
    }


    template <int dim>
    double
    BondOperator<dim>::apply_with_energy(const VectorType &displacement,
                                         VectorType       &force) const
    {
      if (!finite && !with_failure)
        {
          apply_passes<false>(displacement, force);
          return elastic_energy(displacement);
        }
      e_slot.resize_fast(n_slots);
      apply_passes<true>(displacement, force);
      // V_i W_i = 1/2 s_i sum_j b_ij e_ij^2 + 1/2 V_i lambda theta_i^2 as
      // in elastic_energy(), summed in node order (the same on every run).
      const double lambda = model->dilatation_energy_modulus();
      double       energy = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const std::size_t si = slot[i];
          const double      theta =
            state_based && s_slot[si] != 0 ? t_slot[si] / s_slot[si] : 0.;
          energy += 0.5 * s_slot[si] * e_slot[si] +
                    0.5 * (*nodes)[i].volume() * lambda * theta * theta;
        }
      return Utilities::MPI::sum(energy, nodes->get_communicator());
    }


    template <int dim>
    template <bool with_energy>
    void
    BondOperator<dim>::apply_passes(const VectorType &displacement,
                                    VectorType       &force) const
    {
      copy_in(displacement);
      if (finite)
        {
          if (state_based)
            nonlinear_dilatation_pass<true>();
          nonlinear_force_pass<true, with_energy>();
        }
      else if (with_failure)
        {
          if (state_based)
            nonlinear_dilatation_pass<false>();
          nonlinear_force_pass<false, with_energy>();
        }
      else
        {
          if (state_based)
            dilatation_pass();
          force_pass();
        }
      double *values = force.begin();
      parallel::apply_to_subranges(
        0u,
        nodes->n_owned(),
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int i = begin; i < end; ++i)
            for (unsigned int c = 0; c < dim; ++c)
              values[vector_index[i] + c] = f_slot[c][slot[i]];
        },
        node_grain);
    }


    template <int dim>
    void
    BondOperator<dim>::compute_dilatation(const VectorType    &displacement,
                                          std::vector<double> &dilatation) const
    {
      dilatation.assign(nodes->size(), 0.);
      if (!state_based)
        return;
      copy_in(displacement);
      if (finite)
        nonlinear_dilatation_pass<true>();
      else if (with_failure)
        nonlinear_dilatation_pass<false>();
      else
        dilatation_pass();
      for (unsigned int i = 0; i < nodes->size(); ++i)
        if (lists->has_list(i))
          dilatation[i] = t_slot[slot[i]] / s_slot[slot[i]];
    }


    template <int dim>
    void
    BondOperator<dim>::compute_diagonal(VectorType &diagonal) const
    {
      // K_ii = V_i sum_j w [beta (s_i + s_j) n (x) n + alpha s_i n (x) G_i
      //        - alpha s_j n (x) g_ji], G_i = sum_j g_ij, with
      // g_ij = (d / m_i) omega r w_ij n_ij (see the class documentation).
      if (use_lattice)
        {
          // On the lattice every bond's constants are the stencil's:
          // g_ij = g_k m_0 / m_i, and g_ji = g_k m_0 / m_j (w_ji = w_ij).
          const double m0      = stencil_weighted_volume;
          const auto  &lattice = lists->lattice();
          parallel::apply_to_subranges(
            0u,
            nodes->n_owned(),
            [&](const unsigned int begin, const unsigned int end) {
              for (unsigned int i = begin; i < end; ++i)
                {
                  const double   s_i = s_slot[slot[i]];
                  Tensor<1, dim> G, a_sum, diag;
                  auto           add = [&](const unsigned int k) {
                    std::array<std::int64_t, dim> y = lattice.coordinates(i);
                    for (unsigned int d = 0; d < dim; ++d)
                      y[d] += lists->stencil()[k].offset[d];
                    const unsigned int j   = lattice.node_at(y);
                    const double       s_j = s_slot[slot[j]];
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        const double n_c = stencil.n[c][k];
                        diag[c] += BondKernel::extension_stiffness(stencil.b[k],
                                                                   s_i,
                                                                   s_j) *
                                   n_c * n_c;
                        if (state_based)
                          {
                            G[c] += stencil.g[k] * m0 / m[i] * n_c;
                            a_sum[c] +=
                              BondKernel::dilatation_stiffness(stencil.a[k],
                                                               s_i) *
                              n_c;
                            diag[c] +=
                              BondKernel::dilatation_stiffness(stencil.a[k],
                                                               s_j) *
                              n_c * n_c * stencil.g[k] * m0 / m[j];
                          }
                      }
                  };
                  if (on_stencil(i))
                    for (unsigned int k = 0; k < stencil.g.size(); ++k)
                      add(k);
                  else
                    for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                      add(list_stencil_index[b]);
                  for (unsigned int c = 0; c < dim; ++c)
                    diagonal.local_element(vector_index[i] + c) =
                      diag[c] + a_sum[c] * G[c];
                }
            },
            node_grain);
          return;
        }
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const Point<dim> &x      = (*nodes)[i].location;
          const double      volume = (*nodes)[i].volume();
          const double      s_i    = s_slot[slot[i]];
          Tensor<1, dim>    G, a_sum, diag;
          for_each_intact_bond(i, [&](const unsigned int j, const double w) {
            const Tensor<1, dim> xi    = (*nodes)[j].location - x;
            const double         r     = xi.norm();
            const Tensor<1, dim> n     = xi / r;
            const double         s_j   = s_slot[slot[j]];
            const double         alpha = model->dilatation_constant(r, horizon);
            const double         beta  = model->extension_constant(r, horizon);
            for (unsigned int c = 0; c < dim; ++c)
              diag[c] +=
                BondKernel::extension_stiffness(volume * w * beta, s_i, s_j) *
                n[c] * n[c];
            if (!state_based)
              return;
            G += dim / m[i] * model->influence(r, horizon) * r * w * n;
            a_sum +=
              BondKernel::dilatation_stiffness(volume * w * alpha, s_i) * n;
            // g_ji: node j's bond back to i (weight w_ji), if it has one.
            double w_ji = 0;
            if (lists->has_full_stencil(j))
              w_ji = w * (*nodes)[i].volume() / (*nodes)[j].volume();
            else
              for (const auto &bond : lists->bonds(j))
                if (bond.neighbor == i)
                  {
                    w_ji = bond.weight;
                    break;
                  }
            const double g_ji =
              dim / m[j] * model->influence(r, horizon) * r * w_ji;
            for (unsigned int c = 0; c < dim; ++c)
              diag[c] +=
                BondKernel::dilatation_stiffness(volume * w * alpha, s_j) *
                n[c] * g_ji * n[c];
          });
          for (unsigned int c = 0; c < dim; ++c)
            diagonal.local_element(vector_index[i] + c) =
              diag[c] + a_sum[c] * G[c];
        }
    }


    template <int dim>
    const std::shared_ptr<const Utilities::MPI::Partitioner> &
    BondOperator<dim>::get_partitioner() const
    {
      return partitioner;
    }


    template <int dim>
    void
    BondOperator<dim>::initialize_dof_vector(VectorType &v) const
    {
      v.reinit(partitioner);
    }


    template <int dim>
    const std::vector<double> &
    BondOperator<dim>::weighted_volumes() const
    {
      return m;
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::n_stencil_nodes() const
    {
      return n_owned_stencil;
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::n_list_nodes() const
    {
      return force_list_nodes.size();
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::n_run_nodes() const
    {
      unsigned int count = 0;
      for (const Run &run : force_runs)
        count += run.length;
      return count;
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::max_run_length() const
    {
      unsigned int longest = 0;
      for (const Run &run : force_runs)
        longest = std::max(longest, run.length);
      return longest;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::n_bond_visits() const
    {
      return bond_visits;
    }


    template <int dim>
    bool
    BondOperator<dim>::is_state_based() const
    {
      return state_based;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::memory_consumption() const
    {
      std::size_t bytes =
        vector_index.capacity() * sizeof(unsigned int) +
        slot.capacity() * sizeof(std::size_t) + m.capacity() * sizeof(double) +
        (theta_chunks.capacity() + force_chunks.capacity()) * sizeof(Chunk) +
        (theta_list_nodes.capacity() + force_list_nodes.capacity()) *
          sizeof(unsigned int) +
        list_first.capacity() * sizeof(std::size_t) +
        list_bonds.capacity() * sizeof(ListBond) +
        (list_stencil_index.capacity() + bond_stencil_index.capacity() +
         bond_in_stencil_order.capacity()) *
          sizeof(std::uint16_t) +
        bond_stencil_first.capacity() * sizeof(std::size_t) +
        list_theta_scale.capacity() * sizeof(double) +
        (2 * dim + 2) * n_slots * sizeof(double) +
        s0_slot.size() * sizeof(double) +
        (theta_runs.capacity() + force_runs.capacity()) * sizeof(Run) +
        (theta_gather_nodes.capacity() + force_gather_nodes.capacity()) *
          sizeof(unsigned int) +
        run_eligible.capacity() +
        (theta_run_factor.size() + e_slot.size()) * sizeof(double) +
        (full_theta_chunks.capacity() + full_force_chunks.capacity()) *
          sizeof(Chunk) +
        block_mask_first.capacity() * sizeof(std::int64_t) +
        mask_words.capacity() * sizeof(std::uint64_t);
      return bytes;
    }


    template class BondOperator<2>;
    template class BondOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
