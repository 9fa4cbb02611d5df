#ifndef perideal_boundary_layer_system_h
#define perideal_boundary_layer_system_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/discrete_system.h>
#include <perideal/operators/fictitious_layer_operator.h>

#include <map>

namespace PeriDEAL
{
  namespace Boundary
  {
    /**
     * The system of the `fictitious layer` and `surface nodes` treatments
     * (Scabbia, Zaccariotto and Galvanetto 2023): the FictitiousLayerOperator
     * completes every neighbourhood with Taylor-extrapolated fictitious
     * nodes; with surface nodes, each external cell face carries a node with
     * its own unknowns and force-flux equation, and the boundary conditions
     * are imposed there. The system is assembled (not symmetric) and solved
     * by the simulator's linear solver. With `Operator = matrix-free` no
     * product matrix is formed: GMRES or BiCGStab run on the factored
     * operator (FictitiousLayerOperator::apply()), preconditioned by the
     * local elasticity operator on the body unknowns or not at all.
     */
    template <int dim>
    class LayerSystem : public DiscreteSystem<dim>
    {
    public:
      LayerSystem(const std::string &treatment_name,
                  const bool         with_surface_nodes,
                  const unsigned int taylor_order);

      void
      check_input(const Solvers::LinearSolver &linear_solver) const override;

      void
      setup(const SystemContext<dim> &context) override;

      void
      solve_linear(const SystemContext<dim>      &context,
                   TrilinosWrappers::MPI::Vector &displacement) override;

      bool
      is_constrained(const Discretization::Node<dim> &node) const override;

      std::vector<typename DiscreteSystem<dim>::ExtraNode>
      extra_nodes() const override;

      std::string
      extra_nodes_name() const override;

    private:
      /// GMRES or BiCGStab on FictitiousLayerOperator::apply() with the
      /// prescribed unknowns eliminated (no product matrix).
      void
      solve_matrix_free(
        const SystemContext<dim>                        &context,
        const std::map<types::global_dof_index, double> &prescribed,
        TrilinosWrappers::MPI::Vector                   &solution);

      const std::string  treatment_name;
      const bool         with_surface_nodes;
      const unsigned int taylor_order;

      Operators::FictitiousLayerOperator<dim> layer_operator;
      AffineConstraints<double>               constraints;
      TrilinosWrappers::SparseMatrix          system_matrix;
      TrilinosWrappers::SparseMatrix          local_matrix;
      TrilinosWrappers::MPI::Vector           load;
      TrilinosWrappers::MPI::Vector           system_rhs;
      // With surface nodes: their displacements, owned ones, in the order
      // of FictitiousLayerOperator::owned_surface_nodes().
      std::vector<Tensor<1, dim>> surface_displacement;
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
