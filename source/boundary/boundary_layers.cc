#include <deal.II/base/mpi.h>

#include <deal.II/boost_adaptors/bounding_box.h>

#include <deal.II/numerics/rtree.h>

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>

#include <algorithm>
#include <limits>

namespace PeriDEAL
{
  namespace Boundary
  {
    namespace
    {
      /**
       * Call @p visit(i, point, k, candidates) for each node i of @p nodes
       * (owned and ghost; @p point is the degenerate box at its location)
       * and each face set k of @p faces, in this order, with the faces of
       * set k whose boxes meet the node's box grown by @p thickness, as the
       * R-tree of that set lists them.
       */
      template <int dim, typename Visitor>
      void
      for_each_nearby_face_set(
        const std::vector<std::vector<BoundingBox<dim>>> &faces,
        const Discretization::NodeSet<dim>               &nodes,
        const double                                      thickness,
        const Visitor                                    &visit)
      {
        std::vector<decltype(pack_rtree(faces[0]))> trees;
        for (const auto &f : faces)
          trees.push_back(pack_rtree(f));
        std::vector<BoundingBox<dim>> candidates;
        for (unsigned int i = 0; i < nodes.size(); ++i)
          {
            const auto            &x = nodes[i].location;
            const BoundingBox<dim> point(std::make_pair(x, x));
            BoundingBox<dim>       search = point;
            search.extend(thickness);
            for (unsigned int k = 0; k < trees.size(); ++k)
              {
                candidates.clear();
                trees[k].query(boost::geometry::index::intersects(search),
                               std::back_inserter(candidates));
                visit(i, point, k, candidates);
              }
          }
      }
    } // namespace


    std::vector<types::boundary_id>
    parse_boundary_ids(const std::string &text)
    {
      std::vector<types::boundary_id> ids;
      for (const int id :
           Utilities::string_to_int(Utilities::split_string_list(text)))
        ids.push_back(static_cast<types::boundary_id>(id));
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      return ids;
    }


    std::string
    boundary_ids_to_string(const std::vector<types::boundary_id> &ids)
    {
      std::string s;
      for (const auto id : ids)
        s += (s.empty() ? "" : ", ") + std::to_string(id);
      return s;
    }


    template <int dim>
    void
    check_boundary_ids(const Triangulation<dim>              &triangulation,
                       const std::vector<types::boundary_id> &ids,
                       const std::string                     &entry,
                       const std::string                     &text)
    {
      const auto mesh_ids = triangulation.get_boundary_ids();
      for (const auto id : ids)
        AssertThrow(std::find(mesh_ids.begin(), mesh_ids.end(), id) !=
                      mesh_ids.end(),
                    ExcInvalidInput(entry,
                                    text,
                                    "boundary id " + std::to_string(id) +
                                      " does not occur in the mesh, whose "
                                      "boundary ids are " +
                                      boundary_ids_to_string(mesh_ids)));
    }


    template void
    check_boundary_ids(const Triangulation<1> &,
                       const std::vector<types::boundary_id> &,
                       const std::string &,
                       const std::string &);
    template void
    check_boundary_ids(const Triangulation<2> &,
                       const std::vector<types::boundary_id> &,
                       const std::string &,
                       const std::string &);
    template void
    check_boundary_ids(const Triangulation<3> &,
                       const std::vector<types::boundary_id> &,
                       const std::string &,
                       const std::string &);


    template <int dim>
    BoundaryLayers<dim>::BoundaryLayers(
      const Triangulation<dim>              &triangulation,
      const std::vector<types::boundary_id> &ids)
      : comm(triangulation.get_communicator())
      , faces(ids.size())
    {
      std::vector<std::vector<BoundingBox<dim>>> local(ids.size());
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f))
              {
                const auto k = std::find(ids.begin(),
                                         ids.end(),
                                         cell->face(f)->boundary_id()) -
                               ids.begin();
                if (k == static_cast<long>(ids.size()))
                  continue;
                std::vector<Point<dim>> vertices;
                for (const unsigned int v : cell->face(f)->vertex_indices())
                  vertices.push_back(cell->face(f)->vertex(v));
                local[k].emplace_back(vertices);
              }
      for (unsigned int k = 0; k < ids.size(); ++k)
        for (const auto &part : Utilities::MPI::all_gather(comm, local[k]))
          faces[k].insert(faces[k].end(), part.begin(), part.end());
    }


    template <int dim>
    std::vector<unsigned int>
    BoundaryLayers<dim>::layer_of_nodes(
      const Discretization::NodeSet<dim> &nodes,
      const double                        thickness,
      std::vector<unsigned int>          *n_owned_per_id) const
    {
      const double              limit = thickness * (1 - 1e-10);
      std::vector<unsigned int> layer(nodes.size(),
                                      numbers::invalid_unsigned_int);
      std::vector<unsigned int> count(faces.size(), 0);
      for_each_nearby_face_set(
        faces,
        nodes,
        thickness,
        [&](const unsigned int                   i,
            const BoundingBox<dim>              &point,
            const unsigned int                   k,
            const std::vector<BoundingBox<dim>> &candidates) {
          for (const auto &face : candidates)
            if (Discretization::box_distance_squared(face, point) <
                limit * limit)
              {
                if (layer[i] == numbers::invalid_unsigned_int)
                  layer[i] = k;
                if (i < nodes.n_owned())
                  ++count[k];
                break;
              }
        });
      if (n_owned_per_id != nullptr)
        {
          if (!count.empty())
            Utilities::MPI::sum(count, comm, count);
          *n_owned_per_id = count;
        }
      return layer;
    }


    template <int dim>
    std::vector<Point<dim>>
    BoundaryLayers<dim>::nearest_face_points(
      const Discretization::NodeSet<dim> &nodes,
      const double                        thickness) const
    {
      Point<dim> none;
      for (unsigned int d = 0; d < dim; ++d)
        none[d] = std::numeric_limits<double>::quiet_NaN();
      std::vector<Point<dim>> nearest(nodes.size(), none);
      // The squared distance of nearest[i], over all face sets.
      std::vector<double> best(nodes.size(), thickness * thickness);
      for_each_nearby_face_set(
        faces,
        nodes,
        thickness,
        [&](const unsigned int i,
            const BoundingBox<dim> &,
            const unsigned int,
            const std::vector<BoundingBox<dim>> &candidates) {
          const auto &x = nodes[i].location;
          for (const auto &face : candidates)
            {
              Point<dim> p;
              for (unsigned int d = 0; d < dim; ++d)
                p[d] = std::clamp(x[d],
                                  face.get_boundary_points().first[d],
                                  face.get_boundary_points().second[d]);
              const double d2 = p.distance_square(x);
              if (d2 < best[i])
                {
                  best[i]    = d2;
                  nearest[i] = p;
                }
            }
        });
      return nearest;
    }


    template class BoundaryLayers<1>;
    template class BoundaryLayers<2>;
    template class BoundaryLayers<3>;
  } // namespace Boundary
} // namespace PeriDEAL
