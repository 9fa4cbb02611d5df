#include <deal.II/base/mpi.h>

#include <perideal/discretization/extended_lattice.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Discretization
  {
    template <int dim>
    void
    ExtendedLattice<dim>::reinit(const NodeSet<dim> &node_set,
                                 const double        spacing,
                                 const double        reach,
                                 const int           margin)
    {
      const MPI_Comm comm = node_set.get_communicator();
      nodes               = &node_set;
      h                   = spacing;
      margin_cells        = margin;
      body.clear();
      search_offsets.clear();
      search_length2.clear();
      fictitious.clear();
      status_cache.clear();

      // The bounding box of the body, the same on every process.
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          const auto &box = node_set[i].cell;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = std::min(lower[d], box.get_boundary_points().first[d]);
              upper[d] =
                std::max(upper[d], box.get_boundary_points().second[d]);
            }
        }
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = Utilities::MPI::min(lower[d], comm);
          upper[d] = Utilities::MPI::max(upper[d], comm);
        }
      x0              = lower;
      long long total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          extents[d] = static_cast<int>(std::lround((upper[d] - lower[d]) / h));
          stride[d]  = total;
          total *= extents[d] + 2 * margin_cells;
        }
      n_lattice = total;
      AssertThrow(dim * total < INT_MAX,
                  ExcMessage("The lattice around the body is too large for "
                             "32-bit Trilinos indices."));

      for (unsigned int i = 0; i < node_set.size(); ++i)
        {
          const Cell c = cell_of_node(i);
          if (inside(c))
            body[key(c)] = i;
        }

      // Offsets for the nearest-body search, sorted by length.
      {
        const int r = static_cast<int>(std::ceil(reach));
        // squared lengths in cell units; compare with a small tolerance
        const double bound = reach * reach * (1 + 1e-12);
        Cell         o;
        std::vector<std::pair<long long, Cell>> list;
        const auto visit = [&](const auto &self, const unsigned int d) -> void {
          if (d == dim)
            {
              long long l = 0;
              for (unsigned int e = 0; e < dim; ++e)
                l += o[e] * o[e];
              if (l <= bound)
                list.emplace_back(l, o);
              return;
            }
          for (o[d] = -r; o[d] <= r; ++o[d])
            self(self, d + 1);
        };
        visit(visit, 0);
        std::sort(list.begin(), list.end());
        for (const auto &e : list)
          {
            search_length2.push_back(e.first);
            search_offsets.push_back(e.second);
          }
      }

      // Owned fictitious nodes: those whose nearest body node is owned.
      std::unordered_map<int, bool> seen;
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          const Cell ci = cell_of_node(i);
          for (const auto &o : search_offsets)
            {
              Cell c;
              for (unsigned int d = 0; d < dim; ++d)
                c[d] = ci[d] + o[d];
              const int k = key(c);
              if (body.count(k) || seen.count(k))
                continue;
              seen[k]              = true;
              const unsigned int b = nearest_body(c);
              status_cache[k]      = (b != numbers::invalid_unsigned_int) ?
                                       Status::fictitious :
                                       Status::none;
              if (b != numbers::invalid_unsigned_int && b < node_set.n_owned())
                fictitious.emplace_back(k, b);
            }
        }
      std::sort(fictitious.begin(), fictitious.end());
      n_fictitious_global =
        Utilities::MPI::sum(static_cast<unsigned int>(fictitious.size()), comm);
    }


    template <int dim>
    double
    ExtendedLattice<dim>::spacing() const
    {
      return h;
    }


    template <int dim>
    const Point<dim> &
    ExtendedLattice<dim>::origin() const
    {
      return x0;
    }


    template <int dim>
    long long
    ExtendedLattice<dim>::n_cells() const
    {
      return n_lattice;
    }


    template <int dim>
    int
    ExtendedLattice<dim>::extent(const unsigned int d) const
    {
      return extents[d];
    }


    template <int dim>
    int
    ExtendedLattice<dim>::margin() const
    {
      return margin_cells;
    }


    template <int dim>
    int
    ExtendedLattice<dim>::key(const Cell &cell) const
    {
      long long k = 0;
      for (unsigned int d = 0; d < dim; ++d)
        k += (cell[d] + margin_cells) * stride[d];
      return static_cast<int>(k);
    }


    template <int dim>
    typename ExtendedLattice<dim>::Cell
    ExtendedLattice<dim>::cell_of(const int k) const
    {
      Cell      c;
      long long rest = k;
      for (int d = dim - 1; d >= 0; --d)
        {
          c[d] = static_cast<int>(rest / stride[d]) - margin_cells;
          rest = rest % stride[d];
        }
      return c;
    }


    template <int dim>
    bool
    ExtendedLattice<dim>::inside(const Cell &c) const
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (c[d] < -margin_cells || c[d] >= extents[d] + margin_cells)
          return false;
      return true;
    }


    template <int dim>
    typename ExtendedLattice<dim>::HalfPoint
    ExtendedLattice<dim>::half_of_cell(const Cell &c)
    {
      HalfPoint p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = 2 * c[d] + 1;
      return p;
    }


    template <int dim>
    typename ExtendedLattice<dim>::HalfPoint
    ExtendedLattice<dim>::half_point(const Point<dim> &x) const
    {
      HalfPoint p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = static_cast<int>(std::lround(2 * (x[d] - x0[d]) / h));
      return p;
    }


    template <int dim>
    typename ExtendedLattice<dim>::HalfPoint
    ExtendedLattice<dim>::half_point(const unsigned int i) const
    {
      return half_point((*nodes)[i].location);
    }


    template <int dim>
    typename ExtendedLattice<dim>::Cell
    ExtendedLattice<dim>::cell_of_node(const unsigned int i) const
    {
      const HalfPoint p = half_point(i);
      Cell            c;
      for (unsigned int d = 0; d < dim; ++d)
        c[d] = (p[d] - 1) / 2;
      return c;
    }


    template <int dim>
    Point<dim>
    ExtendedLattice<dim>::location(const HalfPoint &p) const
    {
      Point<dim> x;
      for (unsigned int d = 0; d < dim; ++d)
        x[d] = x0[d] + 0.5 * h * p[d];
      return x;
    }


    template <int dim>
    long long
    ExtendedLattice<dim>::half_key(const HalfPoint &p) const
    {
      long long k = 0, s = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          k += (p[d] + 2 * margin_cells + 2) * s;
          s *= 2 * (extents[d] + 2 * margin_cells) + 5;
        }
      return k;
    }


    template <int dim>
    unsigned int
    ExtendedLattice<dim>::nearest_body(const Cell &c) const
    {
      long long    best_length = -1;
      int          best_key    = INT_MAX;
      unsigned int best        = numbers::invalid_unsigned_int;
      for (unsigned int s = 0; s < search_offsets.size(); ++s)
        {
          if (best_length >= 0 && search_length2[s] > best_length)
            break;
          Cell q;
          for (unsigned int d = 0; d < dim; ++d)
            q[d] = c[d] + search_offsets[s][d];
          if (!inside(q))
            continue;
          const int  k  = key(q);
          const auto it = body.find(k);
          if (it != body.end() && k < best_key)
            {
              best_length = search_length2[s];
              best_key    = k;
              best        = it->second;
            }
        }
      return best;
    }


    template <int dim>
    typename ExtendedLattice<dim>::Status
    ExtendedLattice<dim>::status(const Cell &c) const
    {
      if (!inside(c))
        return Status::none;
      const int k = key(c);
      if (body.count(k))
        return Status::body;
      const auto it = status_cache.find(k);
      if (it != status_cache.end())
        return it->second;
      const Status s  = nearest_body(c) != numbers::invalid_unsigned_int ?
                          Status::fictitious :
                          Status::none;
      status_cache[k] = s;
      return s;
    }


    template <int dim>
    const std::vector<std::pair<int, unsigned int>> &
    ExtendedLattice<dim>::owned_fictitious() const
    {
      return fictitious;
    }


    template <int dim>
    unsigned int
    ExtendedLattice<dim>::n_fictitious() const
    {
      return n_fictitious_global;
    }


    template class ExtendedLattice<2>;
    template class ExtendedLattice<3>;
  } // namespace Discretization
} // namespace PeriDEAL
