#ifndef perideal_discretization_lattice_h
#define perideal_discretization_lattice_h

#include <perideal/discretization/node_set.h>

#include <array>
#include <cstdint>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    /**
     * The one place where PeriDEAL decides whether PD nodes lie on a uniform
     * lattice, and the local lattice that the shared stencil runs on.
     *
     * The node set is *uniform* when every cell of the mesh (on every
     * process) is a cube of one side h (equal to 1e-12 relative) and every
     * cell centre lies on the lattice \f$x_0 + h\,\mathbb{Z}^d\f$ (to 1e-9
     * h), where \f$x_0\f$ is the smallest centre coordinate per direction
     * over the whole mesh. Each node then has integer lattice coordinates,
     * the same on every process.
     *
     * On a uniform set the process also lays its nodes (owned and
     * off-process) into a dense box of *slots*, x fastest: slot(i) is node
     * i's position in that box and node_at_slot() the inverse (-1 for an
     * empty slot). A lattice offset is then a constant slot difference
     * (slot_offset()), which is what lets the uniform bulk share one stencil
     * of constant index offsets.
     */
    template <int dim>
    class Lattice
    {
    public:
      /**
       * Decide uniformity (collective over the node set's communicator)
       * and, on a uniform set, build the local slot box. With
       * @p at_cell_centres the cells' centres stand for the nodes (the
       * lattice of the mesh, also when the nodes are perturbed in their
       * cells: NodeSet::set_perturbation()).
       */
      void
      reinit(const NodeSet<dim> &nodes, const bool at_cell_centres = false);

      /// Whether every node of the mesh lies on one lattice of cubes.
      bool
      is_uniform() const;

      /// The lattice spacing h (the cell side); 0 when not uniform.
      double
      spacing() const;

      /// Integer lattice coordinates of node @p i (uniform sets only).
      const std::array<std::int64_t, dim> &
      coordinates(const unsigned int i) const;

      /// The slot of node @p i in the local box (uniform sets only).
      std::size_t
      slot(const unsigned int i) const;

      /// Number of slots of the local box.
      std::size_t
      n_slots() const;

      /// The node in slot @p s, or -1 if the slot is empty.
      int
      node_at_slot(const std::size_t s) const;

      /**
       * The node at integer lattice coordinates @p x, or -1 when no node of
       * this process is there (also outside the local box).
       */
      int
      node_at(const std::array<std::int64_t, dim> &x) const;

      /**
       * Whether the local box holds every lattice point within @p margin
       * (in every direction, a cube) of @p x: then node_at_slot() of the
       * slots around x needs no bounds check.
       */
      bool
      box_holds(const std::array<std::int64_t, dim> &x,
                const std::int64_t                   margin) const;

      /// The slot difference of the lattice offset @p offset.
      std::ptrdiff_t
      slot_offset(const std::array<int, dim> &offset) const;

    private:
      bool                                       uniform = false;
      double                                     h       = 0;
      std::vector<std::array<std::int64_t, dim>> coords;
      std::vector<std::size_t>                   slots;
      std::array<std::int64_t, dim>              box_lower{};
      std::array<std::int64_t, dim>              box_size{};
      std::vector<int>                           slot_to_node;
    };
  } // namespace Discretization
} // namespace PeriDEAL

#endif
