// The adaptive switch of the hybrid scheme (BondOperator::
// switch_critical_nodes(), hybrid-collocation paper Eq. 65) on a distributed
// uniform 2D grid, bond-based, linear kinematics, critical stretch s0 at
// every node. Kinds of check:
//  - brute force: the switched nodes are exactly the owned collocation
//    nodes with a bond (any offset of the full stencil, found here through
//    the lattice coordinates) whose stretch n.(u_j - u_i)/r reaches
//    alpha s0, counted independently; and the late switches exactly those
//    with a bond already at s0;
//  - comparison of evaluations: after the switch the forces of switched
//    nodes are those of an all-standard operator (the same kernel), and
//    those of the remaining collocation nodes are unchanged, bitwise;
//  - property: a second switch with the same field switches nothing (nodes
//    never switch back or twice);
//  - the printed counts do not depend on the number of MPI ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  constexpr int                    dim     = 2;
  const MPI_Comm                   comm    = MPI_COMM_WORLD;
  const unsigned int               n       = 30;
  const double                     horizon = 3, s0 = 1e-2, alpha = 0.8;

  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n, 0, n);
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);
  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection("bond-based");
  prm.set("Poisson's ratio", "0.3333333333333333");
  prm.set("Plane model", "plane stress");
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create("bond-based", prm);

  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, horizon + std::sqrt(dim));
  Discretization::NeighborList<dim> lists;
  lists.reinit(nodes,
               horizon,
               PeriDEAL::Quadrature::ExactPartialVolume<dim>(),
               false,
               false);
  Discretization::BondState<dim> state, state_standard;
  state.reinit(nodes, lists);
  state_standard.reinit(nodes, lists);
  Operators::BondOperator<dim> op, standard;
  op.reinit(nodes, lists, *model, horizon, &state);
  standard.reinit(nodes, lists, *model, horizon, &state_standard);
  const std::vector<double> critical(nodes.size(), s0);
  op.set_kinematics(false, critical);
  standard.set_kinematics(false, critical);
  op.use_collocation(PeriDEAL::Quadrature::CollocationSettings());

  // A band of high strain along x = 15: u_x = s w tanh((x - 15) / w), with
  // the largest stretch s (above s0 in the middle of the band, below alpha
  // s0 away from it), plus a small shear.
  typename Operators::BondOperator<dim>::VectorType u, f_before, f_after,
    f_standard;
  for (auto *v : {&u, &f_before, &f_after, &f_standard})
    op.initialize_dof_vector(*v);
  const auto field = [&](const Point<dim> &x) {
    Tensor<1, dim> v;
    const double   w = 2.5, s = 1.15 * s0;
    v[0] = s * w * std::tanh((x[0] - 15.) / w) + 1e-4 * x[1];
    v[1] = 2e-4 * x[0];
    return v;
  };
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      const Tensor<1, dim> value = field(nodes[i].location);
      for (unsigned int c = 0; c < dim; ++c)
        u[nodes[i].dofs[c]] = value[c];
    }
  u.update_ghost_values();

  // Brute force: the largest stretch of each owned collocation node over
  // the stencil offsets, through the lattice.
  const auto       &lattice  = lists.lattice();
  unsigned int      expected = 0, expected_late = 0;
  unsigned int      collocation_in = 0;
  std::vector<char> was_collocation(nodes.n_owned(), 0);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      if (!op.is_collocation_node(i))
        continue;
      was_collocation[i] = 1;
      ++collocation_in;
      double largest = -1e300;
      for (const auto &o : lists.stencil())
        {
          auto y = lattice.coordinates(i);
          for (unsigned int d = 0; d < dim; ++d)
            y[d] += o.offset[d];
          const unsigned int   j  = lattice.node_at(y);
          const Tensor<1, dim> xi = nodes[j].location - nodes[i].location;
          double               e  = 0;
          for (unsigned int c = 0; c < dim; ++c)
            e +=
              xi[c] / xi.norm() * (u[nodes[j].dofs[c]] - u[nodes[i].dofs[c]]);
          largest = std::max(largest, e / xi.norm());
        }
      expected += largest >= alpha * s0;
      expected_late += largest >= s0;
    }
  expected       = Utilities::MPI::sum(expected, comm);
  expected_late  = Utilities::MPI::sum(expected_late, comm);
  collocation_in = Utilities::MPI::sum(collocation_in, comm);

  op.apply(u, f_before);
  const std::size_t switched = op.switch_critical_nodes(u, alpha);
  const std::size_t late     = op.n_missed_switches();
  op.apply(u, f_after);
  standard.apply(u, f_standard);
  const std::size_t again = op.switch_critical_nodes(u, alpha);
  const std::size_t left  = op.n_collocation_nodes();

  double       switched_diff = 0, scale = 0;
  bool         unchanged  = true;
  unsigned int n_switched = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      {
        const auto dof = nodes[i].dofs[c];
        scale          = std::max(scale, std::abs(f_standard[dof]));
        if (was_collocation[i] && !op.is_collocation_node(i))
          {
            switched_diff =
              std::max(switched_diff, std::abs(f_after[dof] - f_standard[dof]));
            n_switched += (c == 0);
          }
        else if (op.is_collocation_node(i))
          unchanged = unchanged && f_after[dof] == f_before[dof];
      }
  switched_diff = Utilities::MPI::max(switched_diff, comm);
  scale         = Utilities::MPI::max(scale, comm);
  n_switched    = Utilities::MPI::sum(n_switched, comm);
  unchanged     = Utilities::MPI::min(unchanged ? 1 : 0, comm) == 1;

  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << "2D bond-based, " << n << "^2 nodes, m = 3, s0 = " << s0
              << ", alpha = " << alpha << ": " << collocation_in
              << " collocation nodes, " << switched << " switched (" << late
              << " late), " << left << " left\n"
              << "  switched = brute-force count of nodes with a bond at "
                 "alpha s0 (> 0): "
              << (switched == expected && switched > 0 ? "yes" : "NO")
              << "\n  late = brute-force count with a bond at s0 (> 0): "
              << (late == expected_late && late > 0 ? "yes" : "NO")
              << "\n  switched nodes have the standard forces (<= 1e-14 "
                 "relative): "
              << (n_switched == switched && switched_diff <= 1e-14 * scale ?
                    "yes" :
                    "NO")
              << "\n  the other collocation nodes keep their forces "
                 "bitwise: "
              << (unchanged ? "yes" : "NO")
              << "\n  a second switch with the same field switches none: "
              << (again == 0 ? "yes" : "NO") << std::endl;
}
