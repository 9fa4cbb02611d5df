#ifndef perideal_operators_constrained_operator_h
#define perideal_operators_constrained_operator_h

#include <deal.II/base/subscriptor.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/operators/bond_operator.h>

#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    /**
     * The stiffness \f$K = -\partial F/\partial u\f$ of a BondOperator with
     * prescribed DoFs eliminated, as a matrix-free operator for deal.II's
     * Krylov solvers: on free DoFs \f$(K u)_f\f$ with the prescribed entries
     * of \f$u\f$ taken as zero, on a prescribed DoF \f$K_{kk} u_k\f$ (its
     * own diagonal, so that the operator stays symmetric and well scaled).
     * The lifted right-hand side of \f$K u = b\f$ with \f$u_k = g_k\f$ is
     * formed by lift(); the solution of the homogeneous system plus the
     * prescribed values is the answer.
     */
    template <int dim>
    class ConstrainedOperator : public Subscriptor
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /**
       * @p constraints holds identity constraints u_k = g_k only (over the
       * locally relevant DoFs). @p diagonal: BondOperator::compute_diagonal()
       * of @p op in its current bond state, where the caller has it (it is
       * copied instead of computed again).
       */
      void
      initialize(const BondOperator<dim>         &op,
                 const AffineConstraints<double> &constraints,
                 const VectorType                *diagonal = nullptr);

      /// dst = K src, prescribed rows and columns eliminated (K the
      /// linearised stiffness, BondOperator::apply_linearised()).
      void
      vmult(VectorType &dst, const VectorType &src) const;

      /**
       * The residual \f$r = b - A(x)\f$ of the homogeneous system with the
       * right-hand side @p b of lift(). With the bond operator's linearised
       * kinematics A is K (vmult()). With finite kinematics
       * (BondOperator::set_kinematics()) A is the nonlinear operator
       * \f$A(x)_f = -(F(x + g) - F(g))_f\f$ on free DoFs, so that
       * \f$r_f = \mathrm{load}_f + F(x + g)_f\f$ (F from
       * BondOperator::apply() at the whole displacement), and
       * \f$K_{kk} x_k\f$ on a prescribed one.
       */
      void
      residual(VectorType &r, const VectorType &x, const VectorType &b) const;

      /**
       * The right-hand side of the homogeneous system: @p load (owned
       * entries, e.g. \f$V_i b_i\f$) minus \f$K g\f$ on free DoFs (plus
       * \f$F(g)\f$, kept for residual(), with finite kinematics), zero on
       * prescribed ones. @p prescribed receives g (zero on free DoFs).
       */
      void
      lift(const VectorType &load,
           VectorType       &rhs,
           VectorType       &prescribed) const;

      /// The diagonal of the operator (owned DoFs).
      const VectorType &
      diagonal() const;

      /// Whether owned vector entry @p k is prescribed.
      bool
      is_prescribed(const unsigned int k) const
      {
        return prescribed_entry[k];
      }

      /// Size (global) of the operator.
      types::global_dof_index
      m() const;

      types::global_dof_index
      n() const
      {
        return m();
      }

      /// Entry (i, i) of the operator (owned i); only the diagonal is known.
      double
      el(const types::global_dof_index i, const types::global_dof_index j) const
      {
        AssertThrow(i == j,
                    ExcMessage("Only diagonal entries of a matrix-free "
                               "operator are available."));
        return diag(i);
      }

      /// Size @p v like the operator's vectors.
      void
      initialize_dof_vector(VectorType &v) const;

      /// Number of operator applications so far.
      unsigned int
      n_applications() const
      {
        return applications;
      }

      const BondOperator<dim> &
      bond_operator() const
      {
        return *op;
      }

    private:
      const BondOperator<dim> *op = nullptr;
      std::vector<bool>        prescribed_entry;
      std::vector<double>      prescribed_value;
      /// F(g) on free DoFs, from lift() (finite kinematics).
      mutable VectorType   prescribed_force;
      VectorType           diag;
      mutable VectorType   work;
      mutable unsigned int applications = 0;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
