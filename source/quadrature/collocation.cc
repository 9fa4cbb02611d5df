// The WLS collocation quadrature: basis, selection, fit, kernel moments and
// rows (doc/collocation.md Sects. 2-7).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/collocation.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    MonomialBasis<dim>::MonomialBasis(const unsigned int order)
      : k(order)
    {
      // Graded; within a degree the x power first, then y, then z.
      for (unsigned int g = 0; g <= order; ++g)
        {
          std::array<unsigned int, dim> e{};
          if constexpr (dim == 1)
            {
              e[0] = g;
              exponents.push_back(e);
            }
          else if constexpr (dim == 2)
            for (int a = g; a >= 0; --a)
              {
                e = {{unsigned(a), g - unsigned(a)}};
                exponents.push_back(e);
              }
          else
            for (int a = g; a >= 0; --a)
              for (int b = g - a; b >= 0; --b)
                {
                  e = {{unsigned(a), unsigned(b), g - unsigned(a + b)}};
                  exponents.push_back(e);
                }
        }
    }


    template <int dim>
    unsigned int
    MonomialBasis<dim>::degree(const unsigned int a) const
    {
      unsigned int g = 0;
      for (unsigned int d = 0; d < dim; ++d)
        g += exponents[a][d];
      return g;
    }


    template <int dim>
    void
    MonomialBasis<dim>::evaluate(const Tensor<1, dim> &x, double *values) const
    {
      // Powers of each coordinate once, then products.
      std::array<std::vector<double>, dim> power;
      for (unsigned int d = 0; d < dim; ++d)
        {
          power[d].resize(k + 1);
          power[d][0] = 1;
          for (unsigned int p = 1; p <= k; ++p)
            power[d][p] = power[d][p - 1] * x[d];
        }
      for (unsigned int a = 0; a < exponents.size(); ++a)
        {
          double v = 1;
          for (unsigned int d = 0; d < dim; ++d)
            v *= power[d][exponents[a][d]];
          values[a] = v;
        }
    }


    unsigned int
    n_monomials(const unsigned int dim, const unsigned int order)
    {
      // binomial(order + dim, dim)
      unsigned int n = 1;
      for (unsigned int d = 1; d <= dim; ++d)
        n = n * (order + d) / d;
      return n;
    }


    unsigned int
    auxiliary_grid_size(const unsigned int dim, const unsigned int divisions)
    {
      const int    k  = divisions;
      unsigned int n  = 0;
      const int    ky = dim > 1 ? k : 0, kz = dim > 2 ? k : 0;
      for (int a = -k; a <= k; ++a)
        for (int b = -ky; b <= ky; ++b)
          for (int c = -kz; c <= kz; ++c)
            if (a * a + b * b + c * c <= k * k)
              ++n;
      return n;
    }


    unsigned int
    auxiliary_divisions(const unsigned int dim,
                        const unsigned int n_collocation)
    {
      unsigned int best = 1;
      long         gap  = std::numeric_limits<long>::max();
      for (unsigned int k = 1; k <= 12; ++k)
        {
          const long g =
            std::labs(long(auxiliary_grid_size(dim, k)) - long(n_collocation));
          if (g <= gap)
            {
              gap  = g;
              best = k;
            }
          if (auxiliary_grid_size(dim, k) > n_collocation)
            break;
        }
      return best;
    }


    bool
    offers_order(const unsigned int dim, const unsigned int order)
    {
      return order == 2 || order == 4 || (order == 6 && dim == 1);
    }


    unsigned int
    default_collocation_nodes(const unsigned int dim, const unsigned int order)
    {
      AssertThrow(offers_order(dim, order),
                  ExcMessage("The collocation scheme offers orders 2, 4 and "
                             "6 in 1D and 2 and 4 in 2D and 3D, not " +
                             std::to_string(order) + " in " +
                             std::to_string(dim) + "D."));
      if (dim == 1)
        return order == 2 ? 5 : order == 4 ? 11 : 13;
      if (dim == 2)
        return order == 2 ? 29 : 49;
      return order == 2 ? 33 : 123;
    }


    template <int dim>
    CollocationFit<dim>::CollocationFit(const unsigned int order,
                                        const unsigned int n_collocation,
                                        const double       horizon,
                                        const double       weight_radius)
      : monomials(order)
      , k_a(auxiliary_divisions(dim,
                                n_collocation > 0 ?
                                  n_collocation :
                                  default_collocation_nodes(dim, order)))
      , horizon(horizon)
      , weight_radius(weight_radius > 0 ? weight_radius : horizon)
    {}


    template <int dim>
    double
    CollocationFit<dim>::weight(const Tensor<1, dim> &xi) const
    {
      // Eq. 36: (e^{-16 s^2} - e^{-64}) / (1 - e^{-64}), s = |xi| / r~.
      const double s2 = xi.norm_square() / (weight_radius * weight_radius);
      return (std::exp(-16. * s2) - std::exp(-64.)) / (1. - std::exp(-64.));
    }


    template <int dim>
    std::vector<unsigned int>
    CollocationFit<dim>::select(const std::vector<Tensor<1, dim>> &xi) const
    {
      const int         k   = k_a;
      const double      tol = 1e-10 * horizon * horizon;
      std::vector<char> chosen(xi.size(), 0);
      const int         ky = dim > 1 ? k : 0, kz = dim > 2 ? k : 0;
      for (int a = -k; a <= k; ++a)
        for (int b = -ky; b <= ky; ++b)
          for (int c = -kz; c <= kz; ++c)
            {
              if (a * a + b * b + c * c > k * k)
                continue;
              Tensor<1, dim> p;
              const int      ia[3] = {a, b, c};
              for (unsigned int d = 0; d < dim; ++d)
                p[d] = ia[d] * horizon / k;
              double nearest = std::numeric_limits<double>::max();
              for (const auto &x : xi)
                nearest = std::min(nearest, (x - p).norm_square());
              // Among the nearest: the ones nearest to the source, all of
              // them (Sect. 2.2).
              double closest = std::numeric_limits<double>::max();
              for (const auto &x : xi)
                if ((x - p).norm_square() <= nearest + tol)
                  closest = std::min(closest, x.norm_square());
              for (unsigned int j = 0; j < xi.size(); ++j)
                if ((xi[j] - p).norm_square() <= nearest + tol &&
                    xi[j].norm_square() <= closest + tol)
                  chosen[j] = 1;
            }
      std::vector<unsigned int> members;
      for (unsigned int j = 0; j < xi.size(); ++j)
        if (chosen[j])
          members.push_back(j);
      return members;
    }


    template <int dim>
    double
    CollocationFit<dim>::fit(const std::vector<Tensor<1, dim>> &xi,
                             FullMatrix<double>                &q) const
    {
      const unsigned int n_c = xi.size(), n_p = monomials.size();
      q.reinit(n_p, n_c);
      if (n_c < n_p)
        return std::numeric_limits<double>::infinity();
      // W^{1/2} M in the basis p(xi / delta).
      LAPACKFullMatrix<double> m(n_c, n_p);
      std::vector<double>      row(n_p), root_w(n_c);
      for (unsigned int j = 0; j < n_c; ++j)
        {
          monomials.evaluate(xi[j] / horizon, row.data());
          root_w[j] = std::sqrt(weight(xi[j]));
          for (unsigned int a = 0; a < n_p; ++a)
            m(j, a) = root_w[j] * row[a];
        }
      m.compute_svd();
      const double largest  = m.singular_value(0);
      const double smallest = m.singular_value(n_p - 1);
      if (!(smallest > 0) || !(largest > 0))
        return std::numeric_limits<double>::infinity();
      const double condition = (largest / smallest) * (largest / smallest);
      const auto  &u         = m.get_svd_u();
      const auto  &vt        = m.get_svd_vt();
      // Q = V Sigma^{-1} U^T W^{1/2}, then back to the physical basis:
      // coefficient alpha scales with delta^{-|alpha|}.
      for (unsigned int a = 0; a < n_p; ++a)
        {
          const double scale = std::pow(horizon, -double(monomials.degree(a)));
          for (unsigned int j = 0; j < n_c; ++j)
            {
              double sum = 0;
              for (unsigned int s = 0; s < n_p; ++s)
                sum += vt(s, a) * u(j, s) / m.singular_value(s);
              q(a, j) = scale * sum * root_w[j];
            }
        }
      return condition;
    }


    template <int dim>
    double
    sphere_moment(const std::array<unsigned int, dim> &beta)
    {
      const double sphere = dim == 1 ? 2. : dim == 2 ? 2. * M_PI : 4. * M_PI;
      unsigned int total  = 0;
      double       value  = sphere;
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (beta[d] % 2 != 0)
            return 0;
          for (unsigned int f = beta[d]; f >= 2; f -= 2)
            value *= f - 1; // (beta - 1)!!
          total += beta[d];
        }
      for (unsigned int p = dim; p + 2 <= dim + total; p += 2)
        value /= p; // d (d + 2) ... (d + |beta| - 2)
      return value;
    }


    namespace
    {
      // int_0^delta g(r) r^p dr, Gauss-Legendre with 64 points (exact for
      // polynomial g r^p of degree up to 127).
      double
      radial_integral(const std::function<double(double)> &g,
                      const double                         horizon,
                      const unsigned int                   p)
      {
        static const QGauss<1> rule(64);
        double                 sum = 0;
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const double r = horizon * rule.point(q)[0];
            sum += rule.weight(q) * g(r) * std::pow(r, double(p));
          }
        return sum * horizon;
      }
    } // namespace


    template <int dim>
    std::vector<Tensor<2, dim>>
    tensor_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon)
    {
      std::vector<Tensor<2, dim>> moments(basis.size());
      for (unsigned int a = 1; a < basis.size(); ++a)
        {
          const unsigned int g = basis.degree(a);
          const double       r = radial_integral(radial, horizon, g + dim - 1);
          for (unsigned int b = 0; b < dim; ++b)
            for (unsigned int c = 0; c < dim; ++c)
              {
                auto beta = basis.exponent(a);
                ++beta[b];
                ++beta[c];
                moments[a][b][c] = r * sphere_moment<dim>(beta);
              }
        }
      return moments;
    }


    template <int dim>
    std::vector<Tensor<1, dim>>
    vector_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon)
    {
      std::vector<Tensor<1, dim>> moments(basis.size());
      for (unsigned int a = 1; a < basis.size(); ++a)
        {
          const double r =
            radial_integral(radial, horizon, basis.degree(a) + dim - 1);
          for (unsigned int b = 0; b < dim; ++b)
            {
              auto beta = basis.exponent(a);
              ++beta[b];
              moments[a][b] = r * sphere_moment<dim>(beta);
            }
        }
      return moments;
    }


    template <int dim>
    double
    second_radial_moment(const std::function<double(double)> &radial,
                         const double                         horizon)
    {
      // int_B g r^2 dV = |S^{d-1}| int_0^delta g(r) r^{d+1} dr.
      return sphere_moment<dim>(std::array<unsigned int, dim>{}) *
             radial_integral(radial, horizon, dim + 1);
    }


    template <int dim>
    std::vector<Tensor<1, dim>>
    vector_row(const std::vector<Tensor<1, dim>> &moments,
               const FullMatrix<double>          &q)
    {
      std::vector<Tensor<1, dim>> row(q.n());
      for (unsigned int j = 0; j < q.n(); ++j)
        for (unsigned int a = 0; a < q.m(); ++a)
          row[j] += q(a, j) * moments[a];
      return row;
    }


    template <int dim>
    std::vector<double>
    scalar_moments(const MonomialBasis<dim>            &basis,
                   const std::function<double(double)> &radial,
                   const double                         horizon)
    {
      std::vector<double> moments(basis.size(), 0.);
      for (unsigned int a = 1; a < basis.size(); ++a)
        {
          const double omega = sphere_moment<dim>(basis.exponent(a));
          if (omega != 0)
            moments[a] =
              omega *
              radial_integral(radial, horizon, basis.degree(a) + dim - 1);
        }
      return moments;
    }


    template <int dim>
    std::vector<Tensor<2, dim>>
    tensor_row(const std::vector<Tensor<2, dim>> &moments,
               const FullMatrix<double>          &q)
    {
      std::vector<Tensor<2, dim>> row(q.n());
      for (unsigned int j = 0; j < q.n(); ++j)
        for (unsigned int a = 0; a < q.m(); ++a)
          row[j] += q(a, j) * moments[a];
      return row;
    }


    std::vector<double>
    scalar_row(const std::vector<double> &moments, const FullMatrix<double> &q)
    {
      std::vector<double> row(q.n(), 0.);
      for (unsigned int j = 0; j < q.n(); ++j)
        for (unsigned int a = 0; a < q.m(); ++a)
          row[j] += q(a, j) * moments[a];
      return row;
    }


    template <int dim>
    std::vector<double>
    stabilisation_row(const MonomialBasis<dim>            &basis,
                      const std::vector<Tensor<1, dim>>   &cloud,
                      const FullMatrix<double>            &q,
                      const std::function<double(double)> &kernel,
                      const double                         horizon)
    {
      const unsigned int n_c = cloud.size(), n_p = basis.size();
      AssertThrow(q.m() == n_p && q.n() == n_c && n_c > 1, ExcInternalError());
      const double ball = ball_volume<dim>(horizon);
      // v: the positive-weight sum, the node itself weighing minus the
      // others.
      std::vector<double> v(n_c, 0.);
      int                 self  = -1;
      double              total = 0;
      for (unsigned int j = 0; j < n_c; ++j)
        {
          const double r = cloud[j].norm();
          if (r == 0)
            {
              self = j;
              continue;
            }
          v[j] = kernel(r) * ball / (n_c - 1);
          total += v[j];
        }
      AssertThrow(self >= 0,
                  ExcMessage("stabilisation_row(): the cloud must hold its "
                             "node (the zero vector)"));
      v[self] = -total;
      // T = v - Q^T (M^T v).
      std::vector<double> mv(n_p, 0.), p(n_p);
      for (unsigned int l = 0; l < n_c; ++l)
        {
          basis.evaluate(cloud[l], p.data());
          for (unsigned int a = 0; a < n_p; ++a)
            mv[a] += v[l] * p[a];
        }
      std::vector<double> t(v);
      for (unsigned int j = 0; j < n_c; ++j)
        for (unsigned int a = 0; a < n_p; ++a)
          t[j] -= q(a, j) * mv[a];
      return t;
    }


    template <int dim>
    double
    largest_symbol_eigenvalue(const std::vector<Tensor<1, dim>> &xi,
                              const std::vector<Tensor<2, dim>> &blocks,
                              const double                       h,
                              const unsigned int                 n_per_axis,
                              const std::vector<Tensor<1, dim>> &force_row,
                              const std::vector<Tensor<1, dim>> &theta_row)
    {
      double       largest = -std::numeric_limits<double>::max();
      double       lowest  = 0;
      unsigned int n_total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        n_total *= n_per_axis + 1;
      for (unsigned int t = 0; t < n_total; ++t)
        {
          Tensor<1, dim> k;
          unsigned int   rest = t;
          bool           zero = true;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const unsigned int td = rest % (n_per_axis + 1);
              rest /= n_per_axis + 1;
              k[d] = M_PI / h * (2. * td / n_per_axis - 1.);
              zero = zero && 2 * td == n_per_axis;
            }
          if (zero)
            continue;
          Tensor<2, dim> sigma;
          for (unsigned int j = 0; j < xi.size(); ++j)
            sigma += (std::cos(k * xi[j]) - 1.) * blocks[j];
          if (!force_row.empty())
            {
              Tensor<1, dim> s_force, s_theta;
              for (unsigned int j = 0; j < xi.size(); ++j)
                {
                  s_force += std::sin(k * xi[j]) * force_row[j];
                  s_theta += std::sin(k * xi[j]) * theta_row[j];
                }
              sigma -= outer_product(s_force, s_theta);
            }
          const auto lambda = eigenvalues(symmetrize(sigma));
          largest           = std::max(largest, lambda[0]);
          lowest            = std::min(lowest, lambda[dim - 1]);
        }
      return lowest < 0 ? largest / std::abs(lowest) : largest;
    }


    template class MonomialBasis<1>;
    template class MonomialBasis<2>;
    template class MonomialBasis<3>;
    template class CollocationFit<1>;
    template class CollocationFit<2>;
    template class CollocationFit<3>;
#define PERIDEAL_INSTANTIATE(dim)                                            \
  template double sphere_moment<dim>(const std::array<unsigned int, dim> &); \
  template std::vector<Tensor<2, dim>> tensor_moments<dim>(                  \
    const MonomialBasis<dim> &,                                              \
    const std::function<double(double)> &,                                   \
    const double);                                                           \
  template std::vector<double> scalar_moments<dim>(                          \
    const MonomialBasis<dim> &,                                              \
    const std::function<double(double)> &,                                   \
    const double);                                                           \
  template std::vector<Tensor<1, dim>> vector_moments<dim>(                  \
    const MonomialBasis<dim> &,                                              \
    const std::function<double(double)> &,                                   \
    const double);                                                           \
  template double second_radial_moment<dim>(                                 \
    const std::function<double(double)> &,                                   \
    const double);                                                           \
  template std::vector<Tensor<1, dim>> vector_row<dim>(                      \
    const std::vector<Tensor<1, dim>> &,                                     \
    const FullMatrix<double> &);                                             \
  template std::vector<Tensor<2, dim>> tensor_row<dim>(                      \
    const std::vector<Tensor<2, dim>> &,                                     \
    const FullMatrix<double> &);                                             \
  template std::vector<double> stabilisation_row<dim>(                       \
    const MonomialBasis<dim> &,                                              \
    const std::vector<Tensor<1, dim>> &,                                     \
    const FullMatrix<double> &,                                              \
    const std::function<double(double)> &,                                   \
    const double);                                                           \
  template double largest_symbol_eigenvalue<dim>(                            \
    const std::vector<Tensor<1, dim>> &,                                     \
    const std::vector<Tensor<2, dim>> &,                                     \
    const double,                                                            \
    const unsigned int,                                                      \
    const std::vector<Tensor<1, dim>> &,                                     \
    const std::vector<Tensor<1, dim>> &);
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Quadrature
} // namespace PeriDEAL
