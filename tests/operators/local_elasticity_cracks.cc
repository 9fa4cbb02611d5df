// The local elasticity matrix with cracks (the preconditioner of fracture
// runs): a dual cube is cut when every bond between its corners on the two
// sides of one of its mid-planes is broken, and its stiffness is then
// scaled by LocalElasticityOperator::cut_cube_factor.
//
// A crack is the half-plane y = y_c, x < x_c (y_c and x_c between node
// rows and columns; every z in 3D). The bonds crossing it are broken from
// the owned end only (BondState::synchronize() completes them), and one
// lone bond away from it is broken as well, which must cut no cube.
// References, counted by hand from the geometry:
// - the cut cubes are those straddling y_c whose upper x-corner lies
//   below x_c: floor(x_c - 1/2) columns (times n - 1 layers in 3D);
// - a rigid jump of u_y across y = y_c stores energy only in the cubes
//   that straddle y_c, each the same amount e, so the energy of the
//   cracked matrix over the intact one is (s - c + f c) / s, with s the
//   straddling cubes, c the cut ones and f the factor;
// - the same numbers on 1 and 2 processes (the masks of off-process
//   corners come from their owners).
// - the same on the coarse lattice of 'local elasticity/Coarsening = 2':
//   a coarse cube is cut when a cube of side h inside it is; the energy
//   ratio with the coarse cubes counted by hand.
// Kind of test: closed forms (counted by hand), 1 and 2 ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/local_elasticity_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

/// Whether the segment a-b crosses the crack y = y_c, x < x_c.
template <int dim>
bool
crosses_crack(const Point<dim> &a,
              const Point<dim> &b,
              const double      x_c,
              const double      y_c)
{
  if ((a[1] - y_c) * (b[1] - y_c) >= 0)
    return false;
  const double t = (y_c - a[1]) / (b[1] - a[1]);
  return a[0] + t * (b[0] - a[0]) < x_c;
}

template <int dim>
void
check(const unsigned int n_cells, const double horizon)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n_cells, 0, n_cells);
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection("bond-based");
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", "0.25");
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create("bond-based", prm);

  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim)));
  const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
  Discretization::NeighborList<dim>                   lists;
  lists.reinit(nodes, horizon, exact, false, false);
  Discretization::BondState<dim> state;
  state.reinit(nodes, lists);

  // Nodes at the cell centres k + 1/2: the crack between rows and columns.
  const double x_c = 0.5 * n_cells, y_c = 0.5 * n_cells;
  // The lone bond: between the nodes (n - 1/2, 1/2) and (n - 1/2, 3/2)
  // (z = 1/2), far from the crack's tip.
  Point<dim> lone_a, lone_b;
  lone_a[0] = lone_b[0] = n_cells - 0.5;
  lone_a[1]             = 0.5;
  lone_b[1]             = 1.5;
  if (dim == 3)
    lone_a[2] = lone_b[2] = 0.5;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int k = 0; k < lists.n_bonds(i); ++k)
      {
        const auto &a = nodes[i].location;
        const auto &b = nodes[state.neighbor(i, k)].location;
        if ((crosses_crack(a, b, x_c, y_c) && a[1] < y_c) ||
            (a.distance(lone_a) < 1e-12 && b.distance(lone_b) < 1e-12))
          state.break_bond(i, k);
      }
  state.synchronize();

  using LocalElasticity   = Operators::LocalElasticityOperator<dim>;
  const auto     &lattice = lists.lattice();
  const IndexSet &owned   = dof_handler.locally_owned_dofs();
  const auto      masks =
    LocalElasticity::broken_neighbor_masks(nodes, lattice, lists, state);
  const std::size_t n_cut = LocalElasticity::n_cut_cubes(nodes, lattice, masks);
  const std::size_t layers   = dim == 3 ? n_cells - 1 : 1;
  const std::size_t expected = std::size_t(std::floor(x_c - 0.5)) * layers;

  AffineConstraints<double> none;
  none.close();
  TrilinosWrappers::SparseMatrix intact, cracked;
  LocalElasticity::assemble(nodes, lattice, *model, none, intact);
  LocalElasticity::assemble(nodes, lattice, *model, none, cracked, &masks);

  // A rigid jump of u_y across y = y_c.
  TrilinosWrappers::MPI::Vector jump(owned, comm);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    jump[nodes[i].dofs[1]] = nodes[i].location[1] > y_c ? 1. : 0.;
  jump.compress(VectorOperation::insert);
  const double ratio =
    cracked.matrix_norm_square(jump) / intact.matrix_norm_square(jump);
  const double straddling = (n_cells - 1) * layers;
  const double f          = LocalElasticity::cut_cube_factor;
  const double reference  = (straddling - n_cut + f * n_cut) / straddling;

  std::cout << dim << "D, " << n_cells << "^" << dim
            << " nodes, crack y = " << y_c << ", x < " << x_c
            << ", one lone bond broken elsewhere\n"
            << "  cut cubes " << n_cut << ", by hand " << expected << ": "
            << (n_cut == expected ? "yes" : "NO")
            << "\n  energy of a jump across the crack, cracked / intact, "
               "against (s - c + f c) / s within 1e-12: "
            << (std::abs(ratio - reference) <= 1e-12 ? "yes" : "NO")
            << std::endl;
  if (std::abs(ratio - reference) > 1e-12)
    std::cout << "  (ratio " << ratio << ", reference " << reference << ")"
              << std::endl;

  // The same on every second node ('local elasticity/Coarsening = 2'): a
  // coarse cube (side 2) is cut when one of the cubes of side 1 it holds
  // is. By hand: the complete coarse cubes have lower lattice coordinates
  // 0, 2, ..., n - 3 (so (n - 1) / 2 of them per direction); one row of
  // them holds the node rows on both sides of y_c, the same jump in each;
  // a column is cut when its lower x-coordinate 2q lies below the
  // floor(x_c - 1/2) cut columns of the fine grid: (that + 1) / 2 columns.
  Operators::CoarseLattice<dim> coarse;
  coarse.reinit(nodes, lattice, none, 2);
  TrilinosWrappers::SparseMatrix coarse_intact, coarse_cracked;
  LocalElasticity::assemble(nodes,
                            lattice,
                            *model,
                            none,
                            coarse_intact,
                            nullptr,
                            &coarse);
  LocalElasticity::assemble(nodes,
                            lattice,
                            *model,
                            none,
                            coarse_cracked,
                            &masks,
                            &coarse);
  TrilinosWrappers::MPI::Vector coarse_jump(coarse.owned_dofs(), comm);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    if (coarse.is_coarse(i))
      coarse_jump[coarse.dof(i, 1)] = nodes[i].location[1] > y_c ? 1. : 0.;
  coarse_jump.compress(VectorOperation::insert);
  const double coarse_ratio = coarse_cracked.matrix_norm_square(coarse_jump) /
                              coarse_intact.matrix_norm_square(coarse_jump);
  const std::size_t coarse_columns = (n_cells - 1) / 2;
  const std::size_t coarse_layers  = dim == 3 ? (n_cells - 1) / 2 : 1;
  const std::size_t cut_columns =
    std::min(coarse_columns, (std::size_t(std::floor(x_c - 0.5)) + 1) / 2);
  const double coarse_straddling = coarse_columns * coarse_layers;
  const double coarse_cut        = cut_columns * coarse_layers;
  const double coarse_reference =
    (coarse_straddling - coarse_cut + f * coarse_cut) / coarse_straddling;
  std::cout << "  on every second node: energy of the jump, cracked / "
               "intact, against (s - c + f c) / s with s = "
            << coarse_straddling << ", c = " << coarse_cut << " within 1e-12: "
            << (std::abs(coarse_ratio - coarse_reference) <= 1e-12 ? "yes" :
                                                                     "NO")
            << std::endl;
  if (std::abs(coarse_ratio - coarse_reference) > 1e-12)
    std::cout << "  (ratio " << coarse_ratio << ", reference "
              << coarse_reference << ")" << std::endl;
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);
  check<2>(8, 3);
  check<3>(6, 2.5);
}
