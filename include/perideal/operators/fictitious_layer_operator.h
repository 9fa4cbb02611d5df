#ifndef perideal_operators_fictitious_layer_operator_h
#define perideal_operators_fictitious_layer_operator_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/point.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/discretization/node_set.h>
#include <perideal/discretization/surface_nodes.h>
#include <perideal/models/model.h>
#include <perideal/quadrature/partial_volume.h>

#include <map>
#include <memory>
#include <vector>

class Epetra_CrsMatrix;

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    namespace FictitiousLayer
    {
      template <int dim>
      struct LayerData;
    }

    /**
     * The linearised state-based peridynamic system with a fictitious layer
     * and, optionally, surface nodes (Scabbia, Zaccariotto and Galvanetto
     * 2023, Sects. 2.4 and 3; see Boundary::BoundaryTreatment).
     *
     * <h3>Nodes and unknowns</h3>
     * The body's nodes are the cell centres of a uniform Cartesian grid of
     * spacing h. The lattice is continued around the body: a lattice point
     * outside the body whose nearest body node lies within
     * \f$\delta + h\sqrt{d}/2\f$ is a fictitious node (this contains every
     * cell that intersects some body node's horizon, so every body node has
     * a complete neighbourhood). With surface nodes, every external cell face
     * carries one node at its centre. The unknowns are the displacements of
     * body nodes and surface nodes, numbered per process: the owned body
     * DoFs, then dim unknowns per owned surface node (a surface node belongs
     * to the owner of its cell). Without surface nodes the unknowns are the
     * DoFHandler's DoFs.
     *
     * <h3>Extrapolation</h3>
     * A fictitious node f takes \f$\mathbf u_f = \sum_q w_q \mathbf u_q\f$,
     * a Taylor expansion of order N about its nearest surface node (nearest
     * body node without surface nodes), its derivatives fitted over the
     * nearest shells of surface and body nodes (Discretization::
     * taylor_extrapolation_weights), and \f$\theta_f\f$ likewise with order
     * N-1 from body nodes about its nearest body node. Every fictitious and
     * body node has the bulk weighted volume \f$m_0\f$. Ties between
     * equidistant nearest nodes are broken by lattice position, so the
     * choice does not depend on the partition.
     *
     * <h3>Equations</h3>
     * Body node i: \f$-\sum_j \mathbf f_{ij}\beta_{ij}V_jV_i = \mathbf
     * b_iV_i\f$ (paper Eq. 33) over its completed neighbourhood. Surface node s
     * with outward normal \f$\mathbf n_s\f$ and area \f$A_s\f$ (paper Eq. 36):
     * \f$\sum \alpha_{jk}\mathbf f_{jk}\beta_{jk}V_jV_k = \mathbf p_sA_s\f$
     * over the bonds from j (inner side) to k (outer side) whose segment
     * crosses the face; \f$\alpha\f$ is 1 inside the face and is halved for
     * every face edge the crossing point lies on (1/2 on an edge, 1/4 at a
     * vertex). Crossing points are tested in exact integer arithmetic on the
     * half-spacing lattice.
     *
     * <h3>Assembly</h3>
     * The operator is a product of sparse Trilinos matrices over a lattice
     * index space: \f$K = A E + B X D E\f$, with E the displacement
     * extrapolation (lattice DoFs from unknowns), D the body dilatations,
     * X the dilatation extrapolation, A the extension part and B the
     * dilatation part of the bond forces. EpetraExt forms the products in
     * parallel, so off-process rows are fetched by Trilinos and the result
     * does not depend on the partition beyond round-off. The matrix is not
     * symmetric.
     *
     * <h3>Parts</h3>
     * The set-up is in fictitious_layer_operator.cc; the rows of the factors
     * are built by the functions of namespace FictitiousLayer
     * (operators/fictitious_layer/: extrapolation rows of E and X, body
     * rows of D, A, B, surface flux rows of A, B), the products, the
     * elimination and apply() in fictitious_layer_operator_assembly.cc.
     */
    template <int dim>
    class FictitiousLayerOperator
    {
    public:
      /// A node on an external cell face.
      using SurfaceNode = Discretization::SurfaceNode<dim>;

      FictitiousLayerOperator();
      ~FictitiousLayerOperator();

      /**
       * Build the layer (Discretization::ExtendedLattice), the surface nodes
       * if @p with_surface_nodes (Discretization::SurfaceNodes) and the
       * bond constants for the body discretised by @p nodes (built with a
       * coupling range of at least twice the horizon plus two cell
       * diameters). Throws a clear error if the grid is not uniform.
       */
      void
      reinit(const DoFHandler<dim>                &dof_handler,
             const Discretization::NodeSet<dim>   &nodes,
             const Models::Model<dim>             &model,
             const double                          horizon,
             const Quadrature::PartialVolume<dim> &algorithm,
             const bool                            with_surface_nodes,
             const unsigned int                    taylor_order);

      /// The unknowns owned by this process.
      const IndexSet &
      owned_unknowns() const;

      /// The unknown of component @p c of body node @p node (any process).
      types::global_dof_index
      unknown_index(const Discretization::Node<dim> &node,
                    const unsigned int               c) const;

      /// The surface nodes owned by this process.
      const std::vector<SurfaceNode> &
      owned_surface_nodes() const;

      /// Numbers of surface and fictitious nodes over all processes.
      unsigned int
      n_surface_nodes() const;
      unsigned int
      n_fictitious_nodes() const;

      /// Number of neighbours of every node (all neighbourhoods are complete).
      unsigned int
      n_neighbours_per_node() const;

      /// The bulk weighted volume \f$m_0\f$ shared by all nodes.
      double
      bulk_weighted_volume() const;

      /**
       * Assemble the system matrix and complete the right-hand side.
       * @p rhs holds the external loads on the owned unknowns (body force
       * times volume on body nodes, traction times area on surface nodes).
       * The unknowns in @p prescribed (owned ones, with their values) are
       * eliminated: their rows become a diagonal with the value times the
       * diagonal on the right, their columns move to the right-hand side.
       */
      void
      assemble(const std::map<types::global_dof_index, double> &prescribed,
               TrilinosWrappers::SparseMatrix                  &matrix,
               TrilinosWrappers::MPI::Vector                   &rhs) const;

      /**
       * \f$K u\f$ for unknowns @p u (owned entries), without the assembled
       * product and without elimination: the factors of \f$K = A E + B X D
       * E\f$ applied one after the other (Trilinos fetches off-process
       * values). This evaluates the same bond forces and extrapolation as
       * the assembled matrix by another path (no EpetraExt products, no
       * elimination of prescribed unknowns); the quasi-static layer path
       * checks equilibrium with it. Needs assemble() called before.
       */
      void
      apply(const TrilinosWrappers::MPI::Vector &u,
            TrilinosWrappers::MPI::Vector       &ku) const;

      /**
       * Build the sparse factors E, X (extrapolation), D (dilatation), A
       * and B (bond forces) of the operator, for apply(); assemble() calls
       * it when they are not there yet.
       */
      void
      build_factors() const;

    private:
      std::unique_ptr<FictitiousLayer::LayerData<dim>> data;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
