#ifndef perideal_base_memory_guard_h
#define perideal_base_memory_guard_h

/**
 * @file
 * The memory guard: how much memory a process may use (the one reader of
 * /proc/meminfo), and whether an estimate fits into it. Checks that refuse
 * a run before it allocates what the machine does not have use these.
 */

#include <deal.II/base/mpi.h>

namespace PeriDEAL
{
  /**
   * MemAvailable of this host from /proc/meminfo, in bytes; 0 where the
   * file is missing or has no such line (then no guard applies).
   */
  double
  host_available_memory();

  /**
   * The memory available to one process of @p communicator, in bytes:
   * host_available_memory() shared equally among the processes of
   * @p communicator on the same host (0 where unknown). Collective.
   */
  double
  available_memory_per_process(const MPI_Comm communicator);

  /**
   * available_memory_per_process() in MB, capped by the environment
   * variable PERIDEAL_MEMORY_LIMIT_MB (MB per process) where it is set,
   * positive and smaller: a cap for shared machines. Collective.
   */
  double
  capped_available_memory_mb_per_process(const MPI_Comm communicator);

  /**
   * Whether an estimate of @p needed fits into @p available (both in the
   * same unit), with a margin of 10 %: true where @p available is not
   * known (zero or negative).
   */
  bool
  fits_in_memory(const double needed, const double available);
} // namespace PeriDEAL

#endif
