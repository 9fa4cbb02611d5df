/**
 * @file
 * Example 1 of the hybrid-collocation paper (bench/collocation_example1.cc
 * describes the study): what the study (collocation_example1.cc), the
 * problem and its schemes (collocation_example1_problem.cc) and the
 * --quick checks (collocation_example1_checks.cc) share.
 */

#ifndef PERIDEAL_BENCH_COLLOCATION_EXAMPLE1_H
#define PERIDEAL_BENCH_COLLOCATION_EXAMPLE1_H

#include <deal.II/base/exceptions.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace Example1
{
  inline constexpr double euler_gamma = 0.57721566490153286061;
  /// The wavenumber of Eq. 68, u = sin(k x) = sin(x / 10).
  inline constexpr double wavenumber = 0.1;
  /// Omega = (-half_length, half_length).
  inline constexpr double half_length = 100.;

  // The problem (collocation_example1_problem.cc).

  /// Ci(x) for x > 0 (a series, or the continued fraction of E1(i x)).
  double
  cosine_integral(const double x);

  /// Ci(x) by quadrature of its integral (an independent check).
  double
  cosine_integral_by_quadrature(const double x);

  /// The micromodulus c = 2 / delta^2.
  double
  micromodulus(const double delta);

  /// u = sin(k x) (Eq. 68).
  double
  exact_solution(const double x);

  /// Eq. 69: b = 2 c (gamma - Ci(k delta) + ln(k delta)) sin(k x).
  double
  pd_body_force(const double x, const double delta);

  /// Eq. 71: b = -u'' = k^2 sin(k x).
  double
  local_body_force(const double x, const double);

  /// -L u at x by direct quadrature of the PD integral (checks Eq. 69).
  double
  pd_force_by_quadrature(const double x, const double delta);

  // The schemes: one shared row (L u)_i = sum_j w_j u_{i + offset_j}.

  struct Row
  {
    std::vector<int>    offsets;
    std::vector<double> weights;
    double              condition = 0; // cond(A) of the fit (collocation)
    double              symbol    = 0; // largest symbol / |most negative|
    unsigned int
    half_width() const
    {
      int w = 0;
      for (const int o : offsets)
        w = std::max(w, std::abs(o));
      return w;
    }
  };

  // Schemes 0-3 are the paper's four; 4 is an extra reference, the
  // standard scheme with full volumes (volume reduction factor 1, the
  // "original implementation" the paper cites before its Eq. 28).
  inline const std::vector<std::string> scheme_names = {"standard",
                                                        "Proposed-A",
                                                        "Proposed-B",
                                                        "Proposed-C",
                                                        "standard-FV"};
  inline constexpr unsigned int         n_schemes    = 5;

  /// Schemes 1-3 (Proposed-A/B/C).
  bool
  is_collocation(const unsigned int scheme);

  /// The collocation order of a scheme (0: a standard one).
  unsigned int
  order_of(const unsigned int scheme);

  /// The largest value of the row's symbol over |its most negative value|.
  double
  symbol_ratio(const Row &row);

  /// The standard row: exact partial lengths, or full volumes.
  Row
  standard_row(const double delta, const double h, const bool full_volumes);

  /// The family offsets k with |k h| <= delta, 0 first, then 1, -1, 2, ...
  std::vector<int>
  family_offsets(const double delta, const double h);

  /// The collocation row of @p order (empty: the family cannot fit it).
  Row
  collocation_row(const unsigned int order, const double delta, const double h);

  /// The row of @p scheme (0-4).
  Row
  make_row(const unsigned int scheme, const double delta, const double h);

  // ------------------------------------------------------------------
  // Banded LU with partial pivoting (the LAPACK dgbtf2 layout in rows):
  // row i stores columns i - kl ... i + kl + ku (the kl extra upper
  // diagonals take the fill of the row interchanges).

  class BandedSystem
  {
  public:
    BandedSystem(const unsigned int n,
                 const unsigned int kl,
                 const unsigned int ku)
      : n(n)
      , kl(kl)
      , ku(ku)
      , width(2 * kl + ku + 1)
      , band(std::size_t(n) * width, 0.)
      , rhs(n, 0.)
    {}

    double &
    operator()(const unsigned int i, const unsigned int j)
    {
      return band[std::size_t(i) * width + (j + kl - i)];
    }

    double &
    b(const unsigned int i)
    {
      return rhs[i];
    }

    /// Factorises and solves in place; returns the solution and the
    /// number of row interchanges.
    std::vector<double>
    solve(unsigned int &n_swaps)
    {
      n_swaps = 0;
      for (unsigned int j = 0; j < n; ++j)
        {
          const unsigned int last = std::min(n - 1, j + kl);
          unsigned int       p    = j;
          for (unsigned int r = j + 1; r <= last; ++r)
            if (std::abs((*this)(r, j)) > std::abs((*this)(p, j)))
              p = r;
          AssertThrow((*this)(p, j) != 0.,
                      dealii::ExcMessage("singular system"));
          const unsigned int end = std::min(n - 1, j + kl + ku);
          if (p != j)
            {
              ++n_swaps;
              for (unsigned int col = j; col <= end; ++col)
                std::swap((*this)(j, col), (*this)(p, col));
              std::swap(rhs[j], rhs[p]);
            }
          const double pivot = (*this)(j, j);
          for (unsigned int r = j + 1; r <= last; ++r)
            {
              const double l = (*this)(r, j) / pivot;
              if (l == 0.)
                continue;
              for (unsigned int col = j + 1; col <= end; ++col)
                (*this)(r, col) -= l * (*this)(j, col);
              rhs[r] -= l * rhs[j];
            }
        }
      std::vector<double> x(n);
      for (unsigned int i = n; i-- > 0;)
        {
          double             s   = rhs[i];
          const unsigned int end = std::min(n - 1, i + kl + ku);
          for (unsigned int col = i + 1; col <= end; ++col)
            s -= (*this)(i, col) * x[col];
          x[i] = s / (*this)(i, i);
        }
      return x;
    }

  private:
    unsigned int        n, kl, ku, width;
    std::vector<double> band;
    std::vector<double> rhs;
  };

  // One run.

  struct Result
  {
    bool         feasible = false;
    double       h = 0, delta = 0, m = 0;
    unsigned int n_nodes = 0, n_collocation = 0, half_width = 0, n_swaps = 0;
    double       error = 0, error_pd_force = 0, wall_time = 0;
    double       condition = 0, symbol = 0, omega_half_length = 0;
  };

  using Force = std::function<double(double, double)>;

  /// Solves -L u = b on the n cells of Omega_h; the timed part of a run.
  std::vector<double>
  solve(const Row         &row,
        const unsigned int n,
        const double       h,
        const double       delta,
        const Force       &force,
        unsigned int      &n_swaps);

  /// Eq. 66 over the nodes of Omega_h.
  double
  relative_error(const std::vector<double> &u, const double h);

  /// A run of @p scheme (its definition says what it measures).
  Result
  run(const unsigned int scheme,
      const double       m,
      const double       delta,
      const unsigned int n,
      const Force       &force,
      const unsigned int repetitions,
      const bool         pd_force_too);

  /// The CSV header of both studies.
  extern const char *const csv_header;

  /// One CSV row of a run.
  void
  write_row(std::ostream &out, const unsigned int scheme, const Result &r);

  /// One line of a run on standard output.
  void
  print_row(const unsigned int scheme, const Result &r);

  /// The number of cells of Omega for spacing h: round(200 / h).
  unsigned int
  cells_in_omega(const double h);

  // The --quick checks (collocation_example1_checks.cc): each prints a line
  // per check and counts the failed ones.

  void
  check_cosine_integral();

  void
  check_body_force();

  void
  check_collocation_rows();

  void
  check_banded_solver();

  void
  check_claims(const std::vector<std::vector<Result>> &m_results,
               const std::vector<std::vector<Result>> &d_results);

  /// The number of failed checks so far.
  unsigned int
  n_failed_checks();
} // namespace Example1

#endif
