#ifndef perideal_base_read_number_h
#define perideal_base_read_number_h

#include <string>

namespace PeriDEAL
{
  /**
   * Read all of @p text as one number, as std::stod() reads it (leading
   * white space allowed, nothing after the number).
   * @return true, with the number in @p value, if @p text is a number and
   * nothing else (an out-of-range number is not); false otherwise, and
   * @p value is left alone.
   */
  bool
  read_number(const std::string &text, double &value);
} // namespace PeriDEAL

#endif
