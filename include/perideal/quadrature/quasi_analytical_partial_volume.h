#ifndef perideal_quadrature_quasi_analytical_partial_volume_h
#define perideal_quadrature_quasi_analytical_partial_volume_h

#include <perideal/quadrature/partial_volume.h>

#include <vector>

namespace PeriDEAL
{
  namespace Quadrature
  {
    /**
     * Quasi-analytical partial volumes in 3D on uniform grids: the published
     * reference method of Scabbia, Zaccariotto, Galvanetto (2022), "Accurate
     * computation of partial volumes in 3D peridynamics", Comput. Mech.,
     * Sect. 3.5 and Appendices B and C (Algorithms 3 and 4, Functions 2 to
     * 4), implemented as published.
     *
     * In scaled units (grid spacing 1, node at the origin, horizon
     * \f$\bar m=\delta/h\f$) the cell of the neighbour at the integer offset
     * \f$(\bar x_j,\bar y_j,\bar z_j)\f$, reduced by symmetry to
     * \f$0\le\bar x_j\le\bar y_j\le\bar z_j\f$, has the coefficient (Eq. 24)
     * \f[
     *   \beta_{ij} = 2^s \int_{a_x}^{b_x}
     *     \int_{a_y}^{\min(\bar y_2,\sqrt{\bar m^2-\bar x^2-\bar z_1^2})}
     *     \int_{\bar z_1}^{\min(\bar z_2,\sqrt{\bar m^2-\bar x^2-\bar y^2})}
     *     d\bar z\, d\bar y\, d\bar x ,
     * \f]
     * which splits into 10 cases (Algorithm 4). The inner two integrations
     * are done in closed form; of the remaining one-dimensional integrals,
     * \f$\int\sqrt{\bar m^2-\bar x^2-k^2}\,d\bar x\f$ is elementary
     * (Eq. 27), while \f$\int(\bar m^2-\bar x^2)f(\bar x)\,d\bar x\f$ with
     * \f$f=\arcsin(k/\sqrt{\bar m^2-\bar x^2})\f$ and with
     * \f$g=\arcsin(\sqrt{\bar m^2-\bar x^2-k^2}/\sqrt{\bar m^2-\bar x^2})
     * =\pi/2-f\f$ are integrated term by term from the Taylor series of
     * \f$f\f$, \f$g\f$ of order \f$N\f$ around the interval's midpoint
     * (Eqs. 30 to 33), with the derivatives (Eq. C2)
     * \f[
     *   f^{(n)}(\bar x) = \frac{\sum_{p=1}^{\lfloor 3n/2\rfloor}
     *     \left(\sum_{q=1}^{p} c(n,p,q)\,\bar m^{2(p-q)}k^{2q-1}\right)
     *     \bar x^{3n-2p}}
     *   {(\bar m^2-\bar x^2)^n(\bar m^2-\bar x^2-k^2)^{n-1/2}},
     *   \qquad g^{(n)} = -f^{(n)},
     * \f]
     * whose integer coefficients \f$c(n,p,q)\f$ (Algorithm 3) are computed
     * once per object.
     *
     * The result is exact up to the truncation of the series and the
     * rounding of Eq. (C2), and both depend on the offset:
     * - Truncation: the series of \f$f\f$ around \f$\bar x_0\f$ converges
     *   slowly when its branch point \f$\sqrt{\bar m^2-k^2}\f$ lies close to
     *   the integration interval (relative to its length). For
     *   \f$\bar m=3\f$ the offsets (1,1,2) and (1,1,3) are off by 7e-4 with
     *   N = 4 and still by 2e-7 with N = 20 (the published Table 2 carries
     *   this error); for \f$\bar m=2.55\f$, (0,0,2): 7e-3 and 6e-4.
     * - Rounding: the numerator of Eq. (C2) is a sum of large terms of both
     *   signs that cancel more and more as n grows, and the faster the
     *   smaller \f$(\bar m^2-\bar x_0^2-k^2)/\bar m^2\f$ is (200 digits are
     *   needed in the last example below). Large N then hurts near the
     *   poles of the ball: \f$\bar m=9.6\f$, offset (1,1,10) is off by
     *   6e-3 with N = 4 but 2e-2 with N = 20. Near an exact tangency
     *   perturbed by rounding (e.g.
     *   \f$\bar m = 1.5 + 4\cdot 10^{-16}\f$, offset (0,0,1), N = 20) the
     *   result is meaningless (1e118).
     * Use "exact" where this matters, or for cells that are not on a uniform
     * grid around the node.
     *
     * Registered as "quasi-analytical" for dim = 3 only.
     */
    class QuasiAnalyticalPartialVolume : public PartialVolume<3>
    {
    public:
      /// Taylor order N = 4, the paper's choice for its numerical results.
      QuasiAnalyticalPartialVolume();

      /**
       * Use the Taylor order @p taylor_order (1 to 40). Computes the
       * coefficients c(n,p,q) for n = 1..N.
       */
      explicit QuasiAnalyticalPartialVolume(const unsigned int taylor_order);

      /**
       * The general interface, for cells of a uniform grid only: @p cell
       * must be a cube whose centre is offset from @p node by an integer
       * multiple of its side (to a relative tolerance of 1e-10). Then
       * \f$\bar m = \delta/h\f$ and the offset in units of the side are
       * passed to uniform_grid_weight(). Any other cell throws
       * ExcInvalidInput.
       */
      double
      weight(const Point<3>       &node,
             const double          horizon,
             const BoundingBox<3> &cell) const override;

      /**
       * Algorithm 4 of the paper on the integer @p offset, with
       * \f$\bar m\f$ = @p m_ratio > 0. The node's own cell (offset 0), which
       * the paper excludes, gets the value 1 when it lies inside the ball
       * (\f$\bar m\ge\sqrt3/2\f$); smaller horizons throw for it.
       *
       * @return \f$\beta_{ij}\in[0,1]\f$ up to the series' truncation error.
       */
      double
      uniform_grid_weight(const std::array<int, 3> &offset,
                          const double              m_ratio) const override;

      /**
       * Declare "Taylor order" (an integer in [1, 40], default 4), the
       * order N at which the Taylor series of Eqs. (30) and (31) are
       * truncated.
       */
      static void
      declare_parameters(ParameterHandler &prm);

      /// Read "Taylor order" and recompute the coefficients c(n,p,q).
      void
      parse_parameters(ParameterHandler &prm) override;

      /// The Taylor order N.
      unsigned int
      taylor_order() const;

      /**
       * The coefficient c(n,p,q) of Algorithm 3 (1-based indices as in the
       * paper, 1 <= n <= N, 1 <= q <= p <= floor(3n/2)). Exposed for
       * testing.
       */
      double
      taylor_coefficient(const unsigned int n,
                         const unsigned int p,
                         const unsigned int q) const;

    private:
      /// Algorithm 3: fill c(n,p,q) for n = 1..N.
      void
      compute_taylor_coefficients(const unsigned int taylor_order);

      /**
       * Function 2: \f$\int_a^b\sqrt{\bar m^2-\bar x^2-k^2}\,d\bar x\f$ in
       * closed form (Eq. B12).
       */
      static double
      int1(const double a, const double b, const double k, const double m);

      /**
       * \f$f^{(n)}(\bar x_0)\f$ of Eq. (C2) for n = 1..N, returned in
       * @p derivatives[n-1].
       */
      void
      derivatives(const double         x0,
                  const double         k,
                  const double         m,
                  std::vector<double> &derivatives) const;

      /**
       * Functions 3 (@p sign = +1: the integrand \f$(\bar m^2-\bar x^2)f\f$,
       * Eq. 32) and 4 (@p sign = -1: \f$(\bar m^2-\bar x^2)g\f$, Eq. 33) on
       * [@p a, @p b], truncated at order N around the midpoint.
       */
      double
      int23(const double a,
            const double b,
            const double k,
            const double m,
            const int    sign) const;

      unsigned int N;

      /// Largest p in c(n,p,q): floor(3N/2).
      unsigned int max_p;

      /// c(n,p,q) at index ((n-1) * max_p + (p-1)) * max_p + (q-1).
      std::vector<double> c;
    };
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
