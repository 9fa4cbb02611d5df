#ifndef perideal_boundary_boundary_layers_h
#define perideal_boundary_boundary_layers_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <perideal/discretization/node_set.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Boundary
  {
    using namespace dealii;

    /**
     * Volumetric layers along parts of the boundary: which nodes lie closer
     * than a thickness to a boundary face with a given id. Dirichlet layers
     * (BoundaryConditions::make_constraints) and the no-fail layers of
     * explicit dynamics both use it.
     *
     * The faces of every listed id are gathered from all processes (a layer
     * can be several cells thick and cross partition boundaries) into one
     * R-tree per id, so that the answer for a node does not depend on the
     * partition.
     */
    /// Boundary ids from a comma-separated list, sorted, without repeats.
    std::vector<types::boundary_id>
    parse_boundary_ids(const std::string &text);

    /// "0, 2, 3": the ids for a message.
    std::string
    boundary_ids_to_string(const std::vector<types::boundary_id> &ids);

    /**
     * Throw ExcInvalidInput naming @p entry (with its value @p text) if one
     * of @p ids does not occur in @p triangulation. The mesh's ids are the
     * same on every process (Triangulation::get_boundary_ids()), so all
     * processes throw together.
     */
    template <int dim>
    void
    check_boundary_ids(const Triangulation<dim>              &triangulation,
                       const std::vector<types::boundary_id> &ids,
                       const std::string                     &entry,
                       const std::string                     &text);

    template <int dim>
    class BoundaryLayers
    {
    public:
      /**
       * Collect the faces with the (sorted, unique) @p ids of the locally
       * owned cells of @p triangulation from all processes. Collective.
       */
      BoundaryLayers(const Triangulation<dim>              &triangulation,
                     const std::vector<types::boundary_id> &ids);

      /**
       * For each node (owned and ghost) of @p nodes: the position in the id
       * list of the first id whose layer of @p thickness holds the node, or
       * numbers::invalid_unsigned_int. Nodes at exactly the thickness (up to
       * a relative 1e-10) are outside, so that the decision does not depend
       * on round-off in the node coordinates.
       *
       * @p n_owned_per_id, if given, receives the number of owned nodes in
       * the layer of each id (a node near two faces counts for both),
       * summed over the triangulation's processes: the call is then
       * collective.
       */
      std::vector<unsigned int>
      layer_of_nodes(const Discretization::NodeSet<dim> &nodes,
                     const double                        thickness,
                     std::vector<unsigned int> *n_owned_per_id = nullptr) const;

      /**
       * For each node (owned and ghost) of @p nodes closer than
       * @p thickness to a face with one of the ids: the nearest point on
       * those faces (each face taken as its bounding box, exact for the
       * axis-aligned faces of box meshes); for the other nodes a point with
       * NaN coordinates. No communication.
       */
      std::vector<Point<dim>>
      nearest_face_points(const Discretization::NodeSet<dim> &nodes,
                          const double                        thickness) const;

    private:
      /// The triangulation's communicator.
      MPI_Comm                                   comm;
      std::vector<std::vector<BoundingBox<dim>>> faces;
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
