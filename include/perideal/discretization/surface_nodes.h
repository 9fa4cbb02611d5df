#ifndef perideal_discretization_surface_nodes_h
#define perideal_discretization_surface_nodes_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <perideal/discretization/extended_lattice.h>

#include <unordered_map>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    using namespace dealii;

    /// A node at the centre of an external cell face.
    template <int dim>
    struct SurfaceNode
    {
      Point<dim>              location;
      unsigned int            axis;
      int                     side; // +1: outward normal +e_axis
      types::boundary_id      boundary_id;
      double                  area;
      types::global_dof_index first_unknown;

      Tensor<1, dim>
      normal() const
      {
        Tensor<1, dim> n;
        n[axis] = side;
        return n;
      }
    };


    /**
     * The surface nodes of a body on a uniform grid (Scabbia, Zaccariotto
     * and Galvanetto 2023, Sect. 3): one node at the centre of every
     * external cell face, owned by the owner of its cell, with the face's
     * outward normal and area \f$h^{d-1}\f$.
     *
     * Besides the owned nodes (in the order of their half points), every
     * process keeps the half points and first unknowns of all surface nodes
     * of the mesh (their number grows like the surface only), in buckets of
     * half points, so that the nearest surface node and the surface nodes
     * near a point are found without communication and the same on every
     * partition.
     */
    template <int dim>
    class SurfaceNodes
    {
    public:
      using HalfPoint = typename ExtendedLattice<dim>::HalfPoint;

      /**
       * Collect the owned surface nodes of @p dof_handler's mesh on
       * @p lattice (which must stay alive). Their unknowns are set by
       * set_unknowns().
       */
      void
      reinit(const DoFHandler<dim>      &dof_handler,
             const ExtendedLattice<dim> &lattice);

      /**
       * Give the owned surface node k the unknowns @p first + dim k, ...,
       * and gather all surface nodes of the mesh for the lookups, in buckets
       * of @p bucket_size half units (at least the largest distance that
       * for_each_near() is asked for). Collective.
       */
      void
      set_unknowns(const types::global_dof_index first,
                   const int                     bucket_size,
                   const MPI_Comm                comm);

      /// The surface nodes owned by this process.
      const std::vector<SurfaceNode<dim>> &
      owned() const;

      /// Number of surface nodes over all processes.
      unsigned int
      n_global() const;

      /// The half point of surface node @p q (of all nodes).
      const HalfPoint &
      position(const unsigned int q) const;

      /// The first unknown of surface node @p q (of all nodes).
      types::global_dof_index
      first_unknown(const unsigned int q) const;

      /// The nearest surface node of @p p (ties: smallest ExtendedLattice::
      /// half_key()), or numbers::invalid_unsigned_int.
      unsigned int
      nearest(const HalfPoint &p) const;

      /// Call @p f(q) for every surface node q in the buckets next to the
      /// bucket of @p p (at least those within bucket_size half units).
      template <typename F>
      void
      for_each_near(const HalfPoint &p, const F &f) const;

    private:
      long long
      bucket_key(const HalfPoint &p) const;

      const ExtendedLattice<dim>          *lattice = nullptr;
      std::vector<SurfaceNode<dim>>        owned_nodes;
      std::vector<HalfPoint>               positions;
      std::vector<types::global_dof_index> unknowns;
      std::unordered_map<long long, std::vector<unsigned int>> buckets;
      int                                                      bucket_size = 1;
    };


    template <int dim>
    template <typename F>
    void
    SurfaceNodes<dim>::for_each_near(const HalfPoint &p, const F &f) const
    {
      const int            margin = lattice->margin();
      std::array<int, dim> b0;
      for (unsigned int d = 0; d < dim; ++d)
        b0[d] = (p[d] + 2 * margin + 2) / bucket_size;
      const unsigned int n_neighbours = (dim == 2 ? 9 : 27);
      for (unsigned int n = 0; n < n_neighbours; ++n)
        {
          HalfPoint    q;
          unsigned int rest = n;
          bool         ok   = true;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const int b = b0[d] + static_cast<int>(rest % 3) - 1;
              rest /= 3;
              ok   = ok && b >= 0;
              q[d] = b * bucket_size - 2 * margin - 2;
            }
          if (!ok)
            continue;
          const auto it = buckets.find(bucket_key(q));
          if (it != buckets.end())
            for (const unsigned int s : it->second)
              f(s);
        }
    }
  } // namespace Discretization
} // namespace PeriDEAL

#endif
