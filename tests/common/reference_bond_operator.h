#ifndef perideal_tests_common_reference_bond_operator_h
#define perideal_tests_common_reference_bond_operator_h

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
   * Test oracles: independent, brute-force implementations that the tests
   * and benchmarks compare the library against. Not part of the library
   * (nothing here is installed).
   */
  namespace Testing
  {
    using namespace dealii;

    /**
     * One bond i -> j of the reference bond sum, with the model's
     * coefficients evaluated for this bond (make_reference_bond()).
     */
    template <int dim>
    struct ReferenceBond
    {
      /// The caller's handle of node j: what its displacement and
      /// dilatation look-ups receive.
      unsigned int neighbor;
      /// Unit bond vector \f$n_{ij} = \xi/|\xi|\f$.
      Tensor<1, dim> n;
      /// Quadrature weight \f$w_{ij} = \beta_{ij} V_j\f$.
      double weight;
      /// \f$(d/m_i)\,\omega(r)\, r\, w_{ij}\f$ (0 for bond-based models).
      double theta_factor;
      /// Dilatation coefficients \f$a_i(r), a_j(r)\f$ of the model.
      double a_i, a_j;
      /// \f$b_i(r) + b_j(r)\f$, the extension coefficients of both ends.
      double b_sum;
    };

    /**
     * The bond to @p neighbor with bond vector @p xi and weight @p weight,
     * from the model's unfactorised coefficients
     * (Models::Model::dilatation_coefficient(),
     * Models::Model::extension_coefficient()) at the weighted volumes
     * @p m_i and @p m_j. Without a list at node j (@p j_listed false) a
     * state-based bond has no j-side terms.
     */
    template <int dim>
    ReferenceBond<dim>
    make_reference_bond(const Models::Model<dim> &model,
                        const double              horizon,
                        const unsigned int        neighbor,
                        const Tensor<1, dim>     &xi,
                        const double              weight,
                        const double              m_i,
                        const bool                j_listed,
                        const double              m_j);

    /**
     * The linearised extension \f$e_{ij} = n_{ij}\cdot(u_j - u_i)\f$,
     * written out here rather than taken from Operators::BondKernel: the
     * oracle shares no code with the operator it checks.
     */
    template <int dim>
    inline double
    reference_extension(const Tensor<1, dim> &n, const Tensor<1, dim> &eta)
    {
      double e = 0;
      for (unsigned int d = 0; d < dim; ++d)
        e += n[d] * eta[d];
      return e;
    }

    /**
     * The dilatation \f$\theta_i = \sum_j \mathrm{theta\_factor}_{ij}\,
     * e_{ij}\f$ of a node with displacement @p u_i and bonds @p bonds
     * (a range of ReferenceBond), summed in bond order; @p u(bond) is the
     * displacement of the bond's far node.
     */
    template <int dim, typename Bonds, typename Displacement>
    double
    reference_dilatation(const Bonds          &bonds,
                         const Tensor<1, dim> &u_i,
                         const Displacement   &u)
    {
      double theta = 0;
      for (const ReferenceBond<dim> &bond : bonds)
        theta += bond.theta_factor * reference_extension(bond.n, u(bond) - u_i);
      return theta;
    }

    /**
     * The linearised internal force density of a node,
     * \f[
     *   f_i = \sum_j \big(a_i\theta_i + a_j\theta_j + (b_i + b_j)\, e_{ij}
     *         \big)\, w_{ij}\, n_{ij},
     * \f]
     * summed in bond order; @p u(bond) and @p theta(bond) are the
     * displacement and dilatation of the bond's far node.
     */
    template <int dim,
              typename Bonds,
              typename Displacement,
              typename Dilatation>
    Tensor<1, dim>
    reference_force_density(const Bonds          &bonds,
                            const Tensor<1, dim> &u_i,
                            const double          theta_i,
                            const Displacement   &u,
                            const Dilatation     &theta)
    {
      Tensor<1, dim> f;
      for (const ReferenceBond<dim> &bond : bonds)
        {
          const double e = reference_extension(bond.n, u(bond) - u_i);
          f += (bond.a_i * theta_i + bond.a_j * theta(bond) + bond.b_sum * e) *
               bond.weight * bond.n;
        }
      return f;
    }

    /**
     * The test oracle of the linearised peridynamic operator: the internal
     * force of a linear ordinary model (Models::Model) on a node set,
     * \f[
     *   F_i(u) = V_i \sum_j (t_{ij} + t_{ji})\, n_{ij}\, w_{ij},\qquad
     *   t_{ij} = a_i\theta_i + b_i e_{ij},
     * \f]
     * evaluated bond by bond from explicit bond data
     * (reference_force_density()), or assembled row by row as the stiffness
     * matrix \f$K = -\partial F/\partial u\f$ into a Trilinos matrix with a
     * DynamicSparsityPattern. It is a brute-force second implementation of
     * what Operators::BondOperator computes with its stencil, lists and
     * bond kernel, and shares none of that code: the tests compare the two
     * (tests/operators/bond_operator.cc), and check this one against closed
     * forms (tests/operators/linear_operator.cc). All bonds are intact.
     *
     * State-based models couple a node to every node within two horizons
     * (through the neighbours' dilatations); the sparsity pattern is built
     * exactly from the neighbour lists.
     */
    template <int dim>
    class ReferenceBondOperator
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
      using BondData = ReferenceBond<dim>;

      /// The bonds of node @p i, a range for the reference_* functions.
      struct BondRange
      {
        const BondData *first, *last;
        const BondData *
        begin() const
        {
          return first;
        }
        const BondData *
        end() const
        {
          return last;
        }
      };

      const Discretization::NodeSet<dim> *nodes       = nullptr;
      bool                                state_based = true;
      std::vector<double>                 m;
      std::vector<bool>                   listed;
      std::vector<std::size_t>            offsets;
      std::vector<BondData>               bonds;
      IndexSet                            owned;

      BondRange
      bonds_of(const unsigned int i) const;

      void
      assemble_with(TrilinosWrappers::SparseMatrix  &matrix,
                    const AffineConstraints<double> *constraints,
                    TrilinosWrappers::MPI::Vector   *rhs) const;

      template <typename Function>
      void
      for_each_bond(const unsigned int i, const Function &f) const;
    };
  } // namespace Testing
} // namespace PeriDEAL

#endif
