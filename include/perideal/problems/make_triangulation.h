#ifndef perideal_problems_make_triangulation_h
#define perideal_problems_make_triangulation_h

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria_base.h>

#include <memory>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * The mesh of a @p dim-dimensional run (Simulator, and tests that build
     * the same mesh): p4est in 2D and 3D; in 1D, where p4est has none, a
     * shared triangulation (every process holds the whole line)
     * partitioned in z-order, which for a line is into contiguous pieces.
     */
    template <int dim>
    std::unique_ptr<dealii::parallel::TriangulationBase<dim>>
    make_triangulation(const MPI_Comm communicator);
  } // namespace Problems
} // namespace PeriDEAL

#endif
