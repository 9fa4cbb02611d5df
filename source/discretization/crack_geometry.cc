#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/exceptions.h>
#include <perideal/discretization/crack_geometry.h>

#include <cmath>
#include <sstream>

namespace PeriDEAL
{
  namespace Discretization
  {
    namespace
    {
      /// Split "a; b; c" into trimmed non-empty items, each a list of
      /// numbers.
      std::vector<std::vector<double>>
      parse_lists(const std::string &text, const std::string &entry)
      {
        std::vector<std::vector<double>> result;
        for (const auto &item : Utilities::split_string_list(text, ';'))
          {
            if (item.empty())
              continue;
            std::vector<double> numbers;
            for (const auto &word : Utilities::split_string_list(item, ','))
              {
                std::size_t used = 0;
                double      x    = 0;
                try
                  {
                    x = std::stod(word, &used);
                  }
                catch (...)
                  {
                    used = 0;
                  }
                AssertThrow(used == word.size() && !word.empty() &&
                              std::isfinite(x),
                            ExcInvalidInput(entry,
                                            text,
                                            "'" + word + "' in '" + item +
                                              "' is not a number"));
                numbers.push_back(x);
              }
            result.push_back(numbers);
          }
        return result;
      }

      double
      orientation(const Point<2> &a, const Point<2> &b, const Point<2> &c)
      {
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      }

      bool
      on_segment(const Point<2> &a, const Point<2> &b, const Point<2> &p)
      {
        return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
               std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
      }

      /// Whether the closed segments [a, b] and [c, d] intersect.
      bool
      segments_intersect(const Point<2> &a,
                         const Point<2> &b,
                         const Point<2> &c,
                         const Point<2> &d)
      {
        const double o1 = orientation(a, b, c), o2 = orientation(a, b, d),
                     o3 = orientation(c, d, a), o4 = orientation(c, d, b);
        if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) &&
            ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
          return true;
        return (o1 == 0 && on_segment(a, b, c)) ||
               (o2 == 0 && on_segment(a, b, d)) ||
               (o3 == 0 && on_segment(c, d, a)) ||
               (o4 == 0 && on_segment(c, d, b));
      }

      /**
       * Refuse a 3D pre-crack polygon that is not a simple polygon in one
       * plane, each fault in its own words: collinear vertices (no plane),
       * vertices off the plane, a repeated vertex, or edges that cross
       * (an edge order that is not the order around the boundary). Newell's
       * normal alone cannot tell these apart: a symmetric bow tie has zero
       * area, like a segment.
       */
      void
      check_simple_polygon(const std::vector<Point<3>> &vertices,
                           const std::size_t            number,
                           const std::string           &entry,
                           const std::string           &text)
      {
        const unsigned int n    = vertices.size();
        const std::string  name = "pre-crack polygon " + std::to_string(number);
        const BoundingBox<3> box(vertices);
        const double         size =
          box.side_length(0) + box.side_length(1) + box.side_length(2);
        // The plane: the largest cross product of two edges from the first
        // vertex (well conditioned whatever the vertex order).
        Tensor<1, 3> normal;
        for (unsigned int k = 1; k < n; ++k)
          for (unsigned int l = k + 1; l < n; ++l)
            {
              const Tensor<1, 3> c = cross_product_3d(vertices[k] - vertices[0],
                                                      vertices[l] - vertices[0]);
              if (c.norm() > normal.norm())
                normal = c;
            }
        AssertThrow(normal.norm() > 1e-12 * size * size,
                    ExcInvalidInput(entry,
                                    text,
                                    "the " + name +
                                      " has no area (collinear vertices)"));
        normal /= normal.norm();
        for (const auto &p : vertices)
          AssertThrow(std::abs((p - vertices[0]) * normal) <= 1e-9 * size,
                      ExcInvalidInput(entry,
                                      text,
                                      "the vertices of a pre-crack "
                                      "polygon must lie in one plane"));
        Tensor<1, 3> u = vertices[1] - vertices[0];
        for (const auto &p : vertices)
          if ((p - vertices[0]).norm() > u.norm())
            u = p - vertices[0];
        u /= u.norm();
        const Tensor<1, 3>    v = cross_product_3d(normal, u);
        std::vector<Point<2>> q;
        for (const auto &p : vertices)
          q.emplace_back((p - vertices[0]) * u, (p - vertices[0]) * v);
        for (unsigned int k = 0; k < n; ++k)
          for (unsigned int l = k + 1; l < n; ++l)
            AssertThrow(q[k].distance(q[l]) > 1e-12 * size,
                        ExcInvalidInput(entry,
                                        text,
                                        "vertices " + std::to_string(k + 1) +
                                          " and " + std::to_string(l + 1) +
                                          " of the " + name +
                                          " coincide; give each vertex "
                                          "once"));
        const auto edge = [&](const unsigned int k) {
          return std::to_string(k + 1) + "-" + std::to_string((k + 1) % n + 1);
        };
        for (unsigned int k = 0; k < n; ++k)
          for (unsigned int l = k + 1; l < n; ++l)
            {
              const Point<2> &a = q[k], &b = q[(k + 1) % n], &c = q[l],
                             &d = q[(l + 1) % n];
              bool cross = false;
              if (l == k + 1 || (k == 0 && l == n - 1))
                {
                  // Neighbouring edges share a vertex; they overlap only
                  // where the boundary folds back on itself.
                  const Point<2> &shared = l == k + 1 ? b : a;
                  const Point<2> &p      = l == k + 1 ? a : b;
                  const Point<2> &r      = l == k + 1 ? d : c;
                  cross = std::abs(orientation(shared, p, r)) <=
                            1e-12 * size * size &&
                          (p - shared) * (r - shared) > 0;
                }
              else
                cross = segments_intersect(a, b, c, d);
              AssertThrow(!cross,
                          ExcInvalidInput(entry,
                                          text,
                                          "the " + name +
                                            " intersects itself (its edges " +
                                            edge(k) + " and " + edge(l) +
                                            " meet); list the vertices in "
                                            "order around the boundary of "
                                            "the polygon"));
            }
      }
    } // namespace


    template <int dim>
    void
    PreCracks<dim>::parse(const std::string &text, const std::string &entry)
    {
      cracks.clear();
      for (const auto &numbers : parse_lists(text, entry))
        {
          Crack crack;
          if (dim == 2)
            {
              AssertThrow(numbers.size() == 4,
                          ExcInvalidInput(entry,
                                          text,
                                          "a 2D pre-crack is a segment "
                                          "'x1, y1, x2, y2'; separate "
                                          "segments with ';'"));
            }
          else
            AssertThrow(numbers.size() >= 9 && numbers.size() % 3 == 0,
                        ExcInvalidInput(entry,
                                        text,
                                        "a 3D pre-crack is a planar polygon "
                                        "of at least three vertices 'x1, "
                                        "y1, z1, x2, y2, z2, x3, y3, z3, "
                                        "...'; separate polygons with ';'"));
          for (std::size_t k = 0; k < numbers.size(); k += dim)
            {
              Point<dim> p;
              for (unsigned int d = 0; d < dim; ++d)
                p[d] = numbers[k + d];
              crack.vertices.push_back(p);
            }
          crack.box = BoundingBox<dim>(crack.vertices);
          if constexpr (dim == 2)
            AssertThrow(crack.vertices[0] != crack.vertices[1],
                        ExcInvalidInput(entry,
                                        text,
                                        "the pre-crack segment " +
                                          std::to_string(cracks.size() + 1) +
                                          " has zero length (both ends at "
                                          "the same point); give two "
                                          "different end points"));
          if constexpr (dim == 3)
            {
              check_simple_polygon(crack.vertices,
                                   cracks.size() + 1,
                                   entry,
                                   text);
              // Newell's normal; every vertex must lie in its plane.
              Tensor<1, dim>     normal;
              const unsigned int n = crack.vertices.size();
              for (unsigned int k = 0; k < n; ++k)
                {
                  const auto &p = crack.vertices[k];
                  const auto &q = crack.vertices[(k + 1) % n];
                  normal[0] += (p[1] - q[1]) * (p[2] + q[2]);
                  normal[1] += (p[2] - q[2]) * (p[0] + q[0]);
                  normal[2] += (p[0] - q[0]) * (p[1] + q[1]);
                }
              const double size = crack.box.side_length(0) +
                                  crack.box.side_length(1) +
                                  crack.box.side_length(2);
              AssertThrow(normal.norm() > 1e-12 * size * size,
                          ExcInvalidInput(entry,
                                          text,
                                          "a pre-crack polygon has no area "
                                          "(collinear vertices)"));
              crack.normal = normal / normal.norm();
              for (const auto &p : crack.vertices)
                AssertThrow(std::abs((p - crack.vertices[0]) * crack.normal) <=
                              1e-9 * size,
                            ExcInvalidInput(entry,
                                            text,
                                            "the vertices of a pre-crack "
                                            "polygon must lie in one plane"));
              crack.axis_u = crack.vertices[1] - crack.vertices[0];
              crack.axis_u /= crack.axis_u.norm();
              crack.axis_v = cross_product_3d(crack.normal, crack.axis_u);
            }
          cracks.push_back(crack);
        }
    }


    template <int dim>
    bool
    PreCracks<dim>::cuts(const Point<dim> &a, const Point<dim> &b) const
    {
      return first_cut(a, b) >= 0;
    }


    template <int dim>
    int
    PreCracks<dim>::first_cut(const Point<dim> &a, const Point<dim> &b) const
    {
      BoundingBox<dim> bond(std::make_pair(a, a));
      bond.merge_with(BoundingBox<dim>(std::make_pair(b, b)));
      for (unsigned int index = 0; index < cracks.size(); ++index)
        {
          const auto &crack = cracks[index];
          bool overlap = true;
          for (unsigned int d = 0; d < dim; ++d)
            overlap = overlap &&
                      crack.box.lower_bound(d) <= bond.upper_bound(d) &&
                      bond.lower_bound(d) <= crack.box.upper_bound(d);
          if (!overlap)
            continue;
          if constexpr (dim == 2)
            {
              if (segments_intersect(a,
                                     b,
                                     crack.vertices[0],
                                     crack.vertices[1]))
                return index;
            }
          else
            {
              const auto  &o  = crack.vertices[0];
              const double da = (a - o) * crack.normal,
                           db = (b - o) * crack.normal;
              if ((da > 0 && db > 0) || (da < 0 && db < 0) || da == db)
                continue; // same side, or in the plane (no crossing)
              const Point<dim> p = a + (da / (da - db)) * (b - a);
              // Crossing-number test in the plane's coordinates.
              const auto project = [&](const Point<dim> &x) {
                return Point<2>((x - o) * crack.axis_u, (x - o) * crack.axis_v);
              };
              const Point<2>     q      = project(p);
              bool               inside = false;
              const unsigned int n      = crack.vertices.size();
              for (unsigned int k = 0, l = n - 1; k < n; l = k++)
                {
                  const Point<2> vk = project(crack.vertices[k]),
                                 vl = project(crack.vertices[l]);
                  if ((vk[1] > q[1]) != (vl[1] > q[1]) &&
                      q[0] <
                        (vl[0] - vk[0]) * (q[1] - vk[1]) / (vl[1] - vk[1]) +
                          vk[0])
                    inside = !inside;
                }
              if (inside)
                return index;
            }
        }
      return -1;
    }


    template <int dim>
    std::size_t
    PreCracks<dim>::break_bonds(const NodeSet<dim>       &nodes,
                                const NeighborList<dim>  &lists,
                                BondState<dim>           &state,
                                const double              reach,
                                std::vector<std::size_t> *per_crack) const
    {
      std::vector<std::size_t> count(cracks.size(), 0);
      if (!cracks.empty())
        for (unsigned int i = 0; i < nodes.size(); ++i)
          if (lists.has_list(i))
            {
              const Point<dim> &x = nodes[i].location;
              // Only nodes near a crack can have a bond across it.
              bool near = false;
              for (const auto &crack : cracks)
                {
                  BoundingBox<dim> box = crack.box;
                  box.extend(reach);
                  near = near || box.point_inside(x);
                }
              if (!near)
                continue;
              for (unsigned int k = 0; k < lists.n_bonds(i); ++k)
                {
                  const int crack =
                    first_cut(x, nodes[state.neighbor(i, k)].location);
                  if (crack < 0)
                    continue;
                  state.break_bond(i, k);
                  if (i < nodes.n_owned())
                    ++count[crack];
                }
            }
      if (per_crack != nullptr)
        {
          if (!count.empty())
            Utilities::MPI::sum(count, nodes.get_communicator(), count);
          *per_crack = count;
        }
      return state.synchronize();
    }


    template <int dim>
    std::vector<BoundingBox<dim>>
    parse_boxes(const std::string &text, const std::string &entry)
    {
      std::vector<BoundingBox<dim>> boxes;
      for (const auto &numbers : parse_lists(text, entry))
        {
          AssertThrow(numbers.size() == 2 * dim,
                      ExcInvalidInput(entry,
                                      text,
                                      std::string("a box is '") +
                                        (dim == 1 ? "xmin, xmax" :
                                         dim == 2 ? "xmin, ymin, xmax, ymax" :
                                                    "xmin, ymin, zmin, xmax, "
                                                    "ymax, zmax") +
                                        "' in this " + std::to_string(dim) +
                                        "D run; separate boxes with ';'"));
          Point<dim> lower, upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = numbers[d];
              upper[d] = numbers[dim + d];
              AssertThrow(lower[d] < upper[d],
                          ExcInvalidInput(entry,
                                          text,
                                          "give the lower corner first "
                                          "(xmin < xmax, ...)"));
            }
          boxes.emplace_back(std::make_pair(lower, upper));
        }
      return boxes;
    }


    template <int dim>
    std::vector<Point<dim>>
    parse_points(const std::string &text, const std::string &entry)
    {
      std::vector<Point<dim>> points;
      for (const auto &numbers : parse_lists(text, entry))
        {
          AssertThrow(numbers.size() == dim,
                      ExcInvalidInput(entry,
                                      text,
                                      std::string("a point is '") +
                                        (dim == 1 ? "x" :
                                         dim == 2 ? "x, y" :
                                                    "x, y, z") +
                                        "' in this " + std::to_string(dim) +
                                        "D run; separate points with ';'"));
          Point<dim> p;
          for (unsigned int d = 0; d < dim; ++d)
            p[d] = numbers[d];
          points.push_back(p);
        }
      return points;
    }


    template <int dim>
    std::vector<bool>
    nodes_in_boxes(const NodeSet<dim>                  &nodes,
                   const std::vector<BoundingBox<dim>> &boxes,
                   const std::string                   &entry,
                   const std::string                   &text,
                   const std::string                   &purpose)
    {
      std::vector<bool>         inside(nodes.size(), false);
      std::vector<unsigned int> count(boxes.size(), 0);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        for (unsigned int b = 0; b < boxes.size(); ++b)
          if (boxes[b].point_inside(nodes[i].location))
            {
              inside[i] = true;
              if (i < nodes.n_owned())
                ++count[b];
            }
      if (!boxes.empty())
        Utilities::MPI::sum(count, nodes.get_communicator(), count);
      for (unsigned int b = 0; b < boxes.size(); ++b)
        AssertThrow(count[b] > 0,
                    ExcInvalidInput(entry,
                                    text,
                                    "box " + std::to_string(b + 1) +
                                      " holds no node centre, so it " +
                                      purpose +
                                      "; enlarge it or move it onto the "
                                      "body"));
      return inside;
    }


    template <int dim>
    void
    check_points_in_body(const NodeSet<dim>            &nodes,
                         const std::vector<Point<dim>> &points,
                         const std::string             &entry,
                         const std::string             &text)
    {
      if (points.empty())
        return;
      std::vector<unsigned int> inside(points.size(), 0);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int k = 0; k < points.size(); ++k)
          if (nodes[i].cell.point_inside(points[k], 1e-10))
            inside[k] = 1;
      Utilities::MPI::max(inside, nodes.get_communicator(), inside);
      for (unsigned int k = 0; k < points.size(); ++k)
        {
          std::ostringstream point;
          point << points[k];
          AssertThrow(inside[k] != 0,
                      ExcInvalidInput(entry,
                                      text,
                                      "point " + std::to_string(k + 1) +
                                        " (" + point.str() +
                                        ") lies outside the body, where "
                                        "no node is; give a point on the "
                                        "body"));
        }
    }


    template class PreCracks<2>;
    template class PreCracks<3>;
    template std::vector<BoundingBox<1>>
    parse_boxes<1>(const std::string &, const std::string &);
    template std::vector<Point<1>>
    parse_points<1>(const std::string &, const std::string &);
    template std::vector<bool>
    nodes_in_boxes<1>(const NodeSet<1> &,
                      const std::vector<BoundingBox<1>> &,
                      const std::string &,
                      const std::string &,
                      const std::string &);
    template std::vector<BoundingBox<2>>
    parse_boxes<2>(const std::string &, const std::string &);
    template std::vector<BoundingBox<3>>
    parse_boxes<3>(const std::string &, const std::string &);
    template std::vector<Point<2>>
    parse_points<2>(const std::string &, const std::string &);
    template std::vector<Point<3>>
    parse_points<3>(const std::string &, const std::string &);
    template std::vector<bool>
    nodes_in_boxes<2>(const NodeSet<2> &,
                      const std::vector<BoundingBox<2>> &,
                      const std::string &,
                      const std::string &,
                      const std::string &);
    template void
    check_points_in_body<2>(const NodeSet<2> &,
                            const std::vector<Point<2>> &,
                            const std::string &,
                            const std::string &);
    template void
    check_points_in_body<3>(const NodeSet<3> &,
                            const std::vector<Point<3>> &,
                            const std::string &,
                            const std::string &);
    template std::vector<bool>
    nodes_in_boxes<3>(const NodeSet<3> &,
                      const std::vector<BoundingBox<3>> &,
                      const std::string &,
                      const std::string &,
                      const std::string &);
  } // namespace Discretization
} // namespace PeriDEAL
