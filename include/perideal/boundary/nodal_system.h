#ifndef perideal_boundary_nodal_system_h
#define perideal_boundary_nodal_system_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/discrete_system.h>
#include <perideal/discretization/bond_state.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/constrained_operator.h>

namespace PeriDEAL
{
  namespace Boundary
  {
    /**
     * The system of the `none` treatment: the body's own nodes, incomplete
     * neighbourhoods at the surface, Dirichlet values on the nodes of
     * volumetric layers and loads on the nodes (BoundaryConditions).
     *
     * The operator is the BondOperator (shared stencil in the uniform bulk,
     * lists elsewhere, bond state). With `Linear solver/Operator =
     * matrix-free` the prescribed DoFs are eliminated (ConstrainedOperator)
     * and a Krylov method runs on it, preconditioned by Jacobi, Chebyshev or
     * AMG on the local elasticity operator; with `assembled` the stiffness
     * is BondOperator::assemble() and the solver is direct or
     * Krylov on the matrix. Either way equilibrium is checked with
     * BondOperator::apply(), and Dirichlet layers that leave a rigid motion
     * free are an error that names the missing constraint.
     */
    template <int dim>
    class NodalSystem : public DiscreteSystem<dim>
    {
    public:
      void
      setup(const SystemContext<dim> &context) override;

      void
      solve_linear(const SystemContext<dim>      &context,
                   TrilinosWrappers::MPI::Vector &displacement) override;

      std::vector<IO::NodeField>
      node_fields(
        const SystemContext<dim>            &context,
        const TrilinosWrappers::MPI::Vector &displacement) const override;

      bool
      is_constrained(const Discretization::Node<dim> &node) const override;

    private:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// The Dirichlet constraints (with the rigid-motion check) and the
      /// load vector.
      void
      make_constraints_and_load(const SystemContext<dim> &context);

      /// Stop with the free rigid motions named when the Dirichlet
      /// conditions do not fix all of them (the system would be singular).
      void
      check_rigid_motions(const SystemContext<dim> &context) const;

      void
      solve_matrix_free(const SystemContext<dim>      &context,
                        TrilinosWrappers::MPI::Vector &displacement);

      void
      solve_assembled(const SystemContext<dim>      &context,
                      TrilinosWrappers::MPI::Vector &displacement);

      /// Equilibrium with BondOperator::apply() at the free DoFs, into
      /// the run summary and the log.
      void
      check_equilibrium(
        const SystemContext<dim>            &context,
        const TrilinosWrappers::MPI::Vector &displacement) const;

      Discretization::BondState<dim> bond_state;
      Operators::BondOperator<dim>   bond_operator;
      /// What the collocation scheme did (all zero with the standard one).
      typename Operators::BondOperator<dim>::CollocationReport collocation;
      Operators::ConstrainedOperator<dim> constrained_operator;
      TrilinosWrappers::SparseMatrix      local_matrix;
      AffineConstraints<double>           constraints;
      TrilinosWrappers::SparseMatrix      system_matrix;
      TrilinosWrappers::MPI::Vector       load;
      TrilinosWrappers::MPI::Vector       system_rhs;
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
