// Kind of test: closed-form property (patch test: linear fields give zero
// force in the bulk, on a bulk set that is checked to be non-empty) and
// comparison of two evaluations (matrix against matrix-free).
// The test oracle of the linearised PD operator
// (Testing::ReferenceBondOperator, tests/common) checked on its own, on a
// distributed mesh, for the LPS and the bond-based model, 2D and 3D, so that
// tests/operators/bond_operator.cc compares the library against an operator
// that is right:
//  - patch test: a linear displacement field gives zero force at every bulk
//    node (farther than two horizons from the boundary) to round-off, with
//    exact partial volumes;
//  - the assembled Trilinos matrix and the matrix-free evaluation agree:
//    K u = -F(u) for a smooth non-linear field;
//  - K is symmetric on a uniform grid;
//  - the printed norms do not depend on the number of MPI ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include "tests/common/reference_bond_operator.h"

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
void
check(const std::string               &model_name,
      const std::string               &plane_model,
      const double                     poisson,
      const std::string               &influence,
      const std::vector<unsigned int> &repetitions,
      const double                     m_ratio)
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
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(model_name);
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", poisson);
  prm.set("Plane model", plane_model);
  prm.set("Influence function", influence);
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

  const double                 horizon = m_ratio;
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim)));
  Discretization::NeighborList<dim> lists;
  lists.reinit(nodes,
               horizon,
               PeriDEAL::Quadrature::ExactPartialVolume<dim>(),
               model->is_state_based());
  Testing::ReferenceBondOperator<dim> op;
  op.reinit(nodes, lists, *model, horizon);

  const IndexSet               &owned    = op.owned_dofs();
  const IndexSet                relevant = nodes.relevant_dofs();
  TrilinosWrappers::MPI::Vector u(owned, relevant, comm), u_owned(owned, comm),
    force(owned, comm), ku(owned, comm);

  auto set_field = [&](const auto &field) {
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      {
        const Tensor<1, dim> value = field(nodes[i].location);
        for (unsigned int c = 0; c < dim; ++c)
          u_owned[nodes[i].dofs[c]] = value[c];
      }
    u_owned.compress(VectorOperation::insert);
    u = u_owned;
  };

  // Patch test.
  set_field([](const Point<dim> &x) {
    Tensor<1, dim> v;
    for (unsigned int r = 0; r < dim; ++r)
      for (unsigned int c = 0; c < dim; ++c)
        v[r] += (0.3 + 0.1 * r - 0.2 * c + (r == c ? 0.5 : 0.)) * x[c];
    v[0] += 1.5;
    return v;
  });
  op.apply(u, force);
  double       bulk = 0, all = 0;
  unsigned int n_bulk = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      bool in_bulk = true;
      for (unsigned int d = 0; d < dim; ++d)
        in_bulk = in_bulk && nodes[i].location[d] > 2 * horizon + 1 &&
                  nodes[i].location[d] < upper[d] - 2 * horizon - 1;
      n_bulk += in_bulk;
      for (unsigned int c = 0; c < dim; ++c)
        {
          const double f = std::abs(force[nodes[i].dofs[c]]);
          all            = std::max(all, f);
          if (in_bulk)
            bulk = std::max(bulk, f);
        }
    }
  bulk   = Utilities::MPI::max(bulk, comm);
  all    = Utilities::MPI::max(all, comm);
  n_bulk = Utilities::MPI::sum(n_bulk, comm);

  // Matrix against matrix-free evaluation, on a smooth field.
  TrilinosWrappers::SparseMatrix matrix;
  op.assemble(matrix);
  set_field([](const Point<dim> &x) {
    Tensor<1, dim> v;
    for (unsigned int c = 0; c < dim; ++c)
      v[c] = std::sin(0.3 * x[0] + c) * std::cos(0.2 * x[dim - 1] - c) +
             0.01 * x[c] * x[c];
    return v;
  });
  op.apply(u, force);
  matrix.vmult(ku, u_owned);
  ku += force;
  const double mismatch = ku.linfty_norm() / force.linfty_norm();

  // Symmetry: x^T K y = y^T K x.
  TrilinosWrappers::MPI::Vector y(owned, comm), ky(owned, comm);
  for (const auto dof : owned)
    y[dof] = std::cos(1.7 * dof);
  y.compress(VectorOperation::insert);
  matrix.vmult(ky, y);
  const double symmetry =
    std::abs(u_owned * ky - y * ku + y * force) / std::abs(u_owned * ky);

  // Collective queries before printing on rank 0.
  const auto   nonzeros   = matrix.n_nonzero_elements();
  const double force_norm = force.l2_norm();
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << std::setprecision(8) << dim << "D " << model_name
              << (dim == 2 ? " (" + plane_model + ")" : std::string()) << ", "
              << influence << ", m = " << m_ratio << ": " << nonzeros
              << " nonzeros, |F(u)|_2 = " << force_norm << '\n'
              << "  patch test on " << n_bulk
              << " bulk nodes (at least one: " << (n_bulk > 0 ? "yes" : "NO")
              << "): bulk force <= 1e-12 max force: "
              << (n_bulk > 0 && bulk <= 1e-12 * all ? "yes" : "NO") << '\n'
              << "  K u = -F(u) to <= 1e-12 relative: "
              << (mismatch <= 1e-12 ? "yes" : "NO") << '\n'
              << "  K symmetric to <= 1e-12 relative: "
              << (symmetry <= 1e-12 ? "yes" : "NO") << '\n';
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>("linear peridynamic solid",
           "plane strain",
           0.3,
           "gaussian",
           {16, 14},
           2.5);
  check<2>("linear peridynamic solid",
           "plane stress",
           0.2,
           "conical",
           {16, 18},
           3.0);
  check<2>("bond-based", "plane stress", 1. / 3, "constant", {16, 14}, 2.5);
  check<3>("linear peridynamic solid",
           "plane strain",
           0.2,
           "gaussian",
           {10, 10, 9},
           1.5);
  check<3>("bond-based", "plane strain", 0.25, "conical", {12, 12, 12}, 2.0);
}
