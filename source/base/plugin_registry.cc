#include <perideal/base/plugin_registry.h>

namespace PeriDEAL
{
  namespace internal
  {
    RegistrationErrors &
    registration_errors()
    {
      // A function-local static: registrations run during static
      // initialisation, in any order of the translation units.
      static RegistrationErrors errors;
      return errors;
    }
  } // namespace internal
} // namespace PeriDEAL
