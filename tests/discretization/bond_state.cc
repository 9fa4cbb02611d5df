// Bond state: bonds broken by hand are left out of the forces and the
// dilatations of the matrix-free operator, consistently on every process.
//
// Bonds crossing a crack (the segment x = x_c, y < y_c, as a plane in 3D)
// are broken from one end only, on the process that owns that end;
// BondState::synchronize() must break the reverse bond and every ghost
// copy. The forces of the operator are then compared with a brute-force
// sum over all pairs of nodes of the whole mesh (gathered on every
// process), written here from the definitions: weights from the exact
// partial volumes, weighted volumes from all bonds, dilatations and forces
// from intact bonds only, the crack test applied to every pair directly.
// Kind of test: brute-force reference, 1, 2 and 4 ranks. On 4 ranks a
// process holds ghosts of several others, and BondState::exchange() sends
// each pair only to the processes holding one of its owned ends: a pair
// that reached too few processes leaves a ghost's dilatation (LPS) or a
// reverse bond wrong, and the forces differ from the brute force.

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
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
Tensor<1, dim>
field(const Point<dim> &x)
{
  Tensor<1, dim> u;
  for (unsigned int c = 0; c < dim; ++c)
    u[c] = 1e-3 * (std::sin(0.4 * x[0] + c) + 0.3 * x[1] * x[dim - 1]);
  return u;
}

template <int dim>
bool
crosses_crack(const Point<dim> &a,
              const Point<dim> &b,
              const double      x_c,
              const double      y_c)
{
  if ((a[0] - x_c) * (b[0] - x_c) >= 0)
    return false;
  const double t = (x_c - a[0]) / (b[0] - a[0]);
  return a[1] + t * (b[1] - a[1]) < y_c;
}

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

  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(model_name);
  prm.set("Young's modulus", "1");
  prm.set("Poisson's ratio", model_name == "bond-based" ? "0.25" : "0.3");
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
  const unsigned int stencil_before =
    Utilities::MPI::sum(op.n_stencil_nodes(), comm);

  // Break from the owned end only, and only where x_i < x_c.
  const double x_c = 0.5 * n_cells, y_c = 0.6 * n_cells;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    if (nodes[i].location[0] < x_c)
      for (unsigned int k = 0; k < lists.n_bonds(i); ++k)
        if (crosses_crack(nodes[i].location,
                          nodes[state.neighbor(i, k)].location,
                          x_c,
                          y_c))
          state.break_bond(i, k);
  const std::size_t n_pairs = state.synchronize();
  op.update_bond_state();

  typename Operators::BondOperator<dim>::VectorType u, force;
  op.initialize_dof_vector(u);
  op.initialize_dof_vector(force);
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    {
      const auto value = field(nodes[i].location);
      for (unsigned int c = 0; c < dim; ++c)
        u[nodes[i].dofs[c]] = value[c];
    }
  u.update_ghost_values();
  op.apply(u, force);

  // Brute force over the whole mesh.
  std::vector<Discretization::Node<dim>> all;
  for (const auto &part :
       Utilities::MPI::all_gather(comm,
                                  std::vector<Discretization::Node<dim>>(
                                    nodes.nodes().begin(),
                                    nodes.nodes().begin() + nodes.n_owned())))
    all.insert(all.end(), part.begin(), part.end());
  const unsigned int  n = all.size();
  std::vector<double> m(n, 0.), theta(n, 0.);
  auto                weight = [&](const unsigned int i, const unsigned int j) {
    return i == j ? 0. :
                                   exact.weight(all[i].location, horizon, all[j].cell) *
                      all[j].volume();
  };
  std::size_t broken_pairs = 0;
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      {
        const double w = weight(i, j);
        if (w == 0)
          continue;
        const Tensor<1, dim> xi    = all[j].location - all[i].location;
        const double         r     = xi.norm();
        const double         omega = model->influence(r, horizon);
        m[i] += omega * r * r * w;
        if (crosses_crack(all[i].location, all[j].location, x_c, y_c))
          {
            broken_pairs += (i < j);
            continue;
          }
        theta[i] += omega * r * w * (xi / r) *
                    (field(all[j].location) - field(all[i].location));
      }
  for (unsigned int i = 0; i < n; ++i)
    theta[i] *= model->is_state_based() ? dim / m[i] : 0.;

  double diff2 = 0, norm2 = 0;
  for (unsigned int i = 0; i < n; ++i)
    {
      const auto dofs = all[i].dofs;
      if (!dof_handler.locally_owned_dofs().is_element(dofs[0]))
        continue;
      Tensor<1, dim> f;
      for (unsigned int j = 0; j < n; ++j)
        {
          const double w = weight(i, j);
          if (w == 0 ||
              crosses_crack(all[i].location, all[j].location, x_c, y_c))
            continue;
          const Tensor<1, dim> xi  = all[j].location - all[i].location;
          const double         r   = xi.norm();
          const Tensor<1, dim> nij = xi / r;
          const double         e =
            nij * (field(all[j].location) - field(all[i].location));
          const double t =
            model->dilatation_coefficient(m[i], r, horizon) * theta[i] +
            model->dilatation_coefficient(m[j], r, horizon) * theta[j] +
            (model->extension_coefficient(m[i], r, horizon) +
             model->extension_coefficient(m[j], r, horizon)) *
              e;
          f += all[i].volume() * w * t * nij;
        }
      for (unsigned int c = 0; c < dim; ++c)
        {
          diff2 += std::pow(force[dofs[c]] - f[c], 2);
          norm2 += f[c] * f[c];
        }
    }
  diff2                 = Utilities::MPI::sum(diff2, comm);
  norm2                 = Utilities::MPI::sum(norm2, comm);
  const double relative = std::sqrt(diff2 / norm2);

  // The assembled stiffness with the broken bonds: K u + F_brute(u) = 0,
  // compared through the operator's own forces (equal to the brute-force
  // ones, checked above).
  TrilinosWrappers::SparseMatrix matrix;
  op.assemble(matrix);
  const IndexSet               &owned = dof_handler.locally_owned_dofs();
  TrilinosWrappers::MPI::Vector u_owned(owned, comm), ku(owned, comm);
  for (const auto dof : owned)
    u_owned[dof] = u[dof];
  u_owned.compress(VectorOperation::insert);
  matrix.vmult(ku, u_owned);
  double assembled_diff2 = 0;
  for (const auto dof : owned)
    assembled_diff2 += std::pow(ku[dof] + force[dof], 2);
  assembled_diff2                 = Utilities::MPI::sum(assembled_diff2, comm);
  const double assembled_relative = std::sqrt(assembled_diff2 / norm2);

  std::cout << dim << "D " << model_name << ": " << n << " nodes, "
            << broken_pairs << " bonds cross the crack, " << n_pairs
            << " broken by hand and synchronised, " << state.n_broken_global()
            << " broken bond ends at owned nodes\n"
            << "  nodes on the stencil " << stencil_before << " before, "
            << Utilities::MPI::sum(op.n_stencil_nodes(), comm) << " after\n"
            << "  forces against the brute-force sum <= 1e-12: "
            << (relative <= 1e-12 ? "yes" : "NO") << "\n  synchronised pairs "
            << "= pairs crossing the crack: "
            << (n_pairs == broken_pairs ? "yes" : "NO")
            << "\n  assembled K u = -F(u) with the broken bonds <= 1e-12: "
            << (assembled_relative <= 1e-12 ? "yes" : "NO") << std::endl;
  if (relative > 1e-12)
    std::cout << "  (relative difference " << relative << ")" << std::endl;
}


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);
  check<2>("linear peridynamic solid", 16, 3);
  check<2>("bond-based", 14, 2.5);
  check<3>("linear peridynamic solid", 8, 2.5);
  check<3>("bond-based", 7, 2);
}
