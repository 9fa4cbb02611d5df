#ifndef perideal_operators_linear_peridynamic_operator_h
#define perideal_operators_linear_peridynamic_operator_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>

#include <vector>

namespace PeriDEAL
{
  /**
   * Nonlocal operators on PD node sets.
   */
  namespace Operators
  {
    using namespace dealii;

    /**
     * The linearised peridynamic internal force of a linear ordinary model
     * (Models::Model) on a node set: nodal forces
     * \f[
     *   F_i(u) = V_i \sum_j (t_{ij} + t_{ji})\, n_{ij}\, w_{ij},\qquad
     *   t_{ij} = a_i\theta_i + b_i e_{ij},
     * \f]
     * evaluated without a matrix (apply()) or assembled as the stiffness
     * matrix \f$K = -\partial F/\partial u\f$ in a Trilinos matrix
     * (assemble()), so that the quasi-static problem \f$-f = b\f$ reads
     * \f$K u = V b\f$. Multiplying by the node volumes makes \f$K\f$
     * symmetric on uniform grids (the discrete energy's Hessian), which CG
     * and AMG exploit.
     *
     * State-based models couple a node to every node within two horizons
     * (through the neighbours' dilatations); the sparsity pattern is built
     * exactly from the neighbour lists.
     */
    template <int dim>
    class LinearPeridynamicOperator
    {
    public:
      /**
       * Precompute the bond data. @p lists must hold lists for the owned
       * nodes and, for state-based models, for their off-process neighbours.
       */
      void
      reinit(const Discretization::NodeSet<dim>      &nodes,
             const Discretization::NeighborList<dim> &lists,
             const Models::Model<dim>                &model,
             const double                             horizon);

      /// Weighted volume \f$m_i\f$ of every node with a list (0 otherwise).
      const std::vector<double> &
      weighted_volumes() const;

      /**
       * The dilatation \f$\theta_i\f$ of every node with a list, from a
       * displacement vector that holds the values of all nodes of the set
       * (a ghosted vector with NodeSet::relevant_dofs()).
       */
      void
      compute_dilatation(const TrilinosWrappers::MPI::Vector &displacement,
                         std::vector<double>                 &dilatation) const;

      /**
       * Nodal internal forces \f$F_i\f$ of the owned nodes into
       * @p nodal_force (a non-ghosted vector of the owned DoFs), from the
       * ghosted @p displacement.
       */
      void
      apply(const TrilinosWrappers::MPI::Vector &displacement,
            TrilinosWrappers::MPI::Vector       &nodal_force) const;

      /**
       * Build the exact sparsity pattern and assemble
       * \f$K = -\partial F/\partial u\f$ into @p matrix (rows: owned DoFs).
       */
      void
      assemble(TrilinosWrappers::SparseMatrix &matrix) const;

      /**
       * Assemble the stiffness matrix of a problem with prescribed
       * displacements u_k = g_k (@p constraints, over the locally relevant
       * DoFs, holding only such identity constraints). Rows and columns of
       * constrained DoFs are eliminated: a constrained row keeps only its
       * diagonal entry \f$K_{kk}\f$ with right-hand side \f$K_{kk} g_k\f$,
       * and the columns of constrained DoFs move to the right-hand side as
       * \f$-K_{rk} g_k\f$. The matrix stays symmetric when K is; the
       * sparsity pattern holds exactly the remaining entries. Contributions
       * are added into @p rhs (owned DoFs; compressed here).
       */
      void
      assemble(TrilinosWrappers::SparseMatrix  &matrix,
               const AffineConstraints<double> &constraints,
               TrilinosWrappers::MPI::Vector   &rhs) const;

      /**
       * The number of stored (nonzero-pattern) bonds of owned nodes.
       */
      std::size_t
      n_owned_bonds() const;

      /// The owned DoFs (rows of the matrix).
      const IndexSet &
      owned_dofs() const;

    private:
      struct BondData
      {
        unsigned int   neighbor;
        Tensor<1, dim> n;            // unit bond vector
        double         weight;       // w_ij = beta_ij V_j
        double         theta_factor; // (d / m_i) omega r w_ij
        double         a_i, a_j;     // dilatation coefficients at i and j
        double         b_sum;        // b_i + b_j
      };

      const Discretization::NodeSet<dim> *nodes       = nullptr;
      bool                                state_based = true;
      std::vector<double>                 m;
      std::vector<bool>                   listed;
      std::vector<std::size_t>            offsets;
      std::vector<BondData>               bonds;
      IndexSet                            owned;

      void
      assemble_with(TrilinosWrappers::SparseMatrix  &matrix,
                    const AffineConstraints<double> *constraints,
                    TrilinosWrappers::MPI::Vector   *rhs) const;

      template <typename Function>
      void
      for_each_bond(const unsigned int i, const Function &f) const;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
