#ifndef perideal_io_crack_tip_tracker_h
#define perideal_io_crack_tip_tracker_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <perideal/discretization/node_set.h>

#include <functional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace IO
  {
    using namespace dealii;

    /**
     * Tracks a crack tip through the damage field, for crack-speed and
     * crack-path studies (branching, Kalthoff-Winkler).
     *
     * The tip is the damaged node (damage at least 'Crack tip damage')
     * farthest from 'Crack tip origin', among the nodes inside 'Crack tip
     * region' if one is given; R is its distance from the origin. The
     * front spread is the largest distance of a damaged node of the front
     * (distance from the origin at least R minus one horizon) from the
     * straight line through the origin and the tip: about half the width
     * of the damage band for a single straight crack, and growing linearly
     * once the crack has branched.
     *
     * Ties are broken by the lowest coordinates, so the answer does not
     * depend on the partition. Without a damaged node the tip is the
     * origin.
     */
    template <int dim>
    class CrackTipTracker
    {
    public:
      /// Declare the entries in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Read them; @p section names the subsection in error messages.
      void
      parse_parameters(ParameterHandler &prm, const std::string &section);

      /// Whether an origin was given.
      bool
      enabled() const
      {
        return active;
      }

      /**
       * Check, once the nodes exist, that the origin lies on the body and
       * that every box of the region holds a node: otherwise the tracker
       * would measure from a point off the body or count no node of a box.
       * Errors name the entry in @p section. Collective.
       */
      void
      check_on_body(const Discretization::NodeSet<dim> &nodes,
                    const std::string                  &section) const;

      /// tip_x, tip_y[, tip_z], tip_distance, front_spread.
      std::vector<std::string>
      column_names() const;

      /**
       * The values of the columns for the damage @p damage of the owned
       * nodes (index i < nodes.n_owned()). Collective.
       */
      std::vector<double>
      evaluate(const Discretization::NodeSet<dim>        &nodes,
               const std::function<double(unsigned int)> &damage,
               const double                               front_band,
               const MPI_Comm                             comm) const;

    private:
      bool                          active = false;
      Point<dim>                    origin;
      std::vector<BoundingBox<dim>> region;
      double                        threshold = 0.35;
      std::string                   origin_text, region_text;
    };
  } // namespace IO
} // namespace PeriDEAL

#endif
