// Kind of test: independent reference (divergence theorem) for the nodal
// loads of tractions given as a stress tensor.
//
// Every face of a box carries the traction tau(x) n with a stress field
// tau linear in x (not symmetric, so that transposition errors show) and
// the face's outward normal n. The nodal loads are the traction at the
// centre of each boundary cell face times its area, exact for a linear
// field; their sum must therefore equal
//   int_{boundary} tau n dA = int_body div tau dV = (div tau) |body|.
// Checked on 1 and 2 processes, 2D and 3D, on a uniform box and with a
// refined corner (faces of two sizes), to 1e-12 relative. A wrong normal
// sign, a missing face or a transposed tau fails.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/boundary_conditions.h>
#include <perideal/discretization/node_set.h>

#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
void
check(const bool refine_corner)
{
  const MPI_Comm                            comm = MPI_COMM_WORLD;
  parallel::distributed::Triangulation<dim> tria(comm);
  Point<dim>                                lower, upper;
  std::vector<unsigned int>                 subdivisions;
  for (unsigned int d = 0; d < dim; ++d)
    {
      lower[d] = -0.3 * (d + 1);
      upper[d] = 0.7 + 0.4 * d;
      subdivisions.push_back(5 + 2 * d);
    }
  GridGenerator::subdivided_hyper_rectangle(tria,
                                            subdivisions,
                                            lower,
                                            upper,
                                            true);
  if (refine_corner)
    {
      for (const auto &cell : tria.active_cell_iterators())
        if (cell->is_locally_owned() && cell->center()[0] < 0 &&
            cell->center()[1] < 0)
          cell->set_refine_flag();
      tria.execute_coarsening_and_refinement();
    }
  DoFHandler<dim> dof_handler(tria);
  FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
  dof_handler.distribute_dofs(fe);
  Discretization::NodeSet<dim> nodes;
  nodes.reinit(dof_handler, 0.5);

  // tau_ij = a_ij + sum_k b_ijk x_k; div tau_i = sum_j b_ijj.
  std::string    expression;
  Tensor<1, dim> div_tau;
  const char    *names[] = {"x", "y", "z"};
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = 0; j < dim; ++j)
      {
        expression += (expression.empty() ? "" : "; ") +
                      std::to_string(1.5 * i - 0.7 * j + 0.2);
        for (unsigned int k = 0; k < dim; ++k)
          {
            const double b = 0.3 * (i + 1) - 0.2 * j * (k + 1) + 0.1 * k * i;
            expression += " + " + std::to_string(b) + "*" + names[k];
            if (k == j)
              div_tau[i] += b;
          }
      }
  ParameterHandler prm;
  Boundary::BoundaryConditions<dim>::declare_parameters(prm);
  std::string ids;
  for (unsigned int f = 0; f < 2 * dim; ++f)
    ids += (f ? "," : "") + std::to_string(f);
  prm.set("Traction boundary ids", ids);
  prm.set("Traction given as", "stress tensor");
  prm.enter_subsection("Boundary stress");
  prm.set("Variable names", dim == 2 ? "x,y" : "x,y,z");
  prm.set("Function expression", expression);
  prm.leave_subsection();
  Boundary::BoundaryConditions<dim> conditions;
  conditions.parse_parameters(prm);

  AffineConstraints<double> constraints;
  constraints.close();
  TrilinosWrappers::MPI::Vector load(dof_handler.locally_owned_dofs(), comm);
  conditions.add_load(dof_handler, nodes, constraints, load);

  Tensor<1, dim> resultant;
  for (unsigned int i = 0; i < nodes.n_owned(); ++i)
    for (unsigned int c = 0; c < dim; ++c)
      resultant[c] += load[nodes[i].dofs[c]];
  for (unsigned int c = 0; c < dim; ++c)
    resultant[c] = Utilities::MPI::sum(resultant[c], comm);
  double volume = 1;
  for (unsigned int d = 0; d < dim; ++d)
    volume *= upper[d] - lower[d];
  const Tensor<1, dim> expected = div_tau * volume;
  const double relative = (resultant - expected).norm() / expected.norm();
  std::cout << dim << "D" << (refine_corner ? ", refined corner" : "")
            << ": sum of traction loads = (div tau) |body| to 1e-12: "
            << (relative <= 1e-12 ? "yes" : "NO") << std::endl;
  if (relative > 1e-12)
    std::cout << "  (" << resultant << " against " << expected << ")"
              << std::endl;
}

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
    std::cout.setstate(std::ios::failbit);
  check<2>(false);
  check<2>(true);
  check<3>(false);
  check<3>(true);
}
