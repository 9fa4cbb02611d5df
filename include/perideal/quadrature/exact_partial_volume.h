#ifndef perideal_quadrature_exact_partial_volume_h
#define perideal_quadrature_exact_partial_volume_h

#include <perideal/quadrature/partial_volume.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    /**
     * Exact partial areas (2D) and volumes (3D): \f$\beta\f$ is the measure
     * of the intersection of the horizon ball with the cell, divided by the
     * cell's measure, in closed form (ball_box_intersection_measure()).
     * Works for any axis-aligned cell, any position and any horizon, so it
     * serves adaptively refined meshes as well as uniform grids.
     *
     * Registered as "exact" for dim = 2 and 3.
     */
    template <int dim>
    class ExactPartialVolume : public PartialVolume<dim>
    {
    public:
      double
      weight(const Point<dim>       &node,
             const double            horizon,
             const BoundingBox<dim> &cell) const override;

      /**
       * Shares the corner measures between cells
       * (unit_cell_intersection_measures()):
       * same values as weight(), several times faster per cell.
       */
      std::vector<double>
      uniform_grid_weights(const std::vector<std::array<int, dim>> &offsets,
                           const double m_ratio) const override;

      /// No parameters.
      static void
      declare_parameters(ParameterHandler &prm);
    };
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
