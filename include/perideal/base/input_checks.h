#ifndef perideal_base_input_checks_h
#define perideal_base_input_checks_h

#include <string>
#include <vector>

namespace PeriDEAL
{
  /// An entry that a parameter file sets: its subsection path and name.
  struct InputEntry
  {
    std::vector<std::string> path;
    unsigned int             line = 0;

    /// "Subsection/Subsection/Name".
    std::string
    name() const;
  };

  /**
   * The entries that the parameter file @p file sets, in order. Makes the
   * checks that deal.II's ParameterHandler does not, since it keeps the
   * last value of an entry: an entry set twice is an error (naming both
   * lines), and so is a file that sets no entry (it would silently run the
   * default problem). Call it after ParameterHandler has parsed the file,
   * so that its syntax is known to be valid.
   */
  std::vector<InputEntry>
  scan_input_file(const std::string &file);
} // namespace PeriDEAL

#endif
