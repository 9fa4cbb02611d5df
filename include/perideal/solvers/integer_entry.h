#ifndef perideal_solvers_integer_entry_h
#define perideal_solvers_integer_entry_h

#include <deal.II/base/parameter_handler.h>

#include <string>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * An integer entry of a plugin's subsection: its name, default, range
     * [min, max] and help text.
     */
    struct IntegerEntry
    {
      const char *name;
      int         default_value;
      int         min;
      int         max;
      const char *help;
    };

    /**
     * A plugin @p Base (a Preconditioner, or a class derived from one) with
     * one integer parameter, @p entry: declares it, reads it, and holds its
     * value in integer_parameter (the default until parse_parameters() is
     * called).
     */
    template <typename Base, const IntegerEntry &entry>
    class WithIntegerEntry : public Base
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry(entry.name,
                          std::to_string(entry.default_value),
                          Patterns::Integer(entry.min, entry.max),
                          entry.help);
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        integer_parameter = prm.get_integer(entry.name);
      }

    protected:
      unsigned int integer_parameter = entry.default_value;
    };
  } // namespace Solvers
} // namespace PeriDEAL

#endif
