#ifndef perideal_models_crack_plane_integrals_h
#define perideal_models_crack_plane_integrals_h

#include <perideal/models/influence_function.h>

namespace PeriDEAL
{
  namespace Models
  {
    /**
     * Integrals over the bonds that cross a plane, in units of the horizon
     * (δ = 1), for an influence function ω(r): they turn a fracture energy
     * into a critical stretch for state-based models
     * (doc/explicit-dynamics.md, "Critical stretch from the fracture energy
     * (LPS)").
     *
     * A node at depth ζ ∈ (0, 1) from the plane has crossing bonds ρ
     * (|ρ| ≤ 1, ρ·n < -ζ); c is the cosine of the angle between ρ and the
     * plane's normal n, \f$\hat m = \int_{|\rho|\le 1}\omega\,\rho^2\f$ the
     * weighted volume of the unit ball.
     */
    namespace CrackPlaneIntegrals
    {
      /**
       * \f$I_1 = \int_0^1 f(\zeta)\,d\zeta\f$, f(ζ) the share of \f$\hat
       * m\f$ held by the crossing bonds of a node at depth ζ (3D constant
       * ω: 5/24; δ/r: 1/5).
       */
      template <int dim>
      double
      crossing_share(const InfluenceFunction &omega);

      /**
       * The separation integral
       * \f[
       *   J = \frac{2}{\hat m^2}\int_0^1 d\zeta \int_0^\infty
       *       \lambda\,A(\lambda, \zeta)^2\,d\lambda,\qquad
       *   A(\lambda, \zeta) = \int_{\rho\cdot n < -\zeta,\ |\rho|/c >
       *   \lambda} \omega\,|\rho|\,c\,d\rho:
       * \f]
       * when the two half-spaces move apart rigidly by an opening λ s0 δ
       * normal to the plane, a crossing bond of length r and cosine c
       * stretches by λ s0 c / r and breaks at λ = r/c; A is, up to the
       * factor d/m, the dilatation per unit opening that the intact bonds
       * give the node, and \f$\tfrac{K_a}{2}d^2 s_0^2\delta J\f$ the work of
       * the dilatation energy \f$\tfrac{K_a}{2}\theta^2\f$ per unit area
       * until every crossing bond has broken.
       *
       * Nested Gauss rules with the breaks of the integrands as bounds
       * (λ = ζ, λ = 1, c² = ζ/λ) and ζ = t²; 24 points per level give
       * 3e-11 against a 15-digit mpmath quadrature (3D, constant ω).
       */
      template <int dim>
      double
      separation_dilatation(const InfluenceFunction &omega);
    } // namespace CrackPlaneIntegrals
  }   // namespace Models
} // namespace PeriDEAL

#endif
