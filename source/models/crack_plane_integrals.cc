#include <deal.II/base/quadrature_lib.h>

#include <perideal/models/crack_plane_integrals.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Models
  {
    namespace CrackPlaneIntegrals
    {
      namespace
      {
        /// \f$\hat m\f$: 4π M_4 (3D), 2π M_3 (2D).
        template <int dim>
        double
        unit_ball_weighted_volume(const InfluenceFunction &omega)
        {
          return dim == 3 ? 4 * M_PI * omega.moment(4) :
                            2 * M_PI * omega.moment(3);
        }

        /// The inner integrals of separation_dilatation().
        template <int dim>
        class Separation
        {
        public:
          explicit Separation(const InfluenceFunction &omega)
            : omega(omega)
            , gauss(24)
          {}

          /// \f$\int_x^1 \omega(r)\,r^d\,dr\f$.
          double
          radial(const double x) const
          {
            if (x >= 1)
              return 0;
            double sum = 0;
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double r = x + (1 - x) * gauss.point(q)[0];
                sum += gauss.weight(q) * omega.value(r) * std::pow(r, dim);
              }
            return (1 - x) * sum;
          }

          /// A(λ, ζ): the crossing bonds with r > ζ/c and r > λ c.
          double
          intact(const double lambda, const double zeta) const
          {
            const double c_max =
              lambda > 1 ? 1 / lambda : 1.; // r/c > λ needs c < 1/λ
            const double c_star = lambda > 0 ?
                                    std::sqrt(zeta / lambda) :
                                    std::numeric_limits<double>::infinity();
            // Below c*, the crossing bound ζ/c is the larger one.
            const double pieces[3] = {zeta,
                                      std::min(std::max(c_star, zeta), c_max),
                                      c_max};
            double       sum       = 0;
            for (unsigned int p = 0; p < 2; ++p)
              if (pieces[p + 1] > pieces[p])
                sum +=
                  integrate_cosine(pieces[p], pieces[p + 1], [&](double c) {
                    return c * radial(std::max(zeta / c, lambda * c));
                  });
            return sum;
          }

          /// \f$\int_0^\infty \lambda A(\lambda, \zeta)^2 d\lambda\f$.
          double
          opening_integral(const double zeta) const
          {
            // (0, ζ): nothing has broken yet.
            const double a0  = intact(0, zeta);
            double       sum = 0.5 * zeta * zeta * a0 * a0;
            for (unsigned int q = 0; q < gauss.size(); ++q)
              {
                const double t = gauss.point(q)[0], w = gauss.weight(q);
                // (ζ, 1) with λ = ζ + (1 - ζ) t²: A leaves its constant
                // value like a power of λ - ζ.
                const double lambda = zeta + (1 - zeta) * t * t;
                const double a      = intact(lambda, zeta);
                sum += w * 2 * (1 - zeta) * t * lambda * a * a;
                // (1, 1/ζ) with λ = 1/μ, μ in (ζ, 1): λ A² dλ = A²/μ³ dμ,
                // and μ = 1 - (1 - ζ) t²: in 2D, A falls like a square root
                // of λ - 1 (the angle arccos(1/λ) of the longest bonds).
                const double mu = 1 - (1 - zeta) * t * t;
                const double b  = intact(1 / mu, zeta);
                sum += w * 2 * (1 - zeta) * t * b * b / (mu * mu * mu);
              }
            return sum;
          }

        private:
          /// The angular integral over c in (c0, c1): 2π dc in 3D; in 2D
          /// 2 dφ (both signs of the angle) with c = cos φ.
          template <typename F>
          double
          integrate_cosine(const double c0, const double c1, const F &f) const
          {
            double sum = 0;
            if (dim == 3)
              {
                for (unsigned int q = 0; q < gauss.size(); ++q)
                  sum +=
                    gauss.weight(q) * f(c0 + (c1 - c0) * gauss.point(q)[0]);
                return 2 * M_PI * (c1 - c0) * sum;
              }
            const double phi0 = std::acos(c1), phi1 = std::acos(c0);
            for (unsigned int q = 0; q < gauss.size(); ++q)
              sum += gauss.weight(q) *
                     f(std::cos(phi0 + (phi1 - phi0) * gauss.point(q)[0]));
            return 2 * (phi1 - phi0) * sum;
          }

          const InfluenceFunction &omega;
          const QGauss<1>          gauss;
        };
      } // namespace


      template <int dim>
      double
      crossing_share(const InfluenceFunction &omega)
      {
        // 3D: f = ∫_ζ^1 ω (ρ⁴ - ζρ³) dρ / (2 M_4); 2D: f = ∫_ζ^1 ω ρ³
        // arccos(ζ/ρ) dρ / (π M_3). ρ = ζ + (1 - ζ)t² takes the square-root
        // behaviour of arccos at ρ = ζ out of the Gauss rule.
        const QGauss<1> gauss(64);
        const double    norm =
          dim == 3 ? 2 * omega.moment(4) : M_PI * omega.moment(3);
        double i1 = 0;
        for (unsigned int a = 0; a < gauss.size(); ++a)
          {
            // ζ = 1 - s²: f vanishes like a half-integer power of 1 - ζ.
            const double s     = gauss.point(a)[0];
            const double zeta  = 1 - s * s;
            double       share = 0;
            for (unsigned int b = 0; b < gauss.size(); ++b)
              {
                const double t        = gauss.point(b)[0];
                const double rho      = zeta + (1 - zeta) * t * t;
                const double jacobian = 2 * (1 - zeta) * t;
                const double shape =
                  dim == 3 ?
                    rho * rho * rho * (rho - zeta) :
                    rho * rho * rho * std::acos(std::min(1., zeta / rho));
                share += gauss.weight(b) * jacobian * omega.value(rho) * shape;
              }
            i1 += gauss.weight(a) * 2 * s * share / norm;
          }
        return i1;
      }


      template <int dim>
      double
      separation_dilatation(const InfluenceFunction &omega)
      {
        const Separation<dim> separation(omega);
        const QGauss<1>       gauss(24);
        double                sum = 0;
        for (unsigned int q = 0; q < gauss.size(); ++q)
          {
            // ζ = t²: the integrand behaves like a power of ζ near the plane.
            const double t = gauss.point(q)[0];
            sum += gauss.weight(q) * 2 * t * separation.opening_integral(t * t);
          }
        const double m = unit_ball_weighted_volume<dim>(omega);
        return 2 / (m * m) * sum;
      }


      template double
      crossing_share<2>(const InfluenceFunction &);
      template double
      crossing_share<3>(const InfluenceFunction &);
      template double
      separation_dilatation<2>(const InfluenceFunction &);
      template double
      separation_dilatation<3>(const InfluenceFunction &);
    } // namespace CrackPlaneIntegrals
  }   // namespace Models
} // namespace PeriDEAL
