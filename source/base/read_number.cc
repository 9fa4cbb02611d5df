#include <perideal/base/read_number.h>

namespace PeriDEAL
{
  bool
  read_number(const std::string &text, double &value)
  {
    std::size_t used   = 0;
    double      number = 0;
    try
      {
        number = std::stod(text, &used);
      }
    catch (...)
      {
        return false;
      }
    if (used != text.size())
      return false;
    value = number;
    return true;
  }
} // namespace PeriDEAL
