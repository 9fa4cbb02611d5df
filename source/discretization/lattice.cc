#include <deal.II/base/mpi.h>

#include <perideal/discretization/lattice.h>

#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Discretization
  {
    template <int dim>
    void
    Lattice<dim>::reinit(const NodeSet<dim> &nodes, const bool at_cell_centres)
    {
      const MPI_Comm comm = nodes.get_communicator();
      coords.clear();
      slots.clear();
      slot_to_node.clear();

      double     min_side = std::numeric_limits<double>::max(), max_side = 0;
      Point<dim> lowest;
      for (unsigned int d = 0; d < dim; ++d)
        lowest[d] = std::numeric_limits<double>::max();
      for (const auto &node : nodes.nodes())
        for (unsigned int d = 0; d < dim; ++d)
          {
            const double side = node.cell.side_length(d);
            min_side          = std::min(min_side, side);
            max_side          = std::max(max_side, side);
            lowest[d]         = std::min(lowest[d],
                                 at_cell_centres ? node.cell.center()[d] :
                                                           node.location[d]);
          }
      min_side = Utilities::MPI::min(min_side, comm);
      max_side = Utilities::MPI::max(max_side, comm);
      for (unsigned int d = 0; d < dim; ++d)
        lowest[d] = Utilities::MPI::min(lowest[d], comm);
      bool equal_cubes = (max_side - min_side <= 1e-12 * max_side);
      h                = max_side;

      // Lattice coordinates; a centre off the lattice makes the set
      // non-uniform on every process.
      bool on_lattice = equal_cubes;
      if (equal_cubes)
        {
          coords.resize(nodes.size());
          for (unsigned int i = 0; i < nodes.size() && on_lattice; ++i)
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double x = ((at_cell_centres ? nodes[i].cell.center()[d] :
                                                     nodes[i].location[d]) -
                                  lowest[d]) /
                                 h;
                coords[i][d] = std::llround(x);
                on_lattice =
                  on_lattice && std::abs(x - double(coords[i][d])) < 1e-9;
              }
        }
      uniform = Utilities::MPI::min(on_lattice ? 1 : 0, comm) == 1;
      if (!uniform)
        {
          coords.clear();
          h = 0;
          return;
        }

      std::array<std::int64_t, dim> upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          box_lower[d] = std::numeric_limits<std::int64_t>::max();
          upper[d]     = std::numeric_limits<std::int64_t>::min();
        }
      for (const auto &x : coords)
        for (unsigned int d = 0; d < dim; ++d)
          {
            box_lower[d] = std::min(box_lower[d], x[d]);
            upper[d]     = std::max(upper[d], x[d]);
          }
      std::size_t n = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          box_size[d] = nodes.size() > 0 ? upper[d] - box_lower[d] + 1 : 0;
          n *= box_size[d];
        }
      slot_to_node.assign(n, -1);
      slots.resize(nodes.size());
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          std::size_t s = 0;
          for (int d = dim - 1; d >= 0; --d)
            s = s * box_size[d] + (coords[i][d] - box_lower[d]);
          slots[i]        = s;
          slot_to_node[s] = i;
        }
    }


    template <int dim>
    bool
    Lattice<dim>::is_uniform() const
    {
      return uniform;
    }


    template <int dim>
    double
    Lattice<dim>::spacing() const
    {
      return h;
    }


    template <int dim>
    const std::array<std::int64_t, dim> &
    Lattice<dim>::coordinates(const unsigned int i) const
    {
      return coords[i];
    }


    template <int dim>
    std::size_t
    Lattice<dim>::slot(const unsigned int i) const
    {
      return slots[i];
    }


    template <int dim>
    std::size_t
    Lattice<dim>::n_slots() const
    {
      return slot_to_node.size();
    }


    template <int dim>
    int
    Lattice<dim>::node_at_slot(const std::size_t s) const
    {
      return slot_to_node[s];
    }


    template <int dim>
    int
    Lattice<dim>::node_at(const std::array<std::int64_t, dim> &x) const
    {
      if (!uniform)
        return -1;
      std::size_t s = 0;
      for (int d = dim - 1; d >= 0; --d)
        {
          const std::int64_t k = x[d] - box_lower[d];
          if (k < 0 || k >= box_size[d])
            return -1;
          s = s * box_size[d] + k;
        }
      return slot_to_node[s];
    }


    template <int dim>
    bool
    Lattice<dim>::box_holds(const std::array<std::int64_t, dim> &x,
                            const std::int64_t                   margin) const
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          const std::int64_t k = x[d] - box_lower[d];
          if (k < margin || k + margin >= box_size[d])
            return false;
        }
      return true;
    }


    template <int dim>
    std::ptrdiff_t
    Lattice<dim>::slot_offset(const std::array<int, dim> &offset) const
    {
      std::ptrdiff_t s = 0;
      for (int d = dim - 1; d >= 0; --d)
        s = s * static_cast<std::ptrdiff_t>(box_size[d]) + offset[d];
      return s;
    }


    template class Lattice<1>;
    template class Lattice<2>;
    template class Lattice<3>;
  } // namespace Discretization
} // namespace PeriDEAL
