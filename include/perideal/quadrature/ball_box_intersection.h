#ifndef perideal_quadrature_ball_box_intersection_h
#define perideal_quadrature_ball_box_intersection_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <array>
#include <vector>

namespace PeriDEAL
{
  namespace Quadrature
  {
    using namespace dealii;

    /**
     * The exact measure of the intersection of the closed ball (disc in 2D)
     * of radius @p radius around @p centre with the axis-aligned box
     * @p box: an area in 2D, a volume in 3D. Closed form, no series and no
     * quadrature; derivation and error analysis in
     * doc/partial-volumes.md.
     *
     * The box is split at the planes through the centre into pieces that
     * lie in one quadrant/octant each, reflected into the first one; each
     * piece is an inclusion-exclusion over its corners of the "corner
     * measure" \f$V(\mathbf a)=|B(0,R)\cap\{\mathbf x\ge\mathbf a\}|\f$,
     * evaluated in extended (x87, 64-bit mantissa) precision from a form
     * whose small angles are computed without cancellation. The absolute
     * error is of the order of \f$10^{-16}\f$ times the box measure for
     * radii up to a few hundred box sizes.
     *
     * @param[in] centre Centre of the ball.
     * @param[in] radius Radius of the ball, >= 0.
     * @param[in] box Any axis-aligned box (possibly degenerate).
     * @return The measure of the intersection, in the units of the input
     * cubed (squared in 2D).
     */
    template <int dim>
    double
    ball_box_intersection_measure(const Point<dim>       &centre,
                                  const double            radius,
                                  const BoundingBox<dim> &box);

    /**
     * ball_box_intersection_measure() for the unit cells of a uniform grid:
     * the measures of the ball of radius @p radius around the origin
     * intersected with the unit cells centred at the integer @p offsets.
     * The same closed form, organised for a grid: each corner measure (the
     * building block of the closed form) is computed once and shared by the
     * up to 2^dim cells that have the corner in common, and cells entirely
     * inside or outside the ball are decided exactly in integer arithmetic.
     */
    template <int dim>
    std::vector<double>
    unit_cell_intersection_measures(
      const std::vector<std::array<int, dim>> &offsets,
      const double                             radius);

    /**
     * The corner measure \f$|B(0,R)\cap\{x\ge a, y\ge b[, z\ge c]\}|\f$
     * for a corner with non-negative coordinates @p corner. Exposed for
     * testing.
     */
    template <int dim>
    double
    ball_corner_measure(const Point<dim> &corner, const double radius);
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
