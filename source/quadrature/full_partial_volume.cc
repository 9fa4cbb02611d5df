#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/full_partial_volume.h>

#include <string>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    double
    FullPartialVolume<dim>::weight(const Point<dim>       &node,
                                   const double            horizon,
                                   const BoundingBox<dim> &cell) const
    {
      AssertThrow(horizon > 0,
                  ExcInvalidInput("horizon",
                                  format_number(horizon),
                                  "give a horizon > 0"));
      // Compare squares: on a uniform grid both sides are exact for
      // integer offsets and integer or half-integer horizons.
      return node.distance_square(cell.center()) <= horizon * horizon ? 1. : 0.;
    }


    template <int dim>
    void
    FullPartialVolume<dim>::declare_parameters(ParameterHandler &)
    {}


    template class FullPartialVolume<1>;
    template class FullPartialVolume<2>;
    template class FullPartialVolume<3>;
  } // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::FullPartialVolume,
  1,
  "full",
  "Whole cell if its centre lies within the horizon, else nothing.")
PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::FullPartialVolume,
  2,
  "full",
  "Whole cell if its centre lies in the closed horizon disc, else nothing.")
PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::FullPartialVolume,
  3,
  "full",
  "Whole cell if its centre lies in the closed horizon ball, else nothing.")
