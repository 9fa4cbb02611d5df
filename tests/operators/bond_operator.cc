// The matrix-free BondOperator against the assembled stiffness of the test
// oracle Testing::ReferenceBondOperator (tests/common; an independent
// implementation: explicit bond lists, row-by-row assembly into a Trilinos
// matrix), for the LPS and the
// bond-based model in 2D and 3D, on uniform grids (shared stencil in the
// bulk, lists at the boundary) and on locally refined meshes (lists only):
//  - K u = -F(u) for a smooth non-linear field, to 1e-12 relative;
//  - the exact diagonal of K (compute_diagonal) against the matrix, 1e-12;
//  - 1 and 2 threads give bitwise identical forces;
//  - neighbour lists stored for the bulk or not give the same forces;
//  - BondOperator::assemble() (stencil-based rows, own graph) against the
//    reference matrix entry by entry, 1e-12 of the largest entry, without
//    and with prescribed values (matrix and right-hand side), and the same
//    values on 1 and 2 threads.
// Kind of test: comparison of two implementations of the same operator.
// The node counts printed do not depend on the number of MPI ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/affine_constraints.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include "tests/common/reference_bond_operator.h"

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
void
check(const std::string &name,
      const std::string &model_name,
      const std::string &plane_model,
      const double       poisson,
      const unsigned int n_cells,
      const double       m_ratio,
      const bool         refine_corner)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n_cells, 0, n_cells);
  if (refine_corner)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center()[0] < 2.5 &&
            cell->center()[1] < 2.5)
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(model_name);
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", poisson);
  prm.set("Plane model", plane_model);
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

  const double                 horizon = m_ratio; // h = 1 on the coarse cells
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim)));
  const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
  Discretization::NeighborList<dim>                   stored, compact;
  stored.reinit(nodes, horizon, exact, model->is_state_based(), true);
  compact.reinit(nodes, horizon, exact, model->is_state_based(), false);

  Testing::ReferenceBondOperator<dim> reference;
  reference.reinit(nodes, stored, *model, horizon);
  TrilinosWrappers::SparseMatrix matrix;
  reference.assemble(matrix);

  Discretization::BondState<dim> state;
  state.reinit(nodes, compact);
  Operators::BondOperator<dim> op, op_stored;
  op.reinit(nodes, compact, *model, horizon, &state);
  op_stored.reinit(nodes, stored, *model, horizon);

  // A smooth non-linear field.
  const IndexSet               &owned = reference.owned_dofs();
  TrilinosWrappers::MPI::Vector u_owned(owned, comm), ku(owned, comm);
  typename Operators::BondOperator<dim>::VectorType u, force, force_2, diagonal;
  op.initialize_dof_vector(u);
  op.initialize_dof_vector(force);
  op.initialize_dof_vector(force_2);
  op.initialize_dof_vector(diagonal);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      {
        const Point<dim> &x = nodes[i].location;
        const double value  = std::sin(0.3 * x[0] + c) * std::cos(0.2 * x[1]) +
                             0.01 * x[dim - 1] * x[0] * (c + 1);
        u_owned[nodes[i].dofs[c]] = value;
        u[nodes[i].dofs[c]]       = value;
      }
  u_owned.compress(VectorOperation::insert);
  u.update_ghost_values();
  matrix.vmult(ku, u_owned);

  MultithreadInfo::set_thread_limit(1);
  op.apply(u, force);
  double diff2 = 0, norm2 = 0;
  for (const auto dof : owned)
    {
      diff2 += std::pow(ku[dof] + force[dof], 2);
      norm2 += std::pow(ku[dof], 2);
    }
  diff2 = Utilities::MPI::sum(diff2, comm);
  norm2 = Utilities::MPI::sum(norm2, comm);

  op.compute_diagonal(diagonal);
  double diag_diff = 0, diag_max = 0;
  for (const auto dof : owned)
    {
      diag_diff =
        std::max(diag_diff, std::abs(diagonal[dof] - matrix.el(dof, dof)));
      diag_max = std::max(diag_max, std::abs(matrix.el(dof, dof)));
    }
  diag_diff = Utilities::MPI::max(diag_diff, comm);
  diag_max  = Utilities::MPI::max(diag_max, comm);

  MultithreadInfo::set_thread_limit(2);
  op.apply(u, force_2);
  bool identical = true;
  for (const auto dof : owned)
    identical = identical && force[dof] == force_2[dof];
  identical = Utilities::MPI::min(identical ? 1 : 0, comm) == 1;

  op_stored.apply(u, force_2);
  double stored_diff = 0;
  for (const auto dof : owned)
    stored_diff = std::max(stored_diff, std::abs(force[dof] - force_2[dof]));
  stored_diff = Utilities::MPI::max(stored_diff, comm) /
                Utilities::MPI::max(force.linfty_norm(), comm);

  // The assembled stiffness of BondOperator against the reference, entry
  // by entry (every entry of either matrix), without and with prescribed
  // values: nodes with x < 1.5 fully, component 1 of nodes with x > n - 1.5.
  const auto entry_difference = [&](const TrilinosWrappers::SparseMatrix &a,
                                    const TrilinosWrappers::SparseMatrix &b) {
    double difference = 0, largest = 0;
    for (const auto row : owned)
      {
        for (auto e = a.begin(row); e != a.end(row); ++e)
          {
            difference =
              std::max(difference,
                       std::abs(e->value() - b.el(row, e->column())));
            largest = std::max(largest, std::abs(e->value()));
          }
        for (auto e = b.begin(row); e != b.end(row); ++e)
          difference =
            std::max(difference, std::abs(e->value() - a.el(row, e->column())));
      }
    return Utilities::MPI::max(difference, comm) /
           Utilities::MPI::max(largest, comm);
  };
  MultithreadInfo::set_thread_limit(1);
  TrilinosWrappers::SparseMatrix assembled, assembled_2;
  op.assemble(assembled);
  const double assembly_difference = entry_difference(assembled, matrix);

  // Owned and off-process nodes alike: the columns of the latter move to
  // the right-hand side.
  AffineConstraints<double> constraints;
  for (unsigned int i = 0; i < nodes.size(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      if (nodes[i].location[0] < 1.5 ||
          (c == 1 && nodes[i].location[0] > n_cells - 1.5))
        {
          constraints.add_line(nodes[i].dofs[c]);
          constraints.set_inhomogeneity(nodes[i].dofs[c],
                                        0.1 *
                                          std::sin(nodes[i].location[1] + c));
        }
  constraints.close();
  TrilinosWrappers::SparseMatrix reference_constrained, constrained;
  TrilinosWrappers::MPI::Vector  reference_rhs(owned, comm), rhs(owned, comm);
  reference.assemble(reference_constrained, constraints, reference_rhs);
  op.assemble(constrained, &constraints, &rhs);
  const double constrained_difference =
    entry_difference(constrained, reference_constrained);
  TrilinosWrappers::MPI::Vector rhs_difference(rhs);
  rhs_difference -= reference_rhs;
  const double rhs_relative =
    rhs_difference.linfty_norm() / reference_rhs.linfty_norm();

  MultithreadInfo::set_thread_limit(2);
  op.assemble(assembled_2);
  bool assembly_identical =
    assembled.n_nonzero_elements() == assembled_2.n_nonzero_elements();
  for (const auto row : owned)
    for (auto e = assembled.begin(row); e != assembled.end(row); ++e)
      assembly_identical =
        assembly_identical && e->value() == assembled_2.el(row, e->column());
  assembly_identical =
    Utilities::MPI::min(assembly_identical ? 1 : 0, comm) == 1;

  const double relative = std::sqrt(diff2 / norm2);
  std::cout << std::setw(34) << std::left << name << " nodes "
            << tria.n_global_active_cells() << ", on the stencil "
            << Utilities::MPI::sum(op.n_stencil_nodes(), comm) << ", on lists "
            << Utilities::MPI::sum(op.n_list_nodes(), comm)
            << "\n  K u + F(u) <= 1e-12 |K u|: "
            << (relative <= 1e-12 ? "yes" : "NO") << "\n  diagonal <= 1e-12: "
            << (diag_diff <= 1e-12 * diag_max ? "yes" : "NO")
            << "\n  1 and 2 threads identical: " << (identical ? "yes" : "NO")
            << "\n  stored bulk lists give the same forces (1e-14): "
            << (stored_diff <= 1e-14 ? "yes" : "NO")
            << "\n  assembled = reference matrix (1e-12): "
            << (assembly_difference <= 1e-12 ? "yes" : "NO")
            << "\n  with prescribed values, matrix and rhs (1e-12): "
            << (constrained_difference <= 1e-12 && rhs_relative <= 1e-12 ?
                  "yes" :
                  "NO")
            << "\n  assembled on 1 and 2 threads identical: "
            << (assembly_identical ? "yes" : "NO") << std::endl;
  if (assembly_difference > 1e-12 || constrained_difference > 1e-12 ||
      rhs_relative > 1e-12)
    std::cout << "  (assembly " << assembly_difference << ", constrained "
              << constrained_difference << ", rhs " << rhs_relative << ")"
              << std::endl;
  if (relative > 1e-12 || diag_diff > 1e-12 * diag_max)
    std::cout << "  (relative difference " << relative << ", diagonal "
              << diag_diff / diag_max << ")" << std::endl;
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);

  check<3>("3D LPS, uniform",
           "linear peridynamic solid",
           "plane strain",
           0.3,
           9,
           3,
           false);
  check<3>("3D bond-based, uniform",
           "bond-based",
           "plane strain",
           0.25,
           8,
           2.5,
           false);
  check<3>("3D LPS, refined corner",
           "linear peridynamic solid",
           "plane strain",
           0.2,
           5,
           2,
           true);
  check<2>("2D LPS plane strain, uniform",
           "linear peridynamic solid",
           "plane strain",
           0.3,
           20,
           3,
           false);
  check<2>("2D bond-based plane stress",
           "bond-based",
           "plane stress",
           1. / 3,
           16,
           3.5,
           false);
  check<2>("2D LPS plane stress, refined",
           "linear peridynamic solid",
           "plane stress",
           0.25,
           10,
           3,
           true);
}
