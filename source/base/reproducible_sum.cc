#include <deal.II/base/mpi.h>

#include <perideal/base/reproducible_sum.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace PeriDEAL
{
  namespace
  {
    // GCC's 128-bit integers (not ISO C++, hence __extension__).
    __extension__ using int128  = __int128;
    __extension__ using uint128 = unsigned __int128;
  } // namespace


  double
  reproducible_sum(const double *terms, const std::size_t n, MPI_Comm comm)
  {
    double largest = 0;
    bool   finite  = true;
    for (std::size_t k = 0; k < n; ++k)
      {
        finite  = finite && std::isfinite(terms[k]);
        largest = std::max(largest, std::abs(terms[k]));
      }
    if (Utilities::MPI::min(finite ? 1 : 0, comm) == 0)
      return std::numeric_limits<double>::quiet_NaN();
    largest = Utilities::MPI::max(largest, comm);
    if (largest == 0)
      return 0;
    int exponent;
    std::frexp(largest, &exponent); // largest < 2^exponent
    const double scale = std::ldexp(1., 62 - exponent);
    int128       local = 0;
    for (std::size_t k = 0; k < n; ++k)
      local += static_cast<int128>(std::llrint(terms[k] * scale));
    // Integer addition is associative: gather the 128-bit partial sums as
    // two 64-bit halves and add them on every process.
    const auto                 bits      = static_cast<uint128>(local);
    const std::uint64_t        halves[2] = {static_cast<std::uint64_t>(bits),
                                            static_cast<std::uint64_t>(bits >> 64)};
    const unsigned int         n_procs = Utilities::MPI::n_mpi_processes(comm);
    std::vector<std::uint64_t> all(2 * n_procs);
    const int                  ierr =
      MPI_Allgather(halves, 2, MPI_UINT64_T, all.data(), 2, MPI_UINT64_T, comm);
    AssertThrowMPI(ierr);
    uint128 total = 0;
    for (unsigned int p = 0; p < n_procs; ++p)
      total += (static_cast<uint128>(all[2 * p + 1]) << 64) |
               static_cast<uint128>(all[2 * p]);
    return std::ldexp(static_cast<double>(static_cast<int128>(total)),
                      exponent - 62);
  }
} // namespace PeriDEAL
