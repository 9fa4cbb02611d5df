// Kind of test: exact references and partition invariance.
//
// reproducible_sum() (include/perideal/base/reproducible_sum.h) must
//  (a) return the correctly rounded exact sum when the terms are multiples
//      of its rounding unit: 100000 terms n_k 2^-30 with random 52-bit n_k of
//      both signs, against the sum of the integers n_k in 128 bits;
//  (b) return the same bits however the terms are spread over the processes
//      (contiguous blocks and every other term; the test runs on 1 and 2
//      processes with one expected output);
//  (c) keep a 1 that cancellation (1e16 + 1 - 1e16) loses in an ordinary
//      sum, give 0 for no or zero terms, and NaN on every process for a
//      non-finite term on one of them.

#include <deal.II/base/mpi.h>

#include <perideal/base/reproducible_sum.h>

#include <cmath>
#include <cstdint>
#include <iostream>
#include <vector>

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int rank   = Utilities::MPI::this_mpi_process(comm);
  const unsigned int nprocs = Utilities::MPI::n_mpi_processes(comm);

  const unsigned int        n = 100000;
  std::vector<std::int64_t> integers(n);
  std::uint64_t             state = 12345;
  __extension__ __int128    exact = 0;
  for (unsigned int k = 0; k < n; ++k)
    {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      const std::int64_t magnitude = static_cast<std::int64_t>(state >> 12);
      integers[k]                  = (state >> 11) & 1 ? magnitude : -magnitude;
      exact += integers[k];
    }
  const double expected =
    std::ldexp(static_cast<double>(exact), -30); // correctly rounded

  bool all_equal = true;
  for (const bool interleaved : {false, true})
    {
      std::vector<double> mine;
      for (unsigned int k = 0; k < n; ++k)
        if (interleaved ? k % nprocs == rank : k * nprocs / n == rank)
          mine.push_back(std::ldexp(static_cast<double>(integers[k]), -30));
      const double sum =
        PeriDEAL::reproducible_sum(mine.data(), mine.size(), comm);
      all_equal = all_equal && sum == expected;
    }
  if (rank == 0)
    std::cout << "(a, b) 100000 terms, blocks and interleaved: equal to the "
                 "correctly rounded exact sum: "
              << (all_equal ? "yes" : "NO") << std::endl;

  // (c)
  std::vector<double> cancel;
  if (rank == 0)
    cancel = {1e16, 1., -1e16};
  const double one =
    PeriDEAL::reproducible_sum(cancel.data(), cancel.size(), comm);
  std::vector<double> zeros(rank == 0 ? 3 : 0, 0.);
  const double        zero =
    PeriDEAL::reproducible_sum(zeros.data(), zeros.size(), comm);
  std::vector<double> with_nan = {1., 2.};
  if (rank == nprocs - 1)
    with_nan.push_back(std::nan(""));
  const double nan =
    PeriDEAL::reproducible_sum(with_nan.data(), with_nan.size(), comm);
  const bool nan_everywhere =
    Utilities::MPI::min(std::isnan(nan) ? 1 : 0, comm) == 1;
  if (rank == 0)
    std::cout << "(c) 1e16 + 1 - 1e16 = " << one << " (ordinary sum "
              << (1e16 + 1.) - 1e16 << "); zeros: " << zero
              << "; a NaN on the last process gives NaN on all: "
              << (nan_everywhere ? "yes" : "NO") << std::endl;
}
