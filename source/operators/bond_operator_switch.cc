// BondOperator: the adaptive switch of the hybrid scheme (hybrid-collocation
// paper Eq. 65; doc/collocation.md Sect. 11.1): the scan for bonds of
// collocation nodes that near failure, the nodes it makes standard, and the
// drift bound that says, chunk by chunk, when a scan is due.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond/stencil_extensions.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    BondOperator<dim>::setup_switch_tracking()
    {
      SwitchTracking &t          = tracking;
      t                          = SwitchTracking();
      t.active                   = true;
      const auto        &lattice = lists->lattice();
      const unsigned int n_nodes = nodes->size();
      // Tiles of the side of the stencil's reach (in cells), over the box
      // of the local nodes (owned and ghost): the stencil box of a node
      // lies in the 3^dim tiles around its own.
      int reach = 1;
      for (const auto &o : lists->stencil())
        for (unsigned int d = 0; d < dim; ++d)
          reach = std::max(reach, std::abs(int(o.offset[d])));
      t.tile_side = reach;
      std::array<std::int64_t, dim> lower, upper;
      lower.fill(std::numeric_limits<std::int64_t>::max());
      upper.fill(std::numeric_limits<std::int64_t>::min());
      for (unsigned int i = 0; i < n_nodes; ++i)
        {
          const auto x = lattice.coordinates(i);
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = std::min(lower[d], x[d]);
              upper[d] = std::max(upper[d], x[d]);
            }
        }
      std::size_t n_tiles = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          t.n_tiles[d] =
            n_nodes > 0 ? (upper[d] - lower[d]) / t.tile_side + 1 : 1;
          n_tiles *= t.n_tiles[d];
        }
      // Each node's tile and its lattice neighbour in +e_d (-1: none).
      t.node_tile.resize(n_nodes);
      t.node_neighbor.assign(std::size_t(n_nodes) * dim, -1);
      for (unsigned int i = 0; i < n_nodes; ++i)
        {
          const auto  x    = lattice.coordinates(i);
          std::size_t tile = 0;
          for (int d = dim - 1; d >= 0; --d)
            tile = tile * t.n_tiles[d] + (x[d] - lower[d]) / t.tile_side;
          t.node_tile[i] = tile;
          for (unsigned int d = 0; d < dim; ++d)
            {
              auto y = x;
              ++y[d];
              t.node_neighbor[std::size_t(i) * dim + d] = lattice.node_at(y);
            }
        }
      t.tile_first.assign(n_tiles + 1, 0);
      for (unsigned int i = 0; i < n_nodes; ++i)
        ++t.tile_first[t.node_tile[i] + 1];
      for (std::size_t tile = 0; tile < n_tiles; ++tile)
        t.tile_first[tile + 1] += t.tile_first[tile];
      t.tile_nodes.resize(n_nodes);
      {
        std::vector<std::size_t> next(t.tile_first.begin(),
                                      t.tile_first.end() - 1);
        for (unsigned int i = 0; i < n_nodes; ++i)
          t.tile_nodes[next[t.node_tile[i]]++] = i;
      }
      t.slot_tile.assign(layout.n_slots, 0);
      for (unsigned int i = 0; i < n_nodes; ++i)
        t.slot_tile[layout.slot[i]] = t.node_tile[i];
      // A bond of offset k (r_k = |k| h) joins its nodes by a lattice path
      // of |k|_1 edges inside the node's stencil box (the stencil holds
      // every offset that is componentwise no longer than one of its own),
      // so its extension changes by at most |k|_1 E (E: the largest change
      // of an edge there) and its stretch by |k|_1 E / r_k.
      t.path_factor = 0;
      for (unsigned int k = 0; k < lists->stencil().size(); ++k)
        {
          double norm1 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            norm1 += std::abs(lists->stencil()[k].offset[d]);
          t.path_factor = std::max(t.path_factor, norm1 * stencil.inv_r[k]);
        }
      t.tile_edge.assign(n_tiles, 0.);
      t.tile_block.assign(n_tiles, 0.);
      t.step_change.assign(std::size_t(n_nodes) * dim, 0.);
      t.previous_displacement.assign(std::size_t(n_nodes) * dim, 0.);
      // No scan yet: every node is due (margin 0).
      t.slot_margin.assign(layout.n_slots, 0.);
      t.slot_drift.assign(layout.n_slots, 0.);
      t.chunk_due.assign(collocation_chunks.size(), 0);
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::make_standard(const std::vector<unsigned int> &switched)
    {
      // Nodes that switch with every bond intact stay on the shared stencil:
      // only the stencil chunks of the force pass change (the lists hold
      // the nodes off the stencil, and the masks the broken bonds, which
      // the switch changes neither of). A node that lost a bond (from
      // commit_broken_bonds()) needs a list: everything is rebuilt.
      bool all_on_stencil = layout.use_lattice;
      for (const unsigned int i : switched)
        {
          collocation_node[i] = 0;
          all_on_stencil      = all_on_stencil && layout.on_stencil(i);
        }
      const std::size_t n_switched =
        Utilities::MPI::sum(switched.size(), nodes->get_communicator());
      if (n_switched > 0)
        {
          if (all_on_stencil)
            {
              make_stencil_chunks();
              const unsigned int n_owned = nodes->n_owned();
              layout.make_chunks(
                [&](const unsigned int i) {
                  return i < n_owned && !is_collocation_node(i) &&
                         lists->has_full_stencil(i);
                },
                force_work().full_chunks);
              layout.n_owned_stencil += switched.size();
              layout.bond_visits = layout.count_bond_visits();
              layout.make_runs(theta_work());
              layout.make_runs(force_work());
            }
          else
            build_work_lists();
          layout.make_chunks(
            [&](const unsigned int i) { return is_collocation_node(i); },
            collocation_chunks);
          if (tracking.active)
            tracking.chunk_due.assign(collocation_chunks.size(), 0);
        }
      return n_switched;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::switch_critical_nodes(const VectorType &displacement,
                                             const double      fraction,
                                             const bool        switch_nodes,
                                             const bool        only_due)
    {
      AssertThrow(fraction > 0 && fraction <= 1,
                  ExcMessage("BondOperator::switch_critical_nodes() needs a "
                             "fraction in (0, 1]."));
      const MPI_Comm comm = nodes->get_communicator();
      // No failure criterion (set_kinematics()): no bond can break, no
      // node needs to switch, and none will.
      if (!with_failure)
        {
          scan_margin = std::numeric_limits<double>::infinity();
          return 0;
        }
      AssertThrow(tracking.active || collocation_chunks.empty(),
                  ExcInternalError());
      // A scan of every chunk restarts every node's drift from here.
      if (!only_due && tracking.active)
        {
          const double *values = displacement.begin();
          for (unsigned int i = 0; i < nodes->size(); ++i)
            for (unsigned int c = 0; c < dim; ++c)
              tracking.previous_displacement[std::size_t(i) * dim + c] =
                values[layout.vector_index[i] + c];
        }
      copy_in(displacement);
      std::vector<char>         critical(nodes->n_owned(), 0);
      std::vector<unsigned int> chunk_scanned(collocation_chunks.size(), 0);
      // Every bond of the full stencil of each collocation node (of the
      // chunks that are due), with the kinematics and the stretch of the
      // failure test, vectorised over the slots of a chunk as the force
      // passes are and threaded over the chunks. Per lane the largest
      // s - fraction s0 and s - s0 over the bonds: a - b >= 0 exactly when
      // a >= b, and the margin fraction s0 - s is the negative of the
      // first.
      parallel::apply_to_subranges(
        std::size_t(0),
        collocation_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double over_fraction[chunk_size],
            over_critical[chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              if (only_due && !tracking.chunk_due[c])
                continue;
              const std::size_t  first = collocation_chunks[c].first_slot;
              const unsigned int len   = collocation_chunks[c].length;
              chunk_scanned[c]         = len;
              for (unsigned int l = 0; l < len; ++l)
                {
                  over_fraction[l] = -std::numeric_limits<double>::infinity();
                  over_critical[l] = -std::numeric_limits<double>::infinity();
                }
              const double *s0i            = s0_slot.data() + first;
              const auto    lane_of_offset = [&](const std::size_t    k,
                                              const std::ptrdiff_t o) {
                const double inv_r = stencil.inv_r[k];
                return [&over_fraction,
                        &over_critical,
                        s0i,
                        o,
                        inv_r,
                        fraction](const unsigned int l, const double e) {
                  const double s0      = std::min(s0i[l], s0i[l + o]);
                  const double stretch = e * inv_r;
                  over_fraction[l] =
                    std::max(over_fraction[l], stretch - fraction * s0);
                  over_critical[l] = std::max(over_critical[l], stretch - s0);
                };
              };
              // One loop per kinematics, so that the lane body has no
              // branch.
              if (finite)
                for_each_stencil_extension<true, dim>(stencil,
                                                      layout.stencil_offset,
                                                      u_slot,
                                                      first,
                                                      len,
                                                      lane_of_offset);
              else
                for_each_stencil_extension<false, dim>(stencil,
                                                       layout.stencil_offset,
                                                       u_slot,
                                                       first,
                                                       len,
                                                       lane_of_offset);
              for (unsigned int l = 0; l < len; ++l)
                {
                  const unsigned int i = layout.node_of_slot(first + l);
                  if (over_critical[l] >= 0)
                    // Already past the critical stretch: the switch comes
                    // late (the bond would have broken in the standard
                    // scheme).
                    critical[i] = 2;
                  else if (over_fraction[l] >= 0)
                    critical[i] = 1;
                  // The node's margin, its drift counted from now.
                  if (tracking.active)
                    {
                      tracking.slot_margin[first + l] =
                        critical[i] ? 0. : -over_fraction[l];
                      tracking.slot_drift[first + l] = 0;
                    }
                }
            }
        },
        LoopLayout<dim>::chunk_grain);
      for (const unsigned int n : chunk_scanned)
        tracking.n_scanned += n;
      if (!only_due)
        tracking.n_possible += n_owned_collocation_nodes();
      std::vector<unsigned int> switched;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        if (critical[i])
          {
            switched.push_back(i);
            missed_switches += switch_nodes && critical[i] == 2;
          }
      const std::size_t n_critical =
        switch_nodes ? make_standard(switched) :
                       Utilities::MPI::sum(switched.size(), comm);
      // What is left of the margins of the remaining collocation nodes
      // (infinite: none left on any process; critical_bond_possible() then
      // returns at once, on every process alike).
      double margin = std::numeric_limits<double>::infinity();
      if (tracking.active)
        for (const Chunk &chunk : collocation_chunks)
          for (unsigned int l = 0; l < chunk.length; ++l)
            margin = std::min(margin,
                              tracking.slot_margin[chunk.first_slot + l] -
                                tracking.slot_drift[chunk.first_slot + l]);
      scan_margin = Utilities::MPI::min(margin, comm);
      return n_critical;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::n_owned_collocation_nodes() const
    {
      std::size_t n = 0;
      for (const Chunk &chunk : collocation_chunks)
        n += chunk.length;
      return n;
    }


    template <int dim>
    bool
    BondOperator<dim>::critical_bond_possible(const VectorType &displacement)
    {
      // The same margin on every process: no collocation node left
      // anywhere means no reduction anywhere.
      if (!tracking.active ||
          !(scan_margin < std::numeric_limits<double>::infinity()))
        return false;
      SwitchTracking    &t       = tracking;
      const double      *values  = displacement.begin();
      const unsigned int n_nodes = nodes->size();
      // This step's displacement change of every local node (owned and
      // ghost; exact when old and new are within a factor 2, Sterbenz).
      // Threaded: every entry, edge and tile is its own, and a largest
      // value does not depend on the order it is taken in.
      parallel::apply_to_subranges(
        0u,
        n_nodes,
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int i = begin; i < end; ++i)
            {
              const std::size_t base = layout.vector_index[i];
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const std::size_t q = std::size_t(i) * dim + c;
                  t.step_change[q] =
                    values[base + c] - t.previous_displacement[q];
                  t.previous_displacement[q] = values[base + c];
                }
            }
        },
        LoopLayout<dim>::node_grain);
      // The largest change |du_a - du_b|^2 over the lattice edges
      // (a, a + e_d), in the tile of a.
      const std::size_t n_tiles = t.tile_edge.size();
      parallel::apply_to_subranges(
        std::size_t(0),
        n_tiles,
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t tile = begin; tile < end; ++tile)
            {
              double edge = 0;
              for (std::size_t q = t.tile_first[tile];
                   q < t.tile_first[tile + 1];
                   ++q)
                {
                  const unsigned int a = t.tile_nodes[q];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      const int b = t.node_neighbor[std::size_t(a) * dim + d];
                      if (b < 0)
                        continue;
                      double e2 = 0;
                      for (unsigned int c = 0; c < dim; ++c)
                        {
                          const double diff =
                            t.step_change[std::size_t(a) * dim + c] -
                            t.step_change[std::size_t(b) * dim + c];
                          e2 += diff * diff;
                        }
                      edge = std::max(edge, e2);
                    }
                }
              t.tile_edge[tile] = edge;
            }
        },
        16);
      // Over the 3^dim tiles around each tile: a bound of E for every node
      // of the tile (its stencil box lies in them, and so does the lower
      // end of every edge in that box).
      parallel::apply_to_subranges(
        std::size_t(0),
        n_tiles,
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t tile = begin; tile < end; ++tile)
            {
              std::array<std::int64_t, dim> k, lo, hi;
              std::size_t                   rest = tile;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  k[d] = rest % t.n_tiles[d];
                  rest /= t.n_tiles[d];
                  lo[d] = std::max<std::int64_t>(k[d] - 1, 0);
                  hi[d] = std::min<std::int64_t>(k[d] + 1, t.n_tiles[d] - 1);
                }
              double                        largest = 0;
              std::array<std::int64_t, dim> m       = lo;
              while (true)
                {
                  std::size_t other = 0;
                  for (int d = dim - 1; d >= 0; --d)
                    other = other * t.n_tiles[d] + m[d];
                  largest        = std::max(largest, t.tile_edge[other]);
                  unsigned int d = 0;
                  for (; d < dim; ++d)
                    if (++m[d] <= hi[d])
                      break;
                    else
                      m[d] = lo[d];
                  if (d == dim)
                    break;
                }
              // Rounded up, so that the rounding of the bound never makes
              // it smaller than the change it bounds.
              t.tile_block[tile] =
                std::sqrt(largest) * t.path_factor * (1 + 1e-12);
            }
        },
        64);
      // Each collocation node adds its bound to its drift since its last
      // scan; its chunk is due once the drift reaches the node's margin
      // (with a hair of slack for the rounding of the stretches
      // themselves).
      // (Into the kept flags: no allocation per step.)
      std::vector<char> &due = t.chunk_due;
      due.assign(collocation_chunks.size(), 0);
      parallel::apply_to_subranges(
        std::size_t(0),
        collocation_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t first = collocation_chunks[c].first_slot;
              for (unsigned int l = 0; l < collocation_chunks[c].length; ++l)
                {
                  const std::size_t s = first + l;
                  t.slot_drift[s] += t.tile_block[t.slot_tile[s]];
                  if (t.slot_drift[s] >= t.slot_margin[s] * (1 - 1e-9))
                    due[c] = 1;
                }
            }
        },
        LoopLayout<dim>::chunk_grain);
      t.n_possible += n_owned_collocation_nodes();
      const bool any_due =
        std::any_of(due.begin(), due.end(), [](const char x) { return x; });
      return Utilities::MPI::max(int(any_due), nodes->get_communicator()) > 0;
    }


    template <int dim>
    std::pair<std::size_t, std::size_t>
    BondOperator<dim>::n_scanned_nodes() const
    {
      const MPI_Comm comm = nodes->get_communicator();
      return {Utilities::MPI::sum(tracking.n_scanned, comm),
              Utilities::MPI::sum(tracking.n_possible, comm)};
    }


#define PERIDEAL_INSTANTIATE(dim)                                              \
  template void        BondOperator<dim>::setup_switch_tracking();             \
  template std::size_t BondOperator<dim>::make_standard(                       \
    const std::vector<unsigned int> &);                                        \
  template std::size_t BondOperator<dim>::switch_critical_nodes(               \
    const VectorType &,                                                        \
    const double,                                                              \
    const bool,                                                                \
    const bool);                                                               \
  template bool BondOperator<dim>::critical_bond_possible(const VectorType &); \
  template std::pair<std::size_t, std::size_t>                                 \
  BondOperator<dim>::n_scanned_nodes() const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
