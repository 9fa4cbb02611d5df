#ifndef perideal_base_collective_checks_h
#define perideal_base_collective_checks_h

#include <deal.II/base/mpi.h>

#include <functional>
#include <ostream>
#include <sstream>
#include <string>

namespace PeriDEAL
{
  /**
   * Checks that may fail on some processes only, made safe for the others:
   * every process takes part, and if any failed, every process throws the
   * same error (the message of the lowest failing rank). Without this a
   * process that throws leaves the others waiting in the next collective
   * call forever.
   *
   * @p local_error is empty where the check passed.
   */
  void
  throw_on_any_rank(const std::string &local_error, const MPI_Comm comm);

  /**
   * Run @p check on every process, catch what it throws, and throw on all
   * processes if it threw on any (throw_on_any_rank()).
   */
  template <typename Function>
  void
  check_on_all_ranks(const Function &check, const MPI_Comm comm)
  {
    std::string error;
    try
      {
        check();
      }
    catch (const dealii::ExceptionBase &exc)
      {
        std::ostringstream info;
        exc.print_info(info);
        error = info.str();
      }
    catch (const std::exception &exc)
      {
        error = exc.what();
      }
    throw_on_any_rank(error, comm);
  }

  /**
   * Whether the file @p path can be written by this process: its
   * directory exists and is writable or can be created, and the path is
   * not a directory or a read-only file. Creates nothing. Returns an empty
   * string, or what is wrong.
   */
  std::string
  check_writable_file(const std::string &path);

  /**
   * Whether the directory @p path exists and is writable, or can be
   * created (its nearest existing ancestor is a writable directory).
   * Creates nothing. Returns an empty string, or what is wrong.
   */
  std::string
  check_writable_directory(const std::string &path);

  /**
   * Write the file @p path through @p write under the temporary name
   * "<path>.tmp" and rename it into place when complete: a run killed while
   * writing leaves the previous file intact, never a truncated one. Creates
   * the parent directory if missing. Throws nothing: returns an empty
   * string, or what went wrong (for throw_on_any_rank()).
   */
  std::string
  write_then_rename(const std::string                         &path,
                    const std::function<void(std::ostream &)> &write);
} // namespace PeriDEAL

#endif
