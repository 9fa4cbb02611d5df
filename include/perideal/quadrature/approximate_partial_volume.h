#ifndef perideal_quadrature_approximate_partial_volume_h
#define perideal_quadrature_approximate_partial_volume_h

#include <perideal/quadrature/partial_volume.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    /**
     * The common distance-based approximation of partial volumes (Parks et
     * al. 2008, as in LAMMPS and Peridigm; Algorithm 1 of Scabbia,
     * Zaccariotto, Galvanetto 2022, "Accurate computation of partial volumes
     * in 3D peridynamics"): with \f$\xi\f$ the distance from the node to the
     * cell's centre and \f$h\f$ the cell's side,
     * \f[
     *   \beta = \begin{cases}
     *     1 & \text{if } \xi + h/2 \le \delta, \\
     *     \left(\delta - (\xi - h/2)\right)/h
     *       & \text{else if } \xi - h/2 < \delta, \\
     *     0 & \text{otherwise,}
     *   \end{cases}
     * \f]
     * the partial length of a 1D cell along the bond, used unchanged in 2D
     * and 3D.
     *
     * The paper writes \f$\xi + h/2 < \delta\f$ for the first case. At
     * \f$\xi + h/2 = \delta\f$ the second formula gives 1 as well, so the
     * rule is continuous there and the choice changes nothing; we use
     * \f$\le\f$ so that the first case reads "the far side of the cell is in
     * the closed ball". At \f$\xi - h/2 = \delta\f$ both formulas give 0.
     *
     * For non-cubic cells we take \f$h = |C|^{1/dim}\f$, the side of the
     * cube (square) of the same measure, so that \f$\beta|C|\f$ is the
     * volume of that cube's partial length along the bond. On uniform grids
     * this is the grid spacing.
     *
     * Registered as "approximate" for dim = 2 and 3.
     */
    template <int dim>
    class ApproximatePartialVolume : public PartialVolume<dim>
    {
    public:
      /**
       * @param[in] node The node's position.
       * @param[in] horizon The horizon \f$\delta > 0\f$, in the unit of the
       * points.
       * @param[in] cell The neighbour's cell.
       * @return \f$\beta\in[0,1]\f$ as above.
       */
      double
      weight(const Point<dim>       &node,
             const double            horizon,
             const BoundingBox<dim> &cell) const override;

      /// No parameters.
      static void
      declare_parameters(ParameterHandler &prm);
    };

    /**
     * The volume reduction of LAMMPS's PERI package (pair_style peri/pmb,
     * peri/lps): with r the distance from the node to the cell centre and h
     * the cell side, the weight is 1 for \f$r < \delta - h/2\f$,
     * \f$(\delta + h/2 - r)/h\f$ for \f$\delta - h/2 \le r \le \delta\f$
     * and 0 beyond \f$\delta\f$: ApproximatePartialVolume cut at the
     * horizon. It exists to run the same discrete problem as LAMMPS side by
     * side (bench/dynamics); it is not a better rule.
     */
    template <int dim>
    class LammpsPartialVolume : public PartialVolume<dim>
    {
    public:
      double
      weight(const Point<dim>       &node,
             const double            horizon,
             const BoundingBox<dim> &cell) const override;

      /// No parameters.
      static void
      declare_parameters(ParameterHandler &prm);
    };
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
