#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/discretization/taylor_extrapolation.h>

#include <array>
#include <cmath>

namespace PeriDEAL
{
  namespace Discretization
  {
    namespace
    {
      /// Exponents of all monomials of total degree <= order.
      template <int dim>
      std::vector<std::array<unsigned int, dim>>
      exponents(const unsigned int order)
      {
        std::vector<std::array<unsigned int, dim>> result;
        std::array<unsigned int, dim>              e{};
        const auto recurse = [&](const auto &self, const unsigned int d,
                                 const unsigned int left) -> void {
          if (d == dim)
            {
              result.push_back(e);
              return;
            }
          for (unsigned int k = 0; k <= left; ++k)
            {
              e[d] = k;
              self(self, d + 1, left - k);
            }
        };
        recurse(recurse, 0, order);
        return result;
      }


      template <int dim>
      double
      monomial(const std::array<unsigned int, dim> &e, const Tensor<1, dim> &x)
      {
        double value = 1;
        for (unsigned int d = 0; d < dim; ++d)
          value *= std::pow(x[d], static_cast<int>(e[d]));
        return value;
      }
    } // namespace


    unsigned int
    n_taylor_terms(const unsigned int dim, const unsigned int order)
    {
      // binomial(order + dim, dim)
      unsigned int result = 1;
      for (unsigned int k = 1; k <= dim; ++k)
        result = result * (order + k) / k;
      return result;
    }


    template <int dim>
    std::vector<double>
    taylor_extrapolation_weights(const std::vector<Tensor<1, dim>> &stencil,
                                 const Tensor<1, dim>              &target,
                                 const unsigned int                 order)
    {
      if (order == 0)
        {
          std::vector<double> w(stencil.size(), 0.);
          if (!stencil.empty())
            w[0] = 1;
          return w;
        }
      // The expansion point's value enters exactly (paper Eq. 29); the
      // derivatives are fitted to the differences u_q - u_0 of the other
      // stencil points, in the least-squares sense when there are more
      // points than derivatives.
      auto terms = exponents<dim>(order);
      terms.erase(terms.begin()); // the constant term
      const unsigned int n_q = stencil.size();
      const unsigned int n_t = terms.size();
      if (n_q < n_t + 1)
        return {};

      LAPACKFullMatrix<double> v(n_q - 1, n_t);
      for (unsigned int q = 1; q < n_q; ++q)
        for (unsigned int a = 0; a < n_t; ++a)
          v(q - 1, a) = monomial<dim>(terms[a], stencil[q] - stencil[0]);
      std::vector<double> phi(n_t);
      for (unsigned int a = 0; a < n_t; ++a)
        phi[a] = monomial<dim>(terms[a], target - stencil[0]);

      // V = U S W^T; the minimum-norm w' with V^T w' = phi is
      // w' = U S^{-1} W^T phi, and w_0 = 1 - sum w'.
      v.compute_svd();
      const double s_max = v.singular_value(0);
      const double s_min = v.singular_value(n_t - 1);
      if (!(s_min > 1e-10 * s_max))
        return {};
      const auto         &u  = v.get_svd_u();
      const auto         &wt = v.get_svd_vt();
      std::vector<double> y(n_t, 0.);
      for (unsigned int k = 0; k < n_t; ++k)
        {
          double s = 0;
          for (unsigned int a = 0; a < n_t; ++a)
            s += wt(k, a) * phi[a];
          y[k] = s / v.singular_value(k);
        }
      std::vector<double> w(n_q, 0.);
      w[0] = 1;
      for (unsigned int q = 1; q < n_q; ++q)
        {
          for (unsigned int k = 0; k < n_t; ++k)
            w[q] += u(q - 1, k) * y[k];
          w[0] -= w[q];
        }
      return w;
    }


    template std::vector<double>
    taylor_extrapolation_weights<2>(const std::vector<Tensor<1, 2>> &,
                                    const Tensor<1, 2> &,
                                    const unsigned int);
    template std::vector<double>
    taylor_extrapolation_weights<3>(const std::vector<Tensor<1, 3>> &,
                                    const Tensor<1, 3> &,
                                    const unsigned int);
  } // namespace Discretization
} // namespace PeriDEAL
