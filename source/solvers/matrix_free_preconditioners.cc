/**
 * @file
 * The preconditioners that need no PD matrix: 'Chebyshev' on the exact
 * diagonal of the matrix-free operator, and 'local elasticity', algebraic
 * multigrid on classical elasticity discretised on the same nodes (for the
 * matrix-free operator and the layer systems).
 */

#include <deal.II/base/mpi.h>
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


      /// 'local elasticity/PD Jacobi weight': its name and default.
      constexpr const char *jacobi_weight_entry   = "PD Jacobi weight";
      constexpr double      jacobi_weight_default = 0.3;

      /// 'local elasticity/Coarsening': its name.
      constexpr const char *coarsening_entry = "Coarsening";

      /**
       * ML algebraic multigrid on the local elasticity operator: classical
       * elasticity on the same nodes, whose iteration counts stay bounded
       * as the grid is refined (uniform grids). For the matrix-free
       * operator a Jacobi term on the PD operator's exact diagonal D is
       * added: \f$P^{-1} = M + \omega D^{-1}\f$, with M the V-cycle.
       *
       * Why the sum: at wavelengths below the horizon the PD stiffness
       * saturates while the local one grows like \f$1/h^2\f$, so M A is
       * small there (the smallest eigenvalues of the preconditioned
       * operator, which set the CG iteration count); \f$D^{-1} A\f$ is of
       * order one exactly there and small for smooth modes, where M A is
       * about one. The sum is symmetric positive definite and costs a
       * vector operation; \f$\omega = 0.3\f$ keeps the largest eigenvalue
       * (at most about \f$1 + 2\omega\f$) near one. On the PMB
       * centre-cracked plate it cut the CG iterations of a run to failure
       * by 24 % (100²) and 28 % (200²) with the same load-displacement
       * curve (doc/quasi-static-fracture.md).
       *
       * With 'Coarsening = 2' the local matrix lives on every second node
       * in each direction (Operators::CoarseLattice: 8 times fewer rows in
       * 3D), and \f$M = P M_c P^T\f$ with the V-cycle \f$M_c\f$ there and
       * P the multilinear interpolation to the nodes: a two-level additive
       * method whose fine level is the Jacobi term. Its matrix, hierarchy
       * and V-cycle cost about an eighth; the Jacobi term must then carry
       * the wavelengths between the horizon and 2h as well.
       */
      class LocalElasticity : public Preconditioner
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm)
        {
          prm.declare_entry(
            jacobi_weight_entry,
            "0.3",
            Patterns::Double(0, 2),
            "Weight w of the Jacobi term on the exact diagonal D of the "
            "matrix-free PD operator, added to the V-cycle M on the local "
            "elasticity matrix: P^-1 = M + w D^-1. It supplies what "
            "classical elasticity lacks at wavelengths below the horizon "
            "(fewer CG iterations for a vector operation each); 0: the "
            "V-cycle alone. Only for the matrix-free operator (the layer "
            "operators of the boundary treatments have no diagonal: leave "
            "the default there).");
          prm.declare_entry(
            coarsening_entry,
            "1",
            Patterns::Integer(1, 2),
            "The lattice the local elasticity matrix lives on: 1, the nodes "
            "themselves; 2, every second node in each direction (8 times "
            "fewer rows in 3D, 4 in 2D), interpolated multilinearly to the "
            "nodes, which cuts the matrix, the multigrid set-up, its memory "
            "and the V-cycle by about that factor. The PD Jacobi weight "
            "must then be positive, and about 0.8 serves best (it carries "
            "the wavelengths between the horizon and the coarse grid: 3D "
            "LPS, m = 3, 40^3 nodes, 23 CG iterations at 0.3, 15 at 0.8, 17 "
            "at 1.5; 60^3: 23 and 16). 2 needs the matrix-free operator "
            "(boundary treatment 'none') and a uniform grid; with bond "
            "failure a coarse cube is cut where a cube of the nodes inside "
            "it is.");
        }

        void
        parse_parameters(ParameterHandler &prm) override
        {
          jacobi_weight = prm.get_double(jacobi_weight_entry);
          coarsening    = prm.get_integer(coarsening_entry);
          AssertThrow(
            coarsening == 1 || jacobi_weight > 0,
            ExcInvalidInput("Linear solver/local elasticity/" +
                              std::string(jacobi_weight_entry),
                            format_number(jacobi_weight),
                            "with 'Coarsening = 2' the Jacobi term is the only "
                            "part of the preconditioner on the finest "
                            "wavelengths: give it a positive weight (0.3)"));
        }

        unsigned int
        local_matrix_coarsening() const override
        {
          return coarsening;
        }

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
          // The Q1 matrix (3^dim blocks of dim x dim) and ML's hierarchy;
          // on a coarser lattice a 2^dim-th of it, plus the interpolation
          // (about 3.4 corners of 12 bytes per node in 3D) and two coarse
          // vectors.
          const double per_node = dim == 3 ? 6144 : 1536;
          return coarsening == 1 ? per_node :
                                   per_node / (1u << dim) + 12. * dim + 64;
        }

        /**
         * Builds the hierarchy, or keeps the one built for the same local
         * matrix: a load-stepped run solves with one local matrix hundreds
         * of times, and ML's set-up was a third of the run on the 100²
         * centre-cracked plate. The
         * matrix is recognised by its address, the caller's version
         * number (a matrix assembled again is a new one: ML holds the
         * Trilinos matrix it was built on), size and Frobenius norm
         * (collective; a pass over the entries, a small fraction of the
         * set-up), the near-null space and the AMG settings. ML's set-up
         * is deterministic, so the iterates are the same either way.
         */
        void
        initialize(const OperatorForm         form,
                   const PreconditionerSetup &setup) override
        {
          AssertThrow(
            form == OperatorForm::matrix_free ||
              jacobi_weight == jacobi_weight_default,
            ExcInvalidInput("Linear solver/local elasticity/" +
                              std::string(jacobi_weight_entry),
                            format_number(jacobi_weight),
                            "the operator of this boundary treatment has no "
                            "diagonal, so the Jacobi term applies only to the "
                            "matrix-free operator (boundary treatment 'none'): "
                            "remove the entry"));
          AssertThrow(
            coarsening == 1 || (form == OperatorForm::matrix_free &&
                                setup.local_transfer != nullptr),
            ExcInvalidInput("Linear solver/local elasticity/" +
                              std::string(coarsening_entry),
                            std::to_string(coarsening),
                            "a coarser local grid works only with the "
                            "matrix-free operator of boundary treatment "
                            "'none': set it to 1"));
          inverse_diagonal =
            form == OperatorForm::matrix_free && jacobi_weight > 0 ?
              setup.inverse_diagonal :
              nullptr;
          transfer = coarsening > 1 ? setup.local_transfer : nullptr;
          if (transfer != nullptr)
            {
              transfer->initialize_coarse_vector(coarse_rhs);
              transfer->initialize_coarse_vector(coarse_solution);
            }
          const TrilinosWrappers::SparseMatrix &matrix = *setup.local_matrix;
          const Key                             key(setup);
          // Decided together: the set-up is collective.
          if (Utilities::MPI::min(amg != nullptr && key == built_for ? 1 : 0,
                                  matrix.get_mpi_communicator()) == 1)
            return;
          amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
          initialize_amg(*amg, matrix, setup.amg, setup.constant_modes);
          built_for = key;
        }

        void
        vmult(VectorType &dst, const VectorType &src) const override
        {
          if (transfer != nullptr)
            {
              transfer->restrict_residual(coarse_rhs, src);
              amg->vmult(coarse_solution, coarse_rhs);
              dst = 0;
              transfer->prolongate_add(dst, coarse_solution);
            }
          else
            amg->vmult(dst, src);
          if (inverse_diagonal == nullptr)
            return;
          const double      w = jacobi_weight;
          const double     *d = inverse_diagonal->begin();
          const double     *b = src.begin();
          double           *x = dst.begin();
          const std::size_t n = dst.locally_owned_size();
          for (std::size_t k = 0; k < n; ++k)
            x[k] += w * d[k] * b[k];
        }

        void
        layer_vmult(TrilinosWrappers::MPI::Vector       &dst,
                    const TrilinosWrappers::MPI::Vector &src) const override
        {
          amg->vmult(dst, src);
        }

        /// Keeps the hierarchy for the next initialize() with the same
        /// local matrix (the memory 'bytes_per_node' counts stays held).
        void
        clear() override
        {
          inverse_diagonal = nullptr;
          transfer         = nullptr;
          coarse_rhs.reinit(0);
          coarse_solution.reinit(0);
        }

      private:
        /// What a hierarchy was built for.
        struct Key
        {
          Key() = default;

          explicit Key(const PreconditionerSetup &setup)
            : matrix(setup.local_matrix)
            , version(setup.local_matrix_version)
            , rows(matrix->m())
            , nonzeros(matrix->n_nonzero_elements())
            , frobenius_norm(matrix->frobenius_norm())
            , constant_modes(setup.constant_modes)
            , smoother_sweeps(setup.amg.smoother_sweeps)
            , aggregation_threshold(setup.amg.aggregation_threshold)
          {}

          const TrilinosWrappers::SparseMatrix *matrix         = nullptr;
          std::uint64_t                         version        = 0;
          types::global_dof_index               rows           = 0;
          std::uint64_t                         nonzeros       = 0;
          double                                frobenius_norm = 0;
          std::vector<std::vector<bool>>        constant_modes;
          unsigned int                          smoother_sweeps       = 0;
          double                                aggregation_threshold = 0;

          bool
          operator==(const Key &other) const
          {
            return matrix == other.matrix && version == other.version &&
                   rows == other.rows && nonzeros == other.nonzeros &&
                   frobenius_norm == other.frobenius_norm &&
                   constant_modes == other.constant_modes &&
                   smoother_sweeps == other.smoother_sweeps &&
                   aggregation_threshold == other.aggregation_threshold;
          }
        };

        std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
        Key                                                built_for;
        double            jacobi_weight    = jacobi_weight_default;
        const VectorType *inverse_diagonal = nullptr;
        unsigned int      coarsening       = 1;
        /// With coarsening: the transfer and the coarse vectors.
        const Operators::GridTransfer *transfer = nullptr;
        mutable VectorType             coarse_rhs, coarse_solution;
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
  "matrix-free operator (plus a Jacobi term on its diagonal, 'PD Jacobi "
  "weight') and the layer systems; iteration counts stay bounded as h "
  "shrinks (uniform grids).")
