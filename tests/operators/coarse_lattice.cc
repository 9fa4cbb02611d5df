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
//   either grid;
// - the prescribed coarse DoFs, against the rule applied by hand to the
//   layer's position: a clamp on the last layer of an even node count (an
//   odd lattice coordinate, no coarse node in it) prescribes the coarse
//   nodes one layer inside, per component (component-wise clamps); and the
//   coarse matrix then holds the rigid translations (t . A_2h t > 0;
//   without that rule it is singular, t . A_2h t = 0 to round-off);
// - constraints that only the owner knows (nodes held where their bonds
//   broke: each process constrains its owned nodes of the plane x = 2
//   only): not boundary conditions, so no coarse DoF is prescribed on any
//   process; the local matrix on every node is symmetric (y . A x = x . A y
//   for arbitrary x, y): on two processes, with off-process nodes of the
//   plane in the node set (printed), its columns of held off-process DoFs
//   must go as the owner's rows do, which needs the owner's flags.
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

/// Which DoFs are constrained.
enum class Constraints
{
  none,
  dirichlet,     ///< every component of the nodes with x < 2
  thin_clamp,    ///< every component of the last layer of nodes in x
  componentwise, ///< component 0 of the first layer, 1 of the last
  held           ///< each process its owned nodes of the plane x = 2 only
};

template <int dim>
void
check(const unsigned int n, const Constraints kind)
{
  const bool     with_dirichlet = kind != Constraints::none;
  const MPI_Comm comm           = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n, 0, n);
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 3 + std::sqrt(dim)); // m = 3, h = 1
  Discretization::Lattice<dim> lattice;
  lattice.reinit(nodes);

  // The constraints (node i at lattice coordinate x - 1/2, h = 1).
  AffineConstraints<double> constraints;
  const auto constrain = [&](const unsigned int i, const unsigned int p) {
    const double x = nodes[i].location[0];
    switch (kind)
      {
        case Constraints::none:
          return false;
        case Constraints::dirichlet:
          return x < 2;
        case Constraints::thin_clamp:
          return x > n - 1;
        case Constraints::componentwise:
          return (p == 0 && x < 1) || (p == 1 && x > n - 1);
        case Constraints::held:
          return i < nodes.n_owned() && x > 2 && x < 3;
      }
    return false;
  };
  for (unsigned int i = 0; i < nodes.size(); ++i)
    for (unsigned int p = 0; p < dim; ++p)
      if (constrain(i, p))
        constraints.add_line(nodes[i].dofs[p]);
  constraints.close();

  Operators::CoarseLattice<dim>   coarse;
  const AffineConstraints<double> no_boundary_constraints;
  coarse.reinit(nodes,
                lattice,
                constraints,
                2,
                kind == Constraints::held ? &no_boundary_constraints : nullptr);

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

  const char *names[] = {"",
                         ", Dirichlet layer x < 2",
                         ", clamp on the last layer",
                         ", component 0 clamped on the first layer, 1 on "
                         "the last",
                         ", owned nodes of the plane x = 2 held"};
  if (Utilities::MPI::this_mpi_process(comm) == 0)
    std::cout << dim << "D, " << n << " nodes per direction" << names[int(kind)]
              << ": " << coarse.n_global_nodes() << " coarse nodes (expected "
              << std::pow((n + 1) / 2, dim) << ")" << std::endl;

  // The prescribed coarse DoFs, by hand: the coarse nodes of the clamped
  // layer where it has some (even lattice coordinate), else those one
  // layer inside; every process, owned and off-process coarse nodes.
  if (kind != Constraints::none)
    {
      const auto expected = [&](const Point<dim> &x, const unsigned int p) {
        const int layer = int(x[0]); // the lattice coordinate
        switch (kind)
          {
            case Constraints::dirichlet:
              return layer == 0;
            case Constraints::thin_clamp:
              return layer == int(n) - 2;
            case Constraints::componentwise:
              return (p == 0 && layer == 0) || (p == 1 && layer == int(n) - 2);
            default: // held: not a boundary condition, none

              return false;
          }
      };
      unsigned int wrong = 0, n_prescribed = 0;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (coarse.is_coarse(i))
          for (unsigned int p = 0; p < dim; ++p)
            {
              wrong +=
                coarse.is_prescribed(i, p) != expected(nodes[i].location, p);
              n_prescribed += i < nodes.n_owned() && coarse.is_prescribed(i, p);
            }
      wrong        = Utilities::MPI::sum(wrong, comm);
      n_prescribed = Utilities::MPI::sum(n_prescribed, comm);
      // One layer of coarse nodes, all components but in the
      // component-wise case (one each of two layers); none for holds.
      const unsigned int per_layer = std::pow((n + 1) / 2, dim - 1);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "  prescribed coarse DoFs: " << n_prescribed
                  << " (expected "
                  << per_layer * (kind == Constraints::componentwise ? 2 :
                                  kind == Constraints::held          ? 0 :
                                                                       dim)
                  << "), where the rule puts them on every process: "
                  << (wrong == 0 ? "yes" : "NO") << std::endl;
    }

  // Rigid translations.
  if (kind == Constraints::none || kind == Constraints::dirichlet)
    {
      const auto one = [](const Point<dim> &, const unsigned int) {
        return 1.;
      };
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
          if (coarse.is_prescribed(i, p))
            e = std::max(e, std::abs(g2[coarse.dof(i, p)]));
    report("prescribed DoFs take no part", Utilities::MPI::max(e, comm));
  }

  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection("bond-based");
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", "0.25");
  prm.leave_subsection();
  const auto model      = Models::ModelRegistry<dim>::create("bond-based", prm);
  using LocalElasticity = Operators::LocalElasticityOperator<dim>;

  // The coarse matrix holds the translations when only a layer without
  // coarse nodes is clamped: t . A_2h t > 0 relative to t . diag(A_2h) t.
  if (kind == Constraints::thin_clamp)
    {
      TrilinosWrappers::SparseMatrix a_coarse;
      LocalElasticity::assemble(nodes,
                                lattice,
                                *model,
                                constraints,
                                a_coarse,
                                nullptr,
                                &coarse);
      double smallest = 1;
      for (unsigned int p = 0; p < dim; ++p)
        {
          fill_coarse(g, [&](const Point<dim> &, const unsigned int q) {
            return q == p ? 1. : 0.;
          });
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            if (coarse.is_coarse(i) && coarse.is_prescribed(i, p))
              g[coarse.dof(i, p)] = 0;
          a_coarse.vmult(g2, g);
          double diagonal = 0;
          for (const auto k : coarse.owned_dofs())
            diagonal += g[k] * g[k] * a_coarse.diag_element(k);
          diagonal = Utilities::MPI::sum(diagonal, comm);
          smallest = std::min(smallest, (g * g2) / diagonal);
        }
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "  the coarse matrix holds the translations "
                     "(t.At / t.Dt > 1e-6): "
                  << (smallest > 1e-6 ? "yes" : "NO") << std::endl;
    }

  // Owner-only holds: the local matrix on every node is symmetric
  // (y . A x = x . A y), its columns of held off-process DoFs gone as the
  // owner's rows are (a process that took them from its own constraints
  // would keep them).
  if (kind == Constraints::held)
    {
      unsigned int off_process = 0;
      for (unsigned int i = nodes.n_owned(); i < nodes.size(); ++i)
        off_process += int(nodes[i].location[0]) == 2;
      off_process = Utilities::MPI::sum(off_process, comm);
      TrilinosWrappers::SparseMatrix a_fine;
      LocalElasticity::assemble(nodes, lattice, *model, constraints, a_fine);
      VectorType x(owned, comm), y(owned, comm), ax(owned, comm),
        ay(owned, comm);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int p = 0; p < dim; ++p)
          {
            x[nodes[i].dofs[p]] = pseudo_random(nodes[i].location, p);
            y[nodes[i].dofs[p]] = pseudo_random(nodes[i].location, p + 5);
          }
      a_fine.vmult(ax, x);
      a_fine.vmult(ay, y);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::cout << "  off-process nodes of the plane: "
                  << (off_process > 0 ? "some" : "none") << std::endl;
      report("the local matrix with owner-only holds is symmetric",
             std::abs(y * ax - x * ay) / (ax.l2_norm() * y.l2_norm()));
    }

  // The coarse matrix is the Galerkin product of the fine one.
  if (n % 2 == 1 && !with_dirichlet)
    {
      TrilinosWrappers::SparseMatrix a_fine, a_coarse;
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
  check<2>(9, Constraints::none);
  check<2>(10, Constraints::none);
  check<2>(10, Constraints::dirichlet);
  check<2>(10, Constraints::thin_clamp);
  check<2>(10, Constraints::componentwise);
  check<2>(10, Constraints::held);
  check<3>(7, Constraints::none);
  check<3>(8, Constraints::dirichlet);
  check<3>(8, Constraints::thin_clamp);
  check<3>(8, Constraints::componentwise);
  check<3>(8, Constraints::held);
  return 0;
}
