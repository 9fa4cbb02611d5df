#ifndef perideal_base_shared_libraries_h
#define perideal_base_shared_libraries_h

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  /**
   * Declare the top-level entry "Additional shared libraries": a list of
   * shared libraries with a user's own plugins (material models, influence
   * functions, problem types, ...), loaded before the parameters are
   * declared, as in ASPECT. The full declaration (Simulator::
   * declare_parameters()) declares it too, so that a file that sets it is
   * accepted by the full parse.
   */
  void
  declare_shared_library_parameters(dealii::ParameterHandler &prm);

  /**
   * The libraries named by "Additional shared libraries" in the parameter
   * file @p parameter_file, read in a first pass that skips every other
   * entry. The file must parse (ParameterHandler's syntax errors are thrown
   * as they are).
   */
  std::vector<std::string>
  read_shared_library_names(const std::string &parameter_file);

  /**
   * Load the shared libraries @p names with dlopen(RTLD_NOW | RTLD_GLOBAL)
   * on every process of @p comm, in order. Loading runs the libraries'
   * static initialisers, which is when their PERIDEAL_REGISTER_* objects
   * add their plugins to the registries: call it before any parameter is
   * declared, so that the plugins' names appear in the selection patterns
   * and their own parameters are declared.
   *
   * A library that cannot be loaded (no such file, unresolved symbols, a
   * plugin name registered twice) is an ExcInvalidInput naming the entry,
   * the library and dlerror()'s reason, thrown on every process if it
   * happened on any (throw_on_any_rank()): no process is left waiting.
   * Libraries stay loaded until the program ends.
   */
  void
  load_shared_libraries(const std::vector<std::string> &names,
                        const MPI_Comm                  comm);

  /**
   * read_shared_library_names() and load_shared_libraries() in one call:
   * what a driver does first with a parameter file.
   */
  void
  load_shared_libraries(const std::string &parameter_file,
                        const MPI_Comm     comm);
} // namespace PeriDEAL

#endif
