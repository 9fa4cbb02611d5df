// The fracture passes of the matrix-free operator give bitwise the same
// forces, energies and failed bonds on every partition (Kind of test:
// partition invariance, bitwise; the forces themselves are verified against
// brute-force sums in bond_failure). Under mpirun the same problem is
// solved on all processes and, by rank 0 alone, on MPI_COMM_SELF; the
// forces per node (matched by position) must agree bit for bit, before and
// after the commit of the failed bonds.
//
// Why this can fail: where a chunk of the shared stencil or a surface run
// starts depends on the partition, so a node's lane may be evaluated in a
// loop's vector body on one partition and in its scalar remainder on
// another; a multiply-add fused in one and not in the other changes the
// last bit (bond_operator_fracture.cc is compiled without implicit
// contraction for this reason). On one process the two solves coincide
// and the test only checks that it runs.

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

#include <algorithm>
#include <array>
#include <cstring>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  /// Position and force of one node, before and after the commit.
  template <int dim>
  using Record = std::array<double, 3 * dim>;

  /// Forces of the owned nodes on @p comm, gathered on its rank 0 and
  /// sorted by position; the number of committed bonds.
  template <int dim>
  std::pair<std::vector<Record<dim>>, std::size_t>
  solve(const MPI_Comm     comm,
        const std::string &model_name,
        const unsigned int n_cells,
        const double       horizon,
        const bool         graded)
  {
    parallel::distributed::Triangulation<dim> tria(comm);
    if (graded)
      {
        // Widths 0.8 and 1.2 alternating along x (the same total length).
        std::vector<std::vector<double>> steps(dim,
                                               std::vector<double>(n_cells,
                                                                   1.));
        for (unsigned int k = 0; k < n_cells; ++k)
          steps[0][k] = k % 2 == 0 ? 0.8 : 1.2;
        Point<dim> far;
        for (unsigned int d = 0; d < dim; ++d)
          far[d] = n_cells;
        GridGenerator::subdivided_hyper_rectangle(tria,
                                                  steps,
                                                  Point<dim>(),
                                                  far);
      }
    else
      GridGenerator::subdivided_hyper_cube(tria, n_cells, 0, n_cells);
    DoFHandler<dim> dof_handler(tria);
    FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
    dof_handler.distribute_dofs(fe);

    ParameterHandler prm;
    Models::ModelRegistry<dim>::declare_parameters(prm);
    prm.enter_subsection(model_name);
    prm.set("Young's modulus", "1");
    prm.set("Poisson's ratio", model_name == "bond-based" ? "0.25" : "0.3");
    prm.set("Critical stretch", "0.012");
    prm.leave_subsection();
    const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

    Discretization::NodeSet<dim> nodes;
    nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim)));
    const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
    Discretization::NeighborList<dim>                   lists;
    lists.reinit(nodes, horizon, exact, model->is_state_based(), false);
    Discretization::BondState<dim> state;
    state.reinit(nodes, lists);
    Operators::BondOperator<dim> op;
    op.reinit(nodes, lists, *model, horizon, &state);
    op.set_kinematics(true,
                      std::vector<double>(nodes.size(),
                                          model->critical_stretch(horizon)));

    // Smooth, irrational displacements plus an opening across x_c, so
    // that bonds fail and every sum carries rounding.
    const double                                      x_c = 0.5 * n_cells - 0.1;
    typename Operators::BondOperator<dim>::VectorType u, before, after;
    op.initialize_dof_vector(u);
    op.initialize_dof_vector(before);
    op.initialize_dof_vector(after);
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      for (unsigned int c = 0; c < dim; ++c)
        {
          const Point<dim> &x = nodes[i].location;
          u[nodes[i].dofs[c]] =
            2e-3 *
              (std::sin(0.37 * x[0] + c) + 0.3 * std::cos(x[1] * x[dim - 1])) +
            (c == 0 && x[0] > x_c ? 0.03 + 0.01 * std::sin(x[1]) : 0.);
        }
    u.update_ghost_values();
    op.apply_with_energy(u, before);
    const std::size_t committed = op.commit_broken_bonds(state);
    op.apply(u, after);

    std::vector<Record<dim>> mine(nodes.n_owned());
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      for (unsigned int c = 0; c < dim; ++c)
        {
          mine[i][c]           = nodes[i].location[c];
          mine[i][dim + c]     = before[nodes[i].dofs[c]];
          mine[i][2 * dim + c] = after[nodes[i].dofs[c]];
        }
    std::vector<Record<dim>> all;
    for (const auto &part : Utilities::MPI::gather(comm, mine))
      all.insert(all.end(), part.begin(), part.end());
    std::sort(all.begin(), all.end());
    return {all, committed};
  }


  template <int dim>
  void
  check(const std::string &model_name,
        const unsigned int n_cells,
        const double       horizon,
        const bool         graded = false)
  {
    const MPI_Comm     world = MPI_COMM_WORLD;
    const bool         root  = Utilities::MPI::this_mpi_process(world) == 0;
    const unsigned int n     = Utilities::MPI::n_mpi_processes(world);
    const auto [distributed, committed] =
      solve<dim>(world, model_name, n_cells, horizon, graded);
    bool same = true;
    if (root)
      {
        const auto [serial, committed_serial] =
          solve<dim>(MPI_COMM_SELF, model_name, n_cells, horizon, graded);
        same = committed == committed_serial &&
               serial.size() == distributed.size() &&
               std::memcmp(serial.data(),
                           distributed.data(),
                           serial.size() * sizeof(Record<dim>)) == 0;
        if (!same)
          {
            double largest = 0;
            for (std::size_t i = 0;
                 i < std::min(serial.size(), distributed.size());
                 ++i)
              for (unsigned int c = 0; c < 3 * dim; ++c)
                largest =
                  std::max(largest, std::abs(serial[i][c] - distributed[i][c]));

            std::cout << "  (committed " << committed << " against "
                      << committed_serial << ", largest difference " << largest
                      << ")" << std::endl;
          }
      }
    std::cout << dim << "D " << model_name << ", " << n_cells << "^" << dim
              << (graded ? " nodes (cells of unequal widths): " : " nodes: ")
              << (committed > 0 ? "bonds failed" : "NO bonds")
              << "; forces before and after the commit on " << n
              << " process(es) bitwise those of 1: " << (same ? "yes" : "NO")
              << std::endl;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);
  check<2>("bond-based", 40, 3);
  check<2>("linear peridynamic solid", 40, 3);
  check<3>("bond-based", 14, 3);
  check<3>("linear peridynamic solid", 14, 3);
  // Cells of unequal widths: no lattice, every node on its own list.
  check<2>("linear peridynamic solid", 30, 3, true);
}
