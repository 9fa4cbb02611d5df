#include <deal.II/base/mpi.h>

#include <deal.II/fe/fe.h>

#include <deal.II/boost_adaptors/bounding_box.h>

#include <deal.II/numerics/rtree.h>

#include <perideal/discretization/node_set.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  namespace Discretization
  {
    template <int dim>
    double
    box_distance_squared(const BoundingBox<dim> &a, const BoundingBox<dim> &b)
    {
      double d2 = 0;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double gap = std::max({0.,
                                       a.lower_bound(d) - b.upper_bound(d),
                                       b.lower_bound(d) - a.upper_bound(d)});
          d2 += gap * gap;
        }
      return d2;
    }


    template <int dim>
    BoundingBox<dim>
    cell_box(const CellAccessor<dim> &cell)
    {
      // A box iff every vertex is a corner of the bounding box and the
      // vertices are 2^dim distinct corners. (Comparing cell.measure() with
      // the box volume instead loses digits to cancellation on small cells
      // far from the origin and rejected fine Cartesian meshes.)
      const BoundingBox<dim>      box       = cell.bounding_box();
      const double                tolerance = 1e-10 * cell.diameter();
      bool                        is_box    = cell.n_vertices() == (1u << dim);
      std::array<bool, 1u << dim> corner_seen{};
      for (const unsigned int v : cell.vertex_indices())
        {
          unsigned int corner = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double x   = cell.vertex(v)[d];
              const bool lower = std::abs(x - box.lower_bound(d)) <= tolerance;
              const bool upper = std::abs(x - box.upper_bound(d)) <= tolerance;
              is_box = is_box && (lower || upper) && !(lower && upper);
              corner |= (upper ? 1u : 0u) << d;
            }
          is_box              = is_box && !corner_seen[corner];
          corner_seen[corner] = true;
        }
      if (!is_box)
        {
          std::ostringstream where;
          where << "cell " << cell.id() << " with vertices";
          for (const unsigned int v : cell.vertex_indices())
            where << " (" << cell.vertex(v) << ")";
          AssertThrow(false,
                      ExcMessage(
                        "PeriDEAL places PD nodes at the centres of cells "
                        "that are axis-aligned boxes (partial volumes are "
                        "computed for boxes), but the mesh contains a " +
                        where.str() +
                        ". Use a Cartesian mesh: every cell a box with "
                        "faces normal to the coordinate axes."));
        }
      return box;
    }


    template BoundingBox<1>
    cell_box(const CellAccessor<1> &);
    template BoundingBox<2>
    cell_box(const CellAccessor<2> &);
    template BoundingBox<3>
    cell_box(const CellAccessor<3> &);


    template <int dim>
    void
    NodeSet<dim>::set_perturbation(const double        fraction,
                                   const std::uint64_t seed)
    {
      AssertThrow(fraction >= 0 && fraction < 0.5,
                  ExcMessage("NodeSet::set_perturbation: the fraction must "
                             "lie in [0, 0.5)."));
      perturbation      = fraction;
      perturbation_seed = seed;
    }


    template <int dim>
    void
    NodeSet<dim>::reinit(const DoFHandler<dim> &dof_handler,
                         const double           coupling_range)
    {
      const auto    &fe   = dof_handler.get_fe();
      const MPI_Comm comm = dof_handler.get_communicator();
      communicator        = comm;
      const auto rank     = Utilities::MPI::this_mpi_process(comm);
      AssertThrow(fe.n_dofs_per_cell() == dim && fe.n_components() == dim &&
                    fe.degree == 0,
                  ExcMessage("NodeSet needs a DoFHandler with "
                             "FESystem(FE_DGQ(0), dim): one node per cell."));

      all_nodes.clear();
      node_partitioner_cache.reset();
      all_nodes.reserve(dof_handler.n_locally_owned_dofs() / dim);
      double                               local_max_diameter = 0;
      std::vector<types::global_dof_index> dof_indices(dim);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            Node<dim> node;
            node.cell     = cell_box(*cell);
            node.location = node.cell.center();
            if (perturbation > 0)
              {
                // A hash of the seed, the cell's centre and the direction,
                // uniform in [-1, 1): the same offset on every partition.
                // The key: the bits of the cell's centre (FNV-1a over its
                // coordinates), so that a node's offset depends on where
                // its cell is, not on how the mesh was built (coarse cells
                // and refinements, hence CellIds, differ between ways of
                // making the same cells) nor on the partition.
                std::uint64_t key = 14695981039346656037ULL;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const double  c = node.location[d];
                    std::uint64_t bits;
                    std::memcpy(&bits, &c, sizeof bits);
                    for (unsigned int b = 0; b < 8; ++b)
                      key =
                        (key ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ULL;
                  }
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    std::uint64_t z =
                      key ^ (perturbation_seed * 0x9e3779b97f4a7c15ULL) ^
                      ((d + 1) * 0xbf58476d1ce4e5b9ULL);
                    // splitmix64's finaliser.
                    z                 = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
                    z                 = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
                    z                 = z ^ (z >> 31);
                    const double unit = (z >> 11) * 0x1.0p-53; // [0, 1)
                    node.location[d] +=
                      perturbation * node.cell.side_length(d) * (2 * unit - 1);
                  }
              }
            cell->get_dof_indices(dof_indices);
            for (unsigned int i = 0; i < dim; ++i)
              node.dofs[fe.system_to_component_index(i).first] = dof_indices[i];
            node.owner = rank;
            all_nodes.push_back(node);
            local_max_diameter = std::max(local_max_diameter, cell->diameter());
          }
      n_owned_nodes = all_nodes.size();
      max_diameter  = Utilities::MPI::max(local_max_diameter, comm);

      if (Utilities::MPI::n_mpi_processes(comm) > 1)
        {
          // A node j is needed on process r if its cell comes within the
          // coupling range of a node owned by r. Each process describes
          // where its nodes are by the bounding boxes of its cells binned on
          // a grid of the coupling range (few boxes, tight around the
          // partition, whatever the mesh hierarchy), and gathers everyone's.
          const double bin = std::max(coupling_range, local_max_diameter);
          std::map<std::array<long, dim>, BoundingBox<dim>> bins;
          for (unsigned int i = 0; i < n_owned_nodes; ++i)
            {
              std::array<long, dim> key;
              for (unsigned int d = 0; d < dim; ++d)
                key[d] =
                  static_cast<long>(std::floor(all_nodes[i].location[d] / bin));
              const auto it = bins.find(key);
              if (it == bins.end())
                bins.emplace(key, all_nodes[i].cell);
              else
                it->second.merge_with(all_nodes[i].cell);
            }
          std::vector<BoundingBox<dim>> local_boxes;
          for (const auto &entry : bins)
            local_boxes.push_back(entry.second);
          const auto all_boxes = Utilities::MPI::all_gather(comm, local_boxes);

          // The other processes' boxes in an R-tree, searched with each
          // owned cell grown by the coupling range, then checked exactly.
          std::vector<std::pair<BoundingBox<dim>, unsigned int>> remote;
          for (unsigned int r = 0; r < all_boxes.size(); ++r)
            if (r != rank)
              for (const auto &box : all_boxes[r])
                remote.emplace_back(box, r);
          const auto   tree   = pack_rtree(remote);
          const double range2 = coupling_range * coupling_range;

          std::map<unsigned int, std::vector<Node<dim>>>         to_send;
          std::vector<std::pair<BoundingBox<dim>, unsigned int>> found;
          std::vector<unsigned int>                              targets;
          for (unsigned int i = 0; i < n_owned_nodes; ++i)
            {
              BoundingBox<dim> search = all_nodes[i].cell;
              search.extend(coupling_range);
              found.clear();
              tree.query(boost::geometry::index::intersects(search),
                         std::back_inserter(found));
              targets.clear();
              for (const auto &[box, r] : found)
                if (box_distance_squared(box, all_nodes[i].cell) <= range2)
                  targets.push_back(r);
              std::sort(targets.begin(), targets.end());
              targets.erase(std::unique(targets.begin(), targets.end()),
                            targets.end());
              for (const unsigned int r : targets)
                to_send[r].push_back(all_nodes[i]);
            }
          const auto received = Utilities::MPI::some_to_some(comm, to_send);

          std::vector<Node<dim>> ghosts;
          for (const auto &[sender, nodes] : received)
            ghosts.insert(ghosts.end(), nodes.begin(), nodes.end());
          // A deterministic order, independent of the partition's history.
          std::sort(ghosts.begin(),
                    ghosts.end(),
                    [](const auto &a, const auto &b) {
                      return a.dofs[0] < b.dofs[0];
                    });
          all_nodes.insert(all_nodes.end(), ghosts.begin(), ghosts.end());
        }

      relevant = IndexSet(dof_handler.n_dofs());
      std::vector<types::global_dof_index> indices;
      indices.reserve(dim * all_nodes.size());
      for (const auto &node : all_nodes)
        indices.insert(indices.end(), node.dofs.begin(), node.dofs.end());
      std::sort(indices.begin(), indices.end());
      relevant.add_indices(indices.begin(), indices.end());
      relevant.compress();
      // Built here, where every process is, so that node_partitioner() is
      // a plain getter that no process can reach alone for a collective.
      node_partitioner();
    }


    template <int dim>
    unsigned int
    NodeSet<dim>::n_owned() const
    {
      return n_owned_nodes;
    }


    template <int dim>
    unsigned int
    NodeSet<dim>::n_ghost() const
    {
      return all_nodes.size() - n_owned_nodes;
    }


    template <int dim>
    unsigned int
    NodeSet<dim>::size() const
    {
      return all_nodes.size();
    }


    template <int dim>
    const Node<dim> &
    NodeSet<dim>::operator[](const unsigned int i) const
    {
      AssertIndexRange(i, all_nodes.size());
      return all_nodes[i];
    }


    template <int dim>
    const std::vector<Node<dim>> &
    NodeSet<dim>::nodes() const
    {
      return all_nodes;
    }


    template <int dim>
    double
    NodeSet<dim>::max_cell_diameter() const
    {
      return max_diameter;
    }


    template <int dim>
    IndexSet
    NodeSet<dim>::relevant_dofs() const
    {
      return relevant;
    }


    template <int dim>
    std::shared_ptr<const Utilities::MPI::Partitioner>
    NodeSet<dim>::node_partitioner() const
    {
      if (node_partitioner_cache)
        return node_partitioner_cache;
      const types::global_dof_index        n_global = relevant.size() / dim;
      IndexSet                             owned(n_global), all(n_global);
      std::vector<types::global_dof_index> indices;
      indices.reserve(all_nodes.size());
      for (unsigned int i = 0; i < n_owned_nodes; ++i)
        indices.push_back(all_nodes[i].dofs[0] / dim);
      std::sort(indices.begin(), indices.end());
      owned.add_indices(indices.begin(), indices.end());
      owned.compress();
      for (unsigned int i = n_owned_nodes; i < all_nodes.size(); ++i)
        indices.push_back(all_nodes[i].dofs[0] / dim);
      std::sort(indices.begin(), indices.end());
      all.add_indices(indices.begin(), indices.end());
      all.compress();
      node_partitioner_cache =
        std::make_shared<Utilities::MPI::Partitioner>(owned, all, communicator);
      return node_partitioner_cache;
    }


    template <int dim>
    MPI_Comm
    NodeSet<dim>::get_communicator() const
    {
      return communicator;
    }


    template class NodeSet<1>;
    template class NodeSet<2>;
    template class NodeSet<3>;
    template double
    box_distance_squared<1>(const BoundingBox<1> &, const BoundingBox<1> &);
    template double
    box_distance_squared<2>(const BoundingBox<2> &, const BoundingBox<2> &);
    template double
    box_distance_squared<3>(const BoundingBox<3> &, const BoundingBox<3> &);
  } // namespace Discretization
} // namespace PeriDEAL
