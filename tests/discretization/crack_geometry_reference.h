/**
 * @file
 * The exact reference of tests/discretization/crack_geometry.cc (that file
 * says what it checks and how the reference decides): integer and 128-bit
 * predicates, random lattice and double inputs, crack texts for
 * PreCracks::parse(), and the tallies of a family of bonds. Included by
 * that test only, so its helpers keep internal linkage.
 */

#ifndef PERIDEAL_TESTS_CRACK_GEOMETRY_REFERENCE_H
#define PERIDEAL_TESTS_CRACK_GEOMETRY_REFERENCE_H

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

// std::array set from flat lists ({x, y}): legal C++ that -Wmissing-braces
// (in deal.II's flags) would flag at every use.
#pragma GCC diagnostic ignored "-Wmissing-braces"

namespace
{
  using namespace dealii;
  using namespace PeriDEAL;

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
} // namespace

#endif
