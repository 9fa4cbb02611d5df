#ifndef perideal_operators_local_elasticity_operator_h
#define perideal_operators_local_elasticity_operator_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/lattice.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/coarse_lattice.h>

#include <cstdint>
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
       * nodes next to owned ones. A DoF is prescribed (its row and column
       * the identity's) where its owner's @p constraints constrain it. With
       * @p coarse, on its coarse nodes instead: dual cubes of side s h
       * between them (only where every lattice point inside is a node),
       * rows and columns its DoFs, prescribed where
       * CoarseLattice::is_prescribed() says; a coarse cube is cut
       * (@p broken_masks) when one of the cubes of side h it holds is.
       */
      static void
      assemble(const Discretization::NodeSet<dim> &nodes,
               const Discretization::Lattice<dim> &lattice,
               const Models::Model<dim>           &model,
               const AffineConstraints<double>    &constraints,
               TrilinosWrappers::SparseMatrix     &matrix,
               const std::vector<std::uint32_t>   *broken_masks = nullptr,
               const CoarseLattice<dim>           *coarse       = nullptr);

      /**
       * The broken bonds between lattice neighbours, for assemble() to cut
       * the dual cubes a crack runs through: per node of @p nodes (owned
       * and off-process), bit b set when its bond to the lattice neighbour
       * at offset b in {-1, 0, 1}^dim (the 3^dim - 1 offsets in
       * lexicographic order, x fastest, the centre left out) is broken.
       * Collective: the masks of off-process nodes come from their owners
       * (every node of the set).
       */
      static std::vector<std::uint32_t>
      broken_neighbor_masks(const Discretization::NodeSet<dim>      &nodes,
                            const Discretization::Lattice<dim>      &lattice,
                            const Discretization::NeighborList<dim> &lists,
                            const Discretization::BondState<dim>    &bonds);

      /// The number of dual cubes cut by @p broken_masks whose lower
      /// corner is owned here (all processes together; collective).
      static std::size_t
      n_cut_cubes(const Discretization::NodeSet<dim> &nodes,
                  const Discretization::Lattice<dim> &lattice,
                  const std::vector<std::uint32_t>   &broken_masks);

      /**
       * The stiffness factor of a cut dual cube: below the algebraic
       * multigrid's aggregation threshold, so that no aggregate spans the
       * crack, and positive, so that a piece the cracks cut off keeps a
       * regular matrix.
       */
      static constexpr double cut_cube_factor = 1e-6;

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
