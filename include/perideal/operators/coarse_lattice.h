#ifndef perideal_operators_coarse_lattice_h
#define perideal_operators_coarse_lattice_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/discretization/lattice.h>
#include <perideal/discretization/node_set.h>

#include <cstdint>
#include <memory>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * The transfer between the DoFs of the PD nodes and those of a coarser
     * grid on which a preconditioner works: restriction R = P^T and
     * prolongation P. Independent of the dimension, so that the
     * preconditioners (Solvers::PreconditionerSetup) can hold one.
     */
    class GridTransfer
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      virtual ~GridTransfer() = default;

      /// Give @p coarse the layout of the coarse DoFs (with the ghosts the
      /// transfer reads and writes).
      virtual void
      initialize_coarse_vector(VectorType &coarse) const = 0;

      /// @p coarse = P^T @p fine (owned entries of @p fine are read; the
      /// constrained DoFs of either grid take no part). Collective.
      virtual void
      restrict_residual(VectorType &coarse, const VectorType &fine) const = 0;

      /// @p fine += P @p coarse at the free DoFs of the fine grid (the
      /// constrained coarse DoFs count as zero). Collective.
      virtual void
      prolongate_add(VectorType &fine, const VectorType &coarse) const = 0;
    };


    /**
     * The constrained components of every node of @p nodes (owned and
     * off-process) as their owner's @p constraints have them: bit p set
     * when component p is constrained there. An owned node's constraints
     * can be known to its owner only (a node held where its bonds all
     * broke), so a process that reads another's flags from its own
     * AffineConstraints object can disagree with the owner; these masks
     * agree on every process. Collective.
     */
    template <int dim>
    std::vector<std::uint8_t>
    owner_constraint_masks(const Discretization::NodeSet<dim> &nodes,
                           const AffineConstraints<double>    &constraints);


    /**
     * Every s-th node of a uniform lattice in each direction (the nodes
     * whose integer lattice coordinates are all multiples of the stride s;
     * the lattice origin is global, so every process picks the same ones),
     * with a DoF numbering of its own and the interpolation from those
     * coarse nodes to all nodes.
     *
     * The coarse nodes are the vertices of a dual grid of cubes of side
     * s h, on which LocalElasticityOperator::assemble() discretises
     * classical elasticity: \f$8^{-1}\f$ (3D) or \f$4^{-1}\f$ (2D) of the
     * rows of the grid on all nodes at s = 2. The prolongation P is nodal
     * interpolation: a node takes the multilinear interpolant of the
     * corners of the coarse cube it lies in. Near the boundary, where
     * corners are missing, the weights of the present corners are
     * rescaled to sum to one, so that P reproduces rigid translations
     * everywhere (a node with no present corner, in a part thinner than
     * s h, gets no coarse correction). Restriction is the transpose,
     * pushed from each owned node and summed by compress(), so
     * P^T and P are exact transposes and a preconditioner
     * \f$P A_c^{-1} P^T\f$ stays symmetric.
     *
     * Prescribed coarse DoFs: a coarse DoF is prescribed where a boundary
     * condition prescribes its node's PD DoF (a node held where its bonds
     * all broke leaves its coarse DoF free: P skips the held fine DoF
     * itself, and the coarse function still serves the nodes around it),
     * and also where a boundary-prescribed PD DoF in its support
     * (a node it interpolates to) has no prescribed corner: a clamp on one
     * layer at an odd lattice coordinate holds no coarse node, and without
     * this rule the coarse matrix would keep the rigid motions and be
     * singular. The flags of every process come from the owners
     * (owner_constraint_masks()), so P and P^T agree on every process.
     *
     * Off-process nodes needed: the corners of an owned node's coarse
     * cube lie within s - 1 lattice steps of it in each direction, and the
     * dual cubes of an owned coarse node (its row of the coarse matrix)
     * within s steps. NodeSet holds every node whose cell comes within the
     * coupling range (at least a cell diameter) of an owned cell; a cell
     * two steps away leaves a gap of one side per direction, a diameter
     * in all. Hence s = 2 at most (reinit() refuses more).
     */
    template <int dim>
    class CoarseLattice : public GridTransfer
    {
    public:
      /**
       * Pick the coarse nodes of @p lattice (uniform), number their DoFs
       * (node by node, components consecutive, in the order of the owned
       * nodes; processes in rank order) and compute the interpolation
       * weights of the owned nodes. @p constraints (the PD DoFs, each
       * process's own view: only the owner's counts) decide which DoFs take
       * no part. @p boundary_constraints, a subset of @p constraints, are
       * those the coarse grid must represent (the boundary conditions;
       * not the nodes held where their bonds broke); nullptr: all of
       * @p constraints. Collective.
       */
      void
      reinit(const Discretization::NodeSet<dim> &nodes,
             const Discretization::Lattice<dim> &lattice,
             const AffineConstraints<double>    &constraints,
             const unsigned int                  stride,
             const AffineConstraints<double> *boundary_constraints = nullptr);

      /// The stride s.
      unsigned int
      stride() const;

      /// Whether node @p i of the node set (owned or off-process) is a
      /// coarse node.
      bool
      is_coarse(const unsigned int i) const;

      /// The coarse DoF of component @p component of node @p i (a coarse
      /// node of the node set: owned ones and the off-process ones within
      /// two lattice steps of an owned node).
      types::global_dof_index
      dof(const unsigned int i, const unsigned int component) const;

      /// Whether component @p component of coarse node @p i of the node set
      /// is prescribed on the coarse grid (the same on every process).
      bool
      is_prescribed(const unsigned int i, const unsigned int component) const;

      /// The coarse DoFs owned here.
      const IndexSet &
      owned_dofs() const;

      /// Number of coarse nodes (all processes).
      types::global_dof_index
      n_global_nodes() const;

      /// The rigid translations over the owned coarse DoFs, one mask per
      /// component (the near-null space of the coarse matrix's AMG).
      std::vector<std::vector<bool>>
      constant_modes() const;

      void
      initialize_coarse_vector(VectorType &coarse) const override;

      void
      restrict_residual(VectorType       &coarse,
                        const VectorType &fine) const override;

      void
      prolongate_add(VectorType &fine, const VectorType &coarse) const override;

      /// Memory held, in bytes.
      std::size_t
      memory_consumption() const;

    private:
      unsigned int s = 1;
      /// Per node of the node set: its coarse node number, or
      /// numbers::invalid_dof_index.
      std::vector<types::global_dof_index> coarse_number;
      /// Per node of the node set: the prescribed components of its coarse
      /// DoFs (bit p for component p; coarse nodes only).
      std::vector<std::uint8_t>                          coarse_mask;
      types::global_dof_index                            n_global = 0;
      IndexSet                                           owned;
      std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
      /// Interpolation of owned node i: entries row_start[i] to
      /// row_start[i+1] - 1, each the local index of the corner's first
      /// coarse DoF in a coarse vector and its weight.
      std::vector<unsigned int> row_start;
      std::vector<unsigned int> corner_local;
      std::vector<double>       corner_weight;
      /// Per owned node and component: the DoF is constrained.
      std::vector<char> fine_constrained;
      /// Per local element (owned and ghost) of a coarse vector: the coarse
      /// DoF is constrained.
      std::vector<char> coarse_constrained;
      /// The global DoF of component 0 of each owned node.
      std::vector<types::global_dof_index> fine_dof;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
