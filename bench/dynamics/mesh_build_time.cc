// The time deal.II takes to build a box of C^3 coarse cells refined R times
// on a parallel::distributed::Triangulation (or, with a third argument 1, a
// serial Triangulation): the measurement behind 'subdivided box' building
// from few trees (doc/explicit-dynamics.md, "Set-up in seconds").
//
// Usage: perideal-mesh-build-time C R [serial]
//   perideal-mesh-build-time 100 0     10^6 trees, no refinement
//   perideal-mesh-build-time 25 2      the same cells from 25^3 trees

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cstdlib>
#include <iostream>

using namespace dealii;

namespace
{
  template <typename TriangulationType>
  void
  build(TriangulationType &tria, const unsigned int C, const unsigned int R)
  {
    Timer timer;
    GridGenerator::subdivided_hyper_rectangle(tria,
                                              {C, C, C},
                                              Point<3>(),
                                              Point<3>(1, 1, 1),
                                              true);
    const double coarse = timer.wall_time();
    tria.refine_global(R);
    std::cout << "coarse " << coarse << " s, refine "
              << timer.wall_time() - coarse << " s, "
              << tria.n_global_active_cells() << " cells" << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 3)
    {
      std::cerr << "Usage: " << argv[0] << " C R [serial]" << std::endl;
      return 1;
    }
  const unsigned int C = std::atoi(argv[1]), R = std::atoi(argv[2]);
  if (argc > 3 && std::atoi(argv[3]) == 1)
    {
      Triangulation<3> tria;
      std::cout << "serial: ";
      build(tria, C, R);
    }
  else
    {
      parallel::distributed::Triangulation<3> tria(MPI_COMM_WORLD);
      std::cout << "parallel::distributed: ";
      build(tria, C, R);
    }
}
