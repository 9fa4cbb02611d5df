// Finite kinematics and bond failure of the matrix-free operator, against
// brute-force sums written here from the definitions (Kind of test:
// brute-force reference and a derivative check, 1 and 2 ranks):
//
// - forces with the deformed bond direction, f_i = sum_j V_i w_ij
//   (t_ij + t_ji) (xi + eta)/|xi + eta|, extension e = |xi + eta| - |xi|,
//   over the bonds whose stretch e/|xi| stays below the critical stretch;
//   (the surface nodes whose neighbourhoods repeat along x run in runs of
//   consecutive slots, the others one by one with gathers: both paths
//   are in the sum, and the test asserts that runs of two or more nodes
//   were used before the commit and runs after it; after the
//   commit, nodes of the full stencil with broken bonds stay in the
//   stencil chunks, and surface nodes with broken bonds in their runs,
//   with those bonds masked, also asserted);
// - the bonds found over it are exactly the pairs the brute force finds:
//   after commit_broken_bonds() the broken bonds of the bond state are
//   those pairs, pair by pair; and they stay out: after the displacement
//   is relaxed to a tenth, where no bond reaches its critical stretch
//   (asserted by the brute force), the forces and the energy are the
//   brute-force sums without the committed bonds (an uncommitted bond
//   would be back in the sums), and evaluating there breaks no bond;
// - the elastic energy against sum_i V_i W_i (from its own pass, and from
//   the force pass of apply_with_energy()), and its derivative against
//   the forces (central differences: F = -dE/du, which holds because the
//   finite-deformation kernel is hyperelastic);
// - serial only: the power-method estimate of the largest eigenvalue of
//   M^{-1} K against LAPACK on the assembled K, and Gershgorin's bound
//   above it.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <algorithm>
#include <iostream>
#include <utility>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

// A smooth field plus an opening across x = x_c that stretches the bonds
// crossing it by a few per cent (some above, some below the critical
// stretch, depending on their direction and length).
template <int dim>
Tensor<1, dim>
field(const Point<dim> &x, const double x_c)
{
  Tensor<1, dim> u;
  for (unsigned int c = 0; c < dim; ++c)
    u[c] = 2e-3 * (std::sin(0.4 * x[0] + c) + 0.3 * x[1] * x[dim - 1]);
  if (x[0] > x_c)
    u[0] += 0.03 + 0.01 * std::sin(x[1]);
  return u;
}

// The same field relaxed to a tenth: every stretch stays well below the
// critical stretch (the brute force checks it).
constexpr double relaxation = 0.1;

template <int dim>
void
check(const std::string &model_name,
      const unsigned int n_cells,
      const double       m_ratio)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  GridGenerator::subdivided_hyper_cube(tria, n_cells, 0, n_cells);
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);

  const double     s0 = 0.012;
  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(model_name);
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", model_name == "bond-based" ? "0.25" : "0.3");
  prm.set("Critical stretch", "0.012");
  prm.set("Density", "2");
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

  const double                 horizon = m_ratio;
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

  const double                                      x_c = 0.5 * n_cells - 0.1;
  typename Operators::BondOperator<dim>::VectorType u, force;
  op.initialize_dof_vector(u);
  op.initialize_dof_vector(force);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      const auto value = field(nodes[i].location, x_c);
      for (unsigned int c = 0; c < dim; ++c)
        u[nodes[i].dofs[c]] = value[c];
    }
  u.update_ghost_values();
  // Surface runs with more than one node exist before the commit (a run
  // of one node would pass the run path without vectorising anything).
  const unsigned int longest_run =
    Utilities::MPI::max(op.max_run_length(), comm);
  const unsigned int n_run_nodes_before =
    Utilities::MPI::sum(op.n_run_nodes(), comm);
  // The forces before the commit come with the energy of the same pass.
  const double      energy_before = op.apply_with_energy(u, force);
  const std::size_t n_committed   = op.commit_broken_bonds(state);
  typename Operators::BondOperator<dim>::VectorType force_after;
  op.initialize_dof_vector(force_after);
  op.apply(u, force_after);
  const double energy = op.elastic_energy(u);

  // Brute force over the whole mesh.
  std::vector<Discretization::Node<dim>> all;
  for (const auto &part :
       Utilities::MPI::all_gather(comm,
                                  std::vector<Discretization::Node<dim>>(
                                    nodes.nodes().begin(),
                                    nodes.nodes().begin() + nodes.n_owned())))
    all.insert(all.end(), part.begin(), part.end());
  const unsigned int          n = all.size();
  std::vector<Tensor<1, dim>> U(n), U_relaxed(n);
  for (unsigned int i = 0; i < n; ++i)
    {
      U[i]         = field(all[i].location, x_c);
      U_relaxed[i] = relaxation * U[i];
    }
  auto weight = [&](const unsigned int i, const unsigned int j) {
    return i == j ? 0. :
                    exact.weight(all[i].location, horizon, all[j].cell) *
                      all[j].volume();
  };
  // Deformed bond, extension, below the critical stretch?
  auto bond = [&](const std::vector<Tensor<1, dim>> &D,
                  const unsigned int                 i,
                  const unsigned int                 j,
                  Tensor<1, dim>                    &y,
                  double                            &r,
                  double                            &e) {
    const Tensor<1, dim> xi = all[j].location - all[i].location;
    r                       = xi.norm();
    y                       = xi + (D[j] - D[i]);
    e                       = y.norm() - r;
    return e / r < s0;
  };
  // The bond pairs over the critical stretch at u (as global DoF pairs,
  // both directions) and at the relaxed displacement; m_i from all bonds.
  std::vector<double> m(n, 0.);
  std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
              failed;
  std::size_t failed_pairs = 0, failed_relaxed = 0;
  std::vector<std::vector<char>> is_failed(n);
  for (unsigned int i = 0; i < n; ++i)
    {
      is_failed[i].assign(n, 0);
      for (unsigned int j = 0; j < n; ++j)
        {
          const double w = weight(i, j);
          if (w == 0)
            continue;
          Tensor<1, dim> y;
          double         r = (all[j].location - all[i].location).norm(), e;
          m[i] += model->influence(r, horizon) * r * r * w;
          if (!bond(U, i, j, y, r, e))
            {
              is_failed[i][j] = 1;
              failed.emplace_back(all[i].dofs[0], all[j].dofs[0]);
              failed_pairs += (i < j);
            }
          failed_relaxed += (i < j) && !bond(U_relaxed, i, j, y, r, e);
        }
    }
  std::sort(failed.begin(), failed.end());

  // Forces of the owned nodes and their energy sum_i V_i W_i from the
  // displacement D, without the bonds for which is_out(i, j) holds.
  // The potential of the LPS force state (t = (c_K theta omega r + c_mu
  // omega e) / m, c_K = d kappa - c_mu / d): W = c_mu/(2m) sum omega e^2 w +
  // lambda theta^2 / 2 with lambda = c_K / d = kappa - c_mu / d^2, i.e.
  // K - 5 mu / 3 (3D) and kappa - 2 mu (2D). Bond-based: lambda = 0.
  const double K = model->bulk_modulus(), mu = model->shear_modulus();
  const double kappa =
    dim == 3 ?
      K :
      (model->plane_stress() ? 9 * K * mu / (3 * K + 4 * mu) : K + mu / 3);
  const double lambda =
    model->is_state_based() ? (dim == 3 ? K - 5 * mu / 3 : kappa - 2 * mu) : 0.;
  const auto brute_force = [&](const std::vector<Tensor<1, dim>> &D,
                               const auto                        &is_out,
                               std::vector<Tensor<1, dim>>       &f,
                               double                            &energy) {
    std::vector<double> theta(n, 0.);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          const double w = weight(i, j);
          if (w == 0 || is_out(i, j))
            continue;
          Tensor<1, dim> y;
          double         r, e;
          bond(D, i, j, y, r, e);
          theta[i] += model->influence(r, horizon) * r * w * e;
        }
    for (unsigned int i = 0; i < n; ++i)
      theta[i] *= model->is_state_based() ? dim / m[i] : 0.;
    f.assign(n, Tensor<1, dim>());
    energy = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        if (!dof_handler.locally_owned_dofs().is_element(all[i].dofs[0]))
          continue;
        double W = 0;
        for (unsigned int j = 0; j < n; ++j)
          {
            const double w = weight(i, j);
            if (w == 0 || is_out(i, j))
              continue;
            Tensor<1, dim> y;
            double         r, e;
            bond(D, i, j, y, r, e);
            const double t =
              model->dilatation_coefficient(m[i], r, horizon) * theta[i] +
              model->dilatation_coefficient(m[j], r, horizon) * theta[j] +
              (model->extension_coefficient(m[i], r, horizon) +
               model->extension_coefficient(m[j], r, horizon)) *
                e;
            f[i] += all[i].volume() * w * t * y / y.norm();
            W += 0.5 * model->extension_coefficient(m[i], r, horizon) * e * e *
                 w;
          }
        W += 0.5 * lambda * theta[i] * theta[i];
        energy += all[i].volume() * W;
      }
    energy = Utilities::MPI::sum(energy, comm);
  };
  // Relative l2 difference of an operator's forces from brute-force ones.
  const auto difference = [&](const typename Operators::BondOperator<
                                dim>::VectorType                &force_vector,
                              const std::vector<Tensor<1, dim>> &f) {
    double diff2 = 0, norm2 = 0;
    for (unsigned int i = 0; i < n; ++i)
      if (dof_handler.locally_owned_dofs().is_element(all[i].dofs[0]))
        for (unsigned int c = 0; c < dim; ++c)
          {
            diff2 += std::pow(force_vector[all[i].dofs[c]] - f[i][c], 2);
            norm2 += f[i][c] * f[i][c];
          }
    return std::sqrt(Utilities::MPI::sum(diff2, comm) /
                     Utilities::MPI::sum(norm2, comm));
  };

  std::vector<Tensor<1, dim>> brute_f;
  double                      brute_energy = 0;
  brute_force(
    U,
    [&](const unsigned int i, const unsigned int j) {
      return is_failed[i][j] != 0;
    },
    brute_f,
    brute_energy);
  double norm2 = 0;
  for (unsigned int i = 0; i < n; ++i)
    if (dof_handler.locally_owned_dofs().is_element(all[i].dofs[0]))
      norm2 += brute_f[i] * brute_f[i];
  norm2                       = Utilities::MPI::sum(norm2, comm);
  const double relative       = difference(force, brute_f);
  const double relative_after = difference(force_after, brute_f);
  const double energy_error   = std::abs(energy - brute_energy) / brute_energy;
  // Before the commit the bonds over the critical stretch are left out of
  // the same pass, so its energy is the same sum.
  const double energy_before_error =
    std::abs(energy_before - brute_energy) / brute_energy;

  // The broken bonds of the bond state, pair by pair: owned node, then
  // neighbour (global DoF of the first component), both directions.
  std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
    committed;
  {
    std::vector<std::pair<types::global_dof_index, types::global_dof_index>>
      mine;
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      if (lists.has_list(i))
        for (unsigned int k = 0; k < lists.n_bonds(i); ++k)
          if (state.is_broken(i, k))
            mine.emplace_back(nodes[i].dofs[0],
                              nodes[state.neighbor(i, k)].dofs[0]);
    for (const auto &part : Utilities::MPI::all_gather(comm, mine))
      committed.insert(committed.end(), part.begin(), part.end());
    std::sort(committed.begin(), committed.end());
  }
  const bool same_pairs = committed == failed;

  // Relaxed: the committed bonds stay out although no bond is over its
  // critical stretch any more; this evaluation breaks nothing new.
  typename Operators::BondOperator<dim>::VectorType u_relaxed, force_relaxed;
  op.initialize_dof_vector(u_relaxed);
  op.initialize_dof_vector(force_relaxed);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      u_relaxed[nodes[i].dofs[c]] = relaxation * u[nodes[i].dofs[c]];
  u_relaxed.update_ghost_values();
  const double energy_relaxed_pass = op.apply_with_energy(u_relaxed,
                                                          force_relaxed);
  const std::size_t n_committed_relaxed = op.commit_broken_bonds(state);
  const double      energy_relaxed      = op.elastic_energy(u_relaxed);
  std::vector<Tensor<1, dim>> brute_f_relaxed;
  double                      brute_energy_relaxed = 0;
  brute_force(
    U_relaxed,
    [&](const unsigned int i, const unsigned int j) {
      return is_failed[i][j] != 0;
    },
    brute_f_relaxed,
    brute_energy_relaxed);
  const double relative_relaxed = difference(force_relaxed, brute_f_relaxed);
  const double energy_relaxed_error =
    std::max(std::abs(energy_relaxed - brute_energy_relaxed),
             std::abs(energy_relaxed_pass - brute_energy_relaxed)) /
    brute_energy_relaxed;
  // The same sums with every bond in: what an operator that forgot the
  // commit would give (the test must be able to tell them apart).
  std::vector<Tensor<1, dim>> intact_f_relaxed;
  double                      intact_energy_relaxed = 0;
  brute_force(
    U_relaxed,
    [](const unsigned int, const unsigned int) { return false; },
    intact_f_relaxed,
    intact_energy_relaxed);
  const double commit_effect = difference(force_relaxed, intact_f_relaxed);

  const unsigned int n_run_nodes = Utilities::MPI::sum(op.n_run_nodes(), comm);
  // Nodes of the full stencil that lost bonds: the passes keep them in the
  // stencil chunks with their broken bonds masked.
  unsigned int n_masked = 0, n_surface_broken = 0;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      n_masked += lists.has_full_stencil(i) && state.any_broken(i);
      n_surface_broken += !lists.has_full_stencil(i) && state.any_broken(i);
    }
  // Surface nodes that lost bonds stay in their runs, those bonds masked:
  // the runs hold as many nodes as before the commit.
  const bool runs_kept =
    n_run_nodes == n_run_nodes_before &&
    Utilities::MPI::sum(n_surface_broken, comm) > 0;
  n_masked = Utilities::MPI::sum(n_masked, comm);

  // F = -dE/du by central differences at a few DoFs (the bonds over the
  // critical stretch are broken for good now, so E is smooth).
  double       fd_error = 0;
  const double eps      = 1e-6;
  for (const unsigned int node : {0u, n / 3, n / 2 + 1, n - 1})
    for (unsigned int c = 0; c < dim; ++c)
      {
        const auto   dof   = all[node].dofs[c];
        const bool   mine  = dof_handler.locally_owned_dofs().is_element(dof);
        const double value = mine ? u[dof] : 0.;
        u.zero_out_ghost_values();
        if (mine)
          u[dof] = value + eps;
        u.update_ghost_values();
        const double plus = op.elastic_energy(u);
        u.zero_out_ghost_values();
        if (mine)
          u[dof] = value - eps;
        u.update_ghost_values();
        const double minus = op.elastic_energy(u);
        u.zero_out_ghost_values();
        if (mine)
          u[dof] = value;
        u.update_ghost_values();
        const double f =
          Utilities::MPI::sum(mine ? force_after[dof] : 0., comm);
        const double scale = std::sqrt(norm2 / (dim * n));
        fd_error =
          std::max(fd_error, std::abs(-(plus - minus) / (2 * eps) - f) / scale);
      }

  std::cout << dim << "D " << model_name << ": " << n << " nodes, "
            << failed_pairs << " bond pairs over the critical stretch\n"
            << "  finite-kinematics forces against the brute-force sum <= "
               "1e-12: "
            << (relative <= 1e-12 ? "yes" : "NO")
            << "\n  committed pairs = brute-force pairs, pair by pair: "
            << (n_committed == failed_pairs && same_pairs ? "yes" : "NO")
            << "\n  forces after the commit, same displacement, unchanged <= "
               "1e-12: "
            << (relative_after <= 1e-12 ? "yes" : "NO")
            << "\n  elastic energy against the brute-force sum <= 1e-12: "
            << (energy_error <= 1e-12 ? "yes" : "NO")
            << "\n  energy from the force pass before the commit, the same "
               "<= 1e-12: "
            << (energy_before_error <= 1e-12 ? "yes" : "NO")
            << "\n  relaxed to a tenth: no bond over the critical stretch "
               "(brute force): "
            << (failed_relaxed == 0 ? "yes" : "NO")
            << "\n  relaxed: forces = brute force without the committed "
               "bonds <= 1e-12: "
            << (relative_relaxed <= 1e-12 ? "yes" : "NO")
            << "\n  relaxed: forces differ from all bonds intact by > 1e-3: "
            << (commit_effect > 1e-3 ? "yes" : "NO")
            << "\n  relaxed: energy (both passes) without the committed bonds "
               "<= 1e-12: "
            << (energy_relaxed_error <= 1e-12 ? "yes" : "NO")
            << "\n  relaxed: no new bond broken: "
            << (n_committed_relaxed == 0 ? "yes" : "NO")
            << "\n  surface nodes evaluated in runs (after the commit) > 0: "
            << (n_run_nodes > 0 ? "yes" : "NO")
            << "\n  surface nodes that lost bonds stay in their runs "
               "(masked): "
            << (runs_kept ? "yes" : "NO")
            << "\n  longest surface run (before the commit) >= 2 nodes: "
            << (longest_run >= 2 ? "yes" : "NO")
            << "\n  stencil nodes with masked broken bonds (after the commit) "
               "> 0: "
            << (n_masked > 0 ? "yes" : "NO")
            << "\n  F = -dE/du by central differences <= 1e-6: "
            << (fd_error <= 1e-6 ? "yes" : "NO") << std::endl;
  if (relative > 1e-12 || n_committed != failed_pairs || !same_pairs ||
      energy_error > 1e-12 || relative_after > 1e-12 ||
      energy_before_error > 1e-12 || failed_relaxed != 0 ||
      relative_relaxed > 1e-12 || commit_effect <= 1e-3 ||
      energy_relaxed_error > 1e-12 || n_committed_relaxed != 0 ||
      fd_error > 1e-6 || n_run_nodes == 0 || longest_run < 2 || n_masked == 0)
    std::cout << "  (force " << relative << ", after the commit "
              << relative_after << ", committed " << n_committed << " ("
              << committed.size() << " directed, " << failed.size()
              << " by brute force), energy " << energy_error
              << ", energy before " << energy_before_error << ", relaxed: "
              << failed_relaxed << " over, force " << relative_relaxed
              << ", against all intact " << commit_effect << ", energy "
              << energy_relaxed_error << ", new " << n_committed_relaxed
              << "; derivative " << fd_error << ", run nodes " << n_run_nodes
              << ", longest run " << longest_run << ", masked nodes "
              << n_masked << ")" << std::endl;

  if (Utilities::MPI::n_mpi_processes(comm) == 1)
    {
      // lambda_max(M^{-1} K) exactly, with K the linearised stiffness of
      // the intact bonds.
      const double                   rho = model->density();
      TrilinosWrappers::SparseMatrix K;
      op.assemble(K);
      const unsigned int       N = K.m();
      LAPACKFullMatrix<double> A(N, N);
      for (auto it = K.begin(); it != K.end(); ++it)
        A(it->row(), it->column()) =
          it->value() / (rho * std::sqrt(all[it->row() / dim].volume() *
                                         all[it->column() / dim].volume()));
      // Symmetrise (the LPS stiffness is symmetric up to round-off).
      for (unsigned int r = 0; r < N; ++r)
        for (unsigned int c = 0; c < r; ++c)
          A(r, c) = A(c, r) = 0.5 * (A(r, c) + A(c, r));
      Vector<double>     values;
      FullMatrix<double> vectors;
      A.compute_eigenvalues_symmetric(-1e300, 1e300, 0, values, vectors);
      const double largest    = values[values.size() - 1];
      const double power      = op.estimate_largest_eigenvalue(rho, 60);
      const double gershgorin = op.gershgorin_eigenvalue_bound(rho);
      std::cout << "  power method within 3% below the largest eigenvalue: "
                << (power <= largest * (1 + 1e-10) && power >= 0.97 * largest ?
                      "yes" :
                      "NO")
                << "\n  Gershgorin bound above it: "
                << (gershgorin >= largest ? "yes" : "NO") << std::endl;
      std::cout << "  (lambda ratios: power " << std::setprecision(3)
                << power / largest << ", Gershgorin " << gershgorin / largest
                << ")" << std::endl;
    }
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);
  check<2>("linear peridynamic solid", 14, 3);
  check<2>("bond-based", 14, 3);
  check<3>("linear peridynamic solid", 7, 2);
  check<3>("bond-based", 7, 2.5);
}
