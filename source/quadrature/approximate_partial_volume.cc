#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/quadrature/approximate_partial_volume.h>

#include <cmath>
#include <string>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    double
    ApproximatePartialVolume<dim>::weight(const Point<dim>       &node,
                                          const double            horizon,
                                          const BoundingBox<dim> &cell) const
    {
      AssertThrow(horizon > 0,
                  ExcInvalidInput("horizon",
                                  format_number(horizon),
                                  "give a horizon > 0"));
      const double measure = cell.volume();
      if (measure <= 0)
        return 0;
      const double h  = std::pow(measure, 1. / dim);
      const double xi = node.distance(cell.center());
      if (xi + 0.5 * h <= horizon)
        return 1;
      else if (xi - 0.5 * h < horizon)
        return (horizon - (xi - 0.5 * h)) / h;
      else
        return 0;
    }


    template <int dim>
    void
    ApproximatePartialVolume<dim>::declare_parameters(ParameterHandler &)
    {}


    template <int dim>
    double
    LammpsPartialVolume<dim>::weight(const Point<dim>       &node,
                                     const double            horizon,
                                     const BoundingBox<dim> &cell) const
    {
      AssertThrow(horizon > 0,
                  ExcInvalidInput("horizon",
                                  format_number(horizon),
                                  "give a horizon > 0"));
      const double measure = cell.volume();
      if (measure <= 0)
        return 0;
      const double h  = std::pow(measure, 1. / dim);
      const double xi = node.distance(cell.center());
      if (xi > horizon)
        return 0;
      if (std::abs(xi - horizon) <= 0.5 * h)
        return (horizon + 0.5 * h - xi) / h;
      return 1;
    }


    template <int dim>
    void
    LammpsPartialVolume<dim>::declare_parameters(ParameterHandler &)
    {}


    template class ApproximatePartialVolume<2>;
    template class ApproximatePartialVolume<3>;
    template class LammpsPartialVolume<2>;
    template class LammpsPartialVolume<3>;
  } // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::ApproximatePartialVolume,
  2,
  "approximate",
  "Distance-based approximation (Parks et al. 2008, LAMMPS, Peridigm): the "
  "partial length of the cell along the bond, divided by its side.")
PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::ApproximatePartialVolume,
  3,
  "approximate",
  "Distance-based approximation (Parks et al. 2008, LAMMPS, Peridigm): the "
  "partial length of the cell along the bond, divided by its side.")
PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::LammpsPartialVolume,
  2,
  "lammps",
  "The volume reduction of LAMMPS's PERI package, for side-by-side runs: "
  "(delta + h/2 - r)/h for delta - h/2 <= r <= delta, no bond beyond delta.")
PERIDEAL_REGISTER_PARTIAL_VOLUME(
  PeriDEAL::Quadrature::LammpsPartialVolume,
  3,
  "lammps",
  "The volume reduction of LAMMPS's PERI package, for side-by-side runs: "
  "(delta + h/2 - r)/h for delta - h/2 <= r <= delta, no bond beyond delta.")
