#ifndef perideal_discretization_taylor_extrapolation_h
#define perideal_discretization_taylor_extrapolation_h

#include <deal.II/base/tensor.h>

#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    using namespace dealii;

    /// Number of monomials of total degree at most @p order in @p dim variables.
    unsigned int
    n_taylor_terms(const unsigned int dim, const unsigned int order);

    /**
     * Weights of a truncated Taylor extrapolation (paper Sect. 3.2).
     *
     * The value at @p target is \f$\sum_q w_q f(\mathbf x_q)\f$, where
     * @p stencil holds the points \f$\mathbf x_q\f$ and the first entry is the
     * expansion point. The derivatives up to order @p order at the expansion
     * point are fitted to the stencil values; when the stencil has more
     * points than Taylor terms the fit is least squares, and the weights are
     * the minimum-norm solution of
     * \f$\sum_q w_q \phi_\alpha(\mathbf x_q) = \phi_\alpha(\mathbf x_t)\f$
     * for every monomial \f$\phi_\alpha\f$ of degree at most @p order. The
     * extrapolation is therefore exact for polynomials of that degree.
     * Coordinates should be scaled to the grid spacing for conditioning.
     *
     * Returns an empty vector if the stencil does not determine all
     * derivatives (rank deficient, smallest singular value below
     * 1e-10 times the largest).
     */
    template <int dim>
    std::vector<double>
    taylor_extrapolation_weights(const std::vector<Tensor<1, dim>> &stencil,
                                 const Tensor<1, dim>              &target,
                                 const unsigned int                 order);
  } // namespace Discretization
} // namespace PeriDEAL

#endif
