// The collocation rows of the state-based LPS model (BondOperator::
// use_collocation(), doc/collocation.md Sect. 5.2: the dilatation row T of
// every full-stencil node, the force rows K (dilatation) and G (deviatoric)
// of every collocation node) on a distributed uniform grid, 2D and 3D,
// orders 2 and 4 (C4 in 3D is refused at m >= 2.5 as for the bond-based
// model: its diagonal is not positive, doc/collocation.md Sect. 7). Kinds of
// check:
//  - high-precision quadrature: at every collocation node whose cloud
//    nodes all take their dilatation from the collocation row (nodes two
//    horizons from the surface), the force of a polynomial field of the
//    order's degree is V_i times the continuum LPS operator at x_i,
//      theta(x) = d/m int_B omega xi . (u(x + xi) - u(x)) dV,
//      f(x) = 1/m int_B alpha(r) n theta(x + xi) dV
//             + 2/m int_B beta(r) n (n . (u(x + xi) - u(x))) dV,
//    computed here by nested Gauss (radius, polar angle) and trapezoidal
//    (azimuth) quadrature from the model's own omega, alpha, beta, and
//    m = int_B omega r^2 dV the same way; to <= 1e-10 of the largest
//    nodal force. The count of such nodes is printed and must be > 0;
//  - negative control: the C2 rows on a quartic field miss the reference;
//  - closed form: for the quadratic field the reference is also Navier's
//    operator mu Laplace u + (c_K / d + 2 mu) grad div u with the model's
//    constants (doc/collocation.md Sect. 5.2, "Order 2"), which checks the
//    quadrature reference itself;
//  - comparison of evaluations: the assembled matrix against the
//    matrix-free apply (K u = -F(u), 1e-12 relative) on a smooth
//    non-polynomial field, and the diagonal (compute_diagonal(), which
//    takes the dilatation rows of the neighbours into account) against the
//    matrix's (1e-12);
//  - 1 against 2 threads: bitwise the same forces;
//  - the printed counts do not depend on the number of MPI ranks.

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

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

#include <functional>
#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  // Points and weights of a quadrature rule over the ball of radius delta
  // around the origin (Gauss-Legendre in r and in cos(polar angle),
  // trapezoidal in the azimuth).
  template <int dim>
  void
  ball_rule(const double                 delta,
            std::vector<Tensor<1, dim>> &points,
            std::vector<double>         &weights)
  {
    // Exact for the polynomial integrands of a constant or conical
    // influence (radial degree <= 15, trigonometric degree < n_azimuth);
    // the Gaussian's converges to round-off with 16 radial points.
    const QGauss<1>    radial(dim == 2 ? 16 : 8), polar(8);
    const unsigned int n_azimuth = dim == 2 ? 24 : 12;
    points.clear();
    weights.clear();
    for (unsigned int q = 0; q < radial.size(); ++q)
      {
        const double r  = delta * radial.point(q)[0];
        const double wr = delta * radial.weight(q) * std::pow(r, dim - 1);
        for (unsigned int a = 0; a < n_azimuth; ++a)
          {
            const double phi = 2 * M_PI * (a + 0.5) / n_azimuth;
            const double wa  = 2 * M_PI / n_azimuth;
            if constexpr (dim == 2)
              {
                Tensor<1, dim> x;
                x[0] = r * std::cos(phi);
                x[1] = r * std::sin(phi);
                points.push_back(x);
                weights.push_back(wr * wa);
              }
            else
              for (unsigned int p = 0; p < polar.size(); ++p)
                {
                  const double   c = 2 * polar.point(p)[0] - 1;
                  const double   s = std::sqrt(1 - c * c);
                  Tensor<1, dim> x;
                  x[0] = r * s * std::cos(phi);
                  x[1] = r * s * std::sin(phi);
                  x[2] = r * c;
                  points.push_back(x);
                  weights.push_back(wr * wa * 2 * polar.weight(p));
                }
          }
      }
  }
} // namespace


template <int dim>
void
check(const std::string &influence,
      const double       poisson,
      const unsigned int order,
      const unsigned int degree,
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
  prm.enter_subsection("linear peridynamic solid");
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", std::to_string(poisson));
  prm.set("Plane model", "plane strain");
  prm.set("Influence function", influence);
  prm.leave_subsection();
  const auto model =
    Models::ModelRegistry<dim>::create("linear peridynamic solid", prm);

  const double                 horizon = m_ratio; // h = 1
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 2 * horizon + 2 * std::sqrt(dim));
  Discretization::NeighborList<dim> lists;
  lists.reinit(nodes,
               horizon,
               PeriDEAL::Quadrature::ExactPartialVolume<dim>(),
               true,
               false);
  Operators::BondOperator<dim> op;
  op.reinit(nodes, lists, *model, horizon);
  PeriDEAL::Quadrature::CollocationSettings settings;
  settings.order    = order;
  const auto report = op.use_collocation(settings);

  // Collocation nodes whose every stencil neighbour has a full stencil:
  // their clouds' dilatations all come from the collocation row.
  const auto &lattice = lists.lattice();
  const auto  deep    = [&](const unsigned int i) {
    if (!op.is_collocation_node(i))
      return false;
    for (const auto &o : lists.stencil())
      {
        auto y = lattice.coordinates(i);
        for (unsigned int d = 0; d < dim; ++d)
          y[d] += o.offset[d];
        if (!lists.has_full_stencil(lattice.node_at(y)))
          return false;
      }
    return true;
  };

  typename Operators::BondOperator<dim>::VectorType u, force, force_2;
  op.initialize_dof_vector(u);
  op.initialize_dof_vector(force);
  op.initialize_dof_vector(force_2);

  // A polynomial field of degree `degree` (2 or 4) with fixed coefficients:
  // each component a sum over monomials of the degree-graded basis.
  const auto field = [&](const Point<dim> &x) {
    Tensor<1, dim> v;
    Tensor<1, dim> y;
    for (unsigned int d = 0; d < dim; ++d)
      y[d] = (x[d] - 0.5 * n_cells) / n_cells;
    for (unsigned int c = 0; c < dim; ++c)
      {
        double value = 0.3 * (c + 1) * y[c];
        // Products y_a y_b (y_e y_f for order 4), coefficients from a
        // fixed formula.
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = a; b < dim; ++b)
            {
              const double q = 0.2 + 0.1 * c - 0.07 * a + 0.13 * b;
              value += q * y[a] * y[b];
              if (degree >= 4)
                for (unsigned int e = 0; e < dim; ++e)
                  {
                    value += 0.11 * (1 + a + 2 * e - c) * y[a] * y[b] * y[e];
                    value += 0.05 * (1 + b + e + c) * y[a] * y[b] * y[e] *
                             y[(e + c) % dim];
                  }
            }
        v[c] = 1e-3 * value;
      }
    return v;
  };
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      const Tensor<1, dim> value = field(nodes[i].location);
      for (unsigned int c = 0; c < dim; ++c)
        u[nodes[i].dofs[c]] = value[c];
    }
  u.update_ghost_values();
  op.apply(u, force);

  // The continuum operator by quadrature, from the model's functions.
  std::vector<Tensor<1, dim>> xi;
  std::vector<double>         w;
  ball_rule<dim>(horizon, xi, w);
  std::vector<double> omega(xi.size()), alpha(xi.size()), beta(xi.size());
  double              m = 0;
  for (unsigned int q = 0; q < xi.size(); ++q)
    {
      const double r = xi[q].norm();
      omega[q]       = model->influence(r, horizon);
      alpha[q]       = model->dilatation_constant(r, horizon);
      beta[q]        = model->extension_constant(r, horizon);
      m += w[q] * omega[q] * r * r;
    }
  const auto theta = [&](const Point<dim> &x) {
    const Tensor<1, dim> ux  = field(x);
    double               sum = 0;
    for (unsigned int q = 0; q < xi.size(); ++q)
      sum += w[q] * omega[q] * (xi[q] * (field(x + xi[q]) - ux));
    return dim / m * sum;
  };
  const auto continuum = [&](const Point<dim> &x) {
    const Tensor<1, dim> ux = field(x);
    Tensor<1, dim>       f;
    for (unsigned int q = 0; q < xi.size(); ++q)
      {
        const Tensor<1, dim> n = xi[q] / xi[q].norm();
        f += w[q] / m *
             (alpha[q] * theta(x + xi[q]) +
              2 * beta[q] * (n * (field(x + xi[q]) - ux))) *
             n;
      }
    return f;
  };
  // Navier's operator of the quadratic part: mu Laplace u + (c_K / d + 2 mu)
  // grad div u, c_K / d = dilatation_energy_modulus().
  const double mu     = model->shear_modulus();
  const double kd     = model->dilatation_energy_modulus() + 2 * mu;
  const auto   navier = [&](const Point<dim> &x) {
    // Second derivatives by central differences of the quadratic field
    // (exact to round-off for a quadratic, step 1).
    Tensor<1, dim> f;
    for (unsigned int c = 0; c < dim; ++c)
      for (unsigned int a = 0; a < dim; ++a)
        {
          Tensor<1, dim> ea, ec;
          ea[a]             = 1;
          ec[c]             = 1;
          const auto second = [&](const unsigned int    comp,
                                  const Tensor<1, dim> &p,
                                  const Tensor<1, dim> &q) {
            return field(x + p + q)[comp] - field(x + p - q)[comp] -
                   field(x - p + q)[comp] + field(x - p - q)[comp];
          };
          f[c] += mu * second(c, ea, ea) / 4 + kd * second(a, ea, ec) / 4;
        }
    return f;
  };

  double       worst = 0, largest = 0, worst_navier = 0;
  unsigned int n_deep = 0, n_checked = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      largest = std::max(largest, std::abs(force[nodes[i].dofs[c]]));
  largest = Utilities::MPI::max(largest, comm);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    if (deep(i))
      {
        ++n_deep;
        // The quadrature reference at every deep node in 2D, at every
        // third in 3D (it costs a nested quadrature per node).
        if (dim == 3 && (lattice.coordinates(i)[0] + lattice.coordinates(i)[1] +
                         lattice.coordinates(i)[2]) %
                            3 !=
                          0)
          continue;
        ++n_checked;
        const Tensor<1, dim> reference = continuum(nodes[i].location);
        const Tensor<1, dim> closed    = navier(nodes[i].location);
        for (unsigned int c = 0; c < dim; ++c)
          {
            worst = std::max(worst,
                             std::abs(force[nodes[i].dofs[c]] -
                                      nodes[i].volume() * reference[c]));
            if (degree == 2)
              worst_navier =
                std::max(worst_navier, std::abs(reference[c] - closed[c]));
          }
      }
  worst        = Utilities::MPI::max(worst, comm);
  worst_navier = Utilities::MPI::max(worst_navier, comm);
  n_deep       = Utilities::MPI::sum(n_deep, comm);
  n_checked    = Utilities::MPI::sum(n_checked, comm);

  // A smooth non-polynomial field: the assembled matrix against the
  // matrix-free apply, the diagonal, threads.
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      {
        const Point<dim> &x = nodes[i].location;
        u[nodes[i].dofs[c]] =
          1e-3 * (std::sin(0.3 * x[0] + c) * std::cos(0.2 * x[dim - 1]) +
                  0.01 * x[c] * x[0]);
      }
  u.update_ghost_values();
  MultithreadInfo::set_thread_limit(1);
  op.apply(u, force);
  MultithreadInfo::set_thread_limit(2);
  op.apply(u, force_2);

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
  typename Operators::BondOperator<dim>::VectorType diagonal;
  op.initialize_dof_vector(diagonal);
  op.compute_diagonal(diagonal);
  double diag_diff = 0, diag_max = 0;
  for (const auto dof : owned)
    {
      diag_diff =
        std::max(diag_diff, std::abs(diagonal[dof] - matrix.el(dof, dof)));
      diag_max = std::max(diag_max, std::abs(matrix.el(dof, dof)));
    }
  diag_diff      = Utilities::MPI::max(diag_diff, comm);
  diag_max       = Utilities::MPI::max(diag_max, comm);
  bool identical = true;
  for (unsigned int k = 0; k < force.locally_owned_size(); ++k)
    identical = identical && force.local_element(k) == force_2.local_element(k);
  identical = Utilities::MPI::min(identical ? 1 : 0, comm) == 1;

  if (Utilities::MPI::this_mpi_process(comm) == 0)
    {
      std::cout << dim << "D LPS (" << influence << ", nu = " << poisson
                << "), C" << order << ", m = " << m_ratio << ", " << n_cells
                << "^" << dim << " nodes: " << report.n_collocation_nodes
                << " collocation nodes (n_c = " << report.n_collocation << "), "
                << report.n_cut_nodes << " standard, " << n_deep
                << " with every cloud dilatation from collocation\n"
                << "  the dilatation term is present (|c_K / d| > mu / 10): "
                << (std::abs(model->dilatation_energy_modulus()) >
                        0.1 * model->shear_modulus() ?
                      "yes" :
                      "NO")
                << '\n'
                << "  polynomial field of degree " << degree
                << ": V times the continuum LPS operator (quadrature) at the "
                << "checked nodes (" << (n_checked > 0 ? "> 0" : "NONE");
      if (degree <= order)
        std::cout << ") to <= 1e-10 of the largest force: "
                  << (n_checked > 0 && worst <= 1e-10 * largest ? "yes" : "NO")
                  << '\n';
      else
        std::cout << "), negative control (the degree exceeds the order): "
                     "misses by more than 1e-6 of the largest force: "
                  << (worst > 1e-6 * largest ? "yes" : "NO") << '\n';
      if (degree == 2)
        std::cout << "  the quadrature reference is Navier's operator "
                     "mu Laplace u + (c_K/d + 2 mu) grad div u to <= 1e-10 "
                     "of the largest force: "
                  << (worst_navier <= 1e-10 * largest ? "yes" : "NO") << '\n';
      std::cout << "  K u = -F(u) on a smooth field to <= 1e-12 relative "
                   "(assembled against matrix-free): "
                << (diff2 <= 1e-24 * norm2 && norm2 > 0 ? "yes" : "NO") << '\n'
                << "  diagonal (compute_diagonal()) = diag(K) to <= 1e-12 "
                   "relative: "
                << (diag_diff <= 1e-12 * diag_max ? "yes" : "NO") << '\n';
      std::cout << "  1 and 2 threads give bitwise the same forces: "
                << (identical ? "yes" : "NO") << '\n';
    }
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  check<2>("gaussian", 0.3, 2, 2, 24, 3.);
  check<2>("gaussian", 0.3, 2, 4, 24, 3.);
  check<2>("conical", 0.2, 4, 4, 24, 2.5);
  check<3>("conical", 0.3, 2, 2, 16, 2.5);
}
