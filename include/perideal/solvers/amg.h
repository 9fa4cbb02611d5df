#ifndef perideal_solvers_amg_h
#define perideal_solvers_amg_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * The settings of PeriDEAL's algebraic multigrid (Trilinos ML), read
     * from the subsection of the solver that uses it: 'Linear solver' for
     * the AMG on the PD matrix and on the local elasticity operator (both
     * the nodal and the layer systems), 'diffusion' for the AMG on the
     * local Laplacian.
     */
    struct AmgSettings
    {
      /// Chebyshev smoother sweeps per level.
      unsigned int smoother_sweeps = 2;
      /// Entries below this fraction of the diagonal are dropped when ML
      /// builds its aggregates.
      double aggregation_threshold = 1e-4;

      /**
       * Declare 'AMG smoother sweeps' and 'AMG aggregation threshold' in the
       * current subsection, the threshold with the default
       * @p default_threshold (its natural value differs between the PD
       * operators and the Laplacian).
       */
      static void
      declare_parameters(ParameterHandler  &prm,
                         const std::string &default_threshold);

      /// Read what declare_parameters() declared, in the same subsection.
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The one AMG set-up of PeriDEAL: ML on @p matrix as an elliptic
     * operator with @p settings and the near-null space @p constant_modes
     * (one mask over the locally owned rows per displacement component, the
     * rigid translations; empty for a scalar problem).
     */
    void
    initialize_amg(TrilinosWrappers::PreconditionAMG    &amg,
                   const TrilinosWrappers::SparseMatrix &matrix,
                   const AmgSettings                    &settings,
                   const std::vector<std::vector<bool>> &constant_modes);
  } // namespace Solvers
} // namespace PeriDEAL

#endif
