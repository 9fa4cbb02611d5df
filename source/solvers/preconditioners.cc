/**
 * @file
 * The preconditioner interface and the preconditioners of the assembled PD
 * matrix: 'AMG', 'Jacobi' (also matrix-free, on the exact diagonal),
 * 'SSOR', 'ILU', and 'none' (every form).
 */

#include <deal.II/lac/diagonal_matrix.h>

#include <perideal/base/exceptions.h>
#include <perideal/solvers/integer_entry.h>
#include <perideal/solvers/preconditioner.h>

#include <atomic>
#include <cstdlib>
#include <memory>

namespace PeriDEAL
{
  namespace Solvers
  {
    std::string
    name_of(const OperatorForm form)
    {
      switch (form)
        {
          case OperatorForm::assembled:
            return "assembled PD matrix";
          case OperatorForm::matrix_free:
            return "matrix-free PD operator";
          case OperatorForm::layer:
            return "matrix-free layer system";
        }
      return "";
    }


    void
    Preconditioner::parse_parameters(ParameterHandler &)
    {}


    bool
    Preconditioner::needs_local_matrix() const
    {
      return false;
    }


    std::uint64_t
    new_local_matrix_version()
    {
      static std::atomic<std::uint64_t> last{0};
      return ++last;
    }


    unsigned int
    Preconditioner::local_matrix_coarsening() const
    {
      return 1;
    }


    bool
    Preconditioner::is_identity() const
    {
      return false;
    }


    double
    Preconditioner::bytes_per_node(const unsigned int) const
    {
      return 0;
    }


    const TrilinosWrappers::PreconditionBase &
    Preconditioner::trilinos_preconditioner() const
    {
      AssertThrow(false, ExcInternalError());
      std::abort(); // not reached
    }


    void
    Preconditioner::vmult(VectorType &, const VectorType &) const
    {
      AssertThrow(false, ExcInternalError());
    }


    void
    Preconditioner::layer_vmult(TrilinosWrappers::MPI::Vector &,
                                const TrilinosWrappers::MPI::Vector &) const
    {
      AssertThrow(false, ExcInternalError());
    }


    namespace
    {
      /**
       * A preconditioner of the assembled matrix only, given by a Trilinos
       * preconditioner of type @p Trilinos.
       */
      template <typename Trilinos>
      class AssembledOnly : public Preconditioner
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        bool
        supports(const OperatorForm form) const override
        {
          return form == OperatorForm::assembled;
        }

        const TrilinosWrappers::PreconditionBase &
        trilinos_preconditioner() const override
        {
          Assert(preconditioner, ExcNotInitialized());
          return *preconditioner;
        }

        void
        clear() override
        {
          preconditioner.reset();
        }

      protected:
        std::unique_ptr<Trilinos> preconditioner;
      };


      /// ML algebraic multigrid on the PD matrix.
      class AMG : public AssembledOnly<TrilinosWrappers::PreconditionAMG>
      {
      public:
        void
        initialize(const OperatorForm,
                   const PreconditionerSetup &setup) override
        {
          preconditioner =
            std::make_unique<TrilinosWrappers::PreconditionAMG>();
          initialize_amg(*preconditioner,
                         *setup.matrix,
                         setup.amg,
                         setup.constant_modes);
        }
      };


      /// Symmetric successive over-relaxation (Ifpack) on the PD matrix.
      class SSOR : public AssembledOnly<TrilinosWrappers::PreconditionSSOR>
      {
      public:
        void
        initialize(const OperatorForm,
                   const PreconditionerSetup &setup) override
        {
          preconditioner =
            std::make_unique<TrilinosWrappers::PreconditionSSOR>();
          preconditioner->initialize(*setup.matrix);
        }
      };


      /// ILU(k) fills in up to level k (Ifpack's 'fact: level-of-fill').
      constexpr IntegerEntry ilu_fill_level = {
        "Fill level",
        1,
        0,
        10,
        "Level of fill k of the ILU(k) preconditioner."};

      /// Incomplete LU, ILU(k) (Ifpack, on each process).
      class ILU : public WithIntegerEntry<
                    AssembledOnly<TrilinosWrappers::PreconditionILU>,
                    ilu_fill_level>
      {
      public:
        void
        initialize(const OperatorForm,
                   const PreconditionerSetup &setup) override
        {
          preconditioner =
            std::make_unique<TrilinosWrappers::PreconditionILU>();
          TrilinosWrappers::PreconditionILU::AdditionalData data;
          data.ilu_fill = this->integer_parameter;
          preconditioner->initialize(*setup.matrix, data);
        }
      };


      /**
       * Point Jacobi: on the assembled matrix (Ifpack), or on the exact
       * diagonal of the matrix-free operator.
       */
      class Jacobi : public Preconditioner
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        bool
        supports(const OperatorForm form) const override
        {
          return form != OperatorForm::layer;
        }

        void
        initialize(const OperatorForm         form,
                   const PreconditionerSetup &setup) override
        {
          if (form == OperatorForm::assembled)
            {
              assembled =
                std::make_unique<TrilinosWrappers::PreconditionJacobi>();
              assembled->initialize(*setup.matrix);
            }
          else
            diagonal = std::make_unique<DiagonalMatrix<VectorType>>(
              *setup.inverse_diagonal);
        }

        const TrilinosWrappers::PreconditionBase &
        trilinos_preconditioner() const override
        {
          Assert(assembled, ExcNotInitialized());
          return *assembled;
        }

        void
        vmult(VectorType &dst, const VectorType &src) const override
        {
          Assert(diagonal, ExcNotInitialized());
          diagonal->vmult(dst, src);
        }

        void
        clear() override
        {
          assembled.reset();
          diagonal.reset();
        }

      private:
        std::unique_ptr<TrilinosWrappers::PreconditionJacobi> assembled;
        std::unique_ptr<DiagonalMatrix<VectorType>>           diagonal;
      };


      /// The identity, for every form.
      class None : public Preconditioner
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        bool
        supports(const OperatorForm) const override
        {
          return true;
        }

        bool
        is_identity() const override
        {
          return true;
        }

        void
        initialize(const OperatorForm, const PreconditionerSetup &) override
        {}

        const TrilinosWrappers::PreconditionBase &
        trilinos_preconditioner() const override
        {
          return identity;
        }

        void
        vmult(VectorType &dst, const VectorType &src) const override
        {
          dst = src;
        }

        void
        layer_vmult(TrilinosWrappers::MPI::Vector       &dst,
                    const TrilinosWrappers::MPI::Vector &src) const override
        {
          dst = src;
        }

        void
        clear() override
        {}

      private:
        TrilinosWrappers::PreconditionIdentity identity;
      };
    } // namespace
  }   // namespace Solvers

  template class PluginRegistry<Solvers::Preconditioner>;
} // namespace PeriDEAL


PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::AMG,
  "AMG",
  "Trilinos ML algebraic multigrid on the assembled PD matrix, with the "
  "rigid translations as near-null space ('AMG smoother sweeps', 'AMG "
  "aggregation threshold').")
PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::SSOR,
  "SSOR",
  "Symmetric successive over-relaxation (Ifpack) on the assembled PD matrix.")
PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::ILU,
  "ILU",
  "Incomplete LU factorisation ILU(k) (Ifpack, on each process) of the "
  "assembled PD matrix; k is 'ILU/Fill level'.")
PERIDEAL_REGISTER_PRECONDITIONER(
  PeriDEAL::Solvers::Jacobi,
  "Jacobi",
  "Point Jacobi: the inverse diagonal of the assembled matrix, or the exact "
  "diagonal of the matrix-free operator.")
PERIDEAL_REGISTER_PRECONDITIONER(PeriDEAL::Solvers::None,
                                 "none",
                                 "No preconditioner (the identity).")
