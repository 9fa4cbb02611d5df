// step-2: PeriDEAL as a library. The PD internal force of a quadratic
// displacement field, evaluated with three partial-volume algorithms, against
// the closed form; error and wall time of each.
//
// The pieces a PD computation is built from, without the driver:
//   mesh (p4est) -> DoFHandler(FE_DGQ(0)^dim) -> NodeSet (nodes + ghosts)
//   -> NeighborList (bonds, partial-volume weights) -> Model
//   -> BondOperator (forces without a matrix, or the matrix).
// See README.md.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/partial_volume.h>

#include <array>
#include <iomanip>
#include <iostream>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  constexpr int                    dim  = 3;
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  ConditionalOStream               pcout(std::cout,
                           Utilities::MPI::this_mpi_process(comm) == 0);

  // A cube of n^3 cells of side h = 1/n, and the horizon delta = m h.
  const unsigned int n       = argc > 1 ? std::stoi(argv[1]) : 18;
  const double       m_ratio = argc > 2 ? std::stod(argv[2]) : 3.0;
  const double       h       = 1.0 / n;
  const double       horizon = m_ratio * h;

  parallel::distributed::Triangulation<dim> triangulation(comm);
  GridGenerator::subdivided_hyper_cube(triangulation, n, 0., 1.);
  DoFHandler<dim> dof_handler(triangulation);
  dof_handler.distribute_dofs(FESystem<dim>(FE_DGQ<dim>(0), dim));

  // The LPS with E = 1, nu = 1/4, through the registry and its parameters.
  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection("linear peridynamic solid");
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", "0.25");
  prm.leave_subsection();
  const auto model =
    Models::ModelRegistry<dim>::create("linear peridynamic solid", prm);
  const double K = model->bulk_modulus(), mu = model->shear_modulus();

  // Nodes and the off-process nodes within two horizons (state-based).
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim) * h));

  // The quadratic field u = c (x^2 + 2y^2 + yz, xy + z^2, xz + y^2) and the
  // force density it gives in the continuum: f = (K + mu/3) grad div u +
  // mu Laplace u = c (4 (K + mu/3) + 6 mu, 2 mu, 2 mu).
  const double   c = 1e-3;
  Tensor<1, dim> f_exact;
  f_exact[0] = c * (4 * (K + mu / 3) + 6 * mu);
  f_exact[1] = c * 2 * mu;
  f_exact[2] = c * 2 * mu;

  // The nodal values of u at the owned nodes; the operator's vectors hold
  // every node of the set (owned and ghosts), so they are sized by it below.
  std::vector<std::array<double, dim>> u_nodes(nodes.n_owned());
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      const Point<dim> &x = nodes[i].location;
      u_nodes[i]          = {{c * (x[0] * x[0] + 2 * x[1] * x[1] + x[1] * x[2]),
                              c * (x[0] * x[1] + x[2] * x[2]),
                              c * (x[0] * x[2] + x[1] * x[1])}};
    }

  pcout
    << "step-2: PD force of a quadratic field, 3D LPS, " << n
    << "^3 cells, m = " << m_ratio << ", "
    << Utilities::MPI::n_mpi_processes(comm) << " process(es)\n"
    << "  algorithm            bonds/node  max rel. error of f   time [s]\n";

  double last_error = 0;
  for (const std::string name : {"approximate", "quasi-analytical", "exact"})
    {
      Timer timer;
      prm.clear();
      PeriDEAL::Quadrature::PartialVolumeRegistry<dim>::declare_parameters(prm);
      const auto algorithm =
        PeriDEAL::Quadrature::PartialVolumeRegistry<dim>::create(name, prm);

      Discretization::NeighborList<dim> lists;
      lists.reinit(nodes, horizon, *algorithm, model->is_state_based());
      Operators::BondOperator<dim> op;
      op.reinit(nodes, lists, *model, horizon);
      Operators::BondOperator<dim>::VectorType u, force;
      op.initialize_dof_vector(u);
      op.initialize_dof_vector(force);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int d = 0; d < dim; ++d)
          u(nodes[i].dofs[d]) = u_nodes[i][d];
      u.update_ghost_values();
      op.apply(u, force);
      const double seconds = Utilities::MPI::max(timer.wall_time(), comm);

      // Equilibrium reads f_i + b_i = 0, so at bulk nodes (two horizons
      // from the surface, full neighbourhoods) the internal force density
      // F_i / V_i approximates f_exact = -b.
      double error = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          bool bulk = true;
          for (unsigned int d = 0; d < dim; ++d)
            bulk = bulk && nodes[i].location[d] > 2 * horizon &&
                   nodes[i].location[d] < 1 - 2 * horizon;
          if (!bulk)
            continue;
          Tensor<1, dim> f;
          for (unsigned int d = 0; d < dim; ++d)
            f[d] = force(nodes[i].dofs[d]) / nodes[i].volume();
          error = std::max(error, (f - f_exact).norm() / f_exact.norm());
        }
      error      = Utilities::MPI::max(error, comm);
      last_error = error;
      const double bonds =
        double(Utilities::MPI::sum(lists.n_owned_bonds(), comm)) /
        triangulation.n_global_active_cells();
      pcout << "  " << std::left << std::setw(20) << name << std::right
            << std::setw(11) << std::setprecision(4) << bonds << std::setw(20)
            << std::scientific << std::setprecision(3) << error << std::setw(11)
            << std::fixed << std::setprecision(3) << seconds
            << std::defaultfloat << std::endl;
    }
  // A sanity bound, not a tolerance: the exact weights give errors of about
  // 1e-4 at typical m-ratios (doc/verification-bulk.md).
  return last_error < 1e-2 ? 0 : 1;
}
