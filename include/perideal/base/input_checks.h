#ifndef perideal_base_input_checks_h
#define perideal_base_input_checks_h

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <utility>
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


  /**
   * An entry, or a whole subsection, that has no effect on a run as it is
   * configured: a value the user gives there would be ignored silently.
   */
  struct UnusedEntry
  {
    /**
     * The entry's path 'Subsection/Name'; a path that ends in '/' stands
     * for every entry of that subsection (nested ones included), and a
     * component '*' for any one subsection name.
     */
    std::string pattern;
    /// Why it has no effect and what to do, for the error message.
    std::string why;
  };


  /**
   * The entries of @p prm whose value differs from the one in @p defaults
   * (the same declarations, nothing parsed), as pairs of 'Subsection/Name'
   * and value. Values are compared without white space, and numerically
   * where both are numbers ("1e-2" equals "0.01"): an entry set to its
   * default is as good as one left out.
   */
  std::vector<std::pair<std::string, std::string>>
  changed_entries(const dealii::ParameterHandler &prm,
                  const dealii::ParameterHandler &defaults);


  /**
   * Throw ExcInvalidInput for the first entry of @p changed (see
   * changed_entries()) that matches one of @p unused: the message names the
   * entry, its value and the rule's reason.
   */
  void
  check_unused_entries(
    const std::vector<std::pair<std::string, std::string>> &changed,
    const std::vector<UnusedEntry>                         &unused);


  /**
   * Whether the muparser @p expression refers to the variable @p name (as a
   * whole identifier, not inside a longer name or a number such as "1e5").
   */
  bool
  expression_uses_variable(const std::string &expression,
                           const std::string &name);
} // namespace PeriDEAL

#endif
