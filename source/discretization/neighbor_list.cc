#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>

namespace PeriDEAL
{
  namespace Discretization
  {
    namespace
    {
      template <int dim>
      struct BucketHash
      {
        std::size_t
        operator()(const std::array<int, dim> &key) const
        {
          std::size_t h = 0;
          for (const int k : key)
            h = h * 1000003u ^ static_cast<std::size_t>(k + (1 << 20));
          return h;
        }
      };
    } // namespace


    template <int dim>
    void
    NeighborList<dim>::reinit(const NodeSet<dim>                   &nodes,
                              const double                          horizon,
                              const Quadrature::PartialVolume<dim> &algorithm,
                              const bool with_ghost_lists,
                              const bool store_full_lists)
    {
      const unsigned int n = nodes.size();

      grid.reinit(nodes);
      uniform        = grid.is_uniform();
      const double h = grid.spacing();

      std::unique_ptr<Quadrature::UniformGridWeights<dim>> table;
      full_stencil.clear();
      if (uniform)
        {
          table =
            std::make_unique<Quadrature::UniformGridWeights<dim>>(algorithm,
                                                                  horizon / h);
          full_stencil = table->neighbours();
        }
      // Offset -> stencil index, dense over [-bound, bound]^dim.
      stencil_bound = 0;
      for (const auto &o : full_stencil)
        for (unsigned int d = 0; d < dim; ++d)
          stencil_bound = std::max(stencil_bound, std::abs(o.offset[d]));
      {
        std::size_t size = 1;
        for (unsigned int d = 0; d < dim; ++d)
          size *= 2 * stencil_bound + 1;
        offset_to_stencil.assign(full_stencil.empty() ? 0 : size, -1);
        for (unsigned int k = 0; k < full_stencil.size(); ++k)
          {
            std::size_t q = 0;
            for (int d = dim - 1; d >= 0; --d)
              q = q * (2 * stencil_bound + 1) +
                  (full_stencil[k].offset[d] + stencil_bound);
            offset_to_stencil[q] = k;
          }
      }

      // Bucket grid: a neighbour's centre lies within horizon + half a cell
      // diameter, so the adjacent buckets hold every candidate.
      // Nodes off their cells' centres (NodeSet::set_perturbation()) reach
      // that much farther: the largest offset of any node, on every
      // process.
      double shift = 0;
      for (unsigned int j = 0; j < n; ++j)
        shift =
          std::max(shift, nodes[j].location.distance(nodes[j].cell.center()));
      shift              = Utilities::MPI::max(shift, nodes.get_communicator());
      const double reach = horizon + 0.5 * nodes.max_cell_diameter() + shift;
      const double bucket = reach;
      auto         key_of = [&](const Point<dim> &p) {
        std::array<int, dim> key;
        for (unsigned int d = 0; d < dim; ++d)
          key[d] = static_cast<int>(std::floor(p[d] / bucket));
        return key;
      };
      std::unordered_map<std::array<int, dim>,
                         std::vector<unsigned int>,
                         BucketHash<dim>>
        buckets;
      if (!uniform)
        for (unsigned int j = 0; j < n; ++j)
          buckets[key_of(nodes[j].location)].push_back(j);

      // (The bucket search: off the lattice.)
      auto weight_of = [&](const unsigned int i, const unsigned int j) {
        // Nodes moved off their cells' centres: the exact fraction of j's
        // cell in i's ball differs from that of i's cell in j's ball, so the
        // bond takes their mean (the same at both ends: the pair forces
        // stay equal and opposite, the operator symmetric).
        if (shift > 0)
          return 0.5 *
                 (algorithm.weight(nodes[i].location, horizon, nodes[j].cell) +
                  algorithm.weight(nodes[j].location, horizon, nodes[i].cell));
        return algorithm.weight(nodes[i].location, horizon, nodes[j].cell);
      };

      listed.assign(n, 0);
      full.assign(n, 0);
      stored.assign(n, 0);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        listed[i] = 1;
      std::vector<unsigned int> n_bonds_of(n, 0);

      // On the lattice: the stencil as slot differences, for the nodes
      // whose whole stencil lies inside the local box.
      std::vector<std::ptrdiff_t> stencil_slots;
      for (const auto &o : full_stencil)
        stencil_slots.push_back(grid.slot_offset(o.offset));
      auto count_lattice_neighbours = [&](const unsigned int i) {
        const auto  &xi     = grid.coordinates(i);
        unsigned int n_here = 0;
        if (grid.box_holds(xi, stencil_bound))
          {
            const std::size_t s = grid.slot(i);
            for (const std::ptrdiff_t o : stencil_slots)
              n_here += (grid.node_at_slot(s + o) >= 0);
            return n_here;
          }
        for (const auto &o : full_stencil)
          {
            std::array<std::int64_t, dim> y = xi;
            for (unsigned int d = 0; d < dim; ++d)
              y[d] += o.offset[d];
            n_here += (grid.node_at(y) >= 0);
          }
        return n_here;
      };

      // A list in the order of the neighbours' first DoF (deterministic,
      // independent of the search and of the partition), with the keys
      // read once per bond rather than once per comparison.
      auto sort_by_dof =
        [&](Bond                                                  *first,
            Bond                                                  *last,
            std::vector<std::pair<types::global_dof_index, Bond>> &keyed) {
          keyed.clear();
          for (const Bond *bond = first; bond != last; ++bond)
            keyed.emplace_back(nodes[bond->neighbor].dofs[0], *bond);
          std::sort(keyed.begin(),
                    keyed.end(),
                    [](const auto &p, const auto &q) {
                      return p.first < q.first;
                    });
          for (const auto &entry : keyed)
            *first++ = entry.second;
        };

      if (uniform)
        {
          // On the lattice the neighbours are the stencil's offsets that
          // hold a node: no search, no distance test. Three threaded
          // passes, each node writing only its own entries: which
          // off-process nodes get a list, then every listed node's count
          // (a node with its whole stencil keeps only that), then the
          // stored lists, written straight into their place.
          const unsigned int n_owned = nodes.n_owned();
          if (with_ghost_lists)
            {
              // The off-process nodes in the stencil of an owned node. The
              // stencil is symmetric (a ball's partial volumes: offset o
              // and -o weigh the same), so they are the ghosts with an
              // owned node in their own stencil.
              for (const auto &o : full_stencil)
                {
                  std::size_t q = 0;
                  for (int d = dim - 1; d >= 0; --d)
                    q = q * (2 * stencil_bound + 1) +
                        (-o.offset[d] + stencil_bound);
                  AssertThrow(offset_to_stencil[q] >= 0, ExcInternalError());
                }
              parallel::apply_to_subranges(
                n_owned,
                n,
                [&](const unsigned int begin, const unsigned int end) {
                  for (unsigned int j = begin; j < end; ++j)
                    for (const auto &o : full_stencil)
                      {
                        std::array<std::int64_t, dim> y = grid.coordinates(j);
                        for (unsigned int d = 0; d < dim; ++d)
                          y[d] += o.offset[d];
                        const int i = grid.node_at(y);
                        if (i >= 0 && static_cast<unsigned int>(i) < n_owned)
                          {
                            listed[j] = 1;
                            break;
                          }
                      }
                },
                256);
            }
          parallel::apply_to_subranges(
            0u,
            n,
            [&](const unsigned int begin, const unsigned int end) {
              for (unsigned int i = begin; i < end; ++i)
                if (listed[i])
                  {
                    n_bonds_of[i] = count_lattice_neighbours(i);
                    full[i]       = (n_bonds_of[i] == full_stencil.size());
                    stored[i]     = store_full_lists || !full[i];
                  }
            },
            1024);
          offsets.assign(n + 1, 0);
          for (unsigned int i = 0; i < n; ++i)
            offsets[i + 1] =
              offsets[i] + (listed[i] && stored[i] ? n_bonds_of[i] : 0);
          all_bonds.assign(offsets[n], Bond());
          parallel::apply_to_subranges(
            0u,
            n,
            [&](const unsigned int begin, const unsigned int end) {
              std::vector<std::pair<types::global_dof_index, Bond>> keyed;
              for (unsigned int i = begin; i < end; ++i)
                if (offsets[i + 1] > offsets[i])
                  {
                    Bond *const first = all_bonds.data() + offsets[i];
                    Bond       *bond  = first;
                    for (const auto &o : full_stencil)
                      {
                        std::array<std::int64_t, dim> y = grid.coordinates(i);
                        for (unsigned int d = 0; d < dim; ++d)
                          y[d] += o.offset[d];
                        const int j = grid.node_at(y);
                        if (j >= 0)
                          *bond++ = {static_cast<unsigned int>(j),
                                     o.beta * nodes[j].volume()};
                      }
                    Assert(bond == all_bonds.data() + offsets[i + 1],
                           ExcInternalError());
                    sort_by_dof(first, bond, keyed);
                  }
            },
            256);
        }
      else
        {
          // The bucket search, one node after the other.
          std::vector<std::vector<Bond>>                        lists(n);
          std::vector<std::pair<types::global_dof_index, Bond>> keyed;
          auto build = [&](const unsigned int i) {
            const Point<dim>          &x   = nodes[i].location;
            const std::array<int, dim> key = key_of(x);
            std::array<int, dim>       k;
            const unsigned int         n_adjacent = std::pow(3, dim);
            for (unsigned int a = 0; a < n_adjacent; ++a)
              {
                unsigned int code = a;
                for (unsigned int d = 0; d < dim; ++d, code /= 3)
                  k[d] = key[d] + static_cast<int>(code % 3) - 1;
                const auto bucket_nodes = buckets.find(k);
                if (bucket_nodes == buckets.end())
                  continue;
                for (const unsigned int j : bucket_nodes->second)
                  if (j != i &&
                      x.distance_square(nodes[j].location) < reach * reach)
                    {
                      const double beta = weight_of(i, j);
                      if (beta > 0)
                        lists[i].push_back({j, beta * nodes[j].volume()});
                    }
              }
            sort_by_dof(lists[i].data(),
                        lists[i].data() + lists[i].size(),
                        keyed);
            n_bonds_of[i] = lists[i].size();
            stored[i]     = 1;
          };
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            build(i);
          if (with_ghost_lists)
            for (unsigned int i = 0; i < nodes.n_owned(); ++i)
              for (const Bond &bond : lists[i])
                if (!listed[bond.neighbor])
                  {
                    listed[bond.neighbor] = 1;
                    build(bond.neighbor);
                  }
          offsets.assign(n + 1, 0);
          for (unsigned int i = 0; i < n; ++i)
            offsets[i + 1] = offsets[i] + lists[i].size();
          all_bonds.clear();
          all_bonds.reserve(offsets[n]);
          for (const auto &list : lists)
            all_bonds.insert(all_bonds.end(), list.begin(), list.end());
        }
      owned_bonds = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        owned_bonds += n_bonds_of[i];
    }


    template <int dim>
    bool
    NeighborList<dim>::has_list(const unsigned int i) const
    {
      return listed[i];
    }


    template <int dim>
    bool
    NeighborList<dim>::has_full_stencil(const unsigned int i) const
    {
      return full[i];
    }


    template <int dim>
    bool
    NeighborList<dim>::has_stored_list(const unsigned int i) const
    {
      return listed[i] && stored[i];
    }


    template <int dim>
    unsigned int
    NeighborList<dim>::n_bonds(const unsigned int i) const
    {
      if (!listed[i])
        return 0;
      return full[i] ? full_stencil.size() : offsets[i + 1] - offsets[i];
    }


    template <int dim>
    const std::vector<Quadrature::WeightedOffset<dim>> &
    NeighborList<dim>::stencil() const
    {
      return full_stencil;
    }


    template <int dim>
    int
    NeighborList<dim>::stencil_index(const unsigned int i,
                                     const unsigned int j) const
    {
      if (offset_to_stencil.empty())
        return -1;
      std::size_t q = 0;
      for (int d = dim - 1; d >= 0; --d)
        {
          const std::int64_t o =
            grid.coordinates(j)[d] - grid.coordinates(i)[d];
          if (o < -stencil_bound || o > stencil_bound)
            return -1;
          q = q * (2 * stencil_bound + 1) + (o + stencil_bound);
        }
      return offset_to_stencil[q];
    }


    template <int dim>
    const Lattice<dim> &
    NeighborList<dim>::lattice() const
    {
      return grid;
    }


    template <int dim>
    ArrayView<const Bond>
    NeighborList<dim>::bonds(const unsigned int i) const
    {
      Assert(listed[i], ExcMessage("This node has no neighbour list."));
      Assert(stored[i],
             ExcMessage("This node's list is its full stencil and was not "
                        "stored: iterate over stencil() instead."));
      return make_array_view(all_bonds.data() + offsets[i],
                             all_bonds.data() + offsets[i + 1]);
    }


    template <int dim>
    std::size_t
    NeighborList<dim>::n_owned_bonds() const
    {
      return owned_bonds;
    }


    template <int dim>
    bool
    NeighborList<dim>::used_uniform_grid_table() const
    {
      return uniform;
    }


    template class NeighborList<1>;
    template class NeighborList<2>;
    template class NeighborList<3>;
  } // namespace Discretization
} // namespace PeriDEAL
