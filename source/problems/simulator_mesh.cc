/**
 * @file
 * The mesh of a Simulator: the coarse mesh of the MeshGenerator chosen with
 * 'Geometry/Mesh' (after the memory guard when its size is known), globally
 * refined; then the smallest cell side
 * h, the extent of the body and the horizon.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/simulator.h>

#include <iomanip>
#include <limits>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    Simulator<dim>::make_mesh()
    {
      TimerOutput::Scope scope(timer, "mesh");
      if (const auto coarse = mesh_generator->coarse_size())
        check_memory_estimate(*coarse);
      mesh_generator->create_mesh(*triangulation, global_refinements);

      // The smallest cell side and the extent of the body.
      h = std::numeric_limits<double>::max();
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      // Every cell must be an axis-aligned box (a clear error otherwise),
      // before any size is derived from it; the check fails on the process
      // that owns the cell, and all processes stop with its message.
      check_on_all_ranks(
        [&]() {
          for (const auto &cell : triangulation->active_cell_iterators())
            if (cell->is_locally_owned())
              {
                const BoundingBox<dim> box = Discretization::cell_box(*cell);
                for (unsigned int d = 0; d < dim; ++d)
                  h = std::min(h, box.side_length(d));
                for (const unsigned int v : cell->vertex_indices())
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                      upper[d] = std::max(upper[d], cell->vertex(v)[d]);
                    }
              }
        },
        communicator);
      h                      = Utilities::MPI::min(h, communicator);
      double smallest_extent = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        smallest_extent =
          std::min(smallest_extent,
                   Utilities::MPI::max(upper[d], communicator) -
                     Utilities::MPI::min(lower[d], communicator));

      if (horizon_specification == HorizonSpecification::m_ratio)
        horizon = m_ratio * h;
      else
        {
          horizon = horizon_length;
          m_ratio = horizon / h;
        }
      AssertThrow(
        horizon < smallest_extent,
        ExcInvalidInput(horizon_entry().first,
                        horizon_entry().second,
                        "the horizon " + format_number(horizon) +
                          " is not smaller than the smallest extent of the "
                          "body, " +
                          format_number(smallest_extent) +
                          "; use a smaller horizon or a larger body"));

      summary.h       = h;
      summary.horizon = horizon;
      summary.n_ranks = Utilities::MPI::n_mpi_processes(communicator);
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time()
            << " s] mesh: " << triangulation->n_global_active_cells()
            << " cells, h = " << std::defaultfloat << std::setprecision(10) << h
            << ", horizon = " << horizon << " (m-ratio " << m_ratio << "), "
            << Utilities::MPI::n_mpi_processes(communicator)
            << " MPI process(es)" << std::endl;
    }


    template <int dim>
    std::pair<std::string, std::string>
    Simulator<dim>::horizon_entry() const
    {
      if (horizon_specification == HorizonSpecification::m_ratio)
        return {"Horizon/m-ratio", format_number(m_ratio)};
      return {"Horizon/Length", format_number(horizon_length)};
    }


#define PERIDEAL_INSTANTIATE(dim)                                              \
  template void                                Simulator<dim>::make_mesh();    \
  template std::pair<std::string, std::string> Simulator<dim>::horizon_entry() \
    const;
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
  } // namespace Problems
} // namespace PeriDEAL
