// The exact partial volumes of all cells of a uniform grid add up to the
// measure of the horizon ball: sum_j beta_j + beta_self = 4/3 pi m^3 (pi m^2
// in 2D), checked to 1e-14 relative for m from below 1 to 50, including
// half-integers (cells tangent to the sphere). The m-ratios are distributed
// over the MPI ranks, so the .mpirun=2 variant checks that the harness runs
// tests in parallel and that the answers do not depend on the rank count.

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>

#include <perideal/quadrature/ball_box_intersection.h>
#include <perideal/quadrature/exact_partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <utility>
#include <vector>

using namespace dealii;
using namespace PeriDEAL::Quadrature;

template <int dim>
double
relative_error(const double m)
{
  const ExactPartialVolume<dim> exact;
  const UniformGridWeights<dim> table(exact, m);
  // The node's own cell counts with its own partial measure (all of it once
  // m >= sqrt(dim)/2).
  const double own =
    ball_box_intersection_measure(Point<dim>(), m, unit_cell<dim>({}));
  long double sum = own;
  for (const auto &entry : table.neighbours())
    sum += entry.beta;
  const double analytic = dim == 2 ? M_PI * m * m : 4. / 3. * M_PI * m * m * m;
  // neighbourhood_measure() counts the own cell the same way at every m.
  const double measure = table.neighbourhood_measure();
  AssertThrow(std::abs(measure - double(sum)) <= 1e-14 * analytic,
              ExcMessage("neighbourhood_measure() disagrees with the sum"));
  return std::abs(double(sum) / analytic - 1);
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const unsigned int rank    = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
  const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);

  const std::vector<double> m_ratios = {0.3,
                                        0.5,
                                        0.75,
                                        0.999,
                                        1.0,
                                        1.5,
                                        2.5,
                                        3.0,
                                        3.05,
                                        3.5,
                                        4.5,
                                        7.3,
                                        10.,
                                        10.5,
                                        20.,
                                        35.5,
                                        50.0};
  std::vector<double>       errors(2 * m_ratios.size(), 0.);
  for (unsigned int i = 0; i < m_ratios.size(); ++i)
    if (i % n_ranks == rank)
      {
        errors[2 * i]     = relative_error<2>(m_ratios[i]);
        errors[2 * i + 1] = relative_error<3>(m_ratios[i]);
      }
  std::vector<double> all_errors(errors.size());
  Utilities::MPI::sum(make_array_view(std::as_const(errors)),
                      MPI_COMM_WORLD,
                      make_array_view(all_errors));

  if (rank == 0)
    for (unsigned int i = 0; i < m_ratios.size(); ++i)
      for (unsigned int d = 0; d < 2; ++d)
        std::cout << d + 2 << "D m=" << m_ratios[i]
                  << ": sum of beta = ball measure to <= 1e-14 relative: "
                  << (all_errors[2 * i + d] <= 1e-14 ? "yes" : "NO") << '\n';
}
