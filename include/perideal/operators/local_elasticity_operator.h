#ifndef perideal_operators_local_elasticity_operator_h
#define perideal_operators_local_elasticity_operator_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <perideal/discretization/lattice.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>

#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * Classical linear elasticity on the PD nodes themselves: the local
     * operator that preconditions the nonlocal one.
     *
     * On a uniform grid the cell centres are the vertices of a *dual* grid
     * of cubes of the same side h (each dual cube spans 2^dim neighbouring
     * centres). This class assembles the bilinear (\f$Q_1\f$) finite element
     * stiffness of isotropic elasticity (same \f$\lambda, \mu\f$ as the PD
     * model: 3D, plane strain or plane stress) on that dual grid: a compact
     * 27-point (3D) or 9-point (2D) stencil on the cell-centred nodes, with
     * the DoF numbering of the PD operator. The dual grid ends at the outer
     * nodes, where the FE form gives traction-free faces (natural
     * conditions); prescribed DoFs keep their diagonal and lose their
     * off-diagonal entries. The matrix is symmetric positive definite once
     * rigid motions are fixed, and at fixed m-ratio spectrally equivalent to
     * the PD stiffness (Aksoylu & Parks 2011: both behave like
     * \f$-\nabla\cdot\sigma\f$ at wavelengths above the horizon, and the PD
     * symbol saturates below it), so algebraic multigrid on it preconditions
     * CG on the PD operator with iteration counts that do not grow with
     * 1/h.
     */
    template <int dim>
    class LocalElasticityOperator
    {
    public:
      /**
       * Assemble into @p matrix (rows: the owned DoFs of @p nodes). The
       * lattice must be uniform and the node set must hold the off-process
       * nodes next to owned ones.
       */
      static void
      assemble(const Discretization::NodeSet<dim> &nodes,
               const Discretization::Lattice<dim> &lattice,
               const Models::Model<dim>           &model,
               const AffineConstraints<double>    &constraints,
               TrilinosWrappers::SparseMatrix     &matrix);

      /**
       * The \f$Q_1\f$ element stiffness of a cube of side @p h, row and
       * column index vertex * dim + component, vertex bit d set for the
       * upper vertex in direction d.
       */
      static FullMatrix<double>
      element_matrix(const double h, const double lambda, const double mu);
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
