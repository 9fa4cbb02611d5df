#include <perideal/quadrature/ball_box_intersection.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace PeriDEAL
{
  namespace Quadrature
  {
    namespace
    {
      // All internal arithmetic runs in x87 extended precision (64-bit
      // mantissa): the corner measures below are sums of terms up to
      // O(R^2) times a cell size whose result may be O(1), so double
      // arithmetic would lose log10(R^2) digits. See doc/partial-volumes.md.
      using real = long double;

      /**
       * Area of the part of the disc of radius r = sqrt(@p r2) around the
       * origin with x >= a and y >= b, for a, b >= 0 and
       * D = r^2 - a^2 - b^2 > 0 given (passed in so that callers can supply
       * it accurately).
       *
       * With X = sqrt(r^2 - b^2), Y = sqrt(r^2 - a^2) the region is the right
       * triangle (a, b), (X, b), (a, Y) plus the circular segment over its
       * hypotenuse, whose arc subtends the angle psi between (a, Y) and
       * (X, b):
       *   A = (X - a)(Y - b)/2 + r^2 (psi - sin psi)/2.
       * Both terms are non-negative, and X - a = D/(X + a),
       * Y - b = D/(Y + b), r^2 sin psi = X Y - a b = r^2 D/(X Y + a b) are
       * free of cancellation, so the area has a small relative error even
       * for tiny corners far from the centre.
       */
      struct PlanarCorner
      {
        real area;
        real radius2;    // r^2 of the circle
        real psi;        // arc angle
        real sin_psi_r2; // r^2 sin(psi)
        real cos_psi_r2; // r^2 cos(psi)
      };

      /// X = sqrt(r^2 - b^2), Y = sqrt(r^2 - a^2), X - a = D/(X + a) and
      /// Y - b = D/(Y + b) are passed in: in 3D they are shared between the
      /// faces.
      PlanarCorner
      planar_corner(const real r2,
                    const real a,
                    const real b,
                    const real D,
                    const real X,
                    const real Y,
                    const real X_minus_a,
                    const real Y_minus_b)
      {
        const real sin_psi_r2 = r2 * D / (X * Y + a * b);
        const real cos_psi_r2 = a * X + b * Y;
        const real psi        = std::atan2(sin_psi_r2, cos_psi_r2);
        const real triangle   = X_minus_a * Y_minus_b / 2;
        const real segment    = (r2 * psi - sin_psi_r2) / 2;
        return {triangle + segment, r2, psi, sin_psi_r2, cos_psi_r2};
      }


      real
      corner_area(const real a, const real b, const real R)
      {
        // b is the larger coordinate (sorted): R - b is exact, so D keeps
        // its relative accuracy when the corner is close to the circle.
        const real D = (R - b) * (R + b) - a * a;
        if (!(D > 0))
          return 0;
        const real X = std::sqrt(D + a * a);
        const real Y = std::sqrt(D + b * b);
        return planar_corner(D + a * a + b * b,
                             a,
                             b,
                             D,
                             X,
                             Y,
                             D / (X + a),
                             D / (Y + b))
          .area;
      }


      /**
       * Volume of the part of the ball of radius R around the origin with
       * x >= a, y >= b, z >= c, for a, b, c >= 0.
       *
       * Divergence theorem with the position vector:
       *   V = (R |T| - a A_a - b A_b - c A_c) / 3,
       * |T| the area of the spherical patch T (the part of the sphere in the
       * corner region) and A_k the planar corner areas on the three cut
       * planes. T is the geodesic triangle through its three vertices plus
       * three lenses cut off by small circles; the solid angles come from
       * quantities free of cancellation (doc/partial-volumes.md, Sect. 1.3).
       */
      real
      corner_volume(const real a, const real b, const real c, const real R)
      {
        const real R2 = R * R;
        // c is the largest coordinate (sorted): R - c is exact, so D keeps
        // its relative accuracy for corners close to the sphere near the
        // poles; the other squares below are all formed as sums of positive
        // terms from D.
        const real D = (R - c) * (R + c) - a * a - b * b;
        if (!(D > 0))
          return 0;

        // The vertices of T, Px = (X, b, c), Py = (a, Y, c), Pz = (a, b, Z):
        // where the edges from the corner parallel to the axes leave the ball.
        const real X = std::sqrt(D + a * a);
        const real Y = std::sqrt(D + b * b);
        const real Z = std::sqrt(D + c * c);

        // The planar corners on x = a (in-plane corner (b, c), extents Y and
        // Z), on y = b ((a, c); X, Z) and on z = c ((a, b); X, Y).
        const real         Xa = D / (X + a);
        const real         Yb = D / (Y + b);
        const real         Zc = D / (Z + c);
        const PlanarCorner on_a =
          planar_corner(D + b * b + c * c, b, c, D, Y, Z, Yb, Zc);
        const PlanarCorner on_b =
          planar_corner(D + a * a + c * c, a, c, D, X, Z, Xa, Zc);
        const PlanarCorner on_c =
          planar_corner(D + a * a + b * b, a, b, D, X, Y, Xa, Yb);

        // Solid angle of T = geodesic triangle + three lenses:
        //   Omega_g = 2 atan2(Px.(Py x Pz), R^3 + R(Px.Py + Py.Pz + Pz.Px))
        //     (van Oosterom-Strackee; the triple product through the edge
        //     vectors, X - a = D/(X + a) etc.),
        //   L_k = psi_k (R - k)/R - 2 atan(kappa sin psi/(1 + kappa cos psi))
        //       = 2 atan((k/R) tan(psi_k/2)) - (k/R) psi_k,
        // kappa = (R - k)/(R + k). The two forms of the lens are the same
        // function; the first is free of cancellation for k near R, the
        // second for k small (it vanishes exactly for k = 0), so each lens
        // uses the form that suits it: a small lens must come out small in
        // absolute terms, because its error is multiplied by R^3.
        // The four arctangents (each in [0, pi/4]) are summed as the
        // argument of one complex product, saving three extended-precision
        // atan2 calls.
        const real triple = X * Yb * Zc + b * Xa * Zc + c * Xa * Yb;
        const real dots   = (X * a + b * Y + c * c) + (a * a + Y * b + c * Z) +
                          (X * a + b * b + c * Z);
        real re = R2 * R + R * dots, im = triple;
        real linear_part = 0; // the psi terms of the lenses
        for (const auto &[arc, k] : {std::make_pair(&on_a, a),
                                     std::make_pair(&on_b, b),
                                     std::make_pair(&on_c, c)})
          {
            const real r2 = arc->radius2;
            real       q, s;
            if (2 * k >= R)
              {
                // Subtract the argument of ((R + k)^2 + r^2 cos psi) +
                // i r^2 sin psi.
                q = (R + k) * (R + k) + arc->cos_psi_r2;
                s = -arc->sin_psi_r2;
                linear_part += arc->psi * (R - k) / R;
              }
            else
              {
                // Add the argument of R (r^2 + r^2 cos psi) + i k r^2 sin psi:
                // tan(psi/2) = sin psi / (1 + cos psi).
                q = R * (r2 + arc->cos_psi_r2);
                s = k * arc->sin_psi_r2;
                linear_part -= arc->psi * k / R;
              }
            const real new_re = re * q - im * s;
            im                = im * q + re * s;
            re                = new_re;
          }
        // The exact sum of the four angles lies in [-3 pi/4, pi].
        const real patch_solid_angle = 2 * std::atan2(im, re) + linear_part;

        return (R2 * R * patch_solid_angle - a * on_a.area - b * on_b.area -
                c * on_c.area) /
               3;
      }


      /// Sort 2 or 3 coordinates ascending (a sorting network, inlined).
      template <int dim>
      inline void
      sort_coordinates(std::array<real, dim> &x)
      {
        auto order = [&](const unsigned int i, const unsigned int j) {
          if (x[j] < x[i])
            std::swap(x[i], x[j]);
        };
        if constexpr (dim >= 2)
          order(0, 1);
        if constexpr (dim == 3)
          {
            order(1, 2);
            order(0, 1);
          }
      }


      template <int dim>
      real
      first_orthant_corner_measure(std::array<real, dim> corner, const real R)
      {
        // The corner measure is symmetric in the coordinates: evaluating it
        // on sorted coordinates makes the result exactly symmetric, and lets
        // callers memoize it by sorted corner.
        sort_coordinates<dim>(corner);
        // 1D: the part of [0, R] beyond the corner.
        if constexpr (dim == 1)
          return std::max(R - corner[0], real(0));
        else if constexpr (dim == 2)
          return corner_area(corner[0], corner[1], R);
        else
          return corner_volume(corner[0], corner[1], corner[2], R);
      }


      /**
       * Inclusion-exclusion over the corners of the box [lower, upper]: the
       * sum of corner_measure(corner) over the \f$2^{dim}\f$ corners, with
       * sign \f$(-1)^k\f$ for a corner that takes k coordinates from
       * @p upper. Shared by the general boxes (real coordinates) and the
       * uniform-grid tables (integer half units), so that both add the
       * corners in the same order.
       */
      template <int dim, typename Coordinate, typename CornerMeasure>
      real
      signed_corner_sum(const std::array<Coordinate, dim> &lower,
                        const std::array<Coordinate, dim> &upper,
                        const CornerMeasure               &corner_measure)
      {
        real sum = 0;
        for (unsigned int vertex = 0; vertex < (1u << dim); ++vertex)
          {
            std::array<Coordinate, dim> corner;
            int                         sign = 1;
            for (unsigned int d = 0; d < dim; ++d)
              if (vertex & (1u << d))
                {
                  corner[d] = upper[d];
                  sign      = -sign;
                }
              else
                corner[d] = lower[d];
            sum += sign * corner_measure(corner);
          }
        return sum;
      }


      /**
       * Measure of the ball of radius R around the origin intersected with
       * the box [lower, upper], all coordinates >= 0: inclusion-exclusion
       * over the box corners.
       */
      template <int dim, typename CornerMeasure>
      real
      first_orthant_box_measure(const std::array<real, dim> &lower,
                                const std::array<real, dim> &upper,
                                const real                   R,
                                const CornerMeasure         &corner_measure)
      {
        real nearest2 = 0, farthest2 = 0, box_measure = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            nearest2 += lower[d] * lower[d];
            farthest2 += upper[d] * upper[d];
            box_measure *= upper[d] - lower[d];
          }
        if (box_measure == 0 || nearest2 >= R * R)
          return 0;
        if (farthest2 <= R * R)
          return box_measure;

        const real sum = signed_corner_sum<dim>(lower, upper, corner_measure);
        // The exact value lies in [0, box_measure]; clip round-off.
        return std::min(std::max(sum, real(0)), box_measure);
      }
    } // namespace


    template <int dim>
    double
    ball_corner_measure(const Point<dim> &corner, const double radius)
    {
      std::array<real, dim> a;
      for (unsigned int d = 0; d < dim; ++d)
        {
          Assert(corner[d] >= 0, ExcMessage("Corner must be non-negative."));
          a[d] = corner[d];
        }
      return static_cast<double>(
        first_orthant_corner_measure<dim>(a, real(radius)));
    }


    namespace
    {
      template <int dim, typename CornerMeasure>
      double
      intersection_measure(const Point<dim>       &centre,
                           const double            radius,
                           const BoundingBox<dim> &box,
                           const CornerMeasure    &corner_measure)
      {
        Assert(radius >= 0, ExcMessage("The radius must be non-negative."));

        // Cells entirely inside or outside the ball, decided with a safe
        // margin in double precision: most cells of a grid, and the cheap
        // ones.
        {
          double nearest2 = 0, farthest2 = 0, box_measure = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double lo   = box.lower_bound(d) - centre[d];
              const double hi   = box.upper_bound(d) - centre[d];
              const double near = (lo > 0 ? lo : (hi < 0 ? -hi : 0.));
              const double far  = std::max(-lo, hi);
              nearest2 += near * near;
              farthest2 += far * far;
              box_measure *= hi - lo;
            }
          const double R2 = radius * radius;
          if (nearest2 > R2 * (1 + 1e-10) + 1e-300)
            return 0;
          if (farthest2 < R2 * (1 - 1e-10))
            return box_measure;
        }

        // Split every side at the centre's coordinate and reflect the pieces
        // into the first orthant; the ball is symmetric under reflections.
        std::array<std::array<std::array<real, 2>, 2>, dim> pieces;
        std::array<unsigned int, dim>                       n_pieces;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const real lo = real(box.lower_bound(d)) - real(centre[d]);
            const real hi = real(box.upper_bound(d)) - real(centre[d]);
            if (lo >= 0)
              {
                pieces[d][0] = {{lo, hi}};
                n_pieces[d]  = 1;
              }
            else if (hi <= 0)
              {
                pieces[d][0] = {{-hi, -lo}};
                n_pieces[d]  = 1;
              }
            else
              {
                pieces[d][0] = {{0, -lo}};
                pieces[d][1] = {{0, hi}};
                n_pieces[d]  = 2;
              }
          }

        unsigned int n_total = 1;
        for (unsigned int d = 0; d < dim; ++d)
          n_total *= n_pieces[d];

        real measure = 0;
        for (unsigned int p = 0; p < n_total; ++p)
          {
            std::array<real, dim> lower, upper;
            unsigned int          index = p;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const auto &piece = pieces[d][index % n_pieces[d]];
                index /= n_pieces[d];
                lower[d] = piece[0];
                upper[d] = piece[1];
              }
            measure += first_orthant_box_measure<dim>(lower,
                                                      upper,
                                                      radius,
                                                      corner_measure);
          }
        return static_cast<double>(measure);
      }
    } // namespace


    template <int dim>
    double
    ball_box_intersection_measure(const Point<dim>       &centre,
                                  const double            radius,
                                  const BoundingBox<dim> &box)
    {
      return intersection_measure<dim>(
        centre,
        radius,
        box,
        [radius](const std::array<real, dim> &corner) {
          return first_orthant_corner_measure<dim>(corner, radius);
        });
    }


    template <int dim>
    std::vector<double>
    unit_cell_intersection_measures(
      const std::vector<std::array<int, dim>> &offsets,
      const double                             radius)
    {
      const real R  = radius;
      const real R2 = R * R;

      // Corner measures by corner, the corner given by its coordinates in
      // half units (exact integers), sorted and packed into one key.
      std::unordered_map<std::uint64_t, real> corner_measures;
      corner_measures.reserve(offsets.size());
      auto corner_measure = [&](std::array<int, dim> twice) -> real {
        std::uint64_t norm2 = 0;
        for (const int t : twice)
          norm2 += static_cast<std::uint64_t>(t) * t;
        if (norm2 >= 4 * R2)
          return 0;
        if constexpr (dim >= 2)
          if (twice[1] < twice[0])
            std::swap(twice[0], twice[1]);
        if constexpr (dim == 3)
          {
            if (twice[2] < twice[1])
              std::swap(twice[1], twice[2]);
            if (twice[1] < twice[0])
              std::swap(twice[0], twice[1]);
          }
        std::uint64_t key = 0;
        for (const int t : twice)
          key = (key << 21) | static_cast<std::uint64_t>(t);
        const auto [entry, is_new] = corner_measures.try_emplace(key, 0);
        if (is_new)
          {
            std::array<real, dim> corner;
            for (unsigned int d = 0; d < dim; ++d)
              corner[d] = real(twice[d]) / 2;
            entry->second = first_orthant_corner_measure<dim>(corner, R);
          }
        return entry->second;
      };

      std::vector<double> measures;
      measures.reserve(offsets.size());
      for (const auto &offset : offsets)
        {
          // The cell reflected into the first orthant: [2|o| - 1, 2|o| + 1]
          // in half units, or, for o = 0, twice the piece [0, 1].
          std::array<int, dim> lower, upper;
          real                 multiplicity = 1;
          std::uint64_t        nearest2 = 0, farthest2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const int o = std::abs(offset[d]);
              lower[d]    = (o == 0 ? 0 : 2 * o - 1);
              upper[d]    = (o == 0 ? 1 : 2 * o + 1);
              if (o == 0)
                multiplicity *= 2;
              nearest2 += static_cast<std::uint64_t>(lower[d]) * lower[d];
              farthest2 += static_cast<std::uint64_t>(2 * o + 1) * (2 * o + 1);
            }
          if (nearest2 >= 4 * R2)
            measures.push_back(0);
          else if (farthest2 <= 4 * R2)
            measures.push_back(1);
          else
            {
              const real sum =
                signed_corner_sum<dim>(lower, upper, corner_measure);
              const real piece = real(1) / multiplicity;
              measures.push_back(static_cast<double>(
                multiplicity * std::min(std::max(sum, real(0)), piece)));
            }
        }
      return measures;
    }


    template double
    ball_corner_measure(const Point<1> &, const double);
    template double
    ball_corner_measure(const Point<2> &, const double);
    template double
    ball_corner_measure(const Point<3> &, const double);
    template double
    ball_box_intersection_measure(const Point<1> &,
                                  const double,
                                  const BoundingBox<1> &);
    template double
    ball_box_intersection_measure(const Point<2> &,
                                  const double,
                                  const BoundingBox<2> &);
    template double
    ball_box_intersection_measure(const Point<3> &,
                                  const double,
                                  const BoundingBox<3> &);
    template std::vector<double>
    unit_cell_intersection_measures<1>(const std::vector<std::array<int, 1>> &,
                                       const double);
    template std::vector<double>
    unit_cell_intersection_measures<2>(const std::vector<std::array<int, 2>> &,
                                       const double);
    template std::vector<double>
    unit_cell_intersection_measures<3>(const std::vector<std::array<int, 3>> &,
                                       const double);
  } // namespace Quadrature
} // namespace PeriDEAL
