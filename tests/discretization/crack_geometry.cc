// PreCracks::cuts() against an exact reference (Kind of test: brute force
// with exact integer arithmetic, serial).
//
// A bond [a, b] starts broken when it meets a pre-crack, endpoints and the
// crack's boundary included (closed sets): a 2D segment, a 3D planar
// polygon. Every configuration here has coordinates k / 8 with small
// integers k, so the doubles cuts() sees are exactly the rationals the
// reference decides with 64-bit integers: there is no rounding on either
// side, and every degenerate case has one right answer.
//
// The reference is written differently from cuts():
// - 2D: the two segments' parameters by Cramer's rule (0 <= t, s <= 1 as
//   integer comparisons); parallel segments overlap when they are collinear
//   and their projections on the bond overlap.
// - 3D: each polygon is star-shaped about a lattice point c by
//   construction, so it is the union of the closed triangles (c, v_k,
//   v_k+1); a segment meets a closed triangle when its ends are not strictly
//   on one side of the plane and the signed volumes of the line with the
//   three edges do not have opposite signs (orient3d); a segment in the
//   plane meets it when an end lies in it or it meets an edge (the 2D test
//   after dropping the normal's largest component).
//
// Configurations: random ones on small grids (where collinear, touching and
// through-a-vertex cases are frequent), bonds through a crack's endpoints,
// vertices and edge midpoints, bonds in the crack's plane, and a list of
// named degenerate cases.

#include <deal.II/base/point.h>

#include <perideal/discretization/crack_geometry.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  using I2 = std::array<std::int64_t, 2>;
  using I3 = std::array<std::int64_t, 3>;

  // Integer coordinates k stand for k / 8 (exact in binary).
  constexpr double unit = 0.125;

  std::mt19937 rng(20240611);

  /// A uniform integer in [lo, hi] (from the raw engine, whose sequence
  /// the standard fixes).
  std::int64_t
  random(const std::int64_t lo, const std::int64_t hi)
  {
    return lo + static_cast<std::int64_t>(rng() % (hi - lo + 1));
  }

  std::int64_t
  cross2(const I2 &u, const I2 &v)
  {
    return u[0] * v[1] - u[1] * v[0];
  }

  I2
  sub(const I2 &u, const I2 &v)
  {
    return {u[0] - v[0], u[1] - v[1]};
  }

  I3
  sub(const I3 &u, const I3 &v)
  {
    return {u[0] - v[0], u[1] - v[1], u[2] - v[2]};
  }

  I3
  cross3(const I3 &u, const I3 &v)
  {
    return {u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0]};
  }

  std::int64_t
  dot3(const I3 &u, const I3 &v)
  {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  }

  /// Signed volume of (q - p, r - p, s - p).
  std::int64_t
  orient3d(const I3 &p, const I3 &q, const I3 &r, const I3 &s)
  {
    return dot3(cross3(sub(q, p), sub(r, p)), sub(s, p));
  }

  /// Whether 0 <= num / den <= 1 (den != 0).
  bool
  in_unit_interval(std::int64_t num, std::int64_t den)
  {
    if (den < 0)
      {
        num = -num;
        den = -den;
      }
    return 0 <= num && num <= den;
  }

  /// Closed segments [a, b] and [c, d] meet (Cramer's rule; a != b).
  bool
  exact_segments_meet(const I2 &a, const I2 &b, const I2 &c, const I2 &d)
  {
    const I2           r = sub(b, a), q = sub(d, c), w = sub(c, a);
    const std::int64_t den = cross2(r, q);
    if (den != 0)
      // a + t r = c + s q: t = (w x q) / den, s = (w x r) / den.
      return in_unit_interval(cross2(w, q), den) &&
             in_unit_interval(cross2(w, r), den);
    if (cross2(w, r) != 0)
      return false; // parallel, not on one line
    // Collinear: [c, d] projected on r against [0, r.r].
    const auto         proj = [&](const I2 &p) {
      const I2 v = sub(p, a);
      return v[0] * r[0] + v[1] * r[1];
    };
    const std::int64_t lo = std::min(proj(c), proj(d)),
                       hi = std::max(proj(c), proj(d));
    return lo <= r[0] * r[0] + r[1] * r[1] && 0 <= hi;
  }

  /// Point p in the closed triangle (t0, t1, t2) of the plane.
  bool
  exact_in_triangle(const I2 &p, const I2 &t0, const I2 &t1, const I2 &t2)
  {
    const std::int64_t o0 = cross2(sub(t1, t0), sub(p, t0)),
                       o1 = cross2(sub(t2, t1), sub(p, t1)),
                       o2 = cross2(sub(t0, t2), sub(p, t2));
    return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
  }

  /// Closed segment [a, b] meets the closed (non-degenerate) triangle t.
  bool
  exact_segment_meets_triangle(const I3                &a,
                               const I3                &b,
                               const std::array<I3, 3> &t)
  {
    const std::int64_t sa = orient3d(t[0], t[1], t[2], a),
                       sb = orient3d(t[0], t[1], t[2], b);
    if ((sa > 0 && sb > 0) || (sa < 0 && sb < 0))
      return false;
    if (sa == 0 && sb == 0)
      {
        // In the plane: drop the normal's largest component.
        const I3     n    = cross3(sub(t[1], t[0]), sub(t[2], t[0]));
        unsigned int drop = 0;
        for (unsigned int d = 1; d < 3; ++d)
          if (std::abs(n[d]) > std::abs(n[drop]))
            drop = d;
        const auto flat = [&](const I3 &p) {
          return I2{p[drop == 0 ? 1 : 0], p[drop == 2 ? 1 : 2]};
        };
        const I2 a2 = flat(a), b2 = flat(b), t0 = flat(t[0]), t1 = flat(t[1]),
                 t2 = flat(t[2]);
        return exact_in_triangle(a2, t0, t1, t2) ||
               exact_in_triangle(b2, t0, t1, t2) ||
               exact_segments_meet(a2, b2, t0, t1) ||
               exact_segments_meet(a2, b2, t1, t2) ||
               exact_segments_meet(a2, b2, t2, t0);
      }
    // The line ab pierces the plane once, inside the segment; inside the
    // closed triangle when it passes no edge on the other side.
    const std::int64_t v0 = orient3d(a, b, t[0], t[1]),
                       v1 = orient3d(a, b, t[1], t[2]),
                       v2 = orient3d(a, b, t[2], t[0]);
    return (v0 >= 0 && v1 >= 0 && v2 >= 0) || (v0 <= 0 && v1 <= 0 && v2 <= 0);
  }

  /// A polygon star-shaped about its centre, with the 3D vertices.
  struct Polygon
  {
    I3              centre;
    std::vector<I3> vertices;
  };

  bool
  exact_segment_meets_polygon(const I3 &a, const I3 &b, const Polygon &p)
  {
    const unsigned int n = p.vertices.size();
    for (unsigned int k = 0; k < n; ++k)
      if (exact_segment_meets_triangle(
            a, b, {{p.centre, p.vertices[k], p.vertices[(k + 1) % n]}}))
        return true;
    return false;
  }

  template <int dim, typename I>
  Point<dim>
  to_point(const I &x)
  {
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      p[d] = unit * x[d];
    return p;
  }

  /// The input text of cracks given by their integer vertices.
  template <typename I>
  std::string
  crack_text(const std::vector<std::vector<I>> &cracks)
  {
    std::ostringstream text;
    text.precision(17);
    for (unsigned int c = 0; c < cracks.size(); ++c)
      {
        text << (c > 0 ? "; " : "");
        bool first = true;
        for (const auto &v : cracks[c])
          for (const auto x : v)
            {
              text << (first ? "" : ", ") << unit * x;
              first = false;
            }
      }
    return text.str();
  }

  /// Counts of one family of configurations.
  struct Tally
  {
    unsigned int n = 0, n_cut = 0, n_wrong = 0;
    std::string  first_wrong;

    void
    add(const bool reference, const bool code, const std::string &what)
    {
      ++n;
      n_cut += reference;
      if (reference != code)
        {
          if (n_wrong == 0)
            first_wrong = what + ": reference " +
                          (reference ? "cut" : "not cut") + ", cuts() " +
                          (code ? "cut" : "not cut");
          ++n_wrong;
        }
    }

    void
    print(const std::string &name) const
    {
      // Both answers must occur, or the family says nothing.
      std::cout << name << ": " << n
                << " configurations, both answers present: "
                << (n_cut > 0 && n_cut < n ? "yes" : "NO")
                << "; cuts() = exact reference in all: "
                << (n_wrong == 0 ? "yes" : "NO") << std::endl;
      if (n_wrong > 0)
        std::cout << "  (" << n_wrong << " wrong, first: " << first_wrong
                  << ")" << std::endl;
    }
  };

  template <typename I>
  std::string
  describe(const std::vector<I> &points)
  {
    std::ostringstream out;
    for (const auto &p : points)
      {
        out << "(";
        for (unsigned int d = 0; d < p.size(); ++d)
          out << (d > 0 ? ", " : "") << p[d];
        out << ")";
      }
    return out.str() + " x 1/8";
  }


  /// One 2D segment crack, many bonds; both directions of each bond.
  void
  check_2d_crack(const I2              &c,
                 const I2              &d,
                 const std::vector<I2> &bond_ends,
                 Tally                 &tally)
  {
    Discretization::PreCracks<2> cracks;
    cracks.parse(crack_text<I2>({{c, d}}), "test");
    for (std::size_t k = 0; k + 1 < bond_ends.size(); k += 2)
      {
        const I2 &a = bond_ends[k], &b = bond_ends[k + 1];
        if (a == b)
          continue;
        const bool reference = exact_segments_meet(a, b, c, d);
        const auto what      = describe<I2>({a, b, c, d});
        tally.add(reference,
                  cracks.cuts(to_point<2>(a), to_point<2>(b)),
                  "bond, crack " + what);
        tally.add(reference,
                  cracks.cuts(to_point<2>(b), to_point<2>(a)),
                  "reversed bond, crack " + what);
      }
  }


  void
  check_2d()
  {
    Tally random_small, through_ends, named;
    for (unsigned int trial = 0; trial < 400; ++trial)
      {
        I2 c, d;
        do
          {
            c = {random(-4, 4), random(-4, 4)};
            d = {random(-4, 4), random(-4, 4)};
          }
        while (c == d);
        std::vector<I2> ends;
        for (unsigned int k = 0; k < 100; ++k)
          ends.push_back({random(-5, 5), random(-5, 5)});
        check_2d_crack(c, d, ends, random_small);
        // Bonds through an end of the crack, with an end on it, along it.
        ends.clear();
        for (unsigned int k = 0; k < 40; ++k)
          {
            const I2 &p = k % 2 == 0 ? c : d;
            const I2  v = {random(-3, 3), random(-3, 3)};
            ends.push_back({p[0] + v[0], p[1] + v[1]});
            ends.push_back({p[0] - v[0], p[1] - v[1]});
            ends.push_back(p);
            ends.push_back({p[0] + v[0], p[1] + v[1]});
            const std::int64_t s = random(-2, 3), t = random(-2, 3);
            ends.push_back({c[0] + s * (d[0] - c[0]), c[1] + s * (d[1] - c[1])});
            ends.push_back({c[0] + t * (d[0] - c[0]), c[1] + t * (d[1] - c[1])});
          }
        check_2d_crack(c, d, ends, through_ends);
      }
    // Crack from (0, 0) to (8, 0) (1 unit = 1/8), bonds named by what they
    // do.
    const I2 c = {0, 0}, d = {8, 0};
    const std::vector<std::pair<std::string, std::array<I2, 2>>> cases = {
      {"crossing the interior", {{{4, -1}, {4, 1}}}},
      {"through the crack's end", {{{8, -1}, {8, 1}}}},
      {"through the crack's end, oblique", {{{7, -1}, {9, 1}}}},
      {"ending on the crack's end", {{{8, 0}, {9, 3}}}},
      {"ending on the crack's interior", {{{3, 0}, {3, 2}}}},
      {"crack's end on the bond (T)", {{{8, -2}, {8, 2}}}},
      {"collinear, overlapping", {{{6, 0}, {10, 0}}}},
      {"collinear, touching at the end", {{{8, 0}, {12, 0}}}},
      {"collinear, inside", {{{2, 0}, {5, 0}}}},
      {"collinear, containing the crack", {{{-1, 0}, {9, 0}}}},
      {"collinear, disjoint", {{{9, 0}, {12, 0}}}},
      {"parallel, off the line", {{{2, 1}, {5, 1}}}},
      {"passing the end", {{{9, -1}, {9, 1}}}},
      {"stopping short of the crack", {{{4, 1}, {4, 3}}}}};
    Discretization::PreCracks<2> cracks;
    cracks.parse(crack_text<I2>({{c, d}}), "test");
    for (const auto &[name, bond] : cases)
      {
        const bool reference = exact_segments_meet(bond[0], bond[1], c, d);
        named.add(reference,
                  cracks.cuts(to_point<2>(bond[0]), to_point<2>(bond[1])),
                  name);
        named.add(reference,
                  cracks.cuts(to_point<2>(bond[1]), to_point<2>(bond[0])),
                  name + " (reversed)");
      }
    random_small.print("2D, random bonds and cracks on a small grid");
    through_ends.print("2D, bonds through or ending on a crack's end, and "
                       "collinear bonds");
    named.print("2D, the named degenerate cases");
  }


  /// A random polygon star-shaped about (0, 0) in integer plane
  /// coordinates: 3 to 7 vertices with distinct directions in increasing
  /// angle, consecutive ones less than pi apart.
  std::vector<I2>
  random_star()
  {
    const auto upper = [](const I2 &v) {
      return v[1] > 0 || (v[1] == 0 && v[0] > 0);
    };
    const auto before = [&](const I2 &u, const I2 &v) {
      if (upper(u) != upper(v))
        return upper(u);
      return cross2(u, v) > 0;
    };
    for (;;)
      {
        const unsigned int n = random(3, 7);
        std::vector<I2>    v;
        while (v.size() < n)
          {
            const I2 p = {random(-4, 4), random(-4, 4)};
            if (p[0] == 0 && p[1] == 0)
              continue;
            bool same_ray = false;
            for (const auto &q : v)
              same_ray =
                same_ray || (cross2(p, q) == 0 && p[0] * q[0] + p[1] * q[1] > 0);
            if (!same_ray)
              v.push_back(p);
          }
        std::sort(v.begin(), v.end(), before);
        bool ok = true;
        for (unsigned int k = 0; k < n; ++k)
          ok = ok && cross2(v[k], v[(k + 1) % n]) > 0;
        if (ok)
          return v;
      }
  }


  /// The polygon @p star (plane coordinates) on the plane o + i e1 + j e2,
  /// all coordinates doubled so that edge midpoints are lattice points.
  Polygon
  place(const std::vector<I2> &star, const I3 &o, const I3 &e1, const I3 &e2)
  {
    Polygon p;
    p.centre = {2 * o[0], 2 * o[1], 2 * o[2]};
    for (const auto &s : star)
      {
        I3 v;
        for (unsigned int d = 0; d < 3; ++d)
          v[d] = 2 * (o[d] + s[0] * e1[d] + s[1] * e2[d]);
        p.vertices.push_back(v);
      }
    return p;
  }


  void
  check_3d_polygon(const Polygon         &polygon,
                   const std::vector<I3> &bond_ends,
                   Tally                 &tally)
  {
    Discretization::PreCracks<3> cracks;
    cracks.parse(crack_text<I3>({polygon.vertices}), "test");
    for (std::size_t k = 0; k + 1 < bond_ends.size(); k += 2)
      {
        const I3 &a = bond_ends[k], &b = bond_ends[k + 1];
        if (a == b)
          continue;
        const bool reference = exact_segment_meets_polygon(a, b, polygon);
        const auto what      = describe<I3>({a, b}) + ", polygon " +
                          describe<I3>(polygon.vertices);
        tally.add(reference,
                  cracks.cuts(to_point<3>(a), to_point<3>(b)),
                  "bond " + what);
        tally.add(reference,
                  cracks.cuts(to_point<3>(b), to_point<3>(a)),
                  "reversed bond " + what);
      }
  }


  void
  check_3d()
  {
    Tally random_box, through_vertices, through_edges, ending_on, in_plane,
      named;
    for (unsigned int trial = 0; trial < 300; ++trial)
      {
        I3 e1, e2, n;
        do
          {
            for (unsigned int d = 0; d < 3; ++d)
              {
                e1[d] = random(-2, 2);
                e2[d] = random(-2, 2);
              }
            n = cross3(e1, e2);
          }
        while (n[0] == 0 && n[1] == 0 && n[2] == 0);
        // Every third plane a coordinate plane (the usual input).
        if (trial % 3 == 0)
          {
            e1 = {1, 0, 0};
            e2 = {0, 0, 1};
            n  = cross3(e1, e2);
          }
        const I3      o       = {random(-3, 3), random(-3, 3), random(-3, 3)};
        const Polygon polygon = place(random_star(), o, e1, e2);
        const auto   &v       = polygon.vertices;
        const auto    plane_point = [&](const std::int64_t i,
                                     const std::int64_t j,
                                     const std::int64_t k) {
          I3 p;
          for (unsigned int d = 0; d < 3; ++d)
            p[d] = 2 * o[d] + i * e1[d] + j * e2[d] + k * n[d];
          return p;
        };
        const auto random_offset = [&]() {
          I3 w;
          do
            w = {random(-4, 4), random(-4, 4), random(-4, 4)};
          while (w[0] == 0 && w[1] == 0 && w[2] == 0);
          return w;
        };
        const auto plus = [](const I3 &p, const I3 &w, const std::int64_t s) {
          return I3{p[0] + s * w[0], p[1] + s * w[1], p[2] + s * w[2]};
        };
        std::vector<I3> ends;
        // Random bonds in a box around the polygon.
        // (Random numbers drawn in a fixed order: not as function
        // arguments, whose order of evaluation is unspecified.)
        for (unsigned int k = 0; k < 60; ++k)
          {
            const I3 ijk = {random(-12, 12), random(-12, 12), random(-1, 1)};
            ends.push_back(plane_point(ijk[0], ijk[1], ijk[2]));
          }
        for (unsigned int k = 0; k < 40; ++k)
          ends.push_back(I3{2 * o[0] + random(-20, 20),
                            2 * o[1] + random(-20, 20),
                            2 * o[2] + random(-20, 20)});
        check_3d_polygon(polygon, ends, random_box);
        // Through a vertex; through an edge's midpoint (or another lattice
        // point of the edge); ending on a vertex, an edge or inside.
        ends.clear();
        for (unsigned int k = 0; k < 30; ++k)
          {
            const I3 w = random_offset();
            const I3 p = v[random(0, v.size() - 1)];
            ends.push_back(plus(p, w, 1));
            ends.push_back(plus(p, w, -1));
          }
        check_3d_polygon(polygon, ends, through_vertices);
        ends.clear();
        for (unsigned int k = 0; k < 30; ++k)
          {
            const unsigned int e = random(0, v.size() - 1);
            const I3          &p = v[e], &q = v[(e + 1) % v.size()];
            const I3 mid = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
            const I3 w   = random_offset();
            ends.push_back(plus(mid, w, 1));
            ends.push_back(plus(mid, w, -1));
          }
        check_3d_polygon(polygon, ends, through_edges);
        ends.clear();
        for (unsigned int k = 0; k < 30; ++k)
          {
            const unsigned int e = random(0, v.size() - 1);
            const I3          &p = v[e], &q = v[(e + 1) % v.size()];
            const I3 on = k % 3 == 0 ? p :
                          k % 3 == 1 ?
                                       I3{(p[0] + q[0]) / 2,
                                          (p[1] + q[1]) / 2,
                                          (p[2] + q[2]) / 2} :
                                       polygon.centre;
            ends.push_back(on);
            ends.push_back(plus(on, random_offset(), 1));
          }
        check_3d_polygon(polygon, ends, ending_on);
        // In the plane of the polygon: crossing it, along an edge, through
        // a vertex, outside.
        ends.clear();
        for (unsigned int k = 0; k < 60; ++k)
          {
            const I2 ij = {random(-10, 10), random(-10, 10)};
            ends.push_back(plane_point(ij[0], ij[1], 0));
          }
        for (unsigned int e = 0; e < v.size(); ++e)
          {
            const I3 &p = v[e], &q = v[(e + 1) % v.size()];
            ends.push_back(plus(p, sub(q, p), -1));
            ends.push_back(plus(p, sub(q, p), 2));
            ends.push_back(plus(p, sub(q, p), 1));
            ends.push_back(plus(p, sub(q, p), 3));
          }
        check_3d_polygon(polygon, ends, in_plane);
      }

    // The square 0 <= x, z <= 8 in the plane y = 0 (1 unit = 1/8), bonds
    // named by what they do.
    const Polygon square = {{4, 0, 4}, {{0, 0, 0}, {8, 0, 0}, {8, 0, 8}, {0, 0, 8}}};
    const std::vector<std::pair<std::string, std::array<I3, 2>>> cases = {
      {"crossing the interior", {{{4, -1, 4}, {4, 1, 4}}}},
      {"crossing the interior, oblique", {{{3, -1, 2}, {5, 1, 6}}}},
      {"through the edge x = 8", {{{8, -1, 4}, {8, 1, 4}}}},
      {"through the edge x = 0", {{{0, -1, 4}, {0, 1, 4}}}},
      {"through the edge z = 0", {{{4, -1, 0}, {4, 1, 0}}}},
      {"through the edge z = 8", {{{4, -1, 8}, {4, 1, 8}}}},
      {"through the edge x = 8, oblique", {{{7, -1, 4}, {9, 1, 4}}}},
      {"through the vertex (8, 0, 8)", {{{7, -1, 7}, {9, 1, 9}}}},
      {"through the vertex (0, 0, 0)", {{{-1, -1, 1}, {1, 1, -1}}}},
      {"ending on the interior", {{{4, 0, 4}, {4, 2, 4}}}},
      {"ending on an edge", {{{8, 0, 4}, {9, 1, 4}}}},
      {"ending on a vertex", {{{8, 0, 8}, {9, 1, 9}}}},
      {"in the plane, crossing the square", {{{-2, 0, 4}, {10, 0, 4}}}},
      {"in the plane, inside", {{{2, 0, 2}, {5, 0, 6}}}},
      {"in the plane, along an edge", {{{2, 0, 0}, {12, 0, 0}}}},
      {"in the plane, touching a vertex", {{{8, 0, 8}, {10, 0, 12}}}},
      {"in the plane, outside", {{{9, 0, 0}, {9, 0, 8}}}},
      {"parallel to the plane, off it", {{{2, 1, 2}, {6, 1, 6}}}},
      {"crossing the plane outside", {{{9, -1, 4}, {9, 1, 4}}}},
      {"stopping short of the plane", {{{4, 1, 4}, {4, 3, 4}}}}};
    Discretization::PreCracks<3> cracks;
    cracks.parse(crack_text<I3>({square.vertices}), "test");
    for (const auto &[name, bond] : cases)
      {
        const bool reference =
          exact_segment_meets_polygon(bond[0], bond[1], square);
        named.add(reference,
                  cracks.cuts(to_point<3>(bond[0]), to_point<3>(bond[1])),
                  name);
        named.add(reference,
                  cracks.cuts(to_point<3>(bond[1]), to_point<3>(bond[0])),
                  name + " (reversed)");
      }
    random_box.print("3D, random bonds near random polygons");
    through_vertices.print("3D, bonds through a vertex");
    through_edges.print("3D, bonds through a point of an edge");
    ending_on.print("3D, bonds ending on a vertex, an edge or inside");
    in_plane.print("3D, bonds in the polygon's plane");
    named.print("3D, the named degenerate cases");
  }
} // namespace


int
main()
{
  check_2d();
  check_3d();
}
