// BondOperator: the set-up of its loop layout (stencil constants, lists,
// chunks, runs), the work lists after bonds broke, and its statistics.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace PeriDEAL
{
  namespace Operators
  {
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

      const MPI_Comm comm = nodes->get_communicator();
      layout.reinit(nodes_, lists_, state_, false, 2, "BondOperator");
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
          m0 +=
            model->influence(r, horizon) * r * r * o.beta * std::pow(h, dim);
        }
      stencil_weighted_volume = m0;
      m.assign(n, 0.);
      // Threaded over the nodes: each writes its own m_i, summed in the
      // order of the bond vectors (lexicographic): the neighbour search's
      // order may depend on the partition, and m_i must not, to the last
      // bit. On the lattice the stencil's order (lexicographic in the
      // offsets) is that order whenever the nodes sit on the lattice to
      // the bit; the terms are placed by stencil index, checked to be in
      // order, and sorted only where they are not.
      const std::size_t stencil_size = lists->stencil().size();
      parallel::apply_to_subranges(
        0u,
        n,
        [&](const unsigned int begin, const unsigned int end) {
          std::vector<std::pair<std::array<double, dim>, double>> terms,
            by_index(stencil_size);
          std::vector<char> present(stencil_size, 0);
          for (unsigned int i = begin; i < end; ++i)
            if (lists->has_full_stencil(i))
              m[i] = m0;
            else if (lists->has_list(i))
              {
                terms.clear();
                for (const auto &bond : lists->bonds(i))
                  {
                    const Tensor<1, dim> xi =
                      (*nodes)[bond.neighbor].location - (*nodes)[i].location;
                    const double            r = xi.norm();
                    std::array<double, dim> key;
                    for (unsigned int d = 0; d < dim; ++d)
                      key[d] = xi[d];
                    const std::pair<std::array<double, dim>, double> term(
                      key,
                      model->influence(r, horizon) * r * r * bond.weight);
                    const int k = stencil_size > 0 ?
                                    lists->stencil_index(i, bond.neighbor) :
                                    -1;
                    if (k >= 0 && !present[k])
                      {
                        by_index[k] = term;
                        present[k]  = 1;
                      }
                    else
                      terms.push_back(term);
                  }
                // (Terms off the stencil, none on a lattice, went first:
                // then the check below fails and they are sorted.)
                for (std::size_t k = 0; k < stencil_size; ++k)
                  if (present[k])
                    {
                      terms.push_back(by_index[k]);
                      present[k] = 0;
                    }
                if (!std::is_sorted(terms.begin(), terms.end()))
                  std::sort(terms.begin(), terms.end());
                for (const auto &term : terms)
                  m[i] += term.second;
              }
        },
        1024);

      // The shared stencil: slot offsets and per-offset constants.
      stencil = Stencil();
      if (layout.use_lattice)
        {
          const double volume = std::pow(h, dim);
          stencil.node_factor = model->node_factor(m0);
          for (const auto &o : lists->stencil())
            {
              Tensor<1, dim> xi;
              for (unsigned int d = 0; d < dim; ++d)
                xi[d] = o.offset[d] * h;
              const double r = xi.norm();
              const double w = o.beta * volume;
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

      for (unsigned int c = 0; c < dim; ++c)
        {
          u_slot[c].resize_fast(layout.n_slots);
          f_slot[c].resize_fast(layout.n_slots);
          std::fill(u_slot[c].begin(), u_slot[c].end(), 0.);
          std::fill(f_slot[c].begin(), f_slot[c].end(), 0.);
        }
      t_slot.resize_fast(layout.n_slots);
      s_slot.resize_fast(layout.n_slots);
      std::fill(t_slot.begin(), t_slot.end(), 0.);
      std::fill(s_slot.begin(), s_slot.end(), 0.);
      for (unsigned int i = 0; i < n; ++i)
        if (lists->has_list(i))
          s_slot[layout.slot[i]] = model->node_factor(m[i]);
        else if (!state_based)
          s_slot[layout.slot[i]] = model->node_factor(0.);

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

      // Every node standard until use_collocation() says otherwise.
      collocation_node.clear();
      with_collocation = false;
      collocation_row  = CollocationRow();
      node_rows        = NodeRows();
      node_row_of.clear();
      collocation_theta.clear();
      collocation_theta_chunks.clear();
      theta_slot.resize_fast(0);
      collocation_chunks.clear();

      layout.index_list_bonds();
      build_work_lists();
    }


    template <int dim>
    void
    BondOperator<dim>::update_bond_state()
    {
      build_work_lists();
    }


    template <int dim>
    void
    BondOperator<dim>::make_stencil_chunks()
    {
      // Runs of consecutive slots of the nodes on the shared stencil that
      // need the pass: every owned node for the forces, every node with a
      // list for the dilatations of a state-based model.
      layout.make_chunks(
        [&](const unsigned int i) {
          return needs_dilatation(i) && !has_collocation_theta(i) &&
                 layout.on_stencil(i);
        },
        theta_work().chunks);
      const unsigned int n_owned = nodes->n_owned();
      layout.make_chunks(
        [&](const unsigned int i) {
          return i < n_owned && !is_collocation_node(i) && layout.on_stencil(i);
        },
        force_work().chunks);
    }


    template <int dim>
    void
    BondOperator<dim>::build_work_lists()
    {
      const unsigned int n       = nodes->size();
      const unsigned int n_owned = nodes->n_owned();
      // (Nodes whose dilatation comes from collocation have a pass of
      // their own.)
      const auto needs_theta = [&](const unsigned int i) {
        return needs_dilatation(i) && !has_collocation_theta(i);
      };
      // (Nodes evaluated by collocation have a pass of their own.)
      const auto needs_force = [&](const unsigned int i) {
        return i < n_owned && !is_collocation_node(i);
      };

      make_stencil_chunks();
      theta_work().full_chunks.clear();
      force_work().full_chunks.clear();
      layout.clear_masks();
      if (layout.use_lattice)
        {
          const auto full = [&](const unsigned int i) {
            return lists->has_full_stencil(i);
          };
          layout.make_chunks(
            [&](const unsigned int i) { return needs_theta(i) && full(i); },
            theta_work().full_chunks);
          layout.make_chunks(
            [&](const unsigned int i) { return needs_force(i) && full(i); },
            force_work().full_chunks);
          if (bond_state != nullptr)
            for (unsigned int i = 0; i < n; ++i)
              if (layout.masks_bonds(i) && bond_state->any_broken(i))
                layout.set_broken_bits(i);
        }

      theta_work().list_nodes.clear();
      force_work().list_nodes.clear();
      layout.list_first.assign(n + 1, 0);
      list_bonds.clear();
      layout.list_stencil_index.clear();
      list_theta_scale.assign(layout.use_lattice ? n : 0, 0.);
      const double m0        = stencil_weighted_volume;
      layout.n_owned_stencil = 0;
      for (unsigned int i = 0; i < n; ++i)
        {
          if ((needs_theta(i) || needs_force(i)) && !layout.on_stencil(i))
            {
              if (needs_theta(i))
                theta_work().list_nodes.push_back(i);
              if (needs_force(i))
                force_work().list_nodes.push_back(i);
              const Point<dim> &x      = (*nodes)[i].location;
              const double      volume = (*nodes)[i].volume();
              if (layout.use_lattice)
                {
                  // The stencil's constants hold for every node of the
                  // lattice; only the dilatation factor d / m_i differs.
                  list_theta_scale[i]     = m[i] > 0 ? m0 / m[i] : 0.;
                  auto             &index = layout.list_stencil_index;
                  const std::size_t first = index.size();
                  index.resize(first + lists->n_bonds(i));
                  index.resize(layout.write_intact_stencil_indices(i, first));
                  layout.list_first[i + 1] = index.size();
                  continue;
                }
              for_each_intact_bond(
                i,
                [&](const unsigned int j, const double w) {
                  const Tensor<1, dim> xi = (*nodes)[j].location - x;
                  const double         r  = xi.norm();
                  ListBond             bond;
                  bond.neighbor_slot = layout.slot[j];
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
              std::sort(list_bonds.begin() + layout.list_first[i],
                        list_bonds.end(),
                        [](const ListBond &a, const ListBond &b) {
                          for (unsigned int d = 0; d < dim; ++d)
                            if (a.n[d] * a.r != b.n[d] * b.r)
                              return a.n[d] * a.r < b.n[d] * b.r;
                          return false;
                        });
            }
          else if (needs_force(i) && layout.on_stencil(i))
            ++layout.n_owned_stencil;
          layout.list_first[i + 1] = layout.use_lattice ?
                                       layout.list_stencil_index.size() :
                                       list_bonds.size();
        }
      layout.list_end.assign(layout.list_first.begin() + 1,
                             layout.list_first.end());
      layout.is_listed.assign(n, 0);
      for (const auto *work :
           {&theta_work().list_nodes, &force_work().list_nodes})
        for (const unsigned int i : *work)
          layout.is_listed[i] = 1;
      layout.bond_visits = layout.count_bond_visits();
      if (layout.use_lattice && state_based)
        {
          theta_run_factor.resize_fast(layout.n_slots);
          for (const unsigned int i : theta_work().list_nodes)
            theta_run_factor[layout.slot[i]] =
              s_slot[layout.slot[i]] * list_theta_scale[i];
        }
      layout.make_runs(theta_work());
      layout.make_runs(force_work());
    }


    template <int dim>
    const std::shared_ptr<const Utilities::MPI::Partitioner> &
    BondOperator<dim>::get_partitioner() const
    {
      return layout.partitioner;
    }


    template <int dim>
    void
    BondOperator<dim>::initialize_dof_vector(VectorType &v) const
    {
      v.reinit(layout.partitioner);
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
      return layout.n_owned_stencil;
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::n_list_nodes() const
    {
      return force_work().list_nodes.size();
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::n_run_nodes() const
    {
      unsigned int count = 0;
      for (const Run &run : force_work().runs)
        count += run.length;
      return count;
    }


    template <int dim>
    unsigned int
    BondOperator<dim>::max_run_length() const
    {
      unsigned int longest = 0;
      for (const Run &run : force_work().runs)
        longest = std::max(longest, run.length);
      return longest;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::n_bond_visits() const
    {
      // (A collocation node visits the entries of its row.)
      std::size_t visits = layout.bond_visits;
      for (const Chunk &chunk : collocation_chunks)
        visits += chunk.length * collocation_row.offset.size();
      return visits + node_rows.neighbor_slot.size();
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
      return layout.memory_consumption() + m.capacity() * sizeof(double) +
             list_bonds.capacity() * sizeof(ListBond) +
             list_theta_scale.capacity() * sizeof(double) +
             (2 * dim + 2) * layout.n_slots * sizeof(double) +
             s0_slot.size() * sizeof(double) +
             (theta_run_factor.size() + e_slot.size()) * sizeof(double);
    }


    template class BondOperator<2>;
    template class BondOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
