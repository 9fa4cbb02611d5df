#ifndef perideal_quadrature_full_partial_volume_h
#define perideal_quadrature_full_partial_volume_h

#include <perideal/quadrature/partial_volume.h>

namespace PeriDEAL
{
  namespace Quadrature
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
     * Registered as "full" for dim = 2 and 3.
     */
    template <int dim>
    class FullPartialVolume : public PartialVolume<dim>
    {
    public:
      /**
       * @param[in] node The node's position.
       * @param[in] horizon The horizon \f$\delta > 0\f$.
       * @param[in] cell The neighbour's cell.
       * @return 1 or 0 as above.
       */
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
