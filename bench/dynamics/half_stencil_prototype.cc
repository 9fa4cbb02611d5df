// Prototype for issue 10 (not used by the library): how much a bond-based
// kernel gains from Newton's third law on the uniform stencil.
//
// Both loops evaluate the finite-deformation PMB force with a failure test
// (3D, a horizon of 3.5 cells, the cells whose centres lie within it: 178
// offsets) on an N^3 box of slots with a margin of ghost slots, one thread:
//   gather:  every node visits all offsets and sums its own force (what
//            BondOperator does today);
//   half:    every node visits the offsets with a positive slot offset, and
//            the bond force goes to both ends (two contiguous, vectorised
//            updates per offset: f[i] += t, f[i + o] -= t).
// Checks (exit code 1 on failure): the two forces agree at every node at
// least one reach from the box faces to 1e-14 of the largest force (near
// the faces the half loop lacks the bonds from the margin, which a real
// kernel would take from the ghosts' side). Prints both rates in bond
// visits per second (a bond counted from both ends, as LAMMPS and
// BondOperator count) and writes them as CSV.
//
//   perideal-half-stencil-prototype [--n N] [--repetitions R] [--csv FILE]
//
// The bond expression is written out in both loops on purpose: moved into a
// shared inline function (with the components written out, the offset
// copied), GCC 12 no longer vectorised the lanes ("control flow in loop")
// and both loops ran at about 220 M/s instead of 560. y = xi + (u_j - u_i),
// bracketed as in BondOperator, is exactly antisymmetric, so a bond seen
// from either end has the same length and the same failure decision, and
// the two loops differ by summation order only.
//
// Threads would need a scatter without conflicts (slabs of planes at least
// one reach apart, in two colours); that is not tried here.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int
main(int argc, char **argv)
{
  int         n           = 64;
  int         repetitions = 3;
  std::string csv;
  for (int a = 1; a + 1 < argc; a += 2)
    {
      const std::string key = argv[a];
      if (key == "--n")
        n = std::atoi(argv[a + 1]);
      else if (key == "--repetitions")
        repetitions = std::atoi(argv[a + 1]);
      else if (key == "--csv")
        csv = argv[a + 1];
      else
        {
          std::fprintf(stderr, "unknown option %s\n", argv[a]);
          return 2;
        }
    }
  const int reach = 4; // ceil(3.5)
  if (n < 2 * reach + 1 || n > 256 || repetitions < 1)
    {
      std::fprintf(stderr, "--n must be in [9, 256], --repetitions >= 1\n");
      return 2;
    }
  const long side    = n + 2 * reach;
  const long n_slots = side * side * side;
  const auto slot    = [&](const int x, const int y, const int z) {
    return (x + reach) + side * ((y + reach) + side * (z + reach));
  };

  // The stencil: offsets, slot offsets, lengths, micromodulus times volume.
  std::vector<long>   offset;
  std::vector<double> r, b, xi[3];
  for (int z = -reach; z <= reach; ++z)
    for (int y = -reach; y <= reach; ++y)
      for (int x = -reach; x <= reach; ++x)
        {
          const double length = std::sqrt(double(x * x + y * y + z * z));
          if (length == 0 || length > 3.5)
            continue;
          offset.push_back(x + side * (y + side * z));
          r.push_back(length);
          b.push_back(1.0 / length);
          xi[0].push_back(x);
          xi[1].push_back(y);
          xi[2].push_back(z);
        }
  std::vector<std::size_t> half;
  for (std::size_t k = 0; k < offset.size(); ++k)
    if (offset[k] > 0)
      half.push_back(k);

  std::vector<double> u[3], f[3], gathered[3], critical(n_slots, 0.5);
  for (int d = 0; d < 3; ++d)
    {
      u[d].resize(n_slots);
      f[d].assign(n_slots, 0.);
      for (long s = 0; s < n_slots; ++s)
        u[d][s] = 1e-4 * std::sin(1e-3 * s + d);
    }
  // Some bonds fail: a low critical stretch in one corner.
  for (long s = 0; s < n_slots / 8; ++s)
    critical[s] = 1e-5;
  const double visits = double(n) * n * n * offset.size();

  using Clock                        = std::chrono::steady_clock;
  double              gather_seconds = 1e300, half_seconds = 1e300;
  std::vector<double> line[3];
  for (int rep = 0; rep < repetitions; ++rep)
    {
      const auto start = Clock::now();
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          {
            const long s0 = slot(0, y, z);
            for (int d = 0; d < 3; ++d)
              line[d].assign(n, 0.);
            double *l0 = line[0].data(), *l1 = line[1].data(),
                   *l2 = line[2].data();
            for (std::size_t k = 0; k < offset.size(); ++k)
              {
                const long    o  = offset[k];
                const double  rk = r[k], bk = b[k], inv_r = 1 / rk;
                const double  x0 = xi[0][k], x1 = xi[1][k], x2 = xi[2][k];
                const double *u0 = &u[0][s0], *u1 = &u[1][s0], *u2 = &u[2][s0];
                const double *c = &critical[s0];
#pragma omp simd
                for (int l = 0; l < n; ++l)
                  {
                    const double y0 = x0 + (u0[l + o] - u0[l]);
                    const double y1 = x1 + (u1[l + o] - u1[l]);
                    const double y2 = x2 + (u2[l + o] - u2[l]);
                    const double length =
                      std::sqrt(y0 * y0 + y1 * y1 + y2 * y2);
                    const double e      = length - rk;
                    const bool   intact = e * inv_r < std::min(c[l], c[l + o]);
                    const double t      = intact ? 2 * bk * e / length : 0.;
                    l0[l] += t * y0;
                    l1[l] += t * y1;
                    l2[l] += t * y2;
                  }
              }
            for (int d = 0; d < 3; ++d)
              std::copy(line[d].begin(), line[d].end(), f[d].begin() + s0);
          }
      gather_seconds =
        std::min(gather_seconds,
                 std::chrono::duration<double>(Clock::now() - start).count());
    }
  for (int d = 0; d < 3; ++d)
    gathered[d] = f[d];

  std::vector<double> t[3];
  for (int d = 0; d < 3; ++d)
    t[d].resize(n);
  for (int rep = 0; rep < repetitions; ++rep)
    {
      const auto start = Clock::now();
      for (int d = 0; d < 3; ++d)
        std::fill(f[d].begin(), f[d].end(), 0.);
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          {
            const long s0 = slot(0, y, z);
            double    *t0 = t[0].data(), *t1 = t[1].data(), *t2 = t[2].data();
            double    *f0 = &f[0][s0], *f1 = &f[1][s0], *f2 = &f[2][s0];
            for (const std::size_t k : half)
              {
                const long    o  = offset[k];
                const double  rk = r[k], bk = b[k], inv_r = 1 / rk;
                const double  x0 = xi[0][k], x1 = xi[1][k], x2 = xi[2][k];
                const double *u0 = &u[0][s0], *u1 = &u[1][s0], *u2 = &u[2][s0];
                const double *c = &critical[s0];
#pragma omp simd
                for (int l = 0; l < n; ++l)
                  {
                    const double y0 = x0 + (u0[l + o] - u0[l]);
                    const double y1 = x1 + (u1[l + o] - u1[l]);
                    const double y2 = x2 + (u2[l + o] - u2[l]);
                    const double length =
                      std::sqrt(y0 * y0 + y1 * y1 + y2 * y2);
                    const double e      = length - rk;
                    const bool   intact = e * inv_r < std::min(c[l], c[l + o]);
                    const double tl     = intact ? 2 * bk * e / length : 0.;
                    t0[l]               = tl * y0;
                    t1[l]               = tl * y1;
                    t2[l]               = tl * y2;
                  }
#pragma omp simd
                for (int l = 0; l < n; ++l)
                  {
                    f0[l] += t0[l];
                    f1[l] += t1[l];
                    f2[l] += t2[l];
                  }
#pragma omp simd
                for (int l = 0; l < n; ++l)
                  {
                    f0[l + o] -= t0[l];
                    f1[l + o] -= t1[l];
                    f2[l + o] -= t2[l];
                  }
              }
          }
      half_seconds =
        std::min(half_seconds,
                 std::chrono::duration<double>(Clock::now() - start).count());
    }

  double largest = 0, difference = 0;
  for (int z = reach; z < n - reach; ++z)
    for (int y = reach; y < n - reach; ++y)
      for (int x = reach; x < n - reach; ++x)
        for (int d = 0; d < 3; ++d)
          {
            const long s = slot(x, y, z);
            largest      = std::max(largest, std::abs(gathered[d][s]));
            difference =
              std::max(difference, std::abs(gathered[d][s] - f[d][s]));
          }
  const double gather_rate = visits / gather_seconds / 1e6;
  const double half_rate   = visits / half_seconds / 1e6;
  std::printf("N = %d, %zu offsets (%zu in the half stencil), %.0f bond "
              "visits per pass, best of %d\n",
              n,
              offset.size(),
              half.size(),
              visits,
              repetitions);
  std::printf("gather: %.4f s, %.0f M bond visits/s\n",
              gather_seconds,
              gather_rate);
  std::printf("half stencil: %.4f s, %.0f M bond visits/s (%.2fx)\n",
              half_seconds,
              half_rate,
              gather_seconds / half_seconds);
  std::printf("interior: largest |f_gather - f_half| = %.3e, largest |f| = "
              "%.3e\n",
              difference,
              largest);
  if (!csv.empty())
    {
      FILE *out = std::fopen(csv.c_str(), "w");
      if (out == nullptr)
        {
          std::fprintf(stderr, "cannot write %s\n", csv.c_str());
          return 1;
        }
      std::fprintf(out,
                   "n,offsets,visits,gather_s,gather_M_per_s,half_s,"
                   "half_M_per_s,speedup,interior_difference,largest_force\n"
                   "%d,%zu,%.0f,%.6g,%.6g,%.6g,%.6g,%.4g,%.3e,%.3e\n",
                   n,
                   offset.size(),
                   visits,
                   gather_seconds,
                   gather_rate,
                   half_seconds,
                   half_rate,
                   gather_seconds / half_seconds,
                   difference,
                   largest);
      std::fclose(out);
    }
  if (!(largest > 0) || !(difference <= 1e-14 * largest))
    {
      std::printf("FAIL: the two loops disagree in the interior\n");
      return 1;
    }
  return 0;
}
