#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <deal.II/lac/full_matrix.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/diffusion_operator.h>
#include <perideal/quadrature/collocation.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      constexpr auto Lattice =
        Quadrature::CollocationSettings::RowKind::lattice;
      constexpr auto PerNode =
        Quadrature::CollocationSettings::RowKind::per_node;
    } // namespace

    template <int dim>
    void
    DiffusionOperator<dim>::reinit(
      const Discretization::NodeSet<dim>      &nodes_,
      const Discretization::NeighborList<dim> &lists_,
      const Models::DiffusionKernel           &kernel_,
      const Discretization::BondState<dim>    *state_)
    {
      nodes      = &nodes_;
      lists      = &lists_;
      kernel     = &kernel_;
      bond_state = state_;
      layout.reinit(nodes_, lists_, state_, true, 1, "DiffusionOperator");
      const auto &lattice = lists->lattice();

      stencil_mu.clear();
      stencil_sum = 0;
      if (layout.use_lattice)
        {
          const double h      = lattice.spacing();
          const double volume = std::pow(h, dim);
          for (const auto &o : lists->stencil())
            {
              double r2 = 0;
              for (unsigned int d = 0; d < dim; ++d)
                r2 += double(o.offset[d]) * o.offset[d];
              const double mu =
                kernel->conductance(std::sqrt(r2) * h) * o.beta * volume;
              stencil_mu.push_back(mu);
              stencil_sum += mu;
            }
        }
      collocation = false;
      bulk_row    = false;
      symbol      = 0;
      row_node.assign(nodes->n_owned(), false);
      row_first.assign(nodes->n_owned() + 1, 0);
      row_entries.clear();
      standard_node.assign(nodes->n_owned(), false);
      keep_interface = false;
      bulk_offset    = layout.stencil_offset;
      bulk_mu        = stencil_mu;
      bulk_sum       = stencil_sum;
      bulk_abs_sum   = stencil_sum;
      // Bond slots and conductances of the owned nodes that do not have the
      // stencil's neighbourhood (those that do are read off the stencil).
      stored_first.assign(nodes->n_owned() + 1, 0);
      stored_bonds.clear();
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          if (!(layout.use_lattice && lists->has_full_stencil(i)))
            {
              const Point<dim> &x = (*nodes)[i].location;
              lists->for_each_bond(
                i,
                [&](const unsigned int, const unsigned int j, const double w) {
                  stored_bonds.push_back(
                    {static_cast<unsigned int>(layout.slot[j]),
                     0,
                     kernel->conductance(x.distance((*nodes)[j].location)) * w,
                     0.});
                });
            }
          stored_first[i + 1] = stored_bonds.size();
        }
      with_phases = false;
      n_phases    = 1;
      factor      = {1.};
      phase_slot.assign(layout.n_slots, 0);
      c_slot.resize_fast(layout.n_slots);
      r_slot.resize_fast(layout.n_slots);
      std::fill(c_slot.begin(), c_slot.end(), 0.);
      std::fill(r_slot.begin(), r_slot.end(), 0.);
      build_work_lists();
    }


    template <int dim>
    void
    DiffusionOperator<dim>::update_bond_state()
    {
      build_work_lists();
    }


    template <int dim>
    void
    DiffusionOperator<dim>::set_phases(
      const std::vector<unsigned char> &phase_of_node,
      const unsigned int                n_phases_,
      const std::vector<double>        &factor_,
      const double                      gate_,
      const std::vector<double>        &rate_)
    {
      AssertThrow(phase_of_node.size() == nodes->size() &&
                    factor_.size() == n_phases_ * n_phases_,
                  ExcMessage("set_phases(): one phase per node of the set "
                             "and square factor and rate tables"));
      AssertThrow(rate_.empty() || rate_.size() == factor_.size(),
                  ExcMessage("set_phases(): a square rate table"));
      with_phases = true;
      n_phases    = n_phases_;
      factor      = factor_;
      gate        = gate_;
      rate        = rate_;
      phase_slot.assign(layout.n_slots, 0);
      for (unsigned int i = 0; i < nodes->size(); ++i)
        {
          AssertThrow(phase_of_node[i] < n_phases, ExcInternalError());
          phase_slot[layout.slot[i]] = phase_of_node[i];
        }
      build_work_lists();
    }


    template <int dim>
    void
    DiffusionOperator<dim>::set_standard_nodes(
      const std::vector<bool> &standard_of_owned,
      const bool               keep_interface_nodes)
    {
      AssertThrow(standard_of_owned.size() == nodes->n_owned(),
                  ExcMessage("set_standard_nodes(): one flag per owned node"));
      standard_node  = standard_of_owned;
      keep_interface = keep_interface_nodes;
      build_work_lists();
    }


    template <int dim>
    void
    DiffusionOperator<dim>::update_switch_bound()
    {
      switch_bound = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const bool on_stencil =
            layout.use_lattice && lists->has_full_stencil(i);
          double bonds = 0, row = 0;
          if (on_stencil)
            bonds = stencil_sum;
          else
            for (std::size_t b = stored_first[i]; b < stored_first[i + 1]; ++b)
              bonds += std::abs(stored_bonds[b].mu);
          if (row_node[i])
            for (std::size_t b = row_first[i]; b < row_first[i + 1]; ++b)
              row += std::abs(row_entries[b].mu);
          else if (bulk_row && on_stencil)
            row = bulk_abs_sum;
          switch_bound = std::max({switch_bound, bonds, row});
        }
    }


    template <int dim>
    void
    DiffusionOperator<dim>::build_work_lists()
    {
      const unsigned int n_owned = nodes->n_owned();
      // Bulk slots with their row (0: the standard stencil, 1: the
      // collocation row) and phase: runs of one row and one phase only.
      std::vector<std::tuple<std::size_t, unsigned char, unsigned char>>
        bulk_slots;
      zero_slots.clear();
      work().list_nodes.clear();
      list_bond_first.assign(1, 0);
      list_bonds.clear();
      list_sum.clear();
      layout.bond_visits    = 0;
      any_special           = false;
      largest_geometric_sum = 0;
      node_by_row.assign(n_owned, false);
      n_row_nodes = 0;
      // With rows, Gershgorin's bound must hold whatever the nodes take
      // later (a node switches between its row and its bonds as interfaces
      // come and go): the bound of both forms, computed once with the rows.
      if (collocation)
        largest_geometric_sum = switch_bound;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          const unsigned char p = phase_slot[layout.slot[i]];
          const bool          intact =
            bond_state == nullptr || !bond_state->any_broken(i);
          const bool on_stencil =
            layout.use_lattice && lists->has_full_stencil(i);
          // Whether the node's neighbourhood (its bonds) holds one phase
          // only: a row has no phase factors, so a node at an interface is
          // evaluated with its bonds.
          bool uniform = true;
          if (with_phases)
            {
              if (on_stencil)
                for (std::size_t k = 0;
                     k < layout.stencil_offset.size() && uniform;
                     ++k)
                  uniform =
                    phase_slot[layout.slot[i] + layout.stencil_offset[k]] == p;
              else
                for (std::size_t b = stored_first[i];
                     b < stored_first[i + 1] && uniform;
                     ++b)
                  uniform = phase_slot[stored_bonds[b].slot] == p;
            }
          if (!uniform && keep_interface)
            standard_node[i] = true;
          const bool by_row = uniform && intact && !standard_node[i] &&
                              (row_node[i] || (bulk_row && on_stencil));
          node_by_row[i] = by_row;
          n_row_nodes += by_row;
          if (on_stencil && intact && uniform && !(by_row && row_node[i]))
            {
              const unsigned char row = by_row ? 1 : 0;
              const double abs_sum    = row == 1 ? bulk_abs_sum : stencil_sum;
              largest_geometric_sum = std::max(largest_geometric_sum, abs_sum);
              if (factor[p * n_phases + p] == 0)
                zero_slots.push_back(layout.slot[i]);
              else
                {
                  bulk_slots.emplace_back(layout.slot[i], row, p);
                  layout.bond_visits +=
                    row == 1 ? bulk_mu.size() : stencil_mu.size();
                }
              continue;
            }
          double     sum = 0, geometric = 0;
          const auto add = [&](const bool         bond,
                               const unsigned int k,
                               const std::size_t  slot_j,
                               const double       mu) {
            // A collocation row's entries are not bonds (its node has
            // none broken), and its weights may be negative.
            if (bond && bond_state != nullptr && bond_state->is_broken(i, k))
              return;
            geometric += std::abs(mu);
            const unsigned char q = phase_slot[slot_j];
            const double        f = factor[p * n_phases + q];
            const double        r = rate.empty() ? 0. : rate[p * n_phases + q];
            if (f == 0 && r == 0)
              return;
            unsigned char gated = 0;
            if (with_phases && p != q && (p == 0 || q == 0) &&
                std::isfinite(gate))
              gated = p == 0 ? 1 : 2;
            any_special = any_special || gated != 0 || r != 0;
            list_bonds.push_back(
              {static_cast<unsigned int>(slot_j), gated, f * mu, r * mu});
            sum += f * mu;
          };
          if (by_row && row_node[i])
            for (std::size_t b = row_first[i]; b < row_first[i + 1]; ++b)
              add(false, 0, row_entries[b].slot, row_entries[b].mu);
          else if (layout.use_lattice && lists->has_full_stencil(i))
            for (unsigned int k = 0; k < stencil_mu.size(); ++k)
              add(true,
                  k,
                  layout.slot[i] + layout.stencil_offset[k],
                  stencil_mu[k]);
          else
            for (std::size_t b = stored_first[i]; b < stored_first[i + 1]; ++b)
              add(true,
                  b - stored_first[i],
                  stored_bonds[b].slot,
                  stored_bonds[b].mu);
          largest_geometric_sum = std::max(largest_geometric_sum, geometric);
          work().list_nodes.push_back(i);
          list_bond_first.push_back(list_bonds.size());
          list_sum.push_back(sum);
          layout.bond_visits += list_bond_first.back() -
                                list_bond_first[list_bond_first.size() - 2];
        }
      layout.n_owned_stencil = bulk_slots.size() + zero_slots.size();
      // Sorted by slot (the tuple's first entry, unique): runs along the
      // slots, cut where the row or the phase changes.
      std::sort(bulk_slots.begin(), bulk_slots.end());
      std::vector<std::size_t>   sorted_slots;
      std::vector<unsigned char> row_of_slot(
        bulk_slots.empty() ? 0 : std::get<0>(bulk_slots.back()) + 1,
        0);
      for (const auto &bulk : bulk_slots)
        {
          sorted_slots.push_back(std::get<0>(bulk));
          row_of_slot[std::get<0>(bulk)] = std::get<1>(bulk);
        }
      LoopLayout<dim>::cut_into_chunks(
        sorted_slots,
        [&](const Chunk &chunk, const std::size_t s) {
          return phase_slot[chunk.first_slot] == phase_slot[s] &&
                 row_of_slot[chunk.first_slot] == row_of_slot[s];
        },
        work().chunks);
      chunk_factor.clear();
      chunk_row.clear();
      for (const Chunk &chunk : work().chunks)
        {
          const unsigned char p = phase_slot[chunk.first_slot];
          chunk_factor.push_back(factor[p * n_phases + p]);
          chunk_row.push_back(row_of_slot[chunk.first_slot]);
        }
    }


    template <int dim>
    const std::shared_ptr<const Utilities::MPI::Partitioner> &
    DiffusionOperator<dim>::get_partitioner() const
    {
      return layout.partitioner;
    }


    template <int dim>
    void
    DiffusionOperator<dim>::initialize_vector(VectorType &v) const
    {
      v.reinit(layout.partitioner);
    }


    template <int dim>
    void
    DiffusionOperator<dim>::copy_in(const VectorType &concentration) const
    {
      const double *values = concentration.begin();
      layout.for_each_node(nodes->size(), [&](const unsigned int i) {
        c_slot[layout.slot[i]] = values[layout.vector_index[i]];
      });
    }


    template <int dim>
    void
    DiffusionOperator<dim>::apply(const VectorType &concentration,
                                  VectorType       &result) const
    {
      copy_in(concentration);
      const double *c = c_slot.data();

      // The uniform bulk: sum_k mu_k (c_{s+o_k} - c_s), vectorised over a
      // run of consecutive slots, offsets outside (the shared stencil's
      // conductances, or the collocation row's weights: the chunk's row).
      const std::array<const std::vector<std::ptrdiff_t> *, 2> row_offsets = {
        {&layout.stencil_offset, &bulk_offset}};
      const std::array<const std::vector<double> *, 2> row_mu = {
        {&stencil_mu, &bulk_mu}};
      const auto &chunks = work().chunks;
      layout.for_chunk_ranges(
        chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double sum[chunk_size];
          for (std::size_t q = begin; q < end; ++q)
            {
              const std::size_t  s0     = chunks[q].first_slot;
              const unsigned int len    = chunks[q].length;
              const double      *ci     = c + s0;
              const auto        &offset = *row_offsets[chunk_row[q]];
              const auto        &weight = *row_mu[chunk_row[q]];
              for (unsigned int l = 0; l < len; ++l)
                sum[l] = 0;
              for (std::size_t k = 0; k < weight.size(); ++k)
                {
                  const double  mu = weight[k];
                  const double *cj = ci + offset[k];
#pragma omp simd
                  for (unsigned int l = 0; l < len; ++l)
                    sum[l] += mu * (cj[l] - ci[l]);
                }
              for (unsigned int l = 0; l < len; ++l)
                r_slot[s0 + l] = chunk_factor[q] * sum[l];
            }
        });

      // Nodes with lists.
      const auto &list_nodes = work().list_nodes;
      parallel::apply_to_subranges(
        std::size_t(0),
        list_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t q = begin; q < end; ++q)
            {
              const double ci  = c[layout.slot[list_nodes[q]]];
              double       sum = 0;
              if (!any_special)
                for (std::size_t b = list_bond_first[q];
                     b < list_bond_first[q + 1];
                     ++b)
                  sum += list_bonds[b].mu * (c[list_bonds[b].slot] - ci);
              else
                for (std::size_t b = list_bond_first[q];
                     b < list_bond_first[q + 1];
                     ++b)
                  {
                    const ListBond &bond = list_bonds[b];
                    const double    cj   = c[bond.slot];
                    // An interface bond conducts while its phase-0 end is
                    // below the gate.
                    if (bond.gated != 0 && (bond.gated == 1 ? ci : cj) >= gate)
                      continue;
                    sum += bond.mu * (cj - ci) + bond.flow;
                  }
              r_slot[layout.slot[list_nodes[q]]] = sum;
            }
        },
        LoopLayout<dim>::node_grain);

      for (const auto s : zero_slots)
        r_slot[s] = 0;

      double *out = result.begin();
      layout.for_each_node(nodes->n_owned(), [&](const unsigned int i) {
        out[layout.vector_index[i]] = r_slot[layout.slot[i]];
      });
    }


    template <int dim>
    void
    DiffusionOperator<dim>::row_sums(VectorType &sums) const
    {
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const unsigned char p = phase_slot[layout.slot[i]];
          sums.local_element(layout.vector_index[i]) =
            (node_by_row[i] ? bulk_sum : stencil_sum) *
            factor[p * n_phases + p];
        }
      for (std::size_t q = 0; q < work().list_nodes.size(); ++q)
        sums.local_element(layout.vector_index[work().list_nodes[q]]) =
          list_sum[q];
    }


    template <int dim>
    double
    DiffusionOperator<dim>::gershgorin_bound() const
    {
      const double largest_factor =
        *std::max_element(factor.begin(), factor.end());
      return 2 * largest_factor *
             Utilities::MPI::max(largest_geometric_sum,
                                 nodes->get_communicator());
    }


    template <int dim>
    double
    DiffusionOperator<dim>::largest_row_sum() const
    {
      return Utilities::MPI::max(largest_geometric_sum,
                                 nodes->get_communicator());
    }


    template <int dim>
    double
    DiffusionOperator<dim>::estimate_spectral_radius(
      const unsigned int n_iterations) const
    {
      // Power method on L from a fixed, partition-independent start vector
      // that excites the shortest waves: (-1)^(sum of lattice indices) on a
      // lattice, a hash of the global index otherwise.
      VectorType x, y;
      initialize_vector(x);
      initialize_vector(y);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const auto g = (*nodes)[i].dofs[0] / dim;
          double     v = 1. + 0.5 * std::sin(1.7 * double(g));
          if (layout.use_lattice)
            {
              std::int64_t parity = 0;
              for (const auto c : lists->lattice().coordinates(i))
                parity += c;
              v *= (parity % 2 == 0 ? 1. : -1.);
            }
          x.local_element(layout.vector_index[i]) = v;
        }
      double lambda = 0;
      for (unsigned int it = 0; it < n_iterations; ++it)
        {
          const double norm = x.l2_norm();
          if (norm == 0)
            break;
          x /= norm;
          x.update_ghost_values();
          apply(x, y);
          lambda = y.l2_norm();
          x.swap(y);
          x.zero_out_ghost_values();
        }
      return lambda;
    }


    template <int dim>
    unsigned int
    DiffusionOperator<dim>::n_stencil_nodes() const
    {
      return layout.n_owned_stencil;
    }


    template <int dim>
    unsigned int
    DiffusionOperator<dim>::n_list_nodes() const
    {
      return work().list_nodes.size();
    }


    template <int dim>
    std::size_t
    DiffusionOperator<dim>::n_bond_visits() const
    {
      return layout.bond_visits;
    }


    template <int dim>
    std::size_t
    DiffusionOperator<dim>::memory_consumption() const
    {
      return sizeof(*this) + layout.memory_consumption() +
             stencil_mu.capacity() * sizeof(double) +
             chunk_factor.capacity() * sizeof(double) +
             list_bond_first.capacity() * sizeof(std::size_t) +
             list_bonds.capacity() * sizeof(ListBond) +
             list_sum.capacity() * sizeof(double) +
             stored_first.capacity() * sizeof(std::size_t) +
             stored_bonds.capacity() * sizeof(ListBond) +
             row_first.capacity() * sizeof(std::size_t) +
             row_entries.capacity() * sizeof(ListBond) + chunk_row.capacity() +
             (row_node.capacity() + standard_node.capacity() +
              node_by_row.capacity()) /
               8 +
             bulk_offset.capacity() * sizeof(std::ptrdiff_t) +
             bulk_mu.capacity() * sizeof(double) +
             zero_slots.capacity() * sizeof(std::size_t) +
             phase_slot.capacity() +
             (c_slot.memory_consumption() + r_slot.memory_consumption());
    }


    template <int dim>
    double
    DiffusionOperator<dim>::use_collocation(
      const Quadrature::CollocationSettings &settings)
    {
      AssertThrow(layout.use_lattice && !with_phases,
                  ExcMessage("DiffusionOperator: the collocation quadrature "
                             "needs a uniform grid and no phases."));
      // On the lattice 'none' changes a row only where 'automatic' would
      // stabilise it: order 4.
      AssertThrow(
        settings.stabilisation_mode !=
            Quadrature::CollocationSettings::Stabilisation::none ||
          settings.order == 4,
        ExcInvalidInput("Quadrature/collocation/Stabilisation",
                        "none",
                        "on a uniform grid 'automatic' leaves the order-"
                        "2 row as the paper gives it (it stabilises only rows "
                        "per node, on irregular nodes), so the entry has no "
                        "effect; remove it"));
      // The family of a bulk node: itself and the stencil offsets within
      // the horizon, with their stencil index.
      const double                h       = lists->lattice().spacing();
      const double                horizon = kernel->get_horizon();
      std::vector<Tensor<1, dim>> family(1);
      std::vector<int>            stencil_index(1, -1);
      for (unsigned int k = 0; k < lists->stencil().size(); ++k)
        {
          Tensor<1, dim> xi;
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = lists->stencil()[k].offset[d] * h;
          if (xi.norm() <= horizon * (1 + 1e-12))
            {
              family.push_back(xi);
              stencil_index.push_back(k);
            }
        }
      const Quadrature::CollocationFit<dim> fit(
        settings.order,
        settings.n_collocation,
        horizon,
        settings.weight_radius_factor(Lattice) * horizon);
      const std::vector<unsigned int> selected = fit.select(family);
      std::vector<Tensor<1, dim>>     cloud;
      for (const unsigned int j : selected)
        cloud.push_back(family[j]);
      AssertThrow(
        cloud.size() >= fit.basis().size(),
        ExcInvalidInput("Quadrature/collocation/Collocation nodes",
                        std::to_string(settings.n_collocation),
                        "the auxiliary grid for it gives " +
                          std::to_string(cloud.size()) +
                          " collocation nodes at this m-ratio, and a fit of "
                          "order " +
                          std::to_string(settings.order) + " needs at least " +
                          std::to_string(fit.basis().size()) +
                          "; ask for more nodes (0: the default), a lower "
                          "'Order' or a larger m-ratio"));
      FullMatrix<double> q;
      const double       condition = fit.fit(cloud, q);
      const bool         well_conditioned =
        condition <= Quadrature::CollocationSettings::condition_limit;
      AssertThrow(
        well_conditioned || settings.fall_back,
        ExcInvalidInput("Quadrature/collocation/Ill-conditioned clouds",
                        "error",
                        "the collocation cloud of the bulk nodes (" +
                          std::to_string(cloud.size()) + " nodes, order " +
                          std::to_string(settings.order) +
                          ") has cond(A) = " + format_number(condition) +
                          " > 1e12; choose another 'Collocation nodes' or "
                          "'Order', or 'fall back' to the standard scheme"));
      if (!well_conditioned)
        return condition;
      const auto moments = Quadrature::scalar_moments<dim>(
        fit.basis(),
        [&](const double r) { return kernel->conductance(r); },
        horizon);
      std::vector<double> row = Quadrature::scalar_row(moments, q);
      if (settings.stabilisation(Lattice) > 0)
        Quadrature::add_stabilisation<dim>(
          row,
          fit.basis(),
          cloud,
          q,
          [&](const double r) { return kernel->conductance(r); },
          horizon,
          settings.stabilisation(Lattice));
      {
        std::vector<Tensor<2, dim>> blocks;
        for (const double w : row)
          {
            Tensor<2, dim> block;
            for (unsigned int d = 0; d < dim; ++d)
              block[d][d] = w;
            blocks.push_back(block);
          }
        symbol = Quadrature::largest_symbol_eigenvalue<dim>(cloud,
                                                            blocks,
                                                            h,
                                                            dim == 3 ? 12 : 40);
      }
      collocation = true;
      bulk_row    = true;
      bulk_offset.clear();
      bulk_mu.clear();
      bulk_sum     = 0;
      bulk_abs_sum = 0;
      // Without the node itself (sum_k w_k = 0 to round-off): in the order
      // of the cloud, fixed by the bond vectors.
      for (unsigned int j = 0; j < cloud.size(); ++j)
        {
          const int k = stencil_index[selected[j]];
          if (k < 0)
            continue;
          bulk_offset.push_back(layout.stencil_offset[k]);
          bulk_mu.push_back(row[j]);
          bulk_sum += row[j];
          bulk_abs_sum += std::abs(row[j]);
        }
      AssertThrow(bulk_sum > 0,
                  ExcInvalidInput(
                    "Quadrature/collocation/Order",
                    std::to_string(settings.order),
                    "the bulk collocation row of this order at this m-ratio "
                    "weighs its own node against its neighbours (a "
                    "non-positive diagonal; doc/collocation.md Sect. 7): "
                    "the operator has growing modes. Use 'Order = 2'" +
                      settings.stabilisation_hint()));
      update_switch_bound();
      build_work_lists();
      return condition;
    }


    template <int dim>
    CollocationReport
    DiffusionOperator<dim>::use_collocation_per_node(
      const Quadrature::CollocationSettings &settings)
    {
      AssertThrow(!with_phases,
                  ExcMessage("DiffusionOperator: the collocation quadrature "
                             "takes no phases."));
      if constexpr (dim == 1)
        {
          (void)settings;
          AssertThrow(false,
                      ExcMessage("DiffusionOperator: collocation rows per "
                                 "node are built in 2D and 3D."));
          return CollocationReport();
        }
      else
        {
          const unsigned int n_owned = nodes->n_owned();
          const double       horizon = kernel->get_horizon();
          // Nodes with a broken (insulating) bond keep their bonds, and so
          // do the hybrid scheme's standard nodes.
          std::vector<bool> standard = standard_node;
          if (bond_state != nullptr)
            for (unsigned int i = 0; i < n_owned; ++i)
              standard[i] = standard[i] || bond_state->any_broken(i);
          // Rows per node take the stabilised form for order 2 as well
          // (doc/collocation.md Sect. 7.2). A bad order-4 cloud takes an
          // order-2 row ('fall back').
          const auto conductance = [&](const double r) {
            return kernel->conductance(r);
          };
          NodeRowFits<dim, double> fits;
          const CollocationReport  report =
            fit_node_rows_with_fallback<dim, double>(
              *nodes,
              *lists,
              horizon,
              settings,
              standard,
              [&](const Quadrature::CollocationSettings &pass,
                  const Quadrature::CollocationFit<dim> &fit)
                -> RowOfFit<dim, double> {
                const auto moments =
                  Quadrature::scalar_moments<dim>(fit.basis(),
                                                  conductance,
                                                  horizon);
                const double gamma = pass.stabilisation(PerNode);
                return [&, moments, gamma, basis = fit.basis()](
                         const unsigned int,
                         const std::vector<Tensor<1, dim>> &cloud,
                         const FullMatrix<double>          &q) {
                  std::vector<double> row = Quadrature::scalar_row(moments, q);
                  if (gamma > 0)
                    Quadrature::add_stabilisation<dim>(row,
                                                       basis,
                                                       cloud,
                                                       q,
                                                       conductance,
                                                       horizon,
                                                       gamma);
                  return row;
                };
              },
              fits);

          // The rows beside the stored bonds (a node at a phase interface
          // goes back to its bonds).
          row_first.assign(1, 0);
          row_entries.clear();
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              row_node[i] = fits.has_row[i];
              if (fits.has_row[i])
                for (unsigned int k = 0; k < fits.neighbors[i].size(); ++k)
                  row_entries.push_back({static_cast<unsigned int>(
                                           layout.slot[fits.neighbors[i][k]]),
                                         0,
                                         fits.weights[i][k],
                                         0.});
              row_first.push_back(row_entries.size());
            }
          collocation = report.n_collocation_nodes > 0;
          update_switch_bound();
          build_work_lists();
          return report;
        }
    }


    template class DiffusionOperator<1>;
    template class DiffusionOperator<2>;
    template class DiffusionOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
