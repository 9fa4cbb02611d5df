#include <perideal/quadrature/ball_box_intersection.h>
#include <perideal/quadrature/exact_partial_volume.h>
#include <perideal/quadrature/partial_volume_registration.h>

#include <algorithm>
#include <cmath>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    double
    ExactPartialVolume<dim>::weight(const Point<dim>       &node,
                                    const double            horizon,
                                    const BoundingBox<dim> &cell) const
    {
      const double cell_measure = cell.volume();
      if (cell_measure <= 0)
        return 0;
      return std::min(1.0,
                      ball_box_intersection_measure(node, horizon, cell) /
                        cell_measure);
    }


    template <int dim>
    std::vector<double>
    ExactPartialVolume<dim>::uniform_grid_weights(
      const std::vector<std::array<int, dim>> &offsets,
      const double                             m_ratio) const
    {
      // Unit cells: the measure is the coefficient.
      const std::vector<double> betas =
        unit_cell_intersection_measures<dim>(offsets, m_ratio);
      return betas;
    }


    template <int dim>
    void
    ExactPartialVolume<dim>::declare_parameters(ParameterHandler &)
    {}


    template class ExactPartialVolume<1>;
    template class ExactPartialVolume<2>;
    template class ExactPartialVolume<3>;
  } // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_PARTIAL_VOLUME_1D_2D_3D(
  PeriDEAL::Quadrature::ExactPartialVolume,
  "exact",
  "Exact length of the part of the cell within the horizon.",
  "Exact partial area of disc and cell in closed form (any rectangle).",
  "Exact partial volume of ball and cell in closed form (any box), "
  "accurate to about 1e-16 times the cell volume.")
