#ifndef perideal_discretization_node_set_h
#define perideal_discretization_node_set_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/tria_accessor.h>

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace PeriDEAL
{
  /**
   * PD nodes on deal.II meshes: node sets, neighbour lists, the nonlocal
   * ghost exchange.
   */
  namespace Discretization
  {
    using namespace dealii;

    /**
     * One PD node: the centre of an active cell, with the cell's box and
     * the indices of its displacement degrees of freedom.
     */
    template <int dim>
    struct Node
    {
      /// Cell centre, the node's position.
      Point<dim> location;

      /// The cell, an axis-aligned box.
      BoundingBox<dim> cell;

      /// Global indices of the dim displacement components.
      std::array<types::global_dof_index, dim> dofs;

      /// The MPI rank that owns the node.
      types::subdomain_id owner;

      /// The node's volume (area in 2D): the measure of its cell.
      double
      volume() const
      {
        return cell.volume();
      }

      template <class Archive>
      void
      serialize(Archive &ar, const unsigned int)
      {
        ar &location &cell &dofs &owner;
      }
    };

    /**
     * The axis-aligned box that the cell @p cell is, after checking that it
     * is one: every vertex a corner of its bounding box, and the same
     * measure (to 1e-10 relative). Otherwise throws an error that names the
     * cell and its vertices and asks for a Cartesian mesh.
     */
    template <int dim>
    BoundingBox<dim>
    cell_box(const CellAccessor<dim> &cell);

    /// Squared Euclidean distance between two boxes (0 if they overlap; a
    /// point is a box with equal corners).
    template <int dim>
    double
    box_distance_squared(const BoundingBox<dim> &a, const BoundingBox<dim> &b);

    /**
     * The PD nodes a process works with: those of its locally owned cells,
     * followed by every off-process node within a given coupling range of
     * them.
     *
     * deal.II's ghost layer (from p4est) is one cell wide, but a
     * peridynamic horizon spans several cells, so the off-process nodes are
     * obtained by an exchange of PeriDEAL's own: every process publishes
     * bounding boxes of its owned cells
     * (GridTools::compute_mesh_predicate_bounding_box), and sends to every
     * other process the nodes whose cells come within the coupling range of
     * those boxes (Utilities::MPI::some_to_some). The cost scales with the
     * number of nodes near process boundaries, never with the total.
     *
     * The displacement field is indexed by a DoFHandler with
     * FESystem(FE_DGQ(0), dim): one node per active cell, dim DoFs per node.
     * Every cell must be an axis-aligned box: the partial-volume kernels
     * need boxes, and any other cell is an error.
     */
    template <int dim>
    class NodeSet
    {
    public:
      /**
       * Collect the nodes of @p dof_handler: the locally owned ones, and
       * the off-process ones whose cells come within @p coupling_range of a
       * locally owned node (bond-based models need the horizon, state-based
       * ones twice the horizon).
       */
      void
      reinit(const DoFHandler<dim> &dof_handler, const double coupling_range);

      /**
       * Irregular nodes (hybrid-collocation paper Sect. 5, 'Geometry/Node
       * perturbation'): from the next reinit() on, every node lies at its
       * cell's centre plus an offset whose component d is uniform in
       * \f$[-f\,h_d, f\,h_d]\f$, \f$h_d\f$ the cell's side along d and
       * f = @p fraction (0 <= f < 0.5: the node stays inside its cell). The
       * offsets are a hash of @p seed, the bits of the cell's centre and d:
       * the same on every partition and run, and however the mesh was made
       * (coarse cells and refinements). The cell (and so the standard
       * scheme's volumes) is unchanged.
       */
      void
      set_perturbation(const double fraction, const std::uint64_t seed);

      /// Number of locally owned nodes; they come first.
      unsigned int
      n_owned() const;

      /// Number of off-process nodes; they follow the owned ones.
      unsigned int
      n_ghost() const;

      /// Owned plus off-process nodes.
      unsigned int
      size() const;

      /// The node with local index @p i (owned: i < n_owned()).
      const Node<dim> &
      operator[](const unsigned int i) const;

      /// All nodes, owned first.
      const std::vector<Node<dim>> &
      nodes() const;

      /// The largest cell diameter over the whole mesh.
      double
      max_cell_diameter() const;

      /**
       * The DoFs of all nodes known here (owned and off-process): the
       * index set of a ghosted vector holding every value the nonlocal
       * operator of the owned nodes reads.
       */
      IndexSet
      relevant_dofs() const;

      /**
       * A partitioner with one entry per node, at global index dofs[0] /
       * dim (the FE_DGQ(0)^dim numbering: a node's dim DoFs are
       * consecutive from a multiple of dim): the owned nodes owned, every
       * other node of the set a ghost. Its import and ghost targets are
       * the processes this one exchanges node values with. Built once by
       * reinit() (collectively) and kept: fracture runs exchange per-node
       * masks at every load step.
       */
      std::shared_ptr<const Utilities::MPI::Partitioner>
      node_partitioner() const;

      /// The communicator of the mesh.
      MPI_Comm
      get_communicator() const;

    private:
      MPI_Comm               communicator = MPI_COMM_SELF;
      std::vector<Node<dim>> all_nodes;
      unsigned int           n_owned_nodes = 0;
      double                 max_diameter  = 0;
      IndexSet               relevant;
      double                 perturbation      = 0;
      std::uint64_t          perturbation_seed = 1;
      /// node_partitioner(), once built.
      mutable std::shared_ptr<const Utilities::MPI::Partitioner>
        node_partitioner_cache;
    };
  } // namespace Discretization
} // namespace PeriDEAL

#endif
