#include <perideal/quadrature/centre_distance_partial_volume.h>

#include <cmath>

namespace PeriDEAL
{
  namespace Quadrature
  {
    namespace
    {
      /**
       * The rules below in terms of the centre distance
       * \f$\xi = \|\mathbf x_C - \mathbf x_i\|\f$ and the side
       * \f$h = |C|^{1/dim}\f$ of the cube (square) of the cell's measure,
       * as CentreDistancePartialVolume wants them. A cell of no measure
       * takes no weight.
       */
      template <int dim, double (*rule)(double, double, double)>
      double
      cell_side_rule(const double distance_square,
                     const double cell_measure,
                     const double horizon)
      {
        if (cell_measure <= 0)
          return 0;
        return rule(std::sqrt(distance_square),
                    std::pow(cell_measure, 1. / dim),
                    horizon);
      }


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
       *
       * @param[in] xi The distance \f$\xi\f$ from the node to the cell's
       * centre.
       * @param[in] h The cell's side \f$h\f$.
       * @param[in] horizon The horizon \f$\delta > 0\f$.
       * @return \f$\beta\in[0,1]\f$ as above.
       */
      double
      approximate(const double xi, const double h, const double horizon)
      {
        if (xi + 0.5 * h <= horizon)
          return 1;
        else if (xi - 0.5 * h < horizon)
          return (horizon - (xi - 0.5 * h)) / h;
        else
          return 0;
      }

      template <int dim>
      using ApproximatePartialVolume =
        CentreDistancePartialVolume<dim, cell_side_rule<dim, approximate>>;


      /**
       * The volume reduction of LAMMPS's PERI package (pair_style peri/pmb,
       * peri/lps): with r the distance from the node to the cell centre and h
       * the cell side, the weight is 1 for \f$r < \delta - h/2\f$,
       * \f$(\delta + h/2 - r)/h\f$ for \f$\delta - h/2 \le r \le \delta\f$
       * and 0 beyond \f$\delta\f$: ApproximatePartialVolume cut at the
       * horizon. It exists to run the same discrete problem as LAMMPS side by
       * side (bench/dynamics); it is not a better rule. Registered as "lammps"
       * for dim = 2 and 3; the arguments are those of approximate().
       */
      double
      lammps(const double xi, const double h, const double horizon)
      {
        if (xi > horizon)
          return 0;
        if (std::abs(xi - horizon) <= 0.5 * h)
          return (horizon + 0.5 * h - xi) / h;
        return 1;
      }

      template <int dim>
      using LammpsPartialVolume =
        CentreDistancePartialVolume<dim, cell_side_rule<dim, lammps>>;
    } // namespace
  }   // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_PARTIAL_VOLUME_2D_3D(
  PeriDEAL::Quadrature::ApproximatePartialVolume,
  "approximate",
  "Distance-based approximation (Parks et al. 2008, LAMMPS, Peridigm): the "
  "partial length of the cell along the bond, divided by its side.")
PERIDEAL_REGISTER_PARTIAL_VOLUME_2D_3D(
  PeriDEAL::Quadrature::LammpsPartialVolume,
  "lammps",
  "The volume reduction of LAMMPS's PERI package, for side-by-side runs: "
  "(delta + h/2 - r)/h for delta - h/2 <= r <= delta, no bond beyond delta.")
