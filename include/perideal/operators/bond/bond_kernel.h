#ifndef perideal_operators_bond_bond_kernel_h
#define perideal_operators_bond_bond_kernel_h

#include <algorithm>
#include <cmath>
#include <type_traits>

/**
 * The kernel functions below are inlined into every loop that calls them,
 * whatever the optimiser's inlining budget: a loop vectorises over its
 * lanes (or bonds) only if no call is left in its body, and the callers are
 * compiled with different flags (vector width, contraction), each of which
 * must apply to its own copy of the kernel.
 */
#define PERIDEAL_BOND_KERNEL_INLINE inline __attribute__((always_inline))
/// The same for a lambda that holds a vectorised loop over bonds, written
/// after its parameter list.
#define PERIDEAL_BOND_KERNEL_INLINE_LAMBDA __attribute__((always_inline))

namespace PeriDEAL
{
  namespace Operators
  {
    /**
     * The linear ordinary peridynamic bond, written once for every loop
     * over bonds: the matrix-free passes of BondOperator (linearised and
     * fracture passes, the elastic energy), its matrix entries, diagonal and
     * spectral bound.
     *
     * A bond from node i to node j has the reference vector \f$\xi\f$ of
     * length r and direction n, the constants of the factorised force state
     * (Models::Model::dilatation_constant()): \f$a = V_i w_{ij}\alpha(r)\f$,
     * \f$b = V_i w_{ij}\beta(r)\f$ and the dilatation weight
     * \f$g = (d/m_i)\,\omega(r)\, r\, w_{ij}\f$; its ends carry the node
     * factors \f$s_i, s_j\f$ and the scaled dilatations
     * \f$t_i = s_i\theta_i\f$. With the relative displacement
     * \f$\eta = u_j - u_i\f$:
     * - extension: \f$e = n\cdot\eta\f$ (small strain) or
     *   \f$e = |\xi + \eta| - r\f$ (finite kinematics);
     * - intact: the stretch \f$e/r\f$ is below \f$\min(s_{0,i}, s_{0,j})\f$;
     * - dilatation term: \f$g\,e\f$;
     * - pair force: \f$t = a(t_i + t_j) + b(s_i + s_j)e\f$ (bond-based:
     *   \f$s = 1\f$, \f$\alpha = 0\f$, so \f$t = 2be\f$), acting along n or
     *   along the deformed bond \f$(\xi + \eta)/|\xi + \eta|\f$;
     * - energy: \f$b e^2\f$ (the node's energy is half its node factor
     *   times the sum over its bonds, plus the dilatation term);
     * - stiffness: \f$\partial t/\partial e = b(s_i + s_j)\f$ and
     *   \f$\partial t/\partial\theta_k = a s_k\f$.
     *
     * The loops differ in how they reach the values (a shared stencil, lists,
     * vector lanes or gathers), not in the formulas. Components are passed
     * as anything indexable by d (an array, a pointer) or callable with d
     * (a lambda that loads from the loop's own layout), so that a vectorised
     * loop keeps its loads. The multiply-adds go through an Arithmetic
     * policy: PlainArithmetic writes \f$ab + c\f$ (the translation unit's
     * contraction flags decide whether it is fused), FusedArithmetic fuses
     * explicitly where the processor has a fast fused multiply-add, so that
     * the vector body and the scalar remainder of a loop compiled without
     * implicit contraction round alike (the fracture passes: bond failure
     * must not depend on where a partition starts a run of slots).
     */
    namespace BondKernel
    {
      /// \f$ab + c\f$ as written: contracted or not as the translation
      /// unit's flags say.
      struct PlainArithmetic
      {
        static PERIDEAL_BOND_KERNEL_INLINE double
        mul_add(const double a, const double b, const double c)
        {
          return a * b + c;
        }
      };

      /// \f$ab + c\f$ with one rounding (std::fma) where the processor has
      /// a fast fused multiply-add, else with two; either way the same in a
      /// loop's vector body and its scalar remainder.
      struct FusedArithmetic
      {
        static PERIDEAL_BOND_KERNEL_INLINE double
        mul_add(const double a, const double b, const double c)
        {
#ifdef FP_FAST_FMA
          return std::fma(a, b, c);
#else
          return a * b + c;
#endif
        }
      };

      /// Component @p d of @p x: x(d) if x is callable, else x[d].
      template <typename Components>
      PERIDEAL_BOND_KERNEL_INLINE double
      component(const Components &x, const unsigned int d)
      {
        if constexpr (std::is_invocable_v<const Components &, unsigned int>)
          return x(d);
        else
          return x[d];
      }

      /**
       * The small-strain extension \f$e = n\cdot\eta\f$, summed over the
       * components in order from zero. With n scaled by the dilatation
       * weight g it is the bond's dilatation term \f$g\,e\f$.
       */
      template <int dim,
                typename Arithmetic = PlainArithmetic,
                typename Direction,
                typename Difference>
      PERIDEAL_BOND_KERNEL_INLINE double
      linear_extension(const Direction &n, const Difference &eta)
      {
        double e = 0;
#pragma GCC unroll 3
        for (unsigned int d = 0; d < dim; ++d)
          e = Arithmetic::mul_add(component(n, d), component(eta, d), e);
        return e;
      }

      /**
       * linear_extension() of lane @p l of a vectorised chunk: the
       * relative displacement is read straight from the lane arrays
       * \f$\eta_d = u_j[d][l] - u_i[d][l]\f$. No local array is formed in
       * the caller's loop body: GCC lowers "omp simd" before it inlines,
       * and turns an addressable local of the body (an eta[dim] passed by
       * reference) into a per-lane array, which cost the linear passes
       * 5-17 % of their throughput.
       */
      template <int dim, typename Arithmetic = PlainArithmetic>
      PERIDEAL_BOND_KERNEL_INLINE double
      linear_extension_of_lane(const double *const        n,
                               const double *const *const u_j,
                               const double *const *const u_i,
                               const unsigned int         l)
      {
        // The first term alone: 0 + n x would cost an addition per lane
        // (it is not n x for x = -0, so the compiler keeps it).
        double e = n[0] * (u_j[0][l] - u_i[0][l]);
#pragma GCC unroll 2
        for (unsigned int d = 1; d < dim; ++d)
          e = Arithmetic::mul_add(n[d], u_j[d][l] - u_i[d][l], e);
        return e;
      }

      /**
       * A bond's extension and the line of action of its pair force: the
       * force on node i is \f$t\,\mathrm{scale}\; y\f$ with
       * \f$y = n\f$, scale 1 (small strain) or \f$y = \xi + \eta\f$,
       * scale \f$1/|y|\f$ (finite kinematics; 0 for a bond collapsed to a
       * point).
       */
      template <int dim>
      struct Deformation
      {
        double e;
        double y[dim];
        double scale;
      };

      /**
       * The Deformation of a bond with reference vector @p xi, direction
       * @p n and length @p r under the relative displacement @p eta, with
       * the kinematics of @p finite: \f$e = n\cdot\eta\f$ (linear_extension())
       * or \f$e = |\xi + \eta| - r\f$, the squares summed over the
       * components in order from zero.
       *
       * Everything is computed in the returned object, nothing through
       * references: a loop under "omp simd" turns the addressable locals of
       * its body into per-lane arrays, and a store through a reference into
       * one of them does not vectorise.
       */
      template <bool finite,
                int  dim,
                typename Arithmetic = PlainArithmetic,
                typename Reference,
                typename Direction,
                typename Difference>
      PERIDEAL_BOND_KERNEL_INLINE Deformation<dim>
                                  deform(const Reference  &xi,
                                         const Direction  &n,
                                         const double      r,
                                         const Difference &eta)
      {
        Deformation<dim> bond;
        if constexpr (finite)
          {
            double length2 = 0;
#pragma GCC unroll 3
            for (unsigned int d = 0; d < dim; ++d)
              {
                bond.y[d] = component(xi, d) + component(eta, d);
                length2   = Arithmetic::mul_add(bond.y[d], bond.y[d], length2);
              }
            const double length = std::sqrt(length2);
            bond.e              = length - r;
            bond.scale          = length > 0 ? 1. / length : 0.;
          }
        else
          {
#pragma GCC unroll 3
            for (unsigned int d = 0; d < dim; ++d)
              bond.y[d] = component(n, d);
            bond.e     = linear_extension<dim, Arithmetic>(n, eta);
            bond.scale = 1;
          }
        return bond;
      }

      /// The extension alone, with the kinematics of @p finite (deform()).
      template <bool finite,
                int  dim,
                typename Arithmetic = PlainArithmetic,
                typename Reference,
                typename Direction,
                typename Difference>
      PERIDEAL_BOND_KERNEL_INLINE double
      extension(const Reference  &xi,
                const Direction  &n,
                const double      r,
                const Difference &eta)
      {
        return deform<finite, dim, Arithmetic>(xi, n, r, eta).e;
      }

      /**
       * Whether a bond with extension @p e and inverse length @p inv_r is
       * intact: its stretch is below the critical stretch of both ends.
       * Every process that evaluates the bond, from either end, decides
       * alike (the same operands, bit for bit).
       */
      PERIDEAL_BOND_KERNEL_INLINE bool
      is_intact(const double e,
                const double inv_r,
                const double critical_i,
                const double critical_j)
      {
        return e * inv_r < std::min(critical_i, critical_j);
      }

      /**
       * The pair force \f$t = a(t_i + t_j) + b(s_i + s_j)e\f$ of a
       * state-based model. With PlainArithmetic it is one expression, the
       * dilatation term first: where the flags allow contraction, the
       * compiler fuses one of the two products into the sum, and which one
       * follows the order in which they are formed (passed through
       * mul_add(), the extension term would be formed first).
       */
      template <typename Arithmetic = PlainArithmetic>
      PERIDEAL_BOND_KERNEL_INLINE double
      pair_force(const double a,
                 const double t_i,
                 const double t_j,
                 const double b,
                 const double s_i,
                 const double s_j,
                 const double e)
      {
        if constexpr (std::is_same_v<Arithmetic, PlainArithmetic>)
          return a * (t_i + t_j) + b * (s_i + s_j) * e;
        else
          return Arithmetic::mul_add(a, t_i + t_j, b * (s_i + s_j) * e);
      }

      /// The pair force \f$t = 2be\f$ of a bond-based model (s = 1,
      /// \f$\alpha = 0\f$).
      PERIDEAL_BOND_KERNEL_INLINE double
      bond_based_pair_force(const double b, const double e)
      {
        return 2 * b * e;
      }

      /// The bond's share \f$b e^2\f$ of twice its node's elastic energy
      /// over the node factor.
      PERIDEAL_BOND_KERNEL_INLINE double
      energy(const double b, const double e)
      {
        return b * e * e;
      }

      /// \f$\partial t/\partial e = b(s_i + s_j)\f$: the bond's pairwise
      /// stiffness, the factor of \f$n\otimes n\f$ in
      /// \f$-\partial F_i/\partial u_j\f$.
      PERIDEAL_BOND_KERNEL_INLINE double
      extension_stiffness(const double b, const double s_i, const double s_j)
      {
        return b * (s_i + s_j);
      }

      /// \f$\partial t/\partial\theta_k = a s_k\f$: the factor of the
      /// dilatation of end k in the pair force.
      PERIDEAL_BOND_KERNEL_INLINE double
      dilatation_stiffness(const double a, const double s_k)
      {
        return a * s_k;
      }
    } // namespace BondKernel
  }   // namespace Operators
} // namespace PeriDEAL

#endif
