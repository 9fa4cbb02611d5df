// The crack-tip tracker (IO::CrackTipTracker) on a synthetic damage field,
// against a brute force over all nodes gathered on every process (Kind of
// test: brute-force reference, 1 and 2 ranks):
//
// - damage 1 on a straight crack along y = 0 from x = 0 to 20 (two rows
//   of nodes) and 0.8 on two symmetric branches y = +-(x - 20) tan(25 deg)
//   half a cell wide: the tip is the damaged node farthest from the origin
//   (0, 0), ties (upper and lower branch) broken towards the lower y; with
//   the threshold 0.9 the tip is the end of the straight crack;
// - the front spread is the largest distance of a front node (within one
//   horizon of the tip distance) from the line origin-tip;
// - a region restricted to y > 0 follows the upper branch alone;
// - without damage the tip is the origin.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/node_set.h>
#include <perideal/io/crack_tip_tracker.h>

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

double
synthetic_damage(const Point<2> &x)
{
  const double slope = std::tan(25. * numbers::PI / 180.);
  if (x[0] < 20)
    return std::abs(x[1]) < 1 ? 1. : 0.;
  const double branch = (x[0] - 20) * slope;
  if (x[0] > 36)
    return 0;
  return std::abs(std::abs(x[1]) - branch) < 0.5 ? 0.8 : 0.1;
}

// The brute force: every node of every process.
std::vector<double>
brute_force(const std::vector<Point<2>> &all,
            const double                 threshold,
            const double                 y_min,
            const double                 band)
{
  const Point<2> origin;
  int            best = -1;
  for (unsigned int i = 0; i < all.size(); ++i)
    {
      if (synthetic_damage(all[i]) < threshold || all[i][1] < y_min)
        continue;
      if (best < 0)
        {
          best = i;
          continue;
        }
      const double d = all[i].distance(origin), e = all[best].distance(origin);
      if (d > e ||
          (d == e && (all[i][0] < all[best][0] ||
                      (all[i][0] == all[best][0] && all[i][1] < all[best][1]))))
        best = i;
    }
  if (best < 0)
    return {0, 0, 0, 0};
  const Point<2> tip    = all[best];
  const double   R      = tip.norm();
  const auto     n      = tip / R;
  double         spread = 0;
  for (const auto &x : all)
    if (synthetic_damage(x) >= threshold && x[1] >= y_min &&
        x.norm() >= R - band)
      spread = std::max(spread, std::abs(n[0] * x[1] - n[1] * x[0]));
  return {tip[0], tip[1], R, spread};
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize        mpi(argc, argv, 1);
  const MPI_Comm                          comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<2> tria(comm);
  GridGenerator::subdivided_hyper_rectangle(tria,
                                            {50, 40},
                                            Point<2>(-5, -20),
                                            Point<2>(45, 20));
  DoFHandler<2> dof_handler(tria);
  FESystem<2>   fe(FE_DGQ<2>(0), 2);
  dof_handler.distribute_dofs(fe);
  Discretization::NodeSet<2> nodes;
  nodes.reinit(dof_handler, 3);

  std::vector<Point<2>> owned;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    owned.push_back(nodes[i].location);
  std::vector<Point<2>> all;
  for (const auto &part : Utilities::MPI::all_gather(comm, owned))
    all.insert(all.end(), part.begin(), part.end());

  const double band   = 3;
  bool         all_ok = true;
  for (const auto &[region, y_min, threshold] :
       {std::make_tuple(std::string(""), -1e9, 0.35),
        std::make_tuple(std::string("-10, 0, 50, 30"), 0., 0.35),
        std::make_tuple(std::string(""), -1e9, 0.9),
        std::make_tuple(std::string("-10, 25, 50, 30"), 25., 0.35)})
    {
      ParameterHandler prm;
      IO::CrackTipTracker<2>::declare_parameters(prm);
      prm.set("Crack tip origin", "0, 0");
      prm.set("Crack tip region", region);
      prm.set("Crack tip damage", std::to_string(threshold));
      IO::CrackTipTracker<2> tracker;
      tracker.parse_parameters(prm, "test");
      const auto values = tracker.evaluate(
        nodes,
        [&](const unsigned int i) {
          return synthetic_damage(nodes[i].location);
        },
        band,
        comm);
      const auto reference = brute_force(all, threshold, y_min, band);
      double     error     = 0;
      for (unsigned int k = 0; k < 4; ++k)
        error = std::max(error, std::abs(values[k] - reference[k]));
      const bool ok = error <= 1e-12;
      all_ok        = all_ok && ok;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "region '" << region << "', damage >= " << threshold
                  << ": tip (" << values[0] << ", " << values[1]
                  << "), distance " << std::setprecision(6) << values[2]
                  << ", front spread " << values[3]
                  << "; against the brute force <= 1e-12: "
                  << (ok ? "yes" : "no") << std::endl;
    }
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << (all_ok ? "OK" : "FAILED") << std::endl;
  return all_ok ? 0 : 1;
}
