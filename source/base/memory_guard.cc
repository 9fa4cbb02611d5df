/**
 * @file
 * The memory guard of include/perideal/base/memory_guard.h: the one reader
 * of /proc/meminfo, the share of each process on a host, and the margin an
 * estimate must leave.
 */

#include <perideal/base/memory_guard.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace PeriDEAL
{
  double
  host_available_memory()
  {
    // One line at a time: some lines have no unit ("HugePages_Total: 0"),
    // so reading "key value unit" triples would lose step after them.
    std::ifstream meminfo("/proc/meminfo");
    std::string   line;
    while (std::getline(meminfo, line))
      {
        std::istringstream fields(line);
        std::string        key;
        double             kb = 0;
        if (fields >> key >> kb && key == "MemAvailable:")
          return kb * 1024;
      }
    return 0;
  }


  double
  available_memory_per_process(const MPI_Comm communicator)
  {
    const double available = host_available_memory();
    MPI_Comm     host;
    MPI_Comm_split_type(communicator,
                        MPI_COMM_TYPE_SHARED,
                        0,
                        MPI_INFO_NULL,
                        &host);
    const unsigned int on_host = dealii::Utilities::MPI::n_mpi_processes(host);
    MPI_Comm_free(&host);
    return available / on_host;
  }


  double
  capped_available_memory_mb_per_process(const MPI_Comm communicator)
  {
    double available = available_memory_per_process(communicator) / 1048576.;
    if (const char *limit = std::getenv("PERIDEAL_MEMORY_LIMIT_MB"))
      {
        const double cap = std::atof(limit);
        if (cap > 0 && (available <= 0 || cap < available))
          available = cap;
      }
    return available;
  }


  bool
  fits_in_memory(const double needed, const double available)
  {
    return available <= 0 || needed <= 0.9 * available;
  }
} // namespace PeriDEAL
