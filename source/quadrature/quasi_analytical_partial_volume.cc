#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/quasi_analytical_partial_volume.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace PeriDEAL
{
  namespace Quadrature
  {
    namespace
    {
      // The c(n,p,q) reach 7e28 for n = 20 and 2e71 for n = 40, beyond the
      // integers a double holds exactly, and the recursion cancels: Algorithm
      // 3 runs in extended precision, which keeps every c(n,p,q) within
      // 2e-18 of the largest of its order n (checked against exact integer
      // arithmetic for n <= 40), far below the rounding of the double
      // evaluation of Eq. (C2).
      using Extended = long double;

      unsigned int
      floor_3n_over_2(const unsigned int n)
      {
        return (3 * n) / 2;
      }
    } // namespace


    QuasiAnalyticalPartialVolume::QuasiAnalyticalPartialVolume()
      : QuasiAnalyticalPartialVolume(4)
    {}


    QuasiAnalyticalPartialVolume::QuasiAnalyticalPartialVolume(
      const unsigned int taylor_order)
    {
      compute_taylor_coefficients(taylor_order);
    }


    void
    QuasiAnalyticalPartialVolume::compute_taylor_coefficients(
      const unsigned int taylor_order)
    {
      AssertThrow(taylor_order >= 1 && taylor_order <= 40,
                  ExcInvalidInput("Taylor order",
                                  std::to_string(taylor_order),
                                  "give an integer between 1 and 40"));
      N     = taylor_order;
      max_p = floor_3n_over_2(N);

      // Algorithm 3, with 1-based indices as in the paper. Order n-1 has
      // terms up to p = floor(3(n-1)/2); differentiating raises p by at most
      // 2 (line 2 of the listing), so order n is filled up to
      // floor(3(n-1)/2) + 2. For odd n that top row is zero (its factors
      // 3n - 2p + 1 and -3n + 2p - 1 vanish), so every order has terms up to
      // p = floor(3n/2) only, as Eq. (C2) states.
      //
      // The recursion follows from differentiating Eq. (C2) for order n-1.
      // With A = m^2 - x^2 and B = A - k^2 (A' = B' = -2x), the numerator of
      // f^(n) over A^n B^{n-1/2} is
      //   P_n = P_{n-1}' A B + 2x P_{n-1} ((n-1) B + (n-3/2) A)
      //       = P_{n-1}' A B
      //         + P_{n-1} ((4n-5) m^2 x - (4n-5) x^3 - 2(n-1) k^2 x),
      // and collecting the monomials m^{2(p-q)} k^{2q-1} x^{3n-2p} gives the
      // five updates of the listing (lines 7 to 21) term by term.
      const unsigned int    extent = (3 * (N - 1)) / 2 + 2;
      std::vector<Extended> ext((N + 1) * (extent + 1) * (extent + 1), 0);
      const auto            at = [&](const unsigned int n,
                          const unsigned int p,
                          const unsigned int q) -> Extended            &{
        return ext[(n * (extent + 1) + p) * (extent + 1) + q];
      };
      at(1, 1, 1) = 1; // f'(x) = k x / (A B^{1/2})
      for (unsigned int n = 2; n <= N; ++n)
        {
          const int          ni      = n;
          const unsigned int p_prev  = (3 * (n - 1)) / 2;
          const unsigned int p_range = p_prev + 2;
          for (unsigned int p = 1; p <= p_range; ++p)
            for (unsigned int q = 1; q <= p; ++q)
              {
                const int pi = p;
                Extended  v  = 0;
                if (p <= p_prev)
                  v += (-ni - 2 * pi + 2) * at(n - 1, p, q);
                if (2 <= p && p <= p_prev + 1 && q <= p - 1)
                  v += (-2 * ni + 4 * pi - 3) * at(n - 1, p - 1, q);
                if (2 <= p && p <= p_prev + 1 && q >= 2)
                  v += (ni - 2 * pi + 1) * at(n - 1, p - 1, q - 1);
                if (3 <= p && q <= p - 2)
                  v += (3 * ni - 2 * pi + 1) * at(n - 1, p - 2, q);
                if (3 <= p && 2 <= q && q <= p - 1)
                  v += (-3 * ni + 2 * pi - 1) * at(n - 1, p - 2, q - 1);
                at(n, p, q) = v;
              }
        }

      c.assign(N * max_p * max_p, 0.);
      for (unsigned int n = 1; n <= N; ++n)
        for (unsigned int p = 1; p <= floor_3n_over_2(n); ++p)
          for (unsigned int q = 1; q <= p; ++q)
            c[((n - 1) * max_p + (p - 1)) * max_p + (q - 1)] =
              static_cast<double>(at(n, p, q));
    }


    double
    QuasiAnalyticalPartialVolume::taylor_coefficient(const unsigned int n,
                                                     const unsigned int p,
                                                     const unsigned int q) const
    {
      AssertIndexRange(n - 1, N);
      AssertIndexRange(p - 1, floor_3n_over_2(n));
      AssertIndexRange(q - 1, p);
      return c[((n - 1) * max_p + (p - 1)) * max_p + (q - 1)];
    }


    unsigned int
    QuasiAnalyticalPartialVolume::taylor_order() const
    {
      return N;
    }


    void
    QuasiAnalyticalPartialVolume::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Taylor order",
        "4",
        Patterns::Integer(1, 40),
        "Order N at which the Taylor series of the two arcsin integrands are "
        "truncated (Scabbia et al. 2022, Eqs. 30-31). The paper uses N = 4 "
        "for its results and N = 20 for its tables; the cost per cell grows "
        "like N^3. Truncation errors are largest for cells whose integration "
        "interval ends close to a branch point of the integrand (e.g. 7e-4 "
        "at N = 4 and 2e-7 at N = 20 for m = 3, offset (1,1,2)); rounding "
        "errors grow with N for cells near the poles of the ball (m = 9.6, "
        "offset (1,1,10): 6e-3 at N = 4, 2e-2 at N = 20).");
    }


    void
    QuasiAnalyticalPartialVolume::parse_parameters(ParameterHandler &prm)
    {
      compute_taylor_coefficients(prm.get_integer("Taylor order"));
    }


    double
    QuasiAnalyticalPartialVolume::int1(const double a,
                                       const double b,
                                       const double k,
                                       const double m)
    {
      // Function 2 / Eq. (B12). Interval ends computed from square roots may
      // exceed sqrt(m^2 - k^2) by a rounding error: clamp the arguments of
      // asin and sqrt to their domains.
      const double r2 = m * m - k * k;
      if (!(b > a) || r2 <= 0)
        return 0;
      const double r       = std::sqrt(r2);
      const auto   arcsine = [r](const double x) {
        return std::asin(std::clamp(x / r, -1., 1.));
      };
      const auto root = [r2](const double x) {
        return std::sqrt(std::max(0., r2 - x * x));
      };
      return 0.5 * r2 * (arcsine(b) - arcsine(a)) + 0.5 * b * root(b) -
             0.5 * a * root(a);
    }


    void
    QuasiAnalyticalPartialVolume::derivatives(const double         x0,
                                              const double         k,
                                              const double         m,
                                              std::vector<double> &result) const
    {
      // Eq. (C2), evaluated in the variables t = x0/m, kappa = k/m: every
      // monomial m^{2(p-q)} k^{2q-1} x0^{3n-2p} equals
      // m^{3n-1} kappa^{2q-1} t^{3n-2p} and the denominator is
      // m^{4n-1} u^n w^{n-1/2} with u = 1 - t^2, w = u - kappa^2, so
      // f^(n)(x0) = m^{-n} S_n / (u^n w^{n-1/2}). Same formula, but no
      // overflow of x0^{3n-2p} for large m and N.
      const double t     = x0 / m;
      const double kappa = k / m;
      const double u     = 1. - t * t;
      const double w     = u - kappa * kappa;

      std::vector<double> t_power(3 * N + 1), kappa_power(max_p + 1);
      t_power[0] = 1;
      for (unsigned int e = 1; e <= 3 * N; ++e)
        t_power[e] = t_power[e - 1] * t;
      kappa_power[1] = kappa; // kappa^{2q-1} at index q
      for (unsigned int q = 2; q <= max_p; ++q)
        kappa_power[q] = kappa_power[q - 1] * kappa * kappa;

      result.resize(N);
      const double sqrt_w = std::sqrt(w);
      double       u_n = 1, w_n = 1 / sqrt_w, m_n = 1; // u^n, w^{n-1/2}, m^n
      for (unsigned int n = 1; n <= N; ++n)
        {
          u_n *= u;
          w_n *= w;
          m_n *= m;
          double S = 0;
          for (unsigned int p = 1; p <= floor_3n_over_2(n); ++p)
            {
              const double *c_np  = &c[((n - 1) * max_p + (p - 1)) * max_p];
              double        inner = 0;
              for (unsigned int q = 1; q <= p; ++q)
                inner += c_np[q - 1] * kappa_power[q];
              S += inner * t_power[3 * n - 2 * p];
            }
          result[n - 1] = S / (u_n * w_n * m_n);
        }
    }


    double
    QuasiAnalyticalPartialVolume::int23(const double a,
                                        const double b,
                                        const double k,
                                        const double m,
                                        const int    sign) const
    {
      // An empty interval contributes nothing; returning early also avoids
      // 0/0 when its single point is a branch point (w = 0 below).
      if (!(b > a))
        return 0;

      // Function 3 (sign = +1) and Function 4 (sign = -1): g = pi/2 - f, so
      // g^(n) = -f^(n) (Eq. C7).
      const double x0 = 0.5 * (a + b);
      const double A0 = m * m - x0 * x0;
      const double f0 =
        (sign > 0) ? std::asin(std::clamp(k / std::sqrt(A0), -1., 1.)) :
                     std::asin(std::clamp(std::sqrt(std::max(0., A0 - k * k)) /
                                            std::sqrt(A0),
                                          -1.,
                                          1.));
      double I = f0 * (m * m * (b - a) - (b * b * b - a * a * a) / 3.);

      std::vector<double> d;
      derivatives(x0, k, m, d);
      const double upper = b - x0, lower = a - x0;
      double       upper_n = upper, lower_n = lower, factorial = 1;
      for (unsigned int n = 1; n <= N; ++n)
        {
          factorial *= n;
          const double up1 = upper_n * upper, lo1 = lower_n * lower;
          const double up2 = up1 * upper, lo2 = lo1 * lower;
          const double up3 = up2 * upper, lo3 = lo2 * lower;
          const double In1 = A0 / (n + 1) * (up1 - lo1);
          const double In2 = 2 * x0 / (n + 2) * (up2 - lo2);
          const double In3 = 1. / (n + 3) * (up3 - lo3);
          I += sign * d[n - 1] / factorial * (In1 - In2 - In3);
          upper_n = up1;
          lower_n = lo1;
        }
      return I;
    }


    double
    QuasiAnalyticalPartialVolume::uniform_grid_weight(
      const std::array<int, 3> &offset,
      const double              m_ratio) const
    {
      AssertThrow(m_ratio > 0 && std::isfinite(m_ratio),
                  ExcInvalidInput("m-ratio",
                                  format_number(m_ratio),
                                  "give a horizon-to-spacing ratio > 0"));

      // Algorithm 4, lines 1 to 4: reduce to 0 <= x_j <= y_j <= z_j.
      std::array<int, 3> o = {
        {std::abs(offset[0]), std::abs(offset[1]), std::abs(offset[2])}};
      std::sort(o.begin(), o.end());
      const double xj = o[0], yj = o[1], zj = o[2];
      const double m = m_ratio, m2 = m * m;

      // The paper leaves out the node's own cell (z_j = 0, Sect. 3.3). It
      // lies in the ball for m >= sqrt(3)/2; smaller horizons would need
      // the case analysis for z_1 < 0, which Algorithm 4 does not cover.
      if (o[2] == 0)
        {
          AssertThrow(m2 >= 0.75,
                      ExcInvalidInput(
                        "m-ratio",
                        format_number(m_ratio),
                        "the quasi-analytical algorithm does not cover the "
                        "node's own cell when m < sqrt(3)/2; use \"exact\""));
          return 1;
        }

      // Lines 5 to 8. The listing reads "z_j != 0 and z_j > M"; z_j = 0 is
      // handled above, and z_j > M alone decides.
      const double M = std::floor(m + 0.5);
      if (zj > M)
        return 0;

      // Lines 9 to 14 (the listing's z_1 = y_j - 0.5, z_2 = y_j + 0.5 is an
      // extraction typo for z_j, cf. Eq. 24).
      const double x2 = xj + 0.5, y1 = yj - 0.5, y2 = yj + 0.5;
      const double x1 = xj - 0.5, z1 = zj - 0.5, z2 = zj + 0.5;
      const int    s  = (o[0] == 0 && o[1] == 0) ? 2 : (o[0] == 0 ? 1 : 0);
      const double ax = std::max(0., x1);
      const double ay = std::max(0., y1);
      // Eq. (26). Where m^2 < a_y^2 + z_1^2 the cell is in case 10 and b_x
      // is never used; max(0, .) only keeps it finite.
      const double bx =
        std::min(x2, std::sqrt(std::max(0., m2 - ay * ay - z1 * z1)));

      const auto I1 = [m](const double a, const double b, const double k) {
        return int1(a, b, k, m);
      };
      const auto I2 = [this,
                       m](const double a, const double b, const double k) {
        return int23(a, b, k, m, +1);
      };
      const auto I3 = [this,
                       m](const double a, const double b, const double k) {
        return int23(a, b, k, m, -1);
      };
      const auto sq = [](const double v) { return v * v; };

      double beta;
      if (sq(x2) + sq(y2) + sq(z2) <= m2) // case 1
        return 1;
      else if (sq(ax) + sq(y2) + sq(z2) <= m2) // case 2, Eq. (B15)
        {
          const double xe1 = std::sqrt(m2 - sq(y2) - sq(z2));
          beta = 0.5 * z2 * I1(xe1, bx, z2) + 0.5 * y2 * I1(xe1, bx, y2) +
                 0.5 * I2(xe1, bx, y2) - 0.5 * I3(xe1, bx, z2) +
                 z2 * y2 * (xe1 - ax) - z2 * ay * (bx - ax) -
                 z1 * (y2 - ay) * (bx - ax);
        }
      else if (sq(x2) + sq(ay) + sq(z2) <= m2) // case 3, Eq. (B18)
        beta = 0.5 * z2 * I1(ax, bx, z2) + 0.5 * y2 * I1(ax, bx, y2) +
               0.5 * I2(ax, bx, y2) - 0.5 * I3(ax, bx, z2) -
               z2 * ay * (bx - ax) - z1 * (y2 - ay) * (bx - ax);
      else if (sq(ax) + sq(ay) + sq(z2) <= m2 &&
               sq(x2) + sq(y2) + sq(z1) <= m2) // case 4, Eq. (B22)
        {
          const double xe2 = std::sqrt(m2 - sq(ay) - sq(z2));
          beta = 0.5 * z2 * I1(ax, xe2, z2) + 0.5 * y2 * I1(ax, bx, y2) -
                 0.5 * ay * I1(xe2, bx, ay) + 0.5 * I2(ax, bx, y2) -
                 0.5 * I2(xe2, bx, ay) - 0.5 * I3(ax, xe2, z2) -
                 z2 * ay * (xe2 - ax) - z1 * (y2 - ay) * (bx - ax);
        }
      else if (sq(ax) + sq(ay) + sq(z2) <= m2) // case 5, Eq. (B28)
        {
          // The listing's second "x_e2 = sqrt(m^2 - y_2^2 - z_1^2)" is
          // x_e3 (Eq. B24). The last form of Eq. (B28) in the extraction
          // reads "+ 1/2 I3(a_x, x_e2, z_2)"; the derivation (and the
          // listing) give the minus sign used here.
          const double xe2 = std::sqrt(m2 - sq(ay) - sq(z2));
          const double xe3 = std::sqrt(m2 - sq(y2) - sq(z1));
          beta = 0.5 * z2 * I1(ax, xe2, z2) + 0.5 * y2 * I1(ax, xe3, y2) -
                 0.5 * z1 * I1(xe3, bx, z1) - 0.5 * ay * I1(xe2, bx, ay) +
                 0.5 * I2(ax, xe3, y2) - 0.5 * I2(xe2, bx, ay) -
                 0.5 * I3(ax, xe2, z2) + 0.5 * I3(xe3, bx, z1) -
                 z2 * ay * (xe2 - ax) - z1 * y2 * (xe3 - ax) +
                 z1 * ay * (bx - ax);
        }
      else if (sq(x2) + sq(y2) + sq(z1) <= m2) // case 6, Eq. (B31)
        beta = 0.5 * y2 * I1(ax, bx, y2) - 0.5 * ay * I1(ax, bx, ay) +
               0.5 * I2(ax, bx, y2) - 0.5 * I2(ax, bx, ay) -
               z1 * (y2 - ay) * (bx - ax);
      else if (sq(ax) + sq(y2) + sq(z1) <= m2) // case 7, Eq. (B34)
        {
          const double xe3 = std::sqrt(m2 - sq(y2) - sq(z1));
          beta = 0.5 * y2 * I1(ax, xe3, y2) - 0.5 * z1 * I1(xe3, bx, z1) -
                 0.5 * ay * I1(ax, bx, ay) + 0.5 * I2(ax, xe3, y2) -
                 0.5 * I2(ax, bx, ay) + 0.5 * I3(xe3, bx, z1) -
                 z1 * y2 * (xe3 - ax) + z1 * ay * (bx - ax);
        }
      else if (sq(ax) + sq(ay) + sq(z1) <= m2) // cases 8 and 9, Eq. (B38)
        beta = -0.5 * z1 * I1(ax, bx, z1) - 0.5 * ay * I1(ax, bx, ay) -
               0.5 * I2(ax, bx, ay) + 0.5 * I3(ax, bx, z1) +
               z1 * ay * (bx - ax);
      else // case 10
        return 0;

      return (1 << s) * beta;
    }


    double
    QuasiAnalyticalPartialVolume::weight(const Point<3>       &node,
                                         const double          horizon,
                                         const BoundingBox<3> &cell) const
    {
      const double tolerance = 1e-10;
      const double h         = cell.side_length(0);
      bool         on_grid   = h > 0 && std::isfinite(h);
      for (unsigned int d = 1; d < 3 && on_grid; ++d)
        on_grid = std::abs(cell.side_length(d) - h) <= tolerance * h;

      std::array<int, 3> offset = {{0, 0, 0}};
      const Point<3>     centre = cell.center();
      for (unsigned int d = 0; d < 3 && on_grid; ++d)
        {
          const double scaled  = (centre[d] - node[d]) / h;
          const double rounded = std::round(scaled);
          on_grid              = std::abs(scaled - rounded) <=
                    tolerance * std::max(1., std::abs(scaled));
          offset[d] = static_cast<int>(rounded);
        }

      AssertThrow(on_grid,
                  ExcInvalidInput(
                    "cell",
                    "a box of sides " + format_number(cell.side_length(0)) +
                      " x " + format_number(cell.side_length(1)) + " x " +
                      format_number(cell.side_length(2)),
                    "the quasi-analytical algorithm is defined on uniform "
                    "grids only (a cube whose centre is offset from the node "
                    "by an integer multiple of its side); use \"exact\" for "
                    "general cells"));
      return uniform_grid_weight(offset, horizon / h);
    }
  } // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_CLASS(
  ::PeriDEAL::Quadrature::PartialVolume<3>,
  ::PeriDEAL::Quadrature::QuasiAnalyticalPartialVolume,
  "quasi-analytical",
  "Quasi-analytical partial volumes on uniform grids (Scabbia et al. 2022, "
  "Algorithm 4): closed-form inner integrals and Taylor series of order N "
  "for the outer one. Cubic cells at integer offsets only.")
