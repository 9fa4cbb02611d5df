#ifndef perideal_quadrature_collocation_h
#define perideal_quadrature_collocation_h

/**
 * @file
 * The meshfree collocation quadrature of the hybrid-collocation paper
 * (Sect. 3, Eqs. 32-60): the monomial basis, the choice of collocation
 * nodes with an auxiliary grid (Remark 2), the weighted least-squares fit
 * (Eqs. 34-41), the moments of a kernel over the full ball (the L vectors
 * of Eqs. 47-52 and 57-60) and a node's row W_ij = L Q_i (doc/collocation.md
 * Sects. 2-6, where every formula is derived and checked).
 */

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Quadrature
  {
    using namespace dealii;

    /**
     * The complete monomials \f$\xi^\alpha\f$ of degree at most k in dim
     * variables, graded and x-power first (3D, k = 2: 1, x, y, z, x², xy,
     * xz, y², yz, z²; Eq. 33).
     */
    template <int dim>
    class MonomialBasis
    {
    public:
      explicit MonomialBasis(const unsigned int order);

      /// The order k.
      unsigned int
      order() const
      {
        return k;
      }

      /// The number n_p of monomials.
      unsigned int
      size() const
      {
        return exponents.size();
      }

      /// The exponents of monomial @p a.
      const std::array<unsigned int, dim> &
      exponent(const unsigned int a) const
      {
        return exponents[a];
      }

      /// The degree of monomial @p a.
      unsigned int
      degree(const unsigned int a) const;

      /// The values of all monomials at @p x, into @p values (size()).
      void
      evaluate(const Tensor<1, dim> &x, double *values) const;

    private:
      unsigned int                               k;
      std::vector<std::array<unsigned int, dim>> exponents;
    };


    /// n_p: the number of monomials of degree at most @p order in @p dim
    /// variables.
    unsigned int
    n_monomials(const unsigned int dim, const unsigned int order);

    /// The number N_d(k_a) of points a of Z^d with |a| <= k_a (the
    /// auxiliary grid of Remark 2 with k_a divisions of the horizon).
    unsigned int
    auxiliary_grid_size(const unsigned int dim, const unsigned int divisions);

    /**
     * The divisions k_a of the auxiliary grid whose size is closest to
     * @p n_collocation (a tie takes the larger k_a), doc/collocation.md
     * Sect. 2.2.
     */
    unsigned int
    auxiliary_divisions(const unsigned int dim,
                        const unsigned int n_collocation);

    /**
     * The default number of collocation nodes of an order in a dimension:
     * 1D 5, 11, 13 (Table 1), 2D 29, 49 (Table 2), 3D 33, 123
     * (doc/collocation.md Sect. 7). Throws for an order the dimension does
     * not offer.
     */
    unsigned int
    default_collocation_nodes(const unsigned int dim, const unsigned int order);

    /// Whether the collocation scheme offers @p order in @p dim: 2, 4, 6
    /// in 1D, 2 and 4 in 2D and 3D.
    bool
    offers_order(const unsigned int dim, const unsigned int order);


    /**
     * The WLS collocation of one cloud: the choice of collocation nodes,
     * the fit matrix Q_i and its conditioning, for a given order, number of
     * collocation nodes (through the auxiliary grid) and horizon. Everything
     * depends on the bond vectors only, so equal neighbourhoods give equal
     * results to the last bit.
     */
    template <int dim>
    class CollocationFit
    {
    public:
      /**
       * @p order: 2, 4 (or 6 in 1D); @p n_collocation: the requested count
       * (0: the default); @p horizon: \f$\delta\f$, the radius of the
       * auxiliary grid and the length that scales the basis;
       * @p weight_radius: \f$\tilde r\f$ of Eq. 36 (0: the horizon, the
       * paper's choice; CollocationSettings::weight_radius_factor()).
       */
      CollocationFit(const unsigned int order,
                     const unsigned int n_collocation,
                     const double       horizon,
                     const double       weight_radius = 0);

      /// The basis.
      const MonomialBasis<dim> &
      basis() const
      {
        return monomials;
      }

      /// The divisions k_a of the auxiliary grid.
      unsigned int
      divisions() const
      {
        return k_a;
      }

      /**
       * The collocation nodes among the family @p xi (bond vectors
       * x_j - x_i with |xi| <= horizon, the node itself as the zero
       * vector among them): each auxiliary point takes its nearest
       * family node, a tie the one nearer to the source and then all
       * remaining tied ones (Sect. 2.2). Returns the indices into @p xi in
       * increasing order.
       */
      std::vector<unsigned int>
      select(const std::vector<Tensor<1, dim>> &xi) const;

      /**
       * The fit of the cloud @p xi (the selected bond vectors): @p q
       * becomes Q_i (n_p x n_c) in the physical basis, so that the fitted
       * Taylor coefficients of a field g are q g. Computed through the SVD
       * of W^{1/2} M in the basis scaled by the horizon. Returns
       * cond_2(A_i) of the scaled basis (infinity if singular).
       */
      double
      fit(const std::vector<Tensor<1, dim>> &xi, FullMatrix<double> &q) const;

      /// The weight of Eq. 36 with the weight radius \f$\tilde r\f$.
      double
      weight(const Tensor<1, dim> &xi) const;

    private:
      MonomialBasis<dim> monomials;
      unsigned int       k_a;
      double             horizon;
      double             weight_radius;
    };


    /**
     * The angular moment \f$\Omega_d(\beta) = \int_{S^{d-1}} n^\beta dS\f$
     * (doc/collocation.md Sect. 1).
     */
    template <int dim>
    double
    sphere_moment(const std::array<unsigned int, dim> &beta);

    /**
     * The moments of a bond kernel that is radial times n ⊗ n,
     * \f$k(\xi) = g(|\xi|)\, n \otimes n\f$ (the linearised bond-based
     * pair stiffness per unit volume): \f$L_{ba}[\alpha] = \int_B g(r)
     * n_b n_a \xi^\alpha dV\f$ for every monomial of @p basis (zero for
     * the constant), by Gauss quadrature of the radial part and
     * sphere_moment() of the angular one. @p radial must be smooth on
     * (0, horizon].
     */
    template <int dim>
    std::vector<Tensor<2, dim>>
    tensor_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon);

    /**
     * The moments of a scalar radial kernel (diffusion):
     * \f$L[\alpha] = \int_B g(r) \xi^\alpha dV\f$ (zero for the constant).
     */
    template <int dim>
    std::vector<double>
    scalar_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon);

    /**
     * The moments of a kernel that is radial times the direction,
     * \f$k(\xi) = g(|\xi|)\, n\f$: \f$L_a[\alpha] = \int_B g(r) n_a
     * \xi^\alpha dV\f$ for every monomial of @p basis (zero for the
     * constant): the dilatation and the dilatation force of the collocation
     * LPS (doc/collocation.md Sect. 5.2: T with g = d omega r / m, Kf with
     * g = alpha(r) / m).
     */
    template <int dim>
    std::vector<Tensor<1, dim>>
    vector_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon);

    /**
     * The integral \f$\int_B g(|\xi|) |\xi|^2 dV\f$ over the ball of
     * radius @p horizon: with g the influence function, the weighted volume
     * m of a full neighbourhood in the continuum.
     */
    template <int dim>
    double
    second_radial_moment(const std::function<double(double)> &radial,
                         const double                         horizon);

    /// The volume (length, area) of the ball of radius @p horizon.
    template <int dim>
    inline double
    ball_volume(const double horizon)
    {
      return (dim == 1 ? 2. :
              dim == 2 ? M_PI :
                         4. / 3. * M_PI) *
             std::pow(horizon, dim);
    }

    /// A row's vectors: W_j = sum_alpha L[alpha] Q[alpha, j].
    template <int dim>
    std::vector<Tensor<1, dim>>
    vector_row(const std::vector<Tensor<1, dim>> &moments,
               const FullMatrix<double>          &q);

    /// A row's d x d blocks: W_j = sum_alpha L[alpha] Q[alpha, j].
    template <int dim>
    std::vector<Tensor<2, dim>>
    tensor_row(const std::vector<Tensor<2, dim>> &moments,
               const FullMatrix<double>          &q);

    /// A row's scalar weights: w_j = sum_alpha L[alpha] Q[alpha, j].
    std::vector<double>
    scalar_row(const std::vector<double> &moments, const FullMatrix<double> &q);

    /**
     * The stabilisation row of a cloud (doc/collocation.md Sect. 7.1):
     * \f$T = v - Q^T M^T v\f$, where \f$v_j = g(|\xi_j|)\,V_B/(n_c - 1)\f$
     * for the cloud's nodes (@p kernel g, V_B the ball's volume),
     * \f$v_0 = -\sum_j v_j\f$ for the node itself (the zero vector of
     * @p cloud), \f$M_{l\alpha} = P_\alpha(\xi_l)\f$ and @p q the fit
     * Q_i of the cloud. T applied to a field is a positive-weight sum of
     * its differences minus the same sum of its fitted polynomial's
     * differences: zero for every field the fit reproduces (degree <= k),
     * so adding gamma T to a row keeps it exact, and about the
     * positive-weight sum itself for grid-scale waves, which the fit hardly
     * sees. Sum_j T_j = 0.
     */
    template <int dim>
    std::vector<double>
    stabilisation_row(const MonomialBasis<dim>            &basis,
                      const std::vector<Tensor<1, dim>>   &cloud,
                      const FullMatrix<double>            &q,
                      const std::function<double(double)> &kernel,
                      const double                         horizon);


    /**
     * Add the stabilisation term gamma T of stabilisation_row() to a scalar
     * row (diffusion: @p kernel the conductance), ...
     */
    template <int dim>
    void
    add_stabilisation(std::vector<double>                 &row,
                      const MonomialBasis<dim>            &basis,
                      const std::vector<Tensor<1, dim>>   &cloud,
                      const FullMatrix<double>            &q,
                      const std::function<double(double)> &kernel,
                      const double                         horizon,
                      const double                         gamma)
    {
      const std::vector<double> t =
        stabilisation_row<dim>(basis, cloud, q, kernel, horizon);
      for (unsigned int j = 0; j < row.size(); ++j)
        row[j] += gamma * t[j];
    }


    /**
     * ... or gamma T_j times the identity to the d x d blocks of an
     * elasticity row, with the kernel g(r)/d for the pair stiffness
     * g(r) n (x) n (@p stiffness; the trace of the block over d).
     */
    template <int dim>
    void
    add_stabilisation(std::vector<Tensor<2, dim>>         &row,
                      const MonomialBasis<dim>            &basis,
                      const std::vector<Tensor<1, dim>>   &cloud,
                      const FullMatrix<double>            &q,
                      const std::function<double(double)> &stiffness,
                      const double                         horizon,
                      const double                         gamma)
    {
      const std::vector<double> t = stabilisation_row<dim>(
        basis,
        cloud,
        q,
        [&](const double r) { return stiffness(r) / dim; },
        horizon);
      for (unsigned int j = 0; j < row.size(); ++j)
        for (unsigned int c = 0; c < dim; ++c)
          row[j][c][c] += gamma * t[j];
    }

    /**
     * The largest eigenvalue of the Fourier symbol
     * \f$\sigma(k) = \sum_j W_j (\cos(k\cdot\xi_j) - 1)\f$ of a shared
     * stencil on a lattice of spacing @p h, over a grid of
     * @p n_per_axis wave numbers per axis in the Brillouin zone, relative
     * to the magnitude of the most negative one (doc/collocation.md Sect.
     * 7): positive means growing modes. With @p force_row and
     * @p theta_row (the two antisymmetric rows K_j and T_j of the collocation
     * LPS, doc/collocation.md Sect. 5.2) the symbol is that of the
     * composition, \f$\sigma(k) - S_K(k) \otimes S_T(k)\f$ with
     * \f$S(k) = \sum_j (\cdot)_j \sin(k\cdot\xi_j)\f$.
     */
    template <int dim>
    double
    largest_symbol_eigenvalue(
      const std::vector<Tensor<1, dim>> &xi,
      const std::vector<Tensor<2, dim>> &blocks,
      const double                       h,
      const unsigned int                 n_per_axis,
      const std::vector<Tensor<1, dim>> &force_row = {},
      const std::vector<Tensor<1, dim>> &theta_row = {});
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
