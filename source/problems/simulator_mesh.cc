/**
 * @file
 * The mesh of a Simulator: a subdivided box (after the memory guard) or a
 * mesh file read with GridIn, globally refined; then the smallest cell side
 * h, the extent of the body and the horizon.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

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
      if (mesh_kind == "subdivided box")
        check_memory_estimate();
      if (mesh_kind == "subdivided box")
        GridGenerator::subdivided_hyper_rectangle(*triangulation,
                                                  subdivisions,
                                                  lower_corner,
                                                  upper_corner,
                                                  true);
      else
        {
          // GridIn's own messages ("(none)", "No vertices given") name
          // neither the file nor the entry; every process reads the file, so
          // every process fails alike.
          GridIn<dim> grid_in;
          grid_in.attach_triangulation(*triangulation);
          std::string error;
          try
            {
              grid_in.read(mesh_file);
              if (triangulation->n_global_active_cells() == 0)
                error = "it holds no cells";
            }
          catch (const ExceptionBase &exc)
            {
              std::ostringstream info;
              exc.print_info(info);
              error = Utilities::trim(info.str());
            }
          catch (const std::exception &exc)
            {
              error = exc.what();
            }
          AssertThrow(
            error.empty(),
            ExcInvalidInput(
              "Geometry/Mesh file",
              mesh_file,
              "reading it as a " + std::to_string(dim) + "D mesh failed (" +
                (error.empty() ? "" : error) +
                "); check that the extension names its format (.msh, .vtk, "
                ".inp, .ucd, ...), that the file is complete, and that it "
                "holds " +
                std::to_string(dim) +
                "D cells ('Dimension = " + std::to_string(dim) + "')"));
        }
      triangulation->refine_global(global_refinements);

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

      if (horizon_specification == "m-ratio")
        horizon = m_ratio * h;
      else
        {
          horizon = horizon_length;
          m_ratio = horizon / h;
        }
      AssertThrow(
        horizon < smallest_extent,
        ExcInvalidInput(horizon_specification == "m-ratio" ? "Horizon/m-ratio" :
                                                             "Horizon/Length",
                        horizon_specification == "m-ratio" ?
                          format_number(m_ratio) :
                          format_number(horizon_length),
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


    template void
    Simulator<1>::make_mesh();
    template void
    Simulator<2>::make_mesh();
    template void
    Simulator<3>::make_mesh();
  } // namespace Problems
} // namespace PeriDEAL
