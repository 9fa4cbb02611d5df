#ifndef perideal_quadrature_centre_distance_partial_volume_h
#define perideal_quadrature_centre_distance_partial_volume_h

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/partial_volume_registration.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    /**
     * A partial-volume rule that sees a neighbour's cell only through the
     * squared distance from the node to the cell's centre and the cell's
     * measure: \f$\beta = \text{rule}(\|\mathbf x_C - \mathbf x_i\|^2, |C|,
     * \delta)\f$. The distance-based rules ("full", "approximate",
     * "lammps") differ only in @p rule; this class holds what they share,
     * the check of the horizon and the interface.
     *
     * @tparam rule The coefficient \f$\beta\in[0,1]\f$ from the squared
     * centre distance, the cell's measure and the horizon \f$\delta > 0\f$,
     * all in the unit of the points.
     */
    template <int dim, double (*rule)(double, double, double)>
    class CentreDistancePartialVolume : public PartialVolume<dim>
    {
    public:
      /**
       * @param[in] node The node's position.
       * @param[in] horizon The horizon \f$\delta > 0\f$, in the unit of the
       * points.
       * @param[in] cell The neighbour's cell.
       * @return \f$\beta\in[0,1]\f$ given by @p rule.
       */
      double
      weight(const Point<dim>       &node,
             const double            horizon,
             const BoundingBox<dim> &cell) const override
      {
        AssertThrow(horizon > 0,
                    ExcInvalidInput("horizon",
                                    format_number(horizon),
                                    "give a horizon > 0"));
        return rule(node.distance_square(cell.center()),
                    cell.volume(),
                    horizon);
      }

      /// No parameters.
      static void
      declare_parameters(ParameterHandler &)
      {}
    };
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
