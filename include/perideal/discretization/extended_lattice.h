#ifndef perideal_discretization_extended_lattice_h
#define perideal_discretization_extended_lattice_h

#include <deal.II/base/point.h>

#include <perideal/discretization/node_set.h>

#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    using namespace dealii;

    /**
     * The lattice of a uniform grid continued around the body: the body's
     * nodes and the fictitious nodes of a layer around it (Scabbia,
     * Zaccariotto and Galvanetto 2023, Sect. 2.4), for the fictitious-layer
     * boundary treatment.
     *
     * Beside Lattice (which decides uniformity and lays out the slots of the
     * shared stencil), this class numbers every point of a box of lattice
     * cells around the whole body with one integer *key*, the same on every
     * process, x fastest. Cell c (integer coordinates, the body's first cell
     * at 0) has its centre at \f$x_0 + h(c + 1/2)\f$. Positions that are not
     * cell centres (face centres) are *half points*, in units of h/2 from
     * \f$x_0\f$: cell centres have odd coordinates, the centre of a face
     * normal to \f$e_a\f$ an even coordinate a. Distances between half
     * points are exact integers, which is what makes the choices below
     * (nearest node, shell of a stencil, crossing of a face) independent of
     * round-off and partition.
     *
     * A lattice cell without a body node is a *fictitious node* when its
     * nearest body node lies within the reach given to reinit(); ties
     * between equidistant body nodes go to the smallest key. A fictitious
     * node belongs to the owner of its nearest body node.
     */
    template <int dim>
    class ExtendedLattice
    {
    public:
      /// Integer coordinates of a lattice cell.
      using Cell = std::array<int, dim>;
      /// A position in units of h/2 from the origin.
      using HalfPoint = std::array<int, dim>;

      /// What a lattice cell holds.
      enum class Status : signed char
      {
        none       = 0,
        body       = 1,
        fictitious = 2
      };

      /**
       * Build the lattice around the body discretised by @p nodes, a
       * uniform grid of spacing @p spacing (checked by the caller with
       * Lattice). Fictitious nodes are the cells whose nearest body node
       * lies within @p reach cell sides (centre to centre); the box extends
       * @p margin cells beyond the body on every side. Collective over the
       * node set's communicator.
       */
      void
      reinit(const NodeSet<dim> &nodes,
             const double        spacing,
             const double        reach,
             const int           margin);

      /// The lattice spacing h.
      double
      spacing() const;

      /// The origin \f$x_0\f$: the smallest cell corner of the body.
      const Point<dim> &
      origin() const;

      /// Number of lattice cells in the box (the range of key()).
      long long
      n_cells() const;

      /// Cells of the body along direction @p d.
      int
      extent(const unsigned int d) const;

      /// Cells of the box beyond the body on every side.
      int
      margin() const;

      /// The key of cell @p c (inside the box).
      int
      key(const Cell &c) const;

      /// The cell of key @p k.
      Cell
      cell_of(const int k) const;

      /// Whether cell @p c lies in the box.
      bool
      inside(const Cell &c) const;

      /// The half point of the centre of cell @p c.
      static HalfPoint
      half_of_cell(const Cell &c);

      /// The half point of @p x (a cell or face centre).
      HalfPoint
      half_point(const Point<dim> &x) const;

      /// The half point of body node @p i of the node set.
      HalfPoint
      half_point(const unsigned int i) const;

      /// The cell of body node @p i of the node set.
      Cell
      cell_of_node(const unsigned int i) const;

      /// The coordinates of half point @p p.
      Point<dim>
      location(const HalfPoint &p) const;

      /// A key of half points over a box that holds every half point
      /// within two cells of the lattice box (for orderings and lookups).
      long long
      half_key(const HalfPoint &p) const;

      /**
       * The nearest body node (owned or ghost) of cell @p c within the
       * reach; ties go to the smallest key. Returns its index in the node
       * set, or numbers::invalid_unsigned_int.
       */
      unsigned int
      nearest_body(const Cell &c) const;

      /// Whether cell @p c holds a body node, a fictitious node or neither.
      Status
      status(const Cell &c) const;

      /**
       * Call @p f(length2, key, half point, node index) for every body node
       * known here whose centre lies within squared distance @p radius2
       * (half units) of @p centre, the cells in lexicographic order.
       */
      template <typename F>
      void
      for_each_body_near(const HalfPoint &centre,
                         const long long  radius2,
                         const F         &f) const;

      /// The owned fictitious nodes: (key, nearest body node), by key.
      const std::vector<std::pair<int, unsigned int>> &
      owned_fictitious() const;

      /// Number of fictitious nodes over all processes.
      unsigned int
      n_fictitious() const;

    private:
      double                     h = 0;
      Point<dim>                 x0;
      int                        margin_cells = 0;
      std::array<int, dim>       extents{};
      std::array<long long, dim> stride{};
      long long                  n_lattice = 0;

      const NodeSet<dim>                   *nodes = nullptr;
      std::unordered_map<int, unsigned int> body; // key -> node index

      // Offsets for the nearest-body search, by squared length (cells).
      std::vector<Cell>      search_offsets;
      std::vector<long long> search_length2;

      std::vector<std::pair<int, unsigned int>> fictitious;
      unsigned int                              n_fictitious_global = 0;

      // Status of cells without a body node, filled on demand.
      mutable std::unordered_map<int, Status> status_cache;
    };


    /// Squared distance of two half points (exact).
    template <int dim>
    inline long long
    squared_distance(const std::array<int, dim> &a,
                     const std::array<int, dim> &b)
    {
      long long s = 0;
      for (unsigned int d = 0; d < dim; ++d)
        s += static_cast<long long>(a[d] - b[d]) * (a[d] - b[d]);
      return s;
    }


    template <int dim>
    template <typename F>
    void
    ExtendedLattice<dim>::for_each_body_near(const HalfPoint &centre,
                                             const long long  radius2,
                                             const F         &f) const
    {
      const int r = static_cast<int>(std::ceil(std::sqrt(radius2) / 2)) + 1;
      Cell      c0;
      for (unsigned int d = 0; d < dim; ++d)
        c0[d] = static_cast<int>(std::floor(0.5 * (centre[d] - 1)));
      Cell       o;
      const auto visit = [&](const auto &self, const unsigned int d) -> void {
        if (d == dim)
          {
            Cell c;
            for (unsigned int e = 0; e < dim; ++e)
              c[e] = c0[e] + o[e];
            if (!inside(c))
              return;
            const int  k  = key(c);
            const auto it = body.find(k);
            if (it == body.end())
              return;
            const HalfPoint p = half_of_cell(c);
            const long long l = squared_distance<dim>(p, centre);
            if (l > radius2)
              return;
            f(l, k, p, it->second);
            return;
          }
        for (o[d] = -r; o[d] <= r; ++o[d])
          self(self, d + 1);
      };
      visit(visit, 0);
    }
  } // namespace Discretization
} // namespace PeriDEAL

#endif
