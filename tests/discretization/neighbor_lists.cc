// PD nodes on a distributed mesh: the nonlocal ghost exchange brings every
// off-process node the neighbour lists need, and the lists equal a brute
// force search over all nodes of the mesh, for owned nodes and for the
// off-process neighbours whose lists state-based models need. Run on 1, 2
// and 3 ranks: the printed totals must not depend on the partition.

#include <deal.II/base/mpi.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <iomanip>
#include <iostream>
#include <map>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
void
check(const std::vector<unsigned int> &repetitions,
      const double                     m_ratio,
      const unsigned int               n_refinements)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  Point<dim>                                upper;
  for (unsigned int d = 0; d < dim; ++d)
    upper[d] = repetitions[d];
  GridGenerator::subdivided_hyper_rectangle(tria,
                                            repetitions,
                                            Point<dim>(),
                                            upper);
  // A locally refined mesh when asked: general boxes, no uniform table.
  for (unsigned int r = 0; r < n_refinements; ++r)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center()[0] < 0.3 * upper[0])
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }

  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  const double                 horizon = m_ratio; // the coarse spacing is 1
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim)));
  const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
  Discretization::NeighborList<dim>                   lists;
  lists.reinit(nodes, horizon, exact, /*with_ghost_lists*/ true);

  // Brute force over all nodes of the mesh, gathered on every process.
  const auto gathered =
    Utilities::MPI::all_gather(comm,
                               std::vector<Discretization::Node<dim>>(
                                 nodes.nodes().begin(),
                                 nodes.nodes().begin() + nodes.n_owned()));
  std::map<types::global_dof_index, Discretization::Node<dim>> all;
  for (const auto &part : gathered)
    for (const auto &node : part)
      all[node.dofs[0]] = node;

  bool         lists_agree  = true;
  unsigned int n_checked    = 0;
  double       owned_weight = 0;
  for (unsigned int i = 0; i < nodes.size(); ++i)
    if (lists.has_list(i))
      {
        std::map<types::global_dof_index, double> brute;
        for (const auto &[id, other] : all)
          if (id != nodes[i].dofs[0])
            {
              const double beta =
                exact.weight(nodes[i].location, horizon, other.cell);
              if (beta > 0)
                brute[id] = beta * other.volume();
            }
        std::map<types::global_dof_index, double> listed;
        for (const auto &bond : lists.bonds(i))
          listed[nodes[bond.neighbor].dofs[0]] = bond.weight;
        bool same = brute.size() == listed.size();
        for (const auto &[id, w] : brute)
          same =
            same && listed.count(id) && std::abs(listed[id] - w) <= 1e-14 * w;
        lists_agree = lists_agree && same;
        ++n_checked;
        if (i < nodes.n_owned())
          for (const auto &bond : lists.bonds(i))
            owned_weight += bond.weight;
      }

  lists_agree  = Utilities::MPI::min(lists_agree ? 1 : 0, comm) == 1;
  owned_weight = Utilities::MPI::sum(owned_weight, comm);
  const auto n_bonds =
    Utilities::MPI::sum<unsigned long>(lists.n_owned_bonds(), comm);
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << dim << "D, m = " << m_ratio << ", " << all.size() << " nodes"
              << (n_refinements ? " (locally refined)" : "") << ": " << n_bonds
              << " bonds, total weight " << std::setprecision(12)
              << owned_weight << "; owned and ghost lists equal brute force: "
              << (lists_agree ? "yes" : "NO") << '\n';
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>({14, 9}, 2.5, 0);
  check<2>({14, 9}, 1.8, 1);
  check<3>({7, 6, 5}, 1.5, 0);
  check<3>({7, 6, 5}, 2.2, 1);
}
