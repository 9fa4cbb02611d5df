// The collocation rows of BondOperator (use_collocation(), doc/collocation.md
// Sect. 11) on a distributed uniform grid, bond-based, 2D and 3D. Kinds of
// check:
//  - closed form: at every collocation node the force of a quadratic field
//    is V_i (mu Laplace u + 2 mu grad div u) (the PD operator of a full
//    ball on quadratics, lambda = mu), to 1e-10 of the largest nodal force;
//    the number of collocation nodes is the number of owned nodes with a
//    full stencil, counted here independently, and not zero;
//  - comparison of evaluations: the assembled matrix against the
//    matrix-free apply (K u = -F(u), 1e-12 relative) on a smooth
//    non-polynomial field, the exact diagonal (compute_diagonal()) against
//    the matrix's (1e-12); the elastic energy against -1/2 u.F (1e-12) for
//    a field supported farther than a horizon from every standard node
//    (so that only collocation rows, whose energy is -1/2 u_i.F_i, and no
//    standard bond carry it: the energy's one-node form against the
//    vectorised pass);
//  - 1 against 2 threads: bitwise the same forces;
//  - the printed norms do not depend on the number of MPI ranks (the same
//    output file for 1 and 2 ranks).

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
void
check(const std::string &plane_model,
      const double       poisson,
      const double       mu,
      const unsigned int n_cells,
      const double       m_ratio)
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
  prm.set("Poisson's ratio", poisson);
  prm.set("Plane model", plane_model);
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create("bond-based", prm);

  const double                 horizon = m_ratio; // h = 1
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, horizon + std::sqrt(dim));
  Discretization::NeighborList<dim> lists;
  lists.reinit(nodes,
               horizon,
               PeriDEAL::Quadrature::ExactPartialVolume<dim>(),
               false,
               false);
  Operators::BondOperator<dim> op;
  op.reinit(nodes, lists, *model, horizon);
  const auto report =
    op.use_collocation(PeriDEAL::Quadrature::CollocationSettings());
  std::size_t n_full = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    n_full += lists.has_full_stencil(i);
  n_full = Utilities::MPI::sum(n_full, comm);

  typename Operators::BondOperator<dim>::VectorType u, force, force_2, diagonal;
  op.initialize_dof_vector(u);
  op.initialize_dof_vector(force);
  op.initialize_dof_vector(force_2);
  op.initialize_dof_vector(diagonal);
  const auto set_field = [&](const auto &field) {
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      {
        const Tensor<1, dim> value = field(nodes[i].location);
        for (unsigned int c = 0; c < dim; ++c)
          u[nodes[i].dofs[c]] = value[c];
      }
    u.update_ghost_values();
  };

  // Quadratic field u_c = sum_{a <= b} A_cab x_a x_b with fixed
  // coefficients, and its Navier operator mu Laplace u + 2 mu grad div u.
  const auto A =
    [](const unsigned int c, const unsigned int a, const unsigned int b) {
      return 1e-3 * (0.3 + 0.2 * c - 0.1 * a + 0.15 * b + 0.05 * a * b);
    };
  set_field([&](const Point<dim> &x) {
    Tensor<1, dim> v;
    for (unsigned int c = 0; c < dim; ++c)
      {
        v[c] = 1e-3 * (0.5 + c) * x[c];
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            v[c] += A(c, a, b) * x[a] * x[b];
      }
    return v;
  });
  // d2 u_c / dx_a dx_b of u_c = sum_{a <= b} A x_a x_b.
  const auto second =
    [&](const unsigned int c, const unsigned int a, const unsigned int b) {
      return a == b ? 2 * A(c, a, a) : A(c, std::min(a, b), std::max(a, b));
    };
  Tensor<1, dim> navier;
  for (unsigned int c = 0; c < dim; ++c)
    for (unsigned int a = 0; a < dim; ++a)
      navier[c] += mu * second(c, a, a) + 2 * mu * second(a, a, c);
  op.apply(u, force);
  double worst = 0, largest = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      {
        const double f = force[nodes[i].dofs[c]];
        largest        = std::max(largest, std::abs(f));
        if (op.is_collocation_node(i))
          worst = std::max(worst, std::abs(f - nodes[i].volume() * navier[c]));
      }
  worst   = Utilities::MPI::max(worst, comm);
  largest = Utilities::MPI::max(largest, comm);

  // A smooth non-polynomial field: matrix against matrix-free, diagonal,
  // energy, threads.
  set_field([](const Point<dim> &x) {
    Tensor<1, dim> v;
    for (unsigned int c = 0; c < dim; ++c)
      v[c] = 1e-3 * (std::sin(0.3 * x[0] + c) * std::cos(0.2 * x[dim - 1]) +
                     0.01 * x[c] * x[0]);
    return v;
  });
  MultithreadInfo::set_thread_limit(1);
  op.apply(u, force);
  MultithreadInfo::set_thread_limit(2);
  op.apply(u, force_2);
  bool identical = true;
  for (unsigned int k = 0; k < force.locally_owned_size(); ++k)
    identical = identical && force.local_element(k) == force_2.local_element(k);
  identical = Utilities::MPI::min(identical ? 1 : 0, comm) == 1;

  TrilinosWrappers::SparseMatrix matrix;
  op.assemble(matrix);
  const IndexSet               &owned = dof_handler.locally_owned_dofs();
  TrilinosWrappers::MPI::Vector u_owned(owned, comm), ku(owned, comm);
  for (const auto dof : owned)
    u_owned[dof] = u[dof];
  u_owned.compress(VectorOperation::insert);
  matrix.vmult(ku, u_owned);
  double diff2 = 0, norm2 = 0;
  for (const auto dof : owned)
    {
      diff2 += std::pow(ku[dof] + force[dof], 2);
      norm2 += std::pow(force[dof], 2);
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

  // A bump whose support keeps more than a horizon from every node within a
  // horizon of the surface (the standard nodes): no standard bond sees it.
  const double centre = 0.5 * n_cells, radius = 0.5 * n_cells - 2 * horizon - 1;
  set_field([&](const Point<dim> &x) {
    Tensor<1, dim> v;
    double         r2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
      r2 += (x[d] - centre) * (x[d] - centre) / (radius * radius);
    for (unsigned int c = 0; c < dim; ++c)
      v[c] = r2 < 1 ? 1e-3 * (1 + 0.3 * c) * std::pow(1 - r2, 3) : 0.;
    return v;
  });
  op.apply(u, force);
  double bump_u_dot_f = 0, bump_norm = 0;
  for (const auto dof : owned)
    {
      bump_u_dot_f += u[dof] * force[dof];
      bump_norm += std::abs(u[dof]);
    }
  bump_u_dot_f        = Utilities::MPI::sum(bump_u_dot_f, comm);
  bump_norm           = Utilities::MPI::sum(bump_norm, comm);
  const double energy = op.elastic_energy(u);
  const auto   nnz    = matrix.n_nonzero_elements();

  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << std::setprecision(6) << dim << "D bond-based"
              << (dim == 2 ? " (" + plane_model + ")" : std::string())
              << ", m = " << m_ratio << ", " << n_cells << "^" << dim
              << " nodes: " << report.n_collocation_nodes
              << " collocation nodes (n_c = " << report.n_collocation << "), "
              << report.n_cut_nodes << " standard, " << nnz << " nonzeros\n"
              << "  collocation nodes = owned full-stencil nodes > 0: "
              << (report.n_collocation_nodes == n_full && n_full > 0 ? "yes" :
                                                                       "NO")
              << '\n'
              << "  quadratic field: V (mu Laplace u + 2 mu grad div u) at "
                 "every collocation node to <= 1e-10 of the largest force: "
              << (worst <= 1e-10 * largest ? "yes" : "NO") << '\n'
              << "  K u = -F(u) to <= 1e-12 relative: "
              << (diff2 <= 1e-24 * norm2 ? "yes" : "NO") << '\n'
              << "  diagonal = diag(K) to <= 1e-12 relative: "
              << (diag_diff <= 1e-12 * diag_max ? "yes" : "NO") << '\n'
              << "  energy = -1/2 u.F > 0 to <= 1e-12 relative (a bump of "
              << (bump_norm > 0 ? "nonzero" : "ZERO") << " norm): "
              << (energy > 0 && bump_norm > 0 &&
                      std::abs(energy + 0.5 * bump_u_dot_f) <=
                        1e-12 * std::abs(bump_u_dot_f) ?
                    "yes" :
                    "NO")
              << '\n'
              << "  1 and 2 threads give bitwise the same forces: "
              << (identical ? "yes" : "NO") << '\n';
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  // 2D plane stress, nu = 1/3: mu = 3/8; 3D nu = 1/4: mu = 2/5.
  check<2>("plane stress", 1. / 3, 3. / 8, 20, 3.);
  check<3>("plane strain", 0.25, 0.4, 16, 3.);
}
