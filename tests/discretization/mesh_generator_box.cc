// The mesh of 'Geometry/Mesh = subdivided box': MeshGenerator::create_mesh()
// builds the box from Subdivisions / 2^r coarse cells refined r + 'Global
// refinements' times (a p4est forest of few trees: seconds instead of a
// minute at 10^6 cells) and snaps the vertices to the uniform lattice. The
// PD nodes must be where they were: every locally owned cell is looked up,
// by its centre, in GridGenerator::subdivided_hyper_rectangle() of the fine
// subdivisions on a serial Triangulation (the independent reference, whose
// vertices are lower + i (upper - lower) / n), and its vertices and the
// boundary ids of its faces must agree to the bit; the cells found, summed
// over the processes, must be all cells of the reference. Cases with r = 0
// (the subdivisions are odd), r > 0, with and without global refinements,
// in 1D (a shared triangulation), 2D and 3D, on corners whose coordinates
// round.
// Kind of test: independent reference (deal.II's own box), 1 and 2 ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <perideal/problems/make_triangulation.h>
#include <perideal/problems/mesh_generator.h>

#include <array>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  template <int dim>
  std::array<double, dim>
  key(const Point<dim> &p)
  {
    std::array<double, dim> k;
    for (unsigned int d = 0; d < dim; ++d)
      k[d] = p[d];
    return k;
  }


  template <int dim>
  void
  check(const std::vector<unsigned int> &subdivisions,
        const unsigned int               refinements)
  {
    const MPI_Comm     comm  = MPI_COMM_WORLD;
    const double       lo[3] = {-0.3, 0.1, 1.7}, hi[3] = {1.1, 0.75, 2.3};
    Point<dim>         lower, upper;
    std::ostringstream text_sub, text_lo, text_hi;
    for (unsigned int d = 0; d < dim; ++d)
      {
        lower[d] = lo[d];
        upper[d] = hi[d];
        text_sub << (d > 0 ? "," : "") << subdivisions[d];
        text_lo << (d > 0 ? "," : "") << lo[d];
        text_hi << (d > 0 ? "," : "") << hi[d];
      }

    ParameterHandler prm;
    prm.declare_entry("Subdivisions", text_sub.str());
    prm.declare_entry("Lower corner", text_lo.str());
    prm.declare_entry("Upper corner", text_hi.str());
    auto generator =
      Problems::MeshGeneratorRegistry<dim>::create("subdivided box");
    generator->parse_parameters(prm);
    auto triangulation = Problems::make_triangulation<dim>(comm);
    generator->create_mesh(*triangulation, refinements);

    // The reference: the fine box built directly.
    std::vector<unsigned int> fine(subdivisions);
    for (auto &n : fine)
      n <<= refinements;
    Triangulation<dim> reference;
    GridGenerator::subdivided_hyper_rectangle(reference,
                                              fine,
                                              lower,
                                              upper,
                                              true);
    std::map<std::array<double, dim>,
             typename Triangulation<dim>::active_cell_iterator>
      by_centre;
    for (const auto &cell : reference.active_cell_iterators())
      by_centre[key(cell->center())] = cell;

    unsigned int found = 0, wrong = 0;
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto it = by_centre.find(key(cell->center()));
          if (it == by_centre.end())
            {
              ++wrong;
              continue;
            }
          bool same = true;
          for (const unsigned int v : cell->vertex_indices())
            same = same && cell->vertex(v) == it->second->vertex(v);
          for (const unsigned int f : cell->face_indices())
            same = same &&
                   cell->face(f)->at_boundary() ==
                     it->second->face(f)->at_boundary() &&
                   cell->face(f)->boundary_id() ==
                     it->second->face(f)->boundary_id();
          if (same)
            ++found;
          else
            ++wrong;
        }
    found = Utilities::MPI::sum(found, comm);
    wrong = Utilities::MPI::sum(wrong, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      std::cout << dim << "D, Subdivisions = " << text_sub.str()
                << ", Global refinements = " << refinements << ": "
                << triangulation->n_global_active_cells() << " cells ("
                << triangulation->n_cells(0) << " coarse), " << found << " of "
                << reference.n_active_cells()
                << " found at the reference's centres with its vertices and "
                   "boundary ids to the bit: "
                << (found == reference.n_active_cells() && wrong == 0 &&
                        triangulation->n_global_active_cells() ==
                          reference.n_active_cells() ?
                      "yes" :
                      "NO")
                << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<1>({40}, 0);
  check<1>({6}, 2);
  check<2>({12, 20}, 0);
  check<2>({7, 5}, 0);
  check<2>({6, 10}, 1);
  check<3>({8, 12, 4}, 0);
  check<3>({6, 6, 10}, 1);
  check<3>({5, 3, 7}, 1);
}
