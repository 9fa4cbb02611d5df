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

      /// True: the BondOperator breaks bonds (nodal_system_fracture.cc).
      bool
      supports_bond_breaking() const override;

      std::size_t
      setup_failure(const SystemContext<dim>  &context,
                    const std::vector<double> &critical_stretch,
                    const typename DiscreteSystem<dim>::CutBonds &cut) override;

      void
      solve_step(const SystemContext<dim>      &context,
                 TrilinosWrappers::MPI::Vector &displacement) override;

      std::size_t
      count_critical_bonds(const double factor) override;

      bool
      supports_dynamic_relaxation() const override
      {
        return true;
      }

      void
      set_dynamic_relaxation(const Solvers::DynamicRelaxation *solver) override
      {
        dynamic_relaxation = solver;
      }

      /// True: the matrix-free operator or dynamic relaxation
      /// (nodal_system_fracture.cc).
      bool
      supports_finite_deformation() const override
      {
        return true;
      }

      void
      set_finite_deformation(
        const typename DiscreteSystem<dim>::NewtonControl &control) override;

      std::size_t
      break_critical_bonds(const double factor) override;

      std::vector<double>
      damage(const SystemContext<dim> &context) const override;

      unsigned int
      n_isolated_nodes() const override;

      unsigned int
      n_held_dofs_without_stiffness() const override;

      Tensor<1, dim>
      holding_force(const SystemContext<dim> &context,
                    const std::vector<bool>  &flagged) const override;

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

      /// Hold the owned nodes whose bonds all broke, and the directions of
      /// owned nodes in which no intact bond gives stiffness, at their last
      /// displacement: constraints added to those of the boundary
      /// conditions. Collective.
      void
      hold_isolated_nodes(const SystemContext<dim> &context);

      void
      solve_matrix_free(const SystemContext<dim>      &context,
                        TrilinosWrappers::MPI::Vector &displacement);

      /// Constraints and load at the current time, the constrained
      /// operator and the lifted right-hand side (timer "assembly").
      void
      assemble_matrix_free_step(const SystemContext<dim> &context);

      /// The local elasticity matrix and the constant modes, once.
      void
      prepare_preconditioner(const SystemContext<dim> &context);

      /// The Krylov solve of the lifted system, warm-started from the last
      /// solution's free part.
      void
      solve_matrix_free_step(const SystemContext<dim>      &context,
                             TrilinosWrappers::MPI::Vector &displacement);

      /// The log line of the matrix-free operator.
      void
      print_operator(const SystemContext<dim> &context) const;

      void
      solve_assembled(const SystemContext<dim>      &context,
                      TrilinosWrappers::MPI::Vector &displacement,
                      const bool                     verbose);

      /// Equilibrium with BondOperator::apply() at the free DoFs, into
      /// the run summary (and the log if @p verbose); keeps the
      /// displacement and the internal forces.
      void
      check_equilibrium(const SystemContext<dim>            &context,
                        const TrilinosWrappers::MPI::Vector &displacement,
                        const bool                           verbose = true);

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
      /// Matrix-free steps: the lifted right-hand side and prescribed
      /// values, the last solution's free part (warm start), the
      /// preconditioner's matrix and modes (built once).
      VectorType                     step_rhs, step_prescribed, free_solution;
      bool                           preconditioner_ready = false;
      std::vector<std::vector<bool>> constant_modes;
      /// Where the local matrix lives on a coarser lattice
      /// ('local elasticity/Coarsening'): that lattice, and the transfer
      /// handed to the solver (null otherwise).
      Operators::CoarseLattice<dim>  coarse_lattice;
      const Operators::GridTransfer *local_transfer = nullptr;
      /// Counts the assemblies of the local matrix (the preconditioner
      /// builds anew when it changes).
      std::uint64_t local_matrix_version = 0;
      /// The preconditioner's dual grid where the nodes are perturbed in
      /// their cells (empty on a uniform grid, which has its own).
      Discretization::Lattice<dim> preconditioner_cells;
      /// Bond failure: the dual cubes that the local matrix has cut (all
      /// processes together), to decide when the cracks have grown enough
      /// to assemble it again.
      std::size_t cut_cubes_built = 0;
      /// Bond failure: the owned DoFs held by hold_isolated_nodes(), in
      /// the order found, now and when the local matrix was assembled
      /// (which holds them too; assembled again when they differ on any
      /// process).
      std::vector<types::global_dof_index> held_dofs, held_dofs_built;
      /// Bond failure: the constraints of the boundary conditions alone
      /// (those the coarse lattice represents; the holds not).
      AffineConstraints<double> boundary_constraints;
      /// The last solution (ghosted) and its internal forces.
      VectorType last_displacement, last_force;
      /// Bond failure (setup_failure()): the critical stretch per node.
      std::vector<double> critical_stretch;
      /// The bond operator's diagonal in the current bond state
      /// (hold_isolated_nodes(); handed to the constrained operator).
      VectorType diagonal;
      /// Nodes held because all their bonds broke, and DoFs of other nodes
      /// held because no intact bond gives them stiffness (all processes).
      unsigned int n_isolated = 0, n_held_dofs = 0;
      /// solve_step() relaxes with this solver instead of the linear one
      /// when set (on the matrix-free operator, which it then builds
      /// whatever 'Linear solver/Operator' says).
      const Solvers::DynamicRelaxation *dynamic_relaxation = nullptr;
      /// Finite-deformation kinematics (set_finite_deformation()) and the
      /// control of its modified Newton iteration.
      bool                                        finite = false;
      typename DiscreteSystem<dim>::NewtonControl newton;

      /// The modified Newton iteration of a finite-deformation step on the
      /// lifted system: corrections from the linear solver, x updated in
      /// place; throws ExcNoConvergence, x then undefined.
      Solvers::SolverReport
      solve_newton(const SystemContext<dim> &context, VectorType &x);
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
