#ifndef perideal_problems_explicit_dynamics_internal_h
#define perideal_problems_explicit_dynamics_internal_h

/**
 * @file
 * What the source files of the explicit dynamics problem type
 * (Problems::ExplicitDynamics) share besides the class: the format of
 * numbers in their messages and the explicit instantiation of the members
 * each defines. Not part of the library's interface.
 */


#include <perideal/problems/simulator.h>

#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace internal
    {
      namespace ExplicitDynamicsImplementation
      {
        /// @p x with 6 significant digits, for messages.
        inline std::string
        to_string(const double x)
        {
          std::ostringstream s;
          s << std::setprecision(6) << x;
          return s.str();
        }
      } // namespace ExplicitDynamicsImplementation
    }   // namespace internal
  }     // namespace Problems
} // namespace PeriDEAL

/**
 * Instantiate the member function @p name of ExplicitDynamics that takes
 * the simulator and returns @p type, in 2D and 3D; @p qualifier is the
 * member's qualifier (`const`) or empty.
 */
#define PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(type, name, qualifier) \
  template type ExplicitDynamics<2>::name(Simulator<2> &) qualifier;  \
  template type ExplicitDynamics<3>::name(Simulator<3> &) qualifier;

#endif
