/**
 * @file
 * The preconditioners that need no PD matrix: 'Chebyshev' on the exact
 * diagonal of the matrix-free operator, and 'local elasticity', algebraic
 * multigrid on classical elasticity discretised on the same nodes (for the
 * matrix-free operator and the layer systems).
 */

#include <deal.II/base/subscriptor.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/precondition.h>

#include <perideal/base/exceptions.h>
#include <perideal/solvers/integer_entry.h>
#include <perideal/solvers/preconditioner.h>

#include <memory>

namespace PeriDEAL
{
  namespace Solvers
  {
    namespace
    {
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// The matrix-free operator as deal.II's Chebyshev iteration takes it.
      struct OperatorAction : public Subscriptor
      {
        std::function<void(VectorType &, const VectorType &)> apply;
        types::global_dof_index                               n_rows = 0;

        void
        vmult(VectorType &dst, const VectorType &src) const
        {
          apply(dst, src);
        }

        types::global_dof_index
        m() const
        {
          return n_rows;
        }

        /// Needed to compile deal.II's Chebyshev set-up, which computes
        /// the diagonal itself when given none; it is always given one.
        double
        el(const types::global_dof_index, const types::global_dof_index) const
        {
          AssertThrow(false, ExcInternalError());
          return 0;
        }
      };


      /// The degree of the polynomial: more work per application, fewer
      /// iterations.
      constexpr IntegerEntry chebyshev_degree =
        {"Degree", 4, 1, 30, "Degree of the Chebyshev polynomial."};

      /**
       * A Chebyshev polynomial of the operator, on its exact diagonal, over
       * the whole spectrum (the extreme eigenvalues estimated by 20 CG
       * iterations).
       */
      class Chebyshev
        : public WithIntegerEntry<Preconditioner, chebyshev_degree>
      {
      public:
        bool
        supports(const OperatorForm form) const override
        {
          return form == OperatorForm::matrix_free;
        }

        void
        initialize(const OperatorForm,
                   const PreconditionerSetup &setup) override
        {
          action.apply  = setup.apply;
          action.n_rows = setup.n_rows;
          typename Polynomial::AdditionalData data;
          data.degree              = this->integer_parameter;
          data.smoothing_range     = 0.; // precondition the whole spectrum
          data.eig_cg_n_iterations = 20;
          data.preconditioner = std::make_shared<DiagonalMatrix<VectorType>>(
            *setup.inverse_diagonal);
          polynomial = std::make_unique<Polynomial>();
          polynomial->initialize(action, data);
        }

        void
        vmult(VectorType &dst, const VectorType &src) const override
        {
          polynomial->vmult(dst, src);
        }

        void
        clear() override
        {
          polynomial.reset();
          action.apply = nullptr;
        }

      private:
        using Polynomial = PreconditionChebyshev<OperatorAction,
                                                 VectorType,
                                                 DiagonalMatrix<VectorType>>;
        OperatorAction              action;
        std::unique_ptr<Polynomial> polynomial;
      };


      /**
       * ML algebraic multigrid on the local elasticity operator: classical
       * elasticity on the same nodes, whose iteration counts stay bounded
       * as the grid is refined (uniform grids).
       */
      class LocalElasticity : public Preconditioner
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        bool
        supports(const OperatorForm form) const override
        {
          return form != OperatorForm::assembled;
        }

        bool
        needs_local_matrix() const override
        {
          return true;
        }

        double
        bytes_per_node(const unsigned int dim) const override
        {
          // The Q1 matrix (3^dim blocks of dim x dim) and ML's hierarchy.
          return dim == 3 ? 6144 : 1536;
        }

        void
        initialize(const OperatorForm,
                   const PreconditionerSetup &setup) override
        {
          amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
          initialize_amg(*amg,
                         *setup.local_matrix,
                         setup.amg,
                         setup.constant_modes);
        }

        void
        vmult(VectorType &dst, const VectorType &src) const override
        {
          amg->vmult(dst, src);
        }

        void
        layer_vmult(TrilinosWrappers::MPI::Vector       &dst,
                    const TrilinosWrappers::MPI::Vector &src) const override
        {
          amg->vmult(dst, src);
        }

        void
        clear() override
        {
          amg.reset();
        }

      private:
        std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
      };
    } // namespace
  }   // namespace Solvers
} // namespace PeriDEAL


PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::Chebyshev,
  "Chebyshev",
  "A Chebyshev polynomial (degree 'Chebyshev/Degree') of the matrix-free "
  "operator on its exact diagonal, over the whole spectrum.")
PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::LocalElasticity,
  "local elasticity",
  "ML algebraic multigrid on classical elasticity discretised on the same "
  "nodes (Q1 on the dual grid, the same Dirichlet layers), for the "
  "matrix-free operator and the layer systems; iteration counts stay "
  "bounded as h shrinks (uniform grids).")
