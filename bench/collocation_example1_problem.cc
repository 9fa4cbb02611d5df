/**
 * @file
 * Example 1 of the hybrid-collocation paper: the cosine integral, the problem
 * and its body forces, the schemes' rows, one run and its CSV row
 * (bench/collocation_example1.cc describes the study).
 */

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <perideal/quadrature/collocation.h>

#include "collocation_example1.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;

namespace Example1
{
  // ------------------------------------------------------------------
  // The cosine integral.

  /**
   * Ci(x) for x > 0: the power series Ci(x) = gamma + ln x + sum_{k >= 1}
   * (-x^2)^k / (2k (2k)!) for x <= 4 (largest term below 4, so the
   * cancellation costs at most a few ulps), else the continued fraction of
   * E1(i x) (Ci(x) = -Re E1(i x); modified Lentz, as in Numerical Recipes'
   * cisi), which converges fast there.
   */
  double
  cosine_integral(const double x)
  {
    if (!(x > 0))
      return std::numeric_limits<double>::quiet_NaN();
    if (x <= 4.)
      {
        double       sum = 0, term = 1; // term = (-x^2)^k / (2k)!
        const double x2 = x * x;
        for (unsigned int k = 1; k < 100; ++k)
          {
            term *= -x2 / ((2. * k - 1.) * (2. * k));
            const double add = term / (2. * k);
            sum += add;
            if (std::abs(add) < 1e-18 * std::abs(sum))
              break;
          }
        return euler_gamma + std::log(x) + sum;
      }
    using complex     = std::complex<double>;
    const double tiny = 1e-300;
    complex      b(1., x);
    complex      c(1. / tiny, 0.);
    complex      d = 1. / b;
    complex      f = d;
    for (unsigned int i = 2; i < 1000; ++i)
      {
        const double a = -double(i - 1) * double(i - 1);
        b += 2.;
        d                 = 1. / (a * d + b);
        c                 = b + a / c;
        const complex del = c * d;
        f *= del;
        if (std::abs(del - 1.) < 1e-16)
          break;
      }
    f *= complex(std::cos(x), -std::sin(x)); // E1(i x)
    return -f.real();
  }

  /**
   * Reference for the check: Ci(x) = gamma + ln x - int_0^x (1 - cos t) / t
   * dt, the integrand entire, by composite Gauss-Legendre (30 points on
   * panels of length <= 1/2: converged to round-off).
   */
  double
  cosine_integral_by_quadrature(const double x)
  {
    static const QGauss<1> rule(30);
    const unsigned int     panels = std::ceil(2. * x);
    const double           length = x / panels;
    double                 sum    = 0;
    for (unsigned int p = 0; p < panels; ++p)
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const double t = (p + rule.point(q)[0]) * length;
          sum += rule.weight(q) * length * (1. - std::cos(t)) / t;
        }
    return euler_gamma + std::log(x) - sum;
  }


  // ------------------------------------------------------------------
  // The problem.

  double
  micromodulus(const double delta)
  {
    return 2. / (delta * delta);
  }

  double
  exact_solution(const double x)
  {
    return std::sin(wavenumber * x);
  }

  /// Eq. 69: b = 2 c (gamma - Ci(k delta) + ln(k delta)) sin(k x).
  double
  pd_body_force(const double x, const double delta)
  {
    const double z = wavenumber * delta;
    return 2. * micromodulus(delta) *
           (euler_gamma - cosine_integral(z) + std::log(z)) *
           std::sin(wavenumber * x);
  }

  /// Eq. 71: b = -u'' = k^2 sin(k x).
  double
  local_body_force(const double x, const double)
  {
    return wavenumber * wavenumber * std::sin(wavenumber * x);
  }

  /**
   * -L u(x) for u = sin(k x), by direct composite Gauss-Legendre
   * quadrature of the PD integral, the bonds xi and -xi together (the
   * integrand is bounded and smooth on each side of 0): the independent
   * check of Eq. 69. In long double, since u(x + xi) - u(x) cancels to
   * O((k xi)^2) for short bonds.
   */
  double
  pd_force_by_quadrature(const double x, const double delta)
  {
    static const QGauss<1> rule(30);
    const long double      c      = micromodulus(delta);
    const long double      k      = 1.L / 10.L;
    const unsigned int     panels = std::ceil(4. * delta) + 1;
    const long double      length = (long double)delta / panels;
    long double            sum    = 0;
    for (unsigned int p = 0; p < panels; ++p)
      for (unsigned int q = 0; q < rule.size(); ++q)
        {
          const long double xi = (p + (long double)rule.point(q)[0]) * length;
          sum += rule.weight(q) * length * c *
                 (std::sin(k * (x + xi)) + std::sin(k * (x - xi)) -
                  2.L * std::sin(k * x)) /
                 xi;
        }
    return -double(sum);
  }


  // ------------------------------------------------------------------
  // The schemes: one shared row (L u)_i = sum_j w_j u_{i + offset_j}.


  bool
  is_collocation(const unsigned int scheme)
  {
    return scheme >= 1 && scheme <= 3;
  }

  /// The collocation order of a scheme (0: a standard one).
  unsigned int
  order_of(const unsigned int scheme)
  {
    return is_collocation(scheme) ? 2 * scheme : 0;
  }

  /**
   * The largest value of the row's Fourier symbol sigma(theta) = sum_j w_j
   * (cos(o_j theta) - 1), theta in (0, pi], over the magnitude of the most
   * negative one. The PD symbol is negative for all theta; a positive value
   * means an indefinite operator (doc/collocation.md Sect. 7).
   */
  double
  symbol_ratio(const Row &row)
  {
    double largest = -std::numeric_limits<double>::max(), lowest = 0;
    for (unsigned int t = 1; t <= 2000; ++t)
      {
        const double theta = M_PI * t / 2000.;
        double       s     = 0;
        for (unsigned int j = 0; j < row.offsets.size(); ++j)
          s += row.weights[j] * (std::cos(row.offsets[j] * theta) - 1.);
        largest = std::max(largest, s);
        lowest  = std::min(lowest, s);
      }
    return lowest < 0 ? largest / std::abs(lowest) : largest;
  }

  /**
   * The standard scheme: exact partial lengths of the cells (in 1D the
   * same as the paper's volume reduction factor, Eq. 28, for every m), or
   * with @p full_volumes the whole cell of every node with |xi| <= delta.
   */
  Row
  standard_row(const double delta, const double h, const bool full_volumes)
  {
    const double c = micromodulus(delta);
    Row          row;
    row.offsets.push_back(0);
    row.weights.push_back(0.);
    const int reach = std::ceil(delta / h + 0.5);
    for (int k = -reach; k <= reach; ++k)
      {
        if (k == 0)
          continue;
        const double lower  = std::max(k * h - h / 2, -delta);
        const double upper  = std::min(k * h + h / 2, delta);
        double       length = upper - lower;
        if (full_volumes)
          length = std::abs(k) * h <= delta * (1. + 1e-12) ? h : 0.;
        if (length <= 1e-14 * h)
          continue;
        const double w = c * length / (std::abs(k) * h);
        row.offsets.push_back(k);
        row.weights.push_back(w);
        row.weights[0] -= w;
      }
    row.symbol = symbol_ratio(row);
    return row;
  }

  /// The family offsets k with |k h| <= delta, 0 first, then 1, -1, 2, ...
  std::vector<int>
  family_offsets(const double delta, const double h)
  {
    std::vector<int> offsets = {0};
    for (int k = 1; k * h <= delta * (1. + 1e-12); ++k)
      {
        offsets.push_back(k);
        offsets.push_back(-k);
      }
    return offsets;
  }

  /**
   * The collocation row of @p order: the library's selection among the
   * family, its fit and the moments of c / |xi|. Returns a row without
   * offsets where the cloud cannot be fitted (fewer nodes than monomials,
   * or cond(A) above 1e12 as in the library's fall-back rule).
   */
  Row
  collocation_row(const unsigned int order, const double delta, const double h)
  {
    const double                            c = micromodulus(delta);
    PeriDEAL::Quadrature::CollocationFit<1> fit(order, 0, delta);
    const std::vector<int>                  family = family_offsets(delta, h);
    std::vector<Tensor<1, 1>>               xi(family.size());
    for (unsigned int j = 0; j < family.size(); ++j)
      xi[j][0] = family[j] * h;
    const std::vector<unsigned int> chosen = fit.select(xi);
    std::vector<Tensor<1, 1>>       cloud;
    Row                             row;
    for (const unsigned int j : chosen)
      {
        cloud.push_back(xi[j]);
        row.offsets.push_back(family[j]);
      }
    FullMatrix<double> q;
    row.condition = fit.fit(cloud, q);
    if (!(row.condition < 1e12))
      {
        row.offsets.clear();
        return row;
      }
    const std::vector<double> moments = PeriDEAL::Quadrature::scalar_moments<1>(
      fit.basis(),
      [c](const double r) { return c / r; },
      delta);
    row.weights = PeriDEAL::Quadrature::scalar_row(moments, q);
    row.symbol  = symbol_ratio(row);
    return row;
  }

  Row
  make_row(const unsigned int scheme, const double delta, const double h)
  {
    if (is_collocation(scheme))
      return collocation_row(order_of(scheme), delta, h);
    return standard_row(delta, h, scheme == 4);
  }


  // ------------------------------------------------------------------
  // One run.


  /**
   * Solves -L u = b on the n cells of Omega_h = (-n h/2, n h/2) with the
   * exact solution in the layers; returns the solution at the nodes of
   * Omega_h and sets @p n_swaps. The timed part of a run.
   */
  std::vector<double>
  solve(const Row         &row,
        const unsigned int n,
        const double       h,
        const double       delta,
        const Force       &force,
        unsigned int      &n_swaps)
  {
    const int    w = row.half_width();
    BandedSystem system(n, w, w);
    const double left = -0.5 * n * h;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double x = left + (i + 0.5) * h;
        system.b(i)    = force(x, delta);
        for (unsigned int j = 0; j < row.offsets.size(); ++j)
          {
            const int col = int(i) + row.offsets[j];
            if (col >= 0 && col < int(n))
              system(i, col) -= row.weights[j];
            else // a layer node: the exact solution
              system.b(i) +=
                row.weights[j] * exact_solution(left + (col + 0.5) * h);
          }
      }
    return system.solve(n_swaps);
  }

  /// Eq. 66 over the nodes of Omega_h.
  double
  relative_error(const std::vector<double> &u, const double h)
  {
    const unsigned int n    = u.size();
    const double       left = -0.5 * n * h;
    double             e = 0, r = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        const double exact = exact_solution(left + (i + 0.5) * h);
        e += (u[i] - exact) * (u[i] - exact);
        r += exact * exact;
      }
    return std::sqrt(e / r);
  }

  /**
   * A run of @p scheme with horizon @p delta and @p n cells in Omega
   * (h = delta / m, Omega_h = (-n h/2, n h/2)), the force @p force, timed
   * as the fastest of @p repetitions; with @p pd_force_too also solved with
   * the PD force (Eq. 69) for error_pd_force.
   */
  Result
  run(const unsigned int scheme,
      const double       m,
      const double       delta,
      const unsigned int n,
      const Force       &force,
      const unsigned int repetitions,
      const bool         pd_force_too)
  {
    Result result;
    result.m                 = m;
    result.delta             = delta;
    result.h                 = delta / m;
    result.n_nodes           = n;
    result.omega_half_length = 0.5 * n * result.h;
    result.wall_time         = std::numeric_limits<double>::max();
    std::vector<double> u;
    for (unsigned int r = 0; r < std::max(1u, repetitions); ++r)
      {
        const auto start = std::chrono::steady_clock::now();
        const Row  row   = make_row(scheme, delta, result.h);
        if (row.offsets.empty())
          return result; // infeasible cloud: no row
        u = solve(row, n, result.h, delta, force, result.n_swaps);
        const std::chrono::duration<double> t =
          std::chrono::steady_clock::now() - start;
        result.wall_time     = std::min(result.wall_time, t.count());
        result.n_collocation = row.offsets.size();
        result.half_width    = row.half_width();
        result.condition     = row.condition;
        result.symbol        = row.symbol;
      }
    result.feasible = true;
    result.error    = relative_error(u, result.h);
    if (pd_force_too)
      {
        unsigned int swaps;
        const Row    row = make_row(scheme, delta, result.h);
        result.error_pd_force =
          relative_error(solve(row, n, result.h, delta, pd_body_force, swaps),
                         result.h);
      }
    else
      result.error_pd_force = result.error;
    return result;
  }

  const char *const csv_header =
    "scheme,m,delta,h,n_nodes,error,wall_time_s,error_pd_force,row_entries,"
    "half_width,cond_A,symbol_ratio,lu_interchanges,omega_half_length";

  void
  write_row(std::ostream &out, const unsigned int scheme, const Result &r)
  {
    out << scheme_names[scheme] << ',' << r.m << ',' << r.delta << ','
        << std::setprecision(10) << r.h << ',' << r.n_nodes << ','
        << std::setprecision(6) << std::scientific << r.error << ','
        << r.wall_time << ',' << r.error_pd_force << ',' << std::defaultfloat
        << r.n_collocation << ',' << r.half_width << ',' << std::setprecision(3)
        << r.condition << ',' << r.symbol << ',' << r.n_swaps << ','
        << std::setprecision(10) << r.omega_half_length << std::setprecision(6)
        << '\n';
  }

  void
  print_row(const unsigned int scheme, const Result &r)
  {
    std::cout << std::left << std::setw(11) << scheme_names[scheme]
              << std::right << " m = " << std::setw(5) << r.m
              << " delta = " << std::setw(6) << r.delta
              << " N = " << std::setw(5) << r.n_nodes << " entries "
              << std::setw(3) << r.n_collocation << std::scientific
              << std::setprecision(3) << " error " << r.error << " (PD force "
              << r.error_pd_force << ") " << r.wall_time << " s"
              << std::defaultfloat << std::setprecision(6) << std::endl;
  }

  /// The number of cells of Omega for spacing h: round(200 / h).
  unsigned int
  cells_in_omega(const double h)
  {
    return std::lround(2. * half_length / h);
  }
} // namespace Example1
