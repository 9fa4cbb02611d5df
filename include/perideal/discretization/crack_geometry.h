#ifndef perideal_discretization_crack_geometry_h
#define perideal_discretization_crack_geometry_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>

#include <array>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    using namespace dealii;

    /**
     * Pre-cracks: line segments in 2D, planar polygons in 3D. A bond whose
     * segment \f$[x_i, x_j]\f$ meets a pre-crack starts broken.
     *
     * Both are closed sets, in 2D and in 3D alike: a bond that only touches a
     * pre-crack counts. In 2D: a bond through an end of the segment, with an
     * end node on it, or along it (collinear and overlapping). In 3D: a bond
     * through an edge or a vertex of the polygon, with an end node on it, or
     * lying in its plane and meeting it. The 3D rule is the 2D rule with one
     * more dimension, so that a polygon that extrudes a 2D segment (a
     * rectangle through the thickness) cuts exactly the bonds whose 2D
     * projection the segment cuts (bonds within its extent). Consequence: a
     * node exactly on a pre-crack loses every bond; put pre-cracks between
     * layers of nodes.
     *
     * The decisions are exact for the given doubles: the signs of
     * orientation determinants from a floating-point filter with proven
     * error bounds, and exact arithmetic where it cannot decide (Shewchuk's
     * robust predicates). There is no tolerance: a bond that touches a
     * crack only in decimal is decided by the binary values of the node and
     * crack coordinates (0.0195 and 0.02 are not binary numbers; nor are the
     * cell centres that carry the nodes). A crack tip on a cell face, say,
     * that diagonal bonds pass through in decimal then cuts some of them and
     * not others, as rounding falls; where that matters, move the tip or edge
     * off such lines by a small fraction of the node spacing. A 3D polygon is
     * cut into triangles (ear clipping) when it is parsed; it is their
     * union, which is the polygon itself when its vertices lie exactly in
     * one plane (the input check allows 1e-9 of its size off the plane).
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
        // 3D: the polygon as triangles (indices into vertices), each with
        // nonzero area when coordinate drop is left out.
        std::vector<std::array<unsigned int, 3>> triangles;
        unsigned int                             drop = 0;
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
