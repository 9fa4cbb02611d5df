#ifndef perideal_base_exceptions_h
#define perideal_base_exceptions_h

#include <deal.II/base/exceptions.h>

#include <iomanip>
#include <sstream>
#include <string>

namespace PeriDEAL
{
  /**
   * An input value a user gave (in a parameter file or on the command line)
   * that PeriDEAL cannot use. The message names the parameter, the value that
   * was given, and what to do instead, e.g.
   * @code
   *   AssertThrow(m_ratio > 0,
   *               ExcInvalidInput("m-ratio", std::to_string(m_ratio),
   *                               "give a horizon-to-spacing ratio > 0"));
   * @endcode
   */
  DeclException3(ExcInvalidInput,
                 std::string,
                 std::string,
                 std::string,
                 << "Invalid value '" << arg2 << "' for the parameter '" << arg1
                 << "': " << arg3 << '.');

  /**
   * A number for a message: up to 10 significant digits, no trailing
   * zeros ("0.03", not "0.030000"; "3.0001", not "3").
   */
  inline std::string
  format_number(const double value)
  {
    std::ostringstream s;
    s << std::setprecision(10) << value;
    return s.str();
  }

  /**
   * A linear solve that did not reach its tolerance (the message says
   * which, with the residual and a fix). Its own type, so that a caller
   * that can retry (a load step that is cut) catches this and nothing
   * else.
   */
  DeclException1(ExcNoConvergence, std::string, << arg1);

  /**
   * A name (of a model, algorithm, boundary treatment, ...) that is not
   * registered. @p arg3 lists the registered names.
   */
  DeclException3(ExcUnknownName,
                 std::string,
                 std::string,
                 std::string,
                 << "Unknown " << arg1 << " '" << arg2
                 << "'. Registered names are: " << arg3 << '.');
} // namespace PeriDEAL

#endif
