#ifndef perideal_problems_quasi_static_h
#define perideal_problems_quasi_static_h

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/constrained_operator.h>
#include <perideal/operators/fictitious_layer_operator.h>
#include <perideal/operators/linear_peridynamic_operator.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>

#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * The linear quasi-static PD problem \f$K u = V b\f$ with volumetric
     * Dirichlet layers, body forces and tractions (problem type
     * `quasi-static`).
     *
     * run() builds the operator that the input asks for and solves:
     * - `Linear solver/Operator = matrix-free`: the BondOperator (shared
     *   stencil in the uniform bulk, no matrix) with prescribed DoFs
     *   eliminated, and a Krylov method preconditioned by Jacobi, Chebyshev
     *   or AMG on the local elasticity operator;
     * - `assembled`: the Trilinos stiffness assembled by the same
     *   BondOperator (BondOperator::assemble()), solved directly or by a
     *   preconditioned Krylov method;
     * - with the `fictitious layer` or `surface nodes` boundary treatment:
     *   the FictitiousLayerOperator's assembled system (Scabbia et al.
     *   2023).
     * It then checks equilibrium with the matrix-free forces, compares with
     * the analytical solution when one is given, and writes PVTU output and
     * the per-node CSV.
     */
    template <int dim>
    class QuasiStatic : public ProblemType<dim>
    {
    public:
      /// No entries of its own yet.
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      void
      check_input(const Simulator<dim> &simulator) const override;

      void
      run(Simulator<dim> &simulator) override;

    private:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      void
      setup_layer_operator(Simulator<dim> &simulator);

      void
      assemble_and_solve(Simulator<dim> &simulator);

      void
      assemble_and_solve_with_layer(Simulator<dim> &simulator);

      void
      solve_matrix_free(Simulator<dim> &simulator);

      /// The Dirichlet constraints (with the rigid-motion check) and the
      /// load vector of the layer-free paths.
      void
      make_constraints_and_load(Simulator<dim> &simulator);

      void
      postprocess(Simulator<dim> &simulator);

      /// Stop with the free rigid motions named when the Dirichlet
      /// conditions do not fix all of them (the system would be singular).
      void
      check_rigid_motions(Simulator<dim> &simulator) const;

      /// Gather every node's position, displacement and error to the CSV
      /// named in 'Output/Node data file'.
      void
      write_node_data(Simulator<dim>       &simulator,
                      const Tensor<1, dim> &component_max) const;

      Operators::FictitiousLayerOperator<dim>   layer_operator;
      Discretization::BondState<dim>            bond_state;
      Operators::BondOperator<dim>              bond_operator;
      Operators::ConstrainedOperator<dim>       constrained_operator;
      TrilinosWrappers::SparseMatrix            local_matrix;
      AffineConstraints<double>                 constraints;

      TrilinosWrappers::SparseMatrix system_matrix;
      TrilinosWrappers::MPI::Vector  load;
      TrilinosWrappers::MPI::Vector  system_rhs;
      TrilinosWrappers::MPI::Vector  displacement;
      // With surface nodes: their displacements, owned ones, in the order
      // of FictitiousLayerOperator::owned_surface_nodes().
      std::vector<Tensor<1, dim>> surface_displacement;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
