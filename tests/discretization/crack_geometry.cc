// PreCracks::cuts() against an exact reference. Kind of test: brute-force
// reference (exact integer arithmetic), serial.
//
// The convention under test (crack_geometry.h): a bond [a, b] starts broken
// when it meets a pre-crack, both taken as closed sets: a 2D segment or a
// 3D planar polygon, its ends, edges and vertices included; a bond along a
// 2D crack or in a 3D crack's plane counts when it meets the crack. A 3D
// polygon that extrudes a 2D segment cuts the bonds the segment cuts.
//
// The reference decides with integers, on the exact values of the doubles
// that cuts() sees, so every degenerate case has one right answer and no
// tolerance enters:
// - coordinates k / 8 with small integers k (64-bit integers), where
//   collinear, touching and through-a-vertex cases are frequent;
// - doubles in [1, 2) with all 52 bits of mantissa, as multiples of
//   2^-52 (128-bit integers; 2D and 3D axis-aligned polygons only), with
//   points computed on a crack's line or edge and so on it or one rounding
//   off it: the cases that rounded arithmetic misjudges.
// The reference is written differently from cuts():
// - 2D: the two segments' parameters by Cramer's rule (0 <= t, s <= 1 as
//   integer comparisons); parallel segments overlap when they are collinear
//   and their projections on the bond overlap.
// - 3D: each polygon is given as closed triangles of its own (a fan from a
//   lattice point c for the random polygons, star-shaped about c by
//   construction, convex or not; by hand for a U shape, which is star-shaped
//   about no point), not the ear clipping of cuts(); a segment meets a
//   closed triangle when its ends are not strictly on one side of the plane
//   and the signed volumes of the line with the three edges do not have
//   opposite signs; a segment in the plane meets it when an end lies in it
//   or it meets an edge (the 2D test after dropping a coordinate). For the
//   axis-aligned polygons with arbitrary doubles, the bonds cross the plane
//   perpendicularly, end on it or lie in it, so the 2D tests decide.
// - 3D extrusions of the 2D cracks (rectangles through z0 <= z <= z1, the
//   bonds' ends between z0 and z1): the 2D reference decides, and 3D
//   cuts() must also equal 2D cuts() (the consistency the convention is
//   chosen for).
// The 2D family with arbitrary doubles prints whether the rounded 2D test
// that cuts() used before misjudges some of them (it must: otherwise they
// would not need exact predicates).
// Every bond is also checked reversed. Each family must hold both answers
// (or it tests nothing), and cuts() must equal the reference everywhere;
// the program returns 1 otherwise.

#include <deal.II/base/point.h>

#include <perideal/discretization/crack_geometry.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

// std::array set from flat lists ({x, y}): legal C++ that -Wmissing-braces
// (in deal.II's flags) would flag at every use.
#pragma GCC diagnostic ignored "-Wmissing-braces"

namespace
{
  __extension__ typedef __int128 int128;

  template <typename T>
  using V2 = std::array<T, 2>;
  using I2 = V2<std::int64_t>;
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

  /// A double in [1, 2) with 52 random bits of mantissa.
  double
  random_double()
  {
    const std::uint64_t high = rng(), low = rng();
    return 1 + std::ldexp(static_cast<double>((high << 20) | (low >> 12)), -52);
  }

  /// A double in [lo, hi] (not uniform in [1, 2) bits: a computed point).
  double
  random_real(const double lo, const double hi)
  {
    return lo + (hi - lo) * std::ldexp(static_cast<double>(rng()), -32);
  }

  template <typename T>
  T
  cross2(const V2<T> &u, const V2<T> &v)
  {
    return u[0] * v[1] - u[1] * v[0];
  }

  template <typename T>
  V2<T>
  sub(const V2<T> &u, const V2<T> &v)
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
  template <typename T>
  bool
  in_unit_interval(T num, T den)
  {
    if (den < 0)
      {
        num = -num;
        den = -den;
      }
    return 0 <= num && num <= den;
  }

  /// Closed segments [a, b] and [c, d] meet (Cramer's rule; a != b).
  template <typename T>
  bool
  exact_segments_meet(const V2<T> &a,
                      const V2<T> &b,
                      const V2<T> &c,
                      const V2<T> &d)
  {
    const V2<T> r = sub(b, a), q = sub(d, c), w = sub(c, a);
    const T     den = cross2(r, q);
    if (den != 0)
      // a + t r = c + s q: t = (w x q) / den, s = (w x r) / den.
      return in_unit_interval(cross2(w, q), den) &&
             in_unit_interval(cross2(w, r), den);
    if (cross2(w, r) != 0)
      return false; // parallel, not on one line
    // Collinear: [c, d] projected on r against [0, r.r].
    const auto proj = [&](const V2<T> &p) {
      const V2<T> v = sub(p, a);
      return v[0] * r[0] + v[1] * r[1];
    };
    const T lo = std::min(proj(c), proj(d)), hi = std::max(proj(c), proj(d));
    return lo <= r[0] * r[0] + r[1] * r[1] && 0 <= hi;
  }

  /// Point p in the closed triangle (t0, t1, t2) of the plane.
  template <typename T>
  bool
  exact_in_triangle(const V2<T> &p,
                    const V2<T> &t0,
                    const V2<T> &t1,
                    const V2<T> &t2)
  {
    const T o0 = cross2(sub(t1, t0), sub(p, t0)),
            o1 = cross2(sub(t2, t1), sub(p, t1)),
            o2 = cross2(sub(t0, t2), sub(p, t2));
    return (o0 >= 0 && o1 >= 0 && o2 >= 0) || (o0 <= 0 && o1 <= 0 && o2 <= 0);
  }

  /// Closed segment [a, b] (a != b) meets the closed triangle t of the
  /// plane.
  template <typename T>
  bool
  exact_segment_meets_triangle_2d(const V2<T>                &a,
                                  const V2<T>                &b,
                                  const std::array<V2<T>, 3> &t)
  {
    return exact_in_triangle(a, t[0], t[1], t[2]) ||
           exact_in_triangle(b, t[0], t[1], t[2]) ||
           exact_segments_meet(a, b, t[0], t[1]) ||
           exact_segments_meet(a, b, t[1], t[2]) ||
           exact_segments_meet(a, b, t[2], t[0]);
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
        return exact_segment_meets_triangle_2d<std::int64_t>(
          flat(a),
          flat(b),
          {{flat(t[0]), flat(t[1]), flat(t[2])}});
      }
    // The line ab pierces the plane once, inside the segment; inside the
    // closed triangle when it passes no edge on the other side.
    const std::int64_t v0 = orient3d(a, b, t[0], t[1]),
                       v1 = orient3d(a, b, t[1], t[2]),
                       v2 = orient3d(a, b, t[2], t[0]);
    return (v0 >= 0 && v1 >= 0 && v2 >= 0) || (v0 <= 0 && v1 <= 0 && v2 <= 0);
  }

  /// A polygon (3D vertices in order) and closed triangles whose union it
  /// is (the reference's own decomposition).
  struct Polygon
  {
    std::vector<I3>                vertices;
    std::vector<std::array<I3, 3>> pieces;
  };

  bool
  exact_segment_meets_polygon(const I3 &a, const I3 &b, const Polygon &p)
  {
    for (const auto &t : p.pieces)
      if (exact_segment_meets_triangle(a, b, t))
        return true;
    return false;
  }

  /// The integer k 2^-52 equal to x in [1, 2).
  int128
  exact_value(const double x)
  {
    if (!(1 <= x && x < 2))
      std::abort();
    return static_cast<std::int64_t>(std::ldexp(x, 52));
  }

  V2<int128>
  exact_value(const Point<2> &p)
  {
    return {exact_value(p[0]), exact_value(p[1])};
  }

  bool
  in_range(const Point<2> &p)
  {
    return 1 <= p[0] && p[0] < 2 && 1 <= p[1] && p[1] < 2;
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

  /// The input text of cracks given by their vertices.
  template <int dim>
  std::string
  crack_text(const std::vector<std::vector<Point<dim>>> &cracks)
  {
    std::ostringstream text;
    text.precision(17); // the doubles back exactly
    for (unsigned int c = 0; c < cracks.size(); ++c)
      {
        text << (c > 0 ? "; " : "");
        bool first = true;
        for (const auto &v : cracks[c])
          for (unsigned int d = 0; d < dim; ++d)
            {
              text << (first ? "" : ", ") << v[d];
              first = false;
            }
      }
    return text.str();
  }

  template <int dim, typename I>
  std::string
  crack_text(const std::vector<I> &vertices)
  {
    std::vector<Point<dim>> points;
    for (const auto &v : vertices)
      points.push_back(to_point<dim>(v));
    return crack_text<dim>({points});
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

    /// A named case: both directions checked, the reference's answer
    /// printed.
    template <typename Cracks, typename P>
    void
    add_named(const std::string &name,
              const bool         reference,
              const Cracks      &cracks,
              const P           &a,
              const P           &b)
    {
      add(reference, cracks.cuts(a, b), name);
      add(reference, cracks.cuts(b, a), name + " (reversed)");
      lines += "  " + name + ": " + (reference ? "cut" : "not cut") + "\n";
    }

    std::string lines;

    bool
    print(const std::string &name) const
    {
      // Both answers must occur, or the family says nothing.
      const bool both = n_cut > 0 && n_cut < n;
      std::cout << name << ": " << n << " configurations (" << n_cut
                << " cut), both answers present: " << (both ? "yes" : "NO")
                << "; cuts() = exact reference in all: "
                << (n_wrong == 0 ? "yes" : "NO") << std::endl;
      std::cout << lines;
      if (n_wrong > 0)
        std::cout << "  (" << n_wrong << " wrong, first: " << first_wrong << ")"
                  << std::endl;
      return both && n_wrong == 0;
    }
  };

  bool all_passed = true;

  void
  verdict(const std::string &what, const bool ok)
  {
    std::cout << what << ": " << (ok ? "yes" : "NO") << std::endl;
    all_passed = all_passed && ok;
  }

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

  template <int dim>
  std::string
  describe_points(const std::vector<Point<dim>> &points)
  {
    std::ostringstream out;
    out.precision(17);
    for (const auto &p : points)
      out << "(" << p << ")";
    return out.str();
  }


  /**
   * The rectangle that extrudes the 2D segment [c, d] over z0 <= z <= z1,
   * its vertices starting at a random one, in a random direction (so that
   * cuts() cuts it into triangles along either diagonal).
   */
  Discretization::PreCracks<3>
  extrusion(const Point<2> &c,
            const Point<2> &d,
            const double    z0,
            const double    z1)
  {
    std::vector<Point<3>> v = {Point<3>(c[0], c[1], z0),
                               Point<3>(d[0], d[1], z0),
                               Point<3>(d[0], d[1], z1),
                               Point<3>(c[0], c[1], z1)};
    std::rotate(v.begin(), v.begin() + random(0, 3), v.end());
    if (random(0, 1) == 1)
      std::reverse(v.begin(), v.end());
    Discretization::PreCracks<3> cracks;
    cracks.parse(crack_text<3>({v}), "test");
    return cracks;
  }

  /// z0, z1 or a value between them.
  double
  z_between(const double z0, const double z1)
  {
    const std::int64_t k = random(0, 2);
    return k == 0 ? z0 : k == 1 ? z1 : random_real(z0, z1);
  }

  /// The bond between 2D points a and b lifted to z_a and z_b, across the
  /// extrusion of a 2D crack: the 2D reference decides.
  void
  check_extruded(const Discretization::PreCracks<3> &extruded,
                 const Point<2>                     &a,
                 const Point<2>                     &b,
                 const double                        z_a,
                 const double                        z_b,
                 const bool                          reference,
                 const bool                          cut_2d,
                 const std::string                  &what,
                 Tally                              &tally,
                 bool                               &equal_2d)
  {
    const Point<3> a3(a[0], a[1], z_a), b3(b[0], b[1], z_b);
    const bool     cut_3d = extruded.cuts(a3, b3);
    tally.add(reference, cut_3d, what);
    equal_2d = equal_2d && cut_3d == cut_2d;
  }


  /// One 2D segment crack on the k/8 grid, many bonds; both directions of
  /// each bond; the same bonds across its extrusion over -1 <= z <= 1.
  void
  check_2d_crack(const I2              &c,
                 const I2              &d,
                 const std::vector<I2> &bond_ends,
                 Tally                 &tally,
                 Tally                 &extruded_tally,
                 bool                  &equal_2d)
  {
    Discretization::PreCracks<2> cracks;
    cracks.parse(crack_text<2>(std::vector<I2>{c, d}), "test");
    const auto extruded =
      extrusion(to_point<2>(c), to_point<2>(d), -8 * unit, 8 * unit);
    for (std::size_t k = 0; k + 1 < bond_ends.size(); k += 2)
      {
        const I2 &a = bond_ends[k], &b = bond_ends[k + 1];
        if (a == b)
          continue;
        const bool reference = exact_segments_meet(a, b, c, d);
        const auto what      = describe<I2>({a, b, c, d});
        const bool cut       = cracks.cuts(to_point<2>(a), to_point<2>(b));
        tally.add(reference, cut, "bond, crack " + what);
        tally.add(reference,
                  cracks.cuts(to_point<2>(b), to_point<2>(a)),
                  "reversed bond, crack " + what);
        // Ends at the rectangle's bottom, top or in between.
        const std::int64_t za = random(-8, 8), zb = random(-8, 8);
        check_extruded(extruded,
                       to_point<2>(a),
                       to_point<2>(b),
                       unit * za,
                       unit * zb,
                       reference,
                       cut,
                       "bond at z = " + std::to_string(za) + ", " +
                         std::to_string(zb) + ", extruded crack " + what,
                       extruded_tally,
                       equal_2d);
      }
  }


  /// The 2D test of crack_geometry.cc before it used exact predicates
  /// (rounded orientations), to show that a family needs them.
  bool
  rounded_segments_intersect(const Point<2> &a,
                             const Point<2> &b,
                             const Point<2> &c,
                             const Point<2> &d)
  {
    const auto orientation =
      [](const Point<2> &p, const Point<2> &q, const Point<2> &r) {
        return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
      };
    const auto on_segment =
      [](const Point<2> &p, const Point<2> &q, const Point<2> &r) {
        return std::min(p[0], q[0]) <= r[0] && r[0] <= std::max(p[0], q[0]) &&
               std::min(p[1], q[1]) <= r[1] && r[1] <= std::max(p[1], q[1]);
      };
    const double o1 = orientation(a, b, c), o2 = orientation(a, b, d),
                 o3 = orientation(c, d, a), o4 = orientation(c, d, b);
    if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) &&
        ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
      return true;
    return (o1 == 0 && on_segment(a, b, c)) ||
           (o2 == 0 && on_segment(a, b, d)) ||
           (o3 == 0 && on_segment(c, d, a)) || (o4 == 0 && on_segment(c, d, b));
  }


  /// Points near the segment [c, d] and its ends, computed in doubles: on
  /// its line or one rounding off it, one ulp from an end, through an end.
  std::vector<Point<2>>
  near_points(const Point<2> &c, const Point<2> &d)
  {
    std::vector<Point<2>> points = {c, d};
    for (const Point<2> &p : {c, d})
      for (unsigned int axis = 0; axis < 2; ++axis)
        for (const double direction : {0., 3.})
          {
            Point<2> q = p;
            q[axis]    = std::nextafter(p[axis], direction);
            points.push_back(q);
          }
    for (unsigned int k = 0; k < 8; ++k)
      {
        const double t = random_real(-0.5, 1.5);
        points.push_back(c + t * (d - c));
      }
    return points;
  }


  void
  check_2d()
  {
    Tally random_small, through_ends, named, doubles, extruded_small,
      extruded_doubles;
    bool equal_2d = true, rounded_misjudges = false;
    for (unsigned int trial = 0; trial < 400; ++trial)
      {
        I2 c, d;
        do
          {
            c = {random(-4, 4), random(-4, 4)};
            d = {random(-4, 4), random(-4, 4)};
        } while (c == d);
        std::vector<I2> ends;
        for (unsigned int k = 0; k < 100; ++k)
          ends.push_back({random(-5, 5), random(-5, 5)});
        check_2d_crack(c, d, ends, random_small, extruded_small, equal_2d);
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
            ends.push_back(
              {c[0] + s * (d[0] - c[0]), c[1] + s * (d[1] - c[1])});
            ends.push_back(
              {c[0] + t * (d[0] - c[0]), c[1] + t * (d[1] - c[1])});
          }
        check_2d_crack(c, d, ends, through_ends, extruded_small, equal_2d);
      }

    // Arbitrary doubles in [1, 2): bonds between points near the crack's
    // line and ends (see near_points()), random points, and through an end
    // (p + w, p - w rounded).
    for (unsigned int trial = 0; trial < 300; ++trial)
      {
        const Point<2> c(random_double(), random_double());
        Point<2>       d(random_double(), random_double());
        if (trial % 4 == 0)
          d[1] = c[1]; // axis-parallel cracks too
        std::vector<Point<2>> points = near_points(c, d);
        for (unsigned int k = 0; k < 4; ++k)
          points.emplace_back(random_double(), random_double());
        std::vector<std::pair<Point<2>, Point<2>>> bonds;
        for (unsigned int k = 0; k < 60; ++k)
          bonds.emplace_back(points[random(0, points.size() - 1)],
                             points[random(0, points.size() - 1)]);
        for (unsigned int k = 0; k < 20; ++k)
          {
            const Point<2>    &p = k % 2 == 0 ? c : d;
            const Tensor<1, 2> w(
              {random_real(-0.3, 0.3), random_real(-0.3, 0.3)});
            bonds.emplace_back(p + w, p - w);
          }
        Discretization::PreCracks<2> cracks;
        cracks.parse(crack_text<2>({{c, d}}), "test");
        double z_lo = random_double(), z_hi = random_double();
        while (z_hi == z_lo)
          z_hi = random_double();
        if (z_hi < z_lo)
          std::swap(z_lo, z_hi);
        const auto extruded = extrusion(c, d, z_lo, z_hi);
        for (const auto &[a, b] : bonds)
          {
            if (a == b || !in_range(a) || !in_range(b))
              continue;
            const bool reference = exact_segments_meet(exact_value(a),
                                                       exact_value(b),
                                                       exact_value(c),
                                                       exact_value(d));
            const auto what      = describe_points<2>({a, b, c, d});
            const bool cut       = cracks.cuts(a, b);
            doubles.add(reference, cut, "bond, crack " + what);
            doubles.add(reference,
                        cracks.cuts(b, a),
                        "reversed bond, crack " + what);
            rounded_misjudges =
              rounded_misjudges ||
              rounded_segments_intersect(a, b, c, d) != reference;
            const double za = z_between(z_lo, z_hi), zb = z_between(z_lo, z_hi);
            check_extruded(extruded,
                           a,
                           b,
                           za,
                           zb,
                           reference,
                           cut,
                           "bond, extruded crack " + what,
                           extruded_doubles,
                           equal_2d);
          }
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
    cracks.parse(crack_text<2>(std::vector<I2>{c, d}), "test");
    for (const auto &[name, bond] : cases)
      {
        named.add_named(name,
                        exact_segments_meet(bond[0], bond[1], c, d),
                        cracks,
                        to_point<2>(bond[0]),
                        to_point<2>(bond[1]));
      }
    bool ok = true;
    ok =
      random_small.print("2D, random bonds and cracks on the 1/8 grid") && ok;
    ok = through_ends.print("2D, bonds through or ending on a crack's end, "
                            "and collinear bonds") &&
         ok;
    ok = named.print("2D, the named degenerate cases") && ok;
    ok =
      doubles.print("2D, arbitrary doubles near a crack's line and ends") && ok;
    verdict("  rounded arithmetic misjudges some of these (the family needs "
            "exact predicates)",
            rounded_misjudges);
    ok = extruded_small.print("3D, extrusions of the 2D cracks on the 1/8 "
                              "grid, bonds between their z bounds") &&
         ok;
    ok = extruded_doubles.print("3D, extrusions of the 2D cracks with "
                                "arbitrary doubles") &&
         ok;
    verdict("  3D cuts() of an extrusion = 2D cuts() of the segment in all",
            equal_2d);
    all_passed = all_passed && ok;
  }


  /// A random polygon star-shaped about (0, 0) in integer plane
  /// coordinates: 3 to 7 vertices with distinct directions in increasing
  /// angle, consecutive ones less than pi apart (convex or not).
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
              same_ray = same_ray ||
                         (cross2(p, q) == 0 && p[0] * q[0] + p[1] * q[1] > 0);
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


  /// The map of plane coordinates (i, j) to o + i e1 + j e2, all
  /// coordinates doubled so that edge midpoints are lattice points.
  struct Plane
  {
    I3 o, e1, e2;

    I3
    operator()(const I2 &s) const
    {
      I3 v;
      for (unsigned int d = 0; d < 3; ++d)
        v[d] = 2 * (o[d] + s[0] * e1[d] + s[1] * e2[d]);
      return v;
    }
  };


  /// The polygon @p star on @p plane, as the fan of closed triangles from
  /// its centre.
  Polygon
  place_star(const std::vector<I2> &star, const Plane &plane)
  {
    Polygon p;
    for (const auto &s : star)
      p.vertices.push_back(plane(s));
    const I3 centre = plane({0, 0});
    for (unsigned int k = 0; k < star.size(); ++k)
      p.pieces.push_back(
        {{centre, p.vertices[k], p.vertices[(k + 1) % star.size()]}});
    return p;
  }


  void
  check_3d_polygon(const Polygon         &polygon,
                   const std::vector<I3> &bond_ends,
                   Tally                 &tally)
  {
    Discretization::PreCracks<3> cracks;
    cracks.parse(crack_text<3>(polygon.vertices), "test");
    for (std::size_t k = 0; k + 1 < bond_ends.size(); k += 2)
      {
        const I3 &a = bond_ends[k], &b = bond_ends[k + 1];
        if (a == b)
          continue;
        const bool reference = exact_segment_meets_polygon(a, b, polygon);
        const auto what =
          describe<I3>({a, b}) + ", polygon " + describe<I3>(polygon.vertices);
        tally.add(reference,
                  cracks.cuts(to_point<3>(a), to_point<3>(b)),
                  "bond " + what);
        tally.add(reference,
                  cracks.cuts(to_point<3>(b), to_point<3>(a)),
                  "reversed bond " + what);
      }
  }


  I3
  plus(const I3 &p, const I3 &w, const std::int64_t s)
  {
    return I3{p[0] + s * w[0], p[1] + s * w[1], p[2] + s * w[2]};
  }

  /// A random nonzero lattice vector.
  I3
  random_offset()
  {
    I3 w;
    do
      w = {random(-4, 4), random(-4, 4), random(-4, 4)};
    while (w[0] == 0 && w[1] == 0 && w[2] == 0);
    return w;
  }

  /// A random plane through the lattice; every third one a coordinate
  /// plane (the usual input).
  Plane
  random_plane(const unsigned int trial)
  {
    Plane plane;
    I3    n;
    do
      {
        for (unsigned int d = 0; d < 3; ++d)
          {
            plane.e1[d] = random(-2, 2);
            plane.e2[d] = random(-2, 2);
          }
        n = cross3(plane.e1, plane.e2);
    } while (n[0] == 0 && n[1] == 0 && n[2] == 0);
    if (trial % 3 == 0)
      {
        plane.e1 = {1, 0, 0};
        plane.e2 = {0, 0, 1};
      }
    plane.o = {random(-3, 3), random(-3, 3), random(-3, 3)};
    return plane;
  }

  /// Random bonds near @p polygon on @p plane: in a slab of three lattice
  /// planes parallel to it, and in a box around it.
  std::vector<I3>
  random_bonds(const Plane &plane, const std::int64_t reach)
  {
    const I3        n = cross3(plane.e1, plane.e2);
    std::vector<I3> ends;
    // (Random numbers drawn in a fixed order: not as function arguments,
    // whose order of evaluation is unspecified.)
    for (unsigned int k = 0; k < 60; ++k)
      {
        const I3 ijk = {random(-reach, reach),
                        random(-reach, reach),
                        random(-1, 1)};
        I3       p;
        for (unsigned int d = 0; d < 3; ++d)
          p[d] = 2 * plane.o[d] + ijk[0] * plane.e1[d] + ijk[1] * plane.e2[d] +
                 ijk[2] * n[d];
        ends.push_back(p);
      }
    for (unsigned int k = 0; k < 40; ++k)
      {
        const I3 w = {random(-20, 20), random(-20, 20), random(-20, 20)};
        ends.push_back(plus(plane({0, 0}), w, 1));
      }
    return ends;
  }

  I3
  midpoint(const I3 &p, const I3 &q)
  {
    return {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
  }


  /// A U (star-shaped about no point) in plane coordinates, and closed
  /// triangles covering it (three rectangles cut by hand).
  Polygon
  place_u(const Plane &plane)
  {
    const std::vector<I2> u =
      {{0, 0}, {6, 0}, {6, 4}, {4, 4}, {4, 2}, {2, 2}, {2, 4}, {0, 4}};
    const std::vector<std::array<I2, 3>> pieces = {{{{0, 0}, {6, 0}, {6, 2}}},
                                                   {{{0, 0}, {6, 2}, {0, 2}}},
                                                   {{{0, 2}, {2, 2}, {2, 4}}},
                                                   {{{0, 2}, {2, 4}, {0, 4}}},
                                                   {{{4, 2}, {6, 2}, {6, 4}}},
                                                   {{{4, 2}, {6, 4}, {4, 4}}}};
    Polygon                              p;
    for (const auto &s : u)
      p.vertices.push_back(plane(s));
    for (const auto &t : pieces)
      p.pieces.push_back({{plane(t[0]), plane(t[1]), plane(t[2])}});
    return p;
  }


  void
  check_3d_lattice()
  {
    Tally random_box, through_vertices, through_edges, ending_on, in_plane,
      u_random, named, u_named;
    unsigned int n_polygons = 0, n_non_convex = 0, n_straight = 0;
    for (unsigned int trial = 0; trial < 300; ++trial)
      {
        const Plane           plane   = random_plane(trial);
        const std::vector<I2> star    = random_star();
        const Polygon         polygon = place_star(star, plane);
        const auto           &v       = polygon.vertices;
        const I3              centre  = plane({0, 0});
        ++n_polygons;
        bool non_convex = false, straight = false;
        for (unsigned int k = 0; k < star.size(); ++k)
          {
            const I2 &p = star[(k + star.size() - 1) % star.size()],
                     &c = star[k], &q = star[(k + 1) % star.size()];
            const std::int64_t turn = cross2(sub(c, p), sub(q, c));
            non_convex              = non_convex || turn < 0;
            straight                = straight || turn == 0;
          }
        n_non_convex += non_convex;
        n_straight += straight;

        check_3d_polygon(polygon, random_bonds(plane, 12), random_box);
        // Through a vertex and through a point outside, beyond it from the
        // centre (the polygon is star-shaped about the centre, so that
        // point is outside).
        std::vector<I3> ends;
        for (unsigned int k = 0; k < 30; ++k)
          {
            const I3 w       = random_offset();
            const I3 p       = v[random(0, v.size() - 1)];
            const I3 outside = plus(p,
                                    I3{(p[0] - centre[0]) / 2,
                                       (p[1] - centre[1]) / 2,
                                       (p[2] - centre[2]) / 2},
                                    1);
            ends.push_back(plus(p, w, 1));
            ends.push_back(plus(p, w, -1));
            ends.push_back(plus(outside, w, 1));
            ends.push_back(plus(outside, w, -1));
          }
        check_3d_polygon(polygon, ends, through_vertices);
        // Through an edge's midpoint, and through the point outside twice
        // as far from the centre.
        ends.clear();
        for (unsigned int k = 0; k < 30; ++k)
          {
            const unsigned int e       = random(0, v.size() - 1);
            const I3           mid     = midpoint(v[e], v[(e + 1) % v.size()]);
            const I3           outside = plus(plus(mid, mid, 1), centre, -1);
            const I3           w       = random_offset();
            ends.push_back(plus(mid, w, 1));
            ends.push_back(plus(mid, w, -1));
            ends.push_back(plus(outside, w, 1));
            ends.push_back(plus(outside, w, -1));
          }
        check_3d_polygon(polygon, ends, through_edges);
        // Ending on a vertex, an edge's midpoint, the centre, or a point
        // outside beyond the vertex.
        ends.clear();
        for (unsigned int k = 0; k < 40; ++k)
          {
            const unsigned int e = random(0, v.size() - 1);
            const I3          &p = v[e], &q = v[(e + 1) % v.size()];
            const I3           on = k % 4 == 0 ? p :
                                    k % 4 == 1 ? midpoint(p, q) :
                                    k % 4 == 2 ? centre :
                                                 plus(plus(p, p, 1), centre, -1);
            ends.push_back(on);
            ends.push_back(plus(on, random_offset(), 1));
          }
        check_3d_polygon(polygon, ends, ending_on);
        // In the polygon's plane: random, and along the lines of its edges.
        ends.clear();
        for (unsigned int k = 0; k < 60; ++k)
          {
            const I2 ij = {random(-10, 10), random(-10, 10)};
            const I3 p  = plane({0, 0});
            ends.push_back(plus(plus(p, plane.e1, ij[0]), plane.e2, ij[1]));
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
        // The U on the same plane.
        if (trial % 2 == 0)
          check_3d_polygon(place_u(plane), random_bonds(plane, 16), u_random);
      }

    // The square 0 <= x, z <= 8 in the plane y = 0 (1 unit = 1/8), bonds
    // named by what they do.
    const Polygon square = {{{0, 0, 0}, {8, 0, 0}, {8, 0, 8}, {0, 0, 8}},
                            {{{{0, 0, 0}, {8, 0, 0}, {0, 0, 8}}},
                             {{{8, 0, 0}, {8, 0, 8}, {0, 0, 8}}}}};
    const std::vector<std::pair<std::string, std::array<I3, 2>>> cases = {
      {"crossing the interior", {{{2, -1, 5}, {2, 1, 5}}}},
      {"crossing the interior, oblique", {{{3, -1, 2}, {5, 1, 6}}}},
      {"through the edge x = 8", {{{8, -1, 4}, {8, 1, 4}}}},
      {"through the edge x = 0", {{{0, -1, 4}, {0, 1, 4}}}},
      {"through the edge z = 0", {{{4, -1, 0}, {4, 1, 0}}}},
      {"through the edge z = 8", {{{4, -1, 8}, {4, 1, 8}}}},
      {"through the edge x = 8, oblique", {{{7, -1, 4}, {9, 1, 4}}}},
      {"through the vertex (8, 0, 8)", {{{7, -1, 7}, {9, 1, 9}}}},
      {"through the vertex (0, 0, 0)", {{{-1, -1, 1}, {1, 1, -1}}}},
      {"through the diagonal x + z = 8 (where cuts() splits the square)",
       {{{2, -1, 6}, {2, 1, 6}}}},
      {"in the plane, along that diagonal", {{{1, 0, 7}, {7, 0, 1}}}},
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
      {"crossing the plane just past a vertex", {{{9, -1, 9}, {9, 1, 9}}}},
      {"stopping short of the plane", {{{4, 1, 4}, {4, 3, 4}}}}};
    Discretization::PreCracks<3> cracks;
    cracks.parse(crack_text<3>(square.vertices), "test");
    for (const auto &[name, bond] : cases)
      {
        named.add_named(name,
                        exact_segment_meets_polygon(bond[0], bond[1], square),
                        cracks,
                        to_point<3>(bond[0]),
                        to_point<3>(bond[1]));
      }

    // The U in the plane y = 0: 0 <= x <= 12, 0 <= z <= 8, the slot
    // 4 < x < 8, z > 4 cut out (1 unit = 1/8).
    const Polygon u = place_u({{0, 0, 0}, {1, 0, 0}, {0, 0, 1}});
    const std::vector<std::pair<std::string, std::array<I3, 2>>> u_cases = {
      {"through the slot", {{{6, -1, 6}, {6, 1, 6}}}},
      {"through the slot's bottom edge", {{{6, -1, 4}, {6, 1, 4}}}},
      {"through a reflex vertex", {{{4, -1, 4}, {4, 1, 4}}}},
      {"through the slot's side edge", {{{4, -1, 6}, {4, 1, 6}}}},
      {"through an arm", {{{2, -1, 6}, {2, 1, 6}}}},
      {"in the plane, across the slot from arm to arm",
       {{{1, 0, 6}, {11, 0, 6}}}},
      {"in the plane, inside the slot", {{{5, 0, 6}, {7, 0, 6}}}},
      {"in the plane, from the slot into the base", {{{6, 0, 6}, {6, 0, 3}}}},
      {"in the plane, touching the slot's side", {{{5, 0, 6}, {4, 0, 6}}}},
      {"ending on a reflex vertex, from above the slot",
       {{{4, 0, 4}, {6, 1, 6}}}},
      {"crossing the plane in the slot, oblique", {{{5, -1, 5}, {7, 1, 7}}}}};
    cracks.parse(crack_text<3>(u.vertices), "test");
    for (const auto &[name, bond] : u_cases)
      {
        u_named.add_named(name,
                          exact_segment_meets_polygon(bond[0], bond[1], u),
                          cracks,
                          to_point<3>(bond[0]),
                          to_point<3>(bond[1]));
      }

    std::cout << "3D, random polygons on the 1/8 grid: " << n_polygons << " ("
              << n_non_convex << " not convex, " << n_straight
              << " with a vertex on the line of its neighbours)" << std::endl;
    bool ok = true;
    ok      = random_box.print("3D, random bonds near random polygons") && ok;
    ok =
      through_vertices.print("3D, bonds through a vertex or beside it") && ok;
    ok = through_edges.print(
           "3D, bonds through an edge's midpoint or beside it") &&
         ok;
    ok = ending_on.print("3D, bonds ending on a vertex, an edge, inside or "
                         "outside") &&
         ok;
    ok = in_plane.print("3D, bonds in the polygon's plane") && ok;
    ok = named.print("3D, the named degenerate cases (a square)") && ok;
    ok = u_random.print("3D, random bonds near a U-shaped polygon") && ok;
    ok = u_named.print("3D, the named cases of the U") && ok;
    all_passed = all_passed && ok;
  }


  /// The 3D point with coordinate @p axis equal to z and the others x, y.
  Point<3>
  lift(const Point<2> &p, const double z, const unsigned int axis)
  {
    Point<3> q;
    q[axis]           = z;
    q[(axis + 1) % 3] = p[0];
    q[(axis + 2) % 3] = p[1];
    return q;
  }


  /// Polygons in the planes x, y or z = z0 with arbitrary doubles in
  /// [1, 2); bonds perpendicular through the plane, ending on it, or in it,
  /// from points on, near (one rounding or one ulp) and off the vertices
  /// and edges.
  void
  check_3d_doubles()
  {
    Tally through, ending_on, in_plane;
    for (unsigned int trial = 0; trial < 150; ++trial)
      {
        const unsigned int axis = trial % 3;
        const double       z0   = random_double();
        // Star-shaped about c (checked exactly), convex or not.
        const Point<2>        c(random_real(1.3, 1.7), random_real(1.3, 1.7));
        std::vector<Point<2>> v;
        bool                  star = false;
        while (!star)
          {
            v.clear();
            std::vector<double> angle(random(3, 7));
            for (auto &a : angle)
              a = random_real(0, 2 * numbers::PI);
            std::sort(angle.begin(), angle.end());
            for (const double a : angle)
              {
                const double r = random_real(0.05, 0.28);
                v.push_back(c + r * Tensor<1, 2>({std::cos(a), std::sin(a)}));
              }
            star = true;
            for (unsigned int k = 0; k < v.size(); ++k)
              star = star && cross2(sub(exact_value(v[k]), exact_value(c)),
                                    sub(exact_value(v[(k + 1) % v.size()]),
                                        exact_value(c))) > 0;
          }
        std::vector<std::array<V2<int128>, 3>> pieces;
        for (unsigned int k = 0; k < v.size(); ++k)
          pieces.push_back({{exact_value(c),
                             exact_value(v[k]),
                             exact_value(v[(k + 1) % v.size()])}});
        const auto inside = [&](const Point<2> &p) {
          for (const auto &t : pieces)
            if (exact_in_triangle(exact_value(p), t[0], t[1], t[2]))
              return true;
          return false;
        };
        const auto meets = [&](const Point<2> &a, const Point<2> &b) {
          for (const auto &t : pieces)
            if (exact_segment_meets_triangle_2d(exact_value(a),
                                                exact_value(b),
                                                t))
              return true;
          return false;
        };

        std::vector<Point<3>> vertices;
        for (const auto &p : v)
          vertices.push_back(lift(p, z0, axis));
        Discretization::PreCracks<3> cracks;
        cracks.parse(crack_text<3>({vertices}), "test");

        std::vector<Point<2>> points = {c};
        for (unsigned int k = 0; k < v.size(); ++k)
          {
            const auto near = near_points(v[k], v[(k + 1) % v.size()]);
            points.insert(points.end(), near.begin(), near.end());
          }
        for (unsigned int k = 0; k < 4; ++k)
          points.emplace_back(random_real(1.0, 1.99), random_real(1.0, 1.99));
        const auto pick = [&]() {
          Point<2> p;
          do
            p = points[random(0, points.size() - 1)];
          while (!in_range(p));
          return p;
        };
        const std::string what = describe_points<3>(vertices);
        for (unsigned int k = 0; k < 40; ++k)
          {
            // Perpendicular through the plane (or stopping short of it).
            const Point<2> p        = pick();
            const double   h1       = random_real(0.01, 0.4),
                         h2         = random_real(0.01, 0.4);
            const bool     short_of = k % 8 == 0;
            const Point<3> a = lift(p, short_of ? z0 + h1 + h2 : z0 - h1, axis),
                           b = lift(p, z0 + h2, axis);
            const bool reference = !short_of && inside(p);
            const auto bond      = describe_points<3>({a, b}) + ", polygon ";
            through.add(reference, cracks.cuts(a, b), "bond " + bond + what);
            through.add(reference,
                        cracks.cuts(b, a),
                        "reversed bond " + bond + what);
          }
        for (unsigned int k = 0; k < 40; ++k)
          {
            // From a point on the plane to any point off it.
            const Point<2> p = pick(), q = pick();
            const double   h = random_real(-0.4, 0.4);
            if (h == 0)
              continue;
            const Point<3> a = lift(p, z0, axis), b = lift(q, z0 + h, axis);
            const bool     reference = inside(p);
            const auto     bond = describe_points<3>({a, b}) + ", polygon ";
            ending_on.add(reference, cracks.cuts(a, b), "bond " + bond + what);
            ending_on.add(reference,
                          cracks.cuts(b, a),
                          "reversed bond " + bond + what);
          }
        for (unsigned int k = 0; k < 40; ++k)
          {
            // In the plane.
            const Point<2> p = pick(), q = pick();
            if (p == q)
              continue;
            const Point<3> a = lift(p, z0, axis), b = lift(q, z0, axis);
            const bool     reference = meets(p, q);
            const auto     bond = describe_points<3>({a, b}) + ", polygon ";
            in_plane.add(reference, cracks.cuts(a, b), "bond " + bond + what);
            in_plane.add(reference,
                         cracks.cuts(b, a),
                         "reversed bond " + bond + what);
          }
      }
    bool ok = true;
    ok = through.print("3D, arbitrary doubles, axis-aligned polygons, bonds "
                       "perpendicular through the plane") &&
         ok;
    ok = ending_on.print("3D, arbitrary doubles, axis-aligned polygons, bonds "
                         "ending on the plane") &&
         ok;
    ok = in_plane.print("3D, arbitrary doubles, axis-aligned polygons, bonds "
                        "in the plane") &&
         ok;
    all_passed = all_passed && ok;
  }
} // namespace


int
main()
{
  check_2d();
  check_3d_lattice();
  check_3d_doubles();
  std::cout << "every check passed: " << (all_passed ? "yes" : "NO")
            << std::endl;
  return all_passed ? 0 : 1;
}
