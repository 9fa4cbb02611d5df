#include <deal.II/base/mpi.h>

#include <perideal/discretization/surface_nodes.h>

#include <algorithm>
#include <climits>
#include <cmath>

namespace PeriDEAL
{
  namespace Discretization
  {
    template <int dim>
    void
    SurfaceNodes<dim>::reinit(const DoFHandler<dim>      &dof_handler,
                              const ExtendedLattice<dim> &extended_lattice)
    {
      lattice = &extended_lattice;
      owned_nodes.clear();
      positions.clear();
      unknowns.clear();
      buckets.clear();
      const double h = lattice->spacing();
      std::vector<std::pair<HalfPoint, SurfaceNode<dim>>> local;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary())
              {
                const Point<dim>     centre = cell->face(f)->center();
                const Tensor<1, dim> out    = centre - cell->center();
                unsigned int         axis   = 0;
                for (unsigned int d = 1; d < dim; ++d)
                  if (std::abs(out[d]) > std::abs(out[axis]))
                    axis = d;
                SurfaceNode<dim> node;
                node.location    = centre;
                node.axis        = axis;
                node.side        = out[axis] > 0 ? 1 : -1;
                node.boundary_id = cell->face(f)->boundary_id();
                node.area        = std::pow(h, dim - 1);
                local.emplace_back(lattice->half_point(centre), node);
              }
      std::sort(local.begin(), local.end(), [](const auto &a, const auto &b) {
        return a.first < b.first;
      });
      for (const auto &e : local)
        owned_nodes.push_back(e.second);
    }


    template <int dim>
    void
    SurfaceNodes<dim>::set_unknowns(const types::global_dof_index first,
                                    const int                     size,
                                    const MPI_Comm                comm)
    {
      for (unsigned int k = 0; k < owned_nodes.size(); ++k)
        owned_nodes[k].first_unknown = first + dim * k;

      // Flattened: dim half-lattice coordinates and the first unknown.
      std::vector<long long> mine;
      for (const auto &node : owned_nodes)
        {
          for (const int x : lattice->half_point(node.location))
            mine.push_back(x);
          mine.push_back(node.first_unknown);
        }
      const auto all = Utilities::MPI::all_gather(comm, mine);
      bucket_size    = size;
      positions.clear();
      unknowns.clear();
      buckets.clear();
      for (const auto &part : all)
        for (std::size_t e = 0; e < part.size(); e += dim + 1)
          {
            HalfPoint p;
            for (unsigned int d = 0; d < dim; ++d)
              p[d] = static_cast<int>(part[e + d]);
            const unsigned int index = positions.size();
            positions.push_back(p);
            unknowns.push_back(part[e + dim]);
            buckets[bucket_key(p)].push_back(index);
          }
    }


    template <int dim>
    const std::vector<SurfaceNode<dim>> &
    SurfaceNodes<dim>::owned() const
    {
      return owned_nodes;
    }


    template <int dim>
    unsigned int
    SurfaceNodes<dim>::n_global() const
    {
      return positions.size();
    }


    template <int dim>
    const typename SurfaceNodes<dim>::HalfPoint &
    SurfaceNodes<dim>::position(const unsigned int q) const
    {
      return positions[q];
    }


    template <int dim>
    types::global_dof_index
    SurfaceNodes<dim>::first_unknown(const unsigned int q) const
    {
      return unknowns[q];
    }


    template <int dim>
    unsigned int
    SurfaceNodes<dim>::nearest(const HalfPoint &p) const
    {
      unsigned int best        = numbers::invalid_unsigned_int;
      long long    best_length = LLONG_MAX, best_key = LLONG_MAX;
      for_each_near(p, [&](const unsigned int s) {
        const long long l = squared_distance<dim>(p, positions[s]);
        const long long k = lattice->half_key(positions[s]);
        if (l < best_length || (l == best_length && k < best_key))
          {
            best_length = l;
            best_key    = k;
            best        = s;
          }
      });
      return best;
    }


    template <int dim>
    long long
    SurfaceNodes<dim>::bucket_key(const HalfPoint &p) const
    {
      const int margin = lattice->margin();
      long long k = 0, s = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const int b = (p[d] + 2 * margin + 2) / bucket_size; // non-negative
          k += b * s;
          s *= (2 * (lattice->extent(d) + 2 * margin) + 5) / bucket_size + 2;
        }
      return k;
    }


    template class SurfaceNodes<2>;
    template class SurfaceNodes<3>;
  } // namespace Discretization
} // namespace PeriDEAL
