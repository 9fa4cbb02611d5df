#include <perideal/quadrature/ball_box_intersection.h>

#include <array>
#include <cmath>

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
        real psi;        // arc angle
        real sin_psi_r2; // r^2 sin(psi)
        real cos_psi_r2; // r^2 cos(psi)
      };

      PlanarCorner
      planar_corner(const real r2, const real a, const real b, const real D)
      {
        const real X          = std::sqrt(r2 - b * b);
        const real Y          = std::sqrt(r2 - a * a);
        const real sin_psi_r2 = r2 * D / (X * Y + a * b);
        const real cos_psi_r2 = a * X + b * Y;
        const real psi        = std::atan2(sin_psi_r2, cos_psi_r2);
        const real triangle   = (D / (X + a)) * (D / (Y + b)) / 2;
        const real segment    = (r2 * psi - sin_psi_r2) / 2;
        return {triangle + segment, psi, sin_psi_r2, cos_psi_r2};
      }


      real
      corner_area(const real a, const real b, const real R)
      {
        const real D = R * R - a * a - b * b;
        if (!(D > 0))
          return 0;
        return planar_corner(R * R, a, b, D).area;
      }


      /**
       * Solid angle of the lens between the small-circle arc at height k
       * (arc angle psi in its own plane) of the sphere of radius R and the
       * great-circle arc through the same end points:
       *   psi (R - k)/R - 2 atan(kappa sin psi / (1 + kappa cos psi)),
       * kappa = (R - k)/(R + k), written with r^2 sin psi and r^2 cos psi,
       * r^2 = R^2 - k^2, as
       *   psi (R - k)/R - 2 atan2(r^2 sin psi, (R + k)^2 + r^2 cos psi).
       */
      real
      lens_solid_angle(const PlanarCorner &arc, const real k, const real R)
      {
        return arc.psi * (R - k) / R -
               2 *
                 std::atan2(arc.sin_psi_r2, (R + k) * (R + k) + arc.cos_psi_r2);
      }


      /**
       * Volume of the part of the ball of radius R around the origin with
       * x >= a, y >= b, z >= c, for a, b, c >= 0.
       *
       * Divergence theorem with the position vector, which vanishes in the
       * normal direction on the three planes only through the factor of
       * their distance:
       *   V = (R A_T - a A_a - b A_b - c A_c) / 3,
       * A_T the area of the spherical patch T (the part of the sphere in the
       * corner region) and A_k the planar corner areas on the three cut
       * planes. T is the geodesic triangle through its three vertices plus
       * three lenses, each cut off by a small circle; all four solid angles
       * are computed from quantities free of cancellation.
       */
      real
      corner_volume(const real a, const real b, const real c, const real R)
      {
        const real R2 = R * R;
        const real D  = R2 - a * a - b * b - c * c;
        if (!(D > 0))
          return 0;

        // The three vertices of T: where the edges from the corner parallel
        // to the axes leave the ball.
        const real X = std::sqrt(R2 - b * b - c * c);
        const real Y = std::sqrt(R2 - a * a - c * c);
        const real Z = std::sqrt(R2 - a * a - b * b);

        const PlanarCorner on_a = planar_corner(R2 - a * a, b, c, D);
        const PlanarCorner on_b = planar_corner(R2 - b * b, a, c, D);
        const PlanarCorner on_c = planar_corner(R2 - c * c, a, b, D);

        // Geodesic triangle (Px, Py, Pz) with Px = (X, b, c), Py = (a, Y, c),
        // Pz = (a, b, Z): van Oosterom-Strackee,
        //   tan(Omega/2) = Px.(Py x Pz) / (R^3 + R (Px.Py + Py.Pz + Pz.Px)),
        // with the triple product written through the edge vectors, whose
        // components X - a = D/(X + a) etc. are free of cancellation.
        const real Xa     = D / (X + a);
        const real Yb     = D / (Y + b);
        const real Zc     = D / (Z + c);
        const real triple = X * Yb * Zc + b * Xa * Zc + c * Xa * Yb;
        const real dots   = (X * a + b * Y + c * c) + (a * a + Y * b + c * Z) +
                          (X * a + b * b + c * Z);
        const real geodesic_triangle =
          2 * std::atan2(triple, R2 * R + R * dots);

        const real patch_solid_angle =
          geodesic_triangle + lens_solid_angle(on_a, a, R) +
          lens_solid_angle(on_b, b, R) + lens_solid_angle(on_c, c, R);

        return (R2 * R * patch_solid_angle - a * on_a.area - b * on_b.area -
                c * on_c.area) /
               3;
      }


      template <int dim>
      real
      first_orthant_corner_measure(const std::array<real, dim> &corner,
                                   const real                   R)
      {
        if constexpr (dim == 2)
          return corner_area(corner[0], corner[1], R);
        else
          return corner_volume(corner[0], corner[1], corner[2], R);
      }


      /**
       * Measure of the ball of radius R around the origin intersected with
       * the box [lower, upper], all coordinates >= 0: inclusion-exclusion
       * over the box corners.
       */
      template <int dim>
      real
      first_orthant_box_measure(const std::array<real, dim> &lower,
                                const std::array<real, dim> &upper,
                                const real                   R)
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

        real sum = 0;
        for (unsigned int vertex = 0; vertex < (1u << dim); ++vertex)
          {
            std::array<real, dim> corner;
            int                   sign = 1;
            for (unsigned int d = 0; d < dim; ++d)
              if (vertex & (1u << d))
                {
                  corner[d] = upper[d];
                  sign      = -sign;
                }
              else
                corner[d] = lower[d];
            sum += sign * first_orthant_corner_measure<dim>(corner, R);
          }
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


    template <int dim>
    double
    ball_box_intersection_measure(const Point<dim>       &centre,
                                  const double            radius,
                                  const BoundingBox<dim> &box)
    {
      Assert(radius >= 0, ExcMessage("The radius must be non-negative."));

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
          measure += first_orthant_box_measure<dim>(lower, upper, radius);
        }
      return static_cast<double>(measure);
    }


    template double
    ball_corner_measure(const Point<2> &, const double);
    template double
    ball_corner_measure(const Point<3> &, const double);
    template double
    ball_box_intersection_measure(const Point<2> &,
                                  const double,
                                  const BoundingBox<2> &);
    template double
    ball_box_intersection_measure(const Point<3> &,
                                  const double,
                                  const BoundingBox<3> &);
  } // namespace Quadrature
} // namespace PeriDEAL
