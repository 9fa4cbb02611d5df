#ifndef perideal_discretization_crack_geometry_h
#define perideal_discretization_crack_geometry_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    using namespace dealii;

    /**
     * Pre-cracks: line segments in 2D, planar polygons in 3D. A bond whose
     * segment \f$[x_i, x_j]\f$ meets a pre-crack (endpoints included) starts
     * broken.
     *
     * Written in the input as a list separated by ';' of comma-separated
     * coordinates: in 2D "x1, y1, x2, y2" per segment; in 3D "x1, y1, z1,
     * x2, y2, z2, x3, y3, z3[, ...]" per polygon (at least three vertices,
     * in order around the polygon, all in one plane).
     */
    template <int dim>
    class PreCracks
    {
    public:
      /**
       * Parse @p text; errors name @p entry, the offending item and the
       * expected form.
       */
      void
      parse(const std::string &text, const std::string &entry);

      /// Whether there is no pre-crack.
      bool
      empty() const
      {
        return cracks.empty();
      }

      /// Whether the segment [a, b] meets one of the pre-cracks.
      bool
      cuts(const Point<dim> &a, const Point<dim> &b) const;

      /**
       * Break every bond of every node with a list (owned and ghost) that
       * meets a pre-crack, and synchronise @p state (collective). @p reach
       * bounds the length of a bond. Returns the number of bond pairs broken
       * on all processes. With @p per_crack, also the number of bonds of
       * owned nodes (on all processes) that each pre-crack breaks first (a
       * bond that several cross counts for the first): 0 where one lies
       * outside the body and does nothing.
       */
      std::size_t
      break_bonds(const NodeSet<dim>       &nodes,
                  const NeighborList<dim>  &lists,
                  BondState<dim>           &state,
                  const double              reach,
                  std::vector<std::size_t> *per_crack = nullptr) const;

    private:
      /// The first pre-crack that the segment [a, b] meets, or -1.
      int
      first_cut(const Point<dim> &a, const Point<dim> &b) const;

      struct Crack
      {
        std::vector<Point<dim>> vertices;
        BoundingBox<dim>        box;
        // 3D: unit normal and the two in-plane axes.
        Tensor<1, dim> normal, axis_u, axis_v;
      };
      std::vector<Crack> cracks;
    };


    /**
     * Boxes given in the input as "xmin, ymin[, zmin], xmax, ymax[, zmax]"
     * separated by ';' (no-fail regions, say).
     */
    template <int dim>
    std::vector<BoundingBox<dim>>
    parse_boxes(const std::string &text, const std::string &entry);

    /**
     * Which nodes (owned and ghost) of @p nodes lie in one of @p boxes.
     * Every box must hold the centre of an owned node of some process;
     * otherwise all processes throw an error naming @p entry, its value
     * @p text and @p purpose ("prescribes nothing", say). Collective.
     */
    template <int dim>
    std::vector<bool>
    nodes_in_boxes(const NodeSet<dim>                  &nodes,
                   const std::vector<BoundingBox<dim>> &boxes,
                   const std::string                   &entry,
                   const std::string                   &text,
                   const std::string                   &purpose);

    /// Points given as "x, y[, z]" separated by ';'.
    template <int dim>
    std::vector<Point<dim>>
    parse_points(const std::string &text, const std::string &entry);

    /**
     * Check that each of @p points lies on the body: in (or on the boundary
     * of) the cell of an owned node of some process. Otherwise all
     * processes throw an error naming @p entry, its value @p text and the
     * point, instead of letting the nearest node stand for it. Collective.
     */
    template <int dim>
    void
    check_points_in_body(const NodeSet<dim>            &nodes,
                         const std::vector<Point<dim>> &points,
                         const std::string             &entry,
                         const std::string             &text);
  } // namespace Discretization
} // namespace PeriDEAL

#endif
