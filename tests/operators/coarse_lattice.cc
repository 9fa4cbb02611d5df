// The coarse lattice of the local elasticity preconditioner (every second
// node in each direction, Operators::CoarseLattice) and the local matrix
// on it. References, all independent of the code under test:
// - the number of coarse nodes, counted from the lattice: ceil(N/2)^dim;
// - the interpolation P reproduces rigid translations at every node
//   (N even too, where the last layer has no upper corner) and, where the
//   coarse cubes cover the body (N odd), every linear field exactly;
// - restriction is the transpose: g . P^T f = (P g) . f for arbitrary f, g
//   (both directions read the same weights, so on one process this holds
//   by construction; on two it checks the communication: the pushed sums
//   of compress(add) against the pulled ghost values);
// - the coarse matrix is the Galerkin product: for N odd the coarse Q1
//   space is a subspace of the fine one and P its nodal embedding, so
//   A_2h = P^T A_h P to round-off (A_h assembled by the same class on all
//   nodes, A_2h on the coarse ones; the classical identity of nested
//   conforming spaces);
// - with a Dirichlet layer, P and P^T vanish at the prescribed DoFs of
//   either grid.
// On 1 and 2 processes the same output.
// Kind of test: closed forms and algebraic identities, 1 and 2 ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <perideal/discretization/lattice.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/coarse_lattice.h>
#include <perideal/operators/local_elasticity_operator.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;
using VectorType = LinearAlgebra::distributed::Vector<double>;

/// A deterministic value that depends on the position and component only
/// (the same on every partition).
template <int dim>
double
pseudo_random(const Point<dim> &x, const unsigned int p)
{
  double v = 0.3 + p;
  for (unsigned int d = 0; d < dim; ++d)
    v += (1.7 + d) * x[d] + 0.37 * x[d] * x[d] * (d + 1);
  return std::sin(13.1 * v);
}

template <int dim>
void
check(const unsigned int n, const bool with_dirichlet)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n, 0, n);
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 3 + std::sqrt(dim)); // m = 3, h = 1
  Discretization::Lattice<dim> lattice;
  lattice.reinit(nodes);

  // Dirichlet layer: every DoF of the nodes with x < 2 (the first two
  // columns of nodes).
  AffineConstraints<double> constraints;
  if (with_dirichlet)
    for (unsigned int i = 0; i < nodes.size(); ++i)
      if (nodes[i].location[0] < 2)
        for (const auto dof : nodes[i].dofs)
          constraints.add_line(dof);
  constraints.close();

  Operators::CoarseLattice<dim> coarse;
  coarse.reinit(nodes, lattice, constraints, 2);

  const IndexSet &owned = dof_handler.locally_owned_dofs();
  VectorType      fine(owned, comm), fine2(owned, comm);
  VectorType      g, g2;
  coarse.initialize_coarse_vector(g);
  coarse.initialize_coarse_vector(g2);

  // Coarse values from a function of the coarse node's position.
  const auto fill_coarse = [&](VectorType &v, const auto &f) {
    v = 0;
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      if (coarse.is_coarse(i))
        for (unsigned int p = 0; p < dim; ++p)
          v[coarse.dof(i, p)] = f(nodes[i].location, p);
  };
  // The largest |fine - f| over the owned DoFs (prescribed ones against 0).
  const auto max_error = [&](const VectorType &v, const auto &f) {
    double e = 0;
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      for (unsigned int p = 0; p < dim; ++p)
        {
          const auto   dof = nodes[i].dofs[p];
          const double expected =
            constraints.is_constrained(dof) ? 0. : f(nodes[i].location, p);
          e = std::max(e, std::abs(v[dof] - expected));
        }
    return Utilities::MPI::max(e, comm);
  };

  const double tolerance = 1e-13;
  const auto   report    = [&](const char *what, const double error) {
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return;
    std::cout << "  " << what << ": ";
    if (error <= tolerance)
      std::cout << "yes" << std::endl;
    else
      std::cout << "NO, error " << error << std::endl;
  };

  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << dim << "D, " << n << " nodes per direction"
              << (with_dirichlet ? ", Dirichlet layer x < 2" : "") << ": "
              << coarse.n_global_nodes() << " coarse nodes (expected "
              << std::pow((n + 1) / 2, dim) << ")" << std::endl;

  // Rigid translations.
  {
    const auto one = [](const Point<dim> &, const unsigned int) { return 1.; };
    fill_coarse(g, one);
    fine = 0;
    coarse.prolongate_add(fine, g);
    // With the layer (the nodes at lattice coordinate 0 and 1), every
    // free node's corners are free: 1 there, 0 at the prescribed DoFs.
    report("P reproduces the translations", max_error(fine, one));
  }

  // Linear fields, where the coarse cubes cover the body.
  if (n % 2 == 1 && !with_dirichlet)
    {
      const auto linear = [](const Point<dim> &x, const unsigned int p) {
        double v = 0.5 - p;
        for (unsigned int d = 0; d < dim; ++d)
          v += (0.25 + p + 2 * d) * x[d];
        return v;
      };
      fill_coarse(g, linear);
      fine = 0;
      coarse.prolongate_add(fine, g);
      report("P reproduces linear fields", max_error(fine, linear) / n);
    }

  // Restriction is the transpose of the prolongation.
  {
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      for (unsigned int p = 0; p < dim; ++p)
        fine[nodes[i].dofs[p]] = pseudo_random(nodes[i].location, p);
    fill_coarse(g, [](const Point<dim> &x, const unsigned int p) {
      return pseudo_random(x, p + 7);
    });
    coarse.restrict_residual(g2, fine);
    fine2 = 0;
    coarse.prolongate_add(fine2, g);
    const double a = g * g2, b = fine2 * fine;
    report("g . P^T f = (P g) . f",
           std::abs(a - b) / (g.l2_norm() * fine.l2_norm()));

    // Prescribed DoFs: zero in P g, ignored by P^T.
    double e = 0;
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      for (const auto dof : nodes[i].dofs)
        if (constraints.is_constrained(dof))
          e = std::max(e, std::abs(fine2[dof]));
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      if (coarse.is_coarse(i))
        for (unsigned int p = 0; p < dim; ++p)
          if (constraints.is_constrained(nodes[i].dofs[p]))
            e = std::max(e, std::abs(g2[coarse.dof(i, p)]));
    report("prescribed DoFs take no part", Utilities::MPI::max(e, comm));
  }

  // The coarse matrix is the Galerkin product of the fine one.
  if (n % 2 == 1 && !with_dirichlet)
    {
      ParameterHandler prm;
      Models::ModelRegistry<dim>::declare_parameters(prm);
      prm.enter_subsection("bond-based");
      prm.set("Young's modulus", "1");
      prm.set("Poisson's ratio", "0.25");
      prm.leave_subsection();
      const auto model = Models::ModelRegistry<dim>::create("bond-based", prm);
      TrilinosWrappers::SparseMatrix a_fine, a_coarse;
      using LocalElasticity = Operators::LocalElasticityOperator<dim>;
      LocalElasticity::assemble(nodes, lattice, *model, constraints, a_fine);
      LocalElasticity::assemble(nodes,
                                lattice,
                                *model,
                                constraints,
                                a_coarse,
                                nullptr,
                                &coarse);

      fill_coarse(g, [](const Point<dim> &x, const unsigned int p) {
        return pseudo_random(x, p + 3);
      });
      fine = 0;
      coarse.prolongate_add(fine, g);
      a_fine.vmult(fine2, fine);
      coarse.restrict_residual(g2, fine2); // P^T A_h P g
      VectorType direct;
      coarse.initialize_coarse_vector(direct);
      a_coarse.vmult(direct, g); // A_2h g
      direct -= g2;
      report("A_2h = P^T A_h P", direct.linfty_norm() / g2.linfty_norm());
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  check<2>(9, false);
  check<2>(10, false);
  check<2>(10, true);
  check<3>(7, false);
  check<3>(8, true);
  return 0;
}
