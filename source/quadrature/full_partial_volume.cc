#include <perideal/quadrature/centre_distance_partial_volume.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    namespace
    {
      /**
       * The simplest rule (Silling and Askari 2005; reference [11] of
       * Scabbia, Zaccariotto, Galvanetto 2022, "Accurate computation of
       * partial volumes in 3D peridynamics"): a neighbour's cell counts fully
       * if its centre lies in the closed horizon ball, and not at all
       * otherwise,
       * \f[
       *   \beta = \begin{cases}
       *     1 & \text{if } \|\mathbf x_C - \mathbf x_i\| \le \delta, \\
       *     0 & \text{otherwise,}
       *   \end{cases}
       * \f]
       * with \f$\mathbf x_C\f$ the cell's centre. Any cell shape.
       *
       * Registered as "full" for dim = 1, 2 and 3.
       */
      double
      full(const double distance_square, const double, const double horizon)
      {
        // Compare squares: on a uniform grid both sides are exact for
        // integer offsets and integer or half-integer horizons.
        return distance_square <= horizon * horizon ? 1. : 0.;
      }

      template <int dim>
      using FullPartialVolume = CentreDistancePartialVolume<dim, full>;
    } // namespace
  }   // namespace Quadrature
} // namespace PeriDEAL

PERIDEAL_REGISTER_PARTIAL_VOLUME_1D_2D_3D(
  PeriDEAL::Quadrature::FullPartialVolume,
  "full",
  "Whole cell if its centre lies within the horizon, else nothing.",
  "Whole cell if its centre lies in the closed horizon disc, else nothing.",
  "Whole cell if its centre lies in the closed horizon ball, else nothing.")
