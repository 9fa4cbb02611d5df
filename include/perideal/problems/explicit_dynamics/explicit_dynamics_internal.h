#ifndef perideal_problems_explicit_dynamics_internal_h
#define perideal_problems_explicit_dynamics_internal_h

/**
 * @file
 * What the source files of the explicit dynamics problem type
 * (Problems::ExplicitDynamics) share besides the class: the format of
 * numbers in their messages and the explicit instantiation of the members
 * each defines. Not part of the library's interface.
 */

#include <deal.II/base/bounding_box.h>

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

        /**
         * A region of nodes given in the input as boxes and as layers along
         * boundary ids (the no-fail region, the standard region of the
         * hybrid scheme), with the entries that give it, for messages.
         */
        template <int dim>
        struct NodeRegion
        {
          const std::vector<BoundingBox<dim>> &boxes;
          std::string boxes_entry, boxes_text, boxes_purpose;
          const std::vector<types::boundary_id> &ids;
          std::string                            ids_entry, ids_text;
          /// The layer thickness in horizons.
          double      thickness;
          std::string thickness_entry, thickness_text, layer_purpose;
        };

        /**
         * Which nodes (owned and ghost) of the simulator lie in @p region.
         * Every box and every layer must hold a node centre, and every id
         * must occur in the mesh; otherwise all processes throw an error
         * naming the entry. Collective.
         */
        template <int dim>
        std::vector<bool>
        nodes_in_region(const Simulator<dim>  &simulator,
                        const NodeRegion<dim> &region);
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
