// The communication volume of a time step on P processes: the p4est
// partition of the cube of run_lammps_comparison.sh (N^3 cells built as
// 'subdivided box' builds them: (N / 2^r)^3 trees refined r times), the
// nodes each process holds as ghosts for a coupling range of one horizon
// (bond-based) or two (state-based) as Simulator computes it, and the
// processes it exchanges with. The input of the strong-scaling estimate of
// issue 25, item 3 (bench/dynamics/run_partition_volume.sh,
// doc/explicit-dynamics.md, "MPI as good as threads").
//
// Usage: mpirun -np P perideal-partition-volume N m two_horizons
//   N             cells per direction
//   m             horizon in cells (3.0001 in the comparison)
//   two_horizons  1: state-based (LPS), 0: bond-based (PMB)
// Prints one CSV line on rank 0:
//   processes,n,m,two_horizons,owned_min,owned_max,ghosts_avg,ghosts_max,
//   neighbours_avg,neighbours_max

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/node_set.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>

using namespace dealii;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  if (argc < 4)
    {
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cerr << "Usage: " << argv[0] << " N m two_horizons" << std::endl;
      return 1;
    }
  const unsigned int n   = std::atoi(argv[1]);
  const double       m   = std::atof(argv[2]);
  const bool         two = std::atoi(argv[3]) == 1;
  unsigned int       r   = 0;
  while (r < 10 && n % (2u << r) == 0)
    ++r;
  const double h = 1e-3;

  parallel::distributed::Triangulation<3> tria(comm);
  const unsigned int                      coarse = n >> r;
  GridGenerator::subdivided_hyper_rectangle(tria,
                                            {coarse, coarse, coarse},
                                            Point<3>(),
                                            Point<3>(n * h, n * h, n * h),
                                            true);
  tria.refine_global(r);
  DoFHandler<3> dof_handler(tria);
  FESystem<3>   fe(FE_DGQ<3>(0), 3);
  dof_handler.distribute_dofs(fe);
  // As Simulator: horizon plus a cell diameter, twice for state-based
  // models.
  const double horizon  = m * h;
  const double diameter = std::sqrt(3.) * h;
  const double range    = two ? 2 * (horizon + diameter) : horizon + diameter;
  PeriDEAL::Discretization::NodeSet<3> nodes;
  nodes.reinit(dof_handler, range);

  // The processes it exchanges ghost values with (either way).
  const auto                partitioner = nodes.node_partitioner();
  std::vector<unsigned int> neighbours;
  for (const auto &[rank, count] : partitioner->ghost_targets())
    neighbours.push_back(rank);
  for (const auto &[rank, count] : partitioner->import_targets())
    neighbours.push_back(rank);
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()),
                   neighbours.end());

  const auto owned_stats = Utilities::MPI::min_max_avg(nodes.n_owned(), comm);
  const auto ghost_stats = Utilities::MPI::min_max_avg(nodes.n_ghost(), comm);
  const auto neighbour_stats =
    Utilities::MPI::min_max_avg(neighbours.size(), comm);
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << Utilities::MPI::n_mpi_processes(comm) << ',' << n << ',' << m
              << ',' << (two ? 1 : 0) << ',' << owned_stats.min << ','
              << owned_stats.max << ',' << ghost_stats.avg << ','
              << ghost_stats.max << ',' << neighbour_stats.avg << ','
              << neighbour_stats.max << std::endl;
}
