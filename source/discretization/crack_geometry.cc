#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/exceptions.h>
#include <perideal/base/read_number.h>
#include <perideal/discretization/crack_geometry.h>

#include <array>
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
                double x = 0;
                AssertThrow(read_number(word, x) && std::isfinite(x),
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

      /// (b - a) x (c - a) rounded (for the tolerances of the input checks).
      double
      orientation(const Point<2> &a, const Point<2> &b, const Point<2> &c)
      {
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
      }

      // Exact signs of orientation determinants (the robust predicates of
      // the pre-crack test). A floating-point filter with Shewchuk's error
      // bounds (J. R. Shewchuk, Adaptive precision floating-point arithmetic
      // and fast robust geometric predicates, Discrete Comput. Geom. 18,
      // 1997) decides almost every call; where the rounded determinant is
      // too small to trust, it is summed exactly as a floating-point
      // expansion of the products of the input coordinates (each product
      // split exactly with std::fma). No tolerance: the sign is that of the
      // exact determinant of the given doubles, as long as no product
      // overflows or underflows (coordinates between about 1e-90 and 1e90
      // in magnitude, or zero). Fixed-size arrays: nothing is allocated.

      /// a + b = s + e exactly (Knuth's two-sum).
      inline void
      two_sum(const double a, const double b, double &s, double &e)
      {
        s               = a + b;
        const double bv = s - a;
        const double av = s - bv;
        e               = (a - av) + (b - bv);
      }

      /**
       * An exact sum of doubles: a nonoverlapping expansion, components in
       * increasing magnitude, zeros left out (Shewchuk's Grow-Expansion
       * with zero elimination). Its sign is that of its largest component.
       */
      template <unsigned int capacity>
      class ExactSum
      {
      public:
        void
        add(double x)
        {
          unsigned int m = 0;
          for (unsigned int k = 0; k < n; ++k)
            {
              double s, e;
              two_sum(x, component[k], s, e);
              x = s;
              if (e != 0)
                component[m++] = e;
            }
          if (x != 0)
            component[m++] = x;
          n = m;
        }

        /// Add x y z exactly (four doubles).
        void
        add_product(const double x, const double y, const double z)
        {
          const double p = x * y, pe = std::fma(x, y, -p);
          const double q = p * z, qe = std::fma(p, z, -q);
          const double r = pe * z, re = std::fma(pe, z, -r);
          add(q);
          add(qe);
          add(r);
          add(re);
        }

        /// Add x y exactly (two doubles).
        void
        add_product(const double x, const double y)
        {
          const double p = x * y;
          add(p);
          add(std::fma(x, y, -p));
        }

        int
        sign() const
        {
          return n == 0 ? 0 : component[n - 1] > 0 ? 1 : -1;
        }

      private:
        // Each add() lengthens the expansion by at most one component.
        double       component[capacity];
        unsigned int n = 0;
      };

      int
      sign(const double x)
      {
        return (x > 0) - (x < 0);
      }

      /**
       * The sign of (b - a) x (c - a): +1 when a, b, c turn counterclockwise,
       * 0 when they are collinear (exactly).
       */
      int
      orient2d(const Point<2> &a, const Point<2> &b, const Point<2> &c)
      {
        // Shewchuk's orient2d filter, on (a - c) x (b - c) (the same
        // determinant).
        const double left  = (a[0] - c[0]) * (b[1] - c[1]);
        const double right = (a[1] - c[1]) * (b[0] - c[0]);
        const double det   = left - right;
        double       detsum;
        if (left > 0)
          {
            if (right <= 0)
              return sign(det);
            detsum = left + right;
          }
        else if (left < 0)
          {
            if (right >= 0)
              return sign(det);
            detsum = -left - right;
          }
        else
          return sign(det);
        constexpr double eps   = 0x1p-53;
        const double     bound = (3.0 + 16.0 * eps) * eps * detsum;
        if (det >= bound || -det >= bound)
          return sign(det);
        // Exactly: (a - c) x (b - c) = a x b - a x c + b x c.
        ExactSum<13> sum;
        sum.add_product(a[0], b[1]);
        sum.add_product(-a[1], b[0]);
        sum.add_product(-a[0], c[1]);
        sum.add_product(a[1], c[0]);
        sum.add_product(b[0], c[1]);
        sum.add_product(-b[1], c[0]);
        return sum.sign();
      }

      /**
       * The sign of (a - d) . ((b - d) x (c - d)): 0 exactly when the four
       * points lie in one plane; otherwise opposite for points d on
       * opposite sides of the plane through a, b, c.
       */
      int
      orient3d(const Point<3> &a,
               const Point<3> &b,
               const Point<3> &c,
               const Point<3> &d)
      {
        // Shewchuk's orient3d filter.
        const double adx = a[0] - d[0], bdx = b[0] - d[0], cdx = c[0] - d[0];
        const double ady = a[1] - d[1], bdy = b[1] - d[1], cdy = c[1] - d[1];
        const double adz = a[2] - d[2], bdz = b[2] - d[2], cdz = c[2] - d[2];
        const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
        const double cdxady = cdx * ady, adxcdy = adx * cdy;
        const double adxbdy = adx * bdy, bdxady = bdx * ady;
        const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) +
                           cdz * (adxbdy - bdxady);
        const double permanent =
          (std::abs(bdxcdy) + std::abs(cdxbdy)) * std::abs(adz) +
          (std::abs(cdxady) + std::abs(adxcdy)) * std::abs(bdz) +
          (std::abs(adxbdy) + std::abs(bdxady)) * std::abs(cdz);
        constexpr double eps   = 0x1p-53;
        const double     bound = (7.0 + 56.0 * eps) * eps * permanent;
        if (det > bound || -det > bound)
          return sign(det);
        // Exactly: (a - d) . ((b - d) x (c - d))
        //   = a . (b x c) - a . (b x d) + a . (c x d) - d . (b x c),
        // each triple product u . (v x w) a sum of six products.
        ExactSum<97> sum;
        const auto   triple = [&sum](const Point<3> &u,
                                   const Point<3> &v,
                                   const Point<3> &w,
                                   const double    s) {
          for (unsigned int i = 0; i < 3; ++i)
            {
              const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
              sum.add_product(s * u[i], v[j], w[k]);
              sum.add_product(-s * u[i], v[k], w[j]);
            }
        };
        triple(a, b, c, 1);
        triple(a, b, d, -1);
        triple(a, c, d, 1);
        triple(d, b, c, -1);
        return sum.sign();
      }

      bool
      on_segment(const Point<2> &a, const Point<2> &b, const Point<2> &p)
      {
        return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
               std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
      }

      /**
       * Whether the closed segments [a, b] and [c, d] intersect (exactly:
       * touching at an end, and overlapping when collinear, count).
       */
      bool
      segments_intersect(const Point<2> &a,
                         const Point<2> &b,
                         const Point<2> &c,
                         const Point<2> &d)
      {
        const int o1 = orient2d(a, b, c), o2 = orient2d(a, b, d),
                  o3 = orient2d(c, d, a), o4 = orient2d(c, d, b);
        if (o1 * o2 < 0 && o3 * o4 < 0)
          return true;
        return (o1 == 0 && on_segment(a, b, c)) ||
               (o2 == 0 && on_segment(a, b, d)) ||
               (o3 == 0 && on_segment(c, d, a)) ||
               (o4 == 0 && on_segment(c, d, b));
      }

      /// Whether p lies in the closed triangle t (nonzero area) of the plane.
      bool
      in_triangle(const Point<2> &p, const std::array<Point<2>, 3> &t)
      {
        const int o0 = orient2d(t[0], t[1], p), o1 = orient2d(t[1], t[2], p),
                  o2 = orient2d(t[2], t[0], p);
        return (o0 >= 0 && o1 >= 0 && o2 >= 0) ||
               (o0 <= 0 && o1 <= 0 && o2 <= 0);
      }

      /// The point p without its coordinate @p drop.
      Point<2>
      drop_coordinate(const Point<3> &p, const unsigned int drop)
      {
        return Point<2>(p[drop == 0 ? 1 : 0], p[drop == 2 ? 1 : 2]);
      }

      /**
       * Whether the closed segment [a, b] meets the closed triangle t (in 3D),
       * exactly. The triangle's projection without coordinate @p drop has
       * nonzero area (PreCracks::parse() made it so).
       */
      bool
      segment_meets_triangle(const Point<3>                &a,
                             const Point<3>                &b,
                             const std::array<Point<3>, 3> &t,
                             const unsigned int             drop)
      {
        const int sa = orient3d(t[0], t[1], t[2], a),
                  sb = orient3d(t[0], t[1], t[2], b);
        if (sa * sb > 0)
          return false; // both strictly on one side
        if (sa == 0 && sb == 0)
          {
            // The bond lies in the triangle's plane, on which dropping a
            // coordinate is one-to-one: the 2D test of the projections.
            const Point<2> a2                = drop_coordinate(a, drop),
                           b2                = drop_coordinate(b, drop);
            const std::array<Point<2>, 3> t2 = {{drop_coordinate(t[0], drop),
                                                 drop_coordinate(t[1], drop),
                                                 drop_coordinate(t[2], drop)}};
            return in_triangle(a2, t2) || in_triangle(b2, t2) ||
                   segments_intersect(a2, b2, t2[0], t2[1]) ||
                   segments_intersect(a2, b2, t2[1], t2[2]) ||
                   segments_intersect(a2, b2, t2[2], t2[0]);
          }
        // The segment meets the plane in one point (maybe an end): in the
        // closed triangle when the line ab passes no edge on the far side,
        // i.e. the volumes of ab with the three edges have no opposite
        // signs.
        const int v0 = orient3d(a, b, t[0], t[1]),
                  v1 = orient3d(a, b, t[1], t[2]),
                  v2 = orient3d(a, b, t[2], t[0]);
        return (v0 >= 0 && v1 >= 0 && v2 >= 0) ||
               (v0 <= 0 && v1 <= 0 && v2 <= 0);
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
              const Tensor<1, 3> c =
                cross_product_3d(vertices[k] - vertices[0],
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
              bool cross        = false;
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

      /**
       * Cut the polygon @p vertices (simple, nonzero area) into triangles
       * whose projections without coordinate @p drop have nonzero area: ear
       * clipping with exact orientations. Vertices exactly on the line of
       * their neighbours (in the projection) are left out: they lie on an
       * edge and change nothing. Returns indices into @p vertices.
       */
      std::vector<std::array<unsigned int, 3>>
      triangulate(const std::vector<Point<3>> &vertices,
                  const unsigned int           drop,
                  const std::size_t            number,
                  const std::string           &entry,
                  const std::string           &text)
      {
        std::vector<Point<2>> q;
        for (const auto &p : vertices)
          q.push_back(drop_coordinate(p, drop));
        double area = 0;
        for (unsigned int k = 0, l = q.size() - 1; k < q.size(); l = k++)
          area += q[l][0] * q[k][1] - q[k][0] * q[l][1];
        const int turn = area > 0 ? 1 : -1;

        std::vector<unsigned int> ring(vertices.size());
        for (unsigned int k = 0; k < ring.size(); ++k)
          ring[k] = k;
        std::vector<std::array<unsigned int, 3>> triangles;
        while (ring.size() >= 3)
          {
            const unsigned int m        = ring.size();
            int                straight = -1, ear = -1;
            for (unsigned int k = 0; k < m && straight < 0 && ear < 0; ++k)
              {
                const Point<2> &p = q[ring[(k + m - 1) % m]], &c = q[ring[k]],
                               &r = q[ring[(k + 1) % m]];
                const int o       = orient2d(p, c, r);
                if (o == 0)
                  straight = k;
                else if (o == turn)
                  {
                    bool empty = true;
                    for (unsigned int l = 0; l < m && empty; ++l)
                      if (l != k && l != (k + 1) % m && l != (k + m - 1) % m)
                        empty = !in_triangle(q[ring[l]], {{p, c, r}});
                    if (empty)
                      ear = k;
                  }
              }
            if (straight >= 0)
              {
                ring.erase(ring.begin() + straight);
                continue;
              }
            AssertThrow(ear >= 0,
                        ExcInvalidInput(entry,
                                        text,
                                        "the pre-crack polygon " +
                                          std::to_string(number) +
                                          " cannot be cut into triangles "
                                          "(its boundary touches itself)"));
            triangles.push_back(
              {{ring[(ear + m - 1) % m], ring[ear], ring[(ear + 1) % m]}});
            ring.erase(ring.begin() + ear);
          }
        return triangles;
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
              normal /= normal.norm();
              for (const auto &p : crack.vertices)
                AssertThrow(std::abs((p - crack.vertices[0]) * normal) <=
                              1e-9 * size,
                            ExcInvalidInput(entry,
                                            text,
                                            "the vertices of a pre-crack "
                                            "polygon must lie in one plane"));
              // Projected without the normal's largest component, the
              // polygon keeps at least 1/sqrt(3) of its area.
              crack.drop = 0;
              for (unsigned int d = 1; d < dim; ++d)
                if (std::abs(normal[d]) > std::abs(normal[crack.drop]))
                  crack.drop = d;
              crack.triangles = triangulate(crack.vertices,
                                            crack.drop,
                                            cracks.size() + 1,
                                            entry,
                                            text);
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
          const auto &crack   = cracks[index];
          bool        overlap = true;
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
              // The closed polygon is the union of its closed triangles.
              for (const auto &t : crack.triangles)
                if (segment_meets_triangle(a,
                                           b,
                                           {{crack.vertices[t[0]],
                                             crack.vertices[t[1]],
                                             crack.vertices[t[2]]}},
                                           crack.drop))
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
                                      "point " + std::to_string(k + 1) + " (" +
                                        point.str() +
                                        ") lies outside the body, where "
                                        "no node is; give a point on the "
                                        "body"));
        }
    }


    template class PreCracks<2>;
    template class PreCracks<3>;
#define PERIDEAL_INSTANTIATE(dim)                                          \
  template std::vector<BoundingBox<dim>> parse_boxes<dim>(                 \
    const std::string &,                                                   \
    const std::string &);                                                  \
  template std::vector<Point<dim>> parse_points<dim>(const std::string &,  \
                                                     const std::string &); \
  template std::vector<bool>       nodes_in_boxes<dim>(                    \
    const NodeSet<dim> &,                                            \
    const std::vector<BoundingBox<dim>> &,                           \
    const std::string &,                                             \
    const std::string &,                                             \
    const std::string &);
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
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
  } // namespace Discretization
} // namespace PeriDEAL
