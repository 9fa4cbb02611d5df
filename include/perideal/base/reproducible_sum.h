#ifndef perideal_base_reproducible_sum_h
#define perideal_base_reproducible_sum_h

#include <deal.II/base/mpi.h>

#include <cstddef>

namespace PeriDEAL
{
  using namespace dealii;

  /**
   * The sum of @p n terms on each process of @p comm, the same to the last
   * bit however the terms are spread over processes and in whatever order
   * they come: each term is rounded to an integer multiple of \f$2^{e -
   * 62}\f$ (\f$2^e\f$ above the largest |term| of all processes, a
   * reduction that does not depend on order), the integers are summed
   * exactly in 128 bits, and the total is converted back once. The result
   * is within \f$n_{\rm total}\,2^{e - 63}\f$ of the exact sum (a relative
   * 1e-19 per term of the largest), against the round-off of an ordinary
   * sum that depends on the partition. Up to \f$2^{64}\f$ terms. A
   * non-finite term makes the result NaN on every process. Collective.
   */
  double
  reproducible_sum(const double *terms, const std::size_t n, MPI_Comm comm);
} // namespace PeriDEAL

#endif
