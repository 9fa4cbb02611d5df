#ifndef perideal_solvers_preconditioner_h
#define perideal_solvers_preconditioner_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/base/plugin_registry.h>
#include <perideal/operators/coarse_lattice.h>
#include <perideal/solvers/amg.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Solvers
  {
    using namespace dealii;

    /**
     * The three forms in which a PD operator reaches a Krylov method.
     */
    enum class OperatorForm
    {
      /// A Trilinos matrix ('Linear solver/Operator = assembled'), solved by
      /// Trilinos' AztecOO methods.
      assembled,
      /// The matrix-free bond operator with its exact diagonal
      /// ('Operator = matrix-free', boundary treatment 'none').
      matrix_free,
      /// The non-symmetric layer operators of the boundary treatments
      /// 'fictitious layer' and 'surface nodes', known only by their action:
      /// no matrix and no diagonal.
      layer
    };

    /// The name of @p form in messages.
    std::string
    name_of(const OperatorForm form);

    /**
     * What a preconditioner may use when it is set up. Which members are
     * set depends on the operator form (see each member); a preconditioner
     * reads only those of the forms it supports().
     */
    struct PreconditionerSetup
    {
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// OperatorForm::assembled: the PD matrix.
      const TrilinosWrappers::SparseMatrix *matrix = nullptr;

      /// Where needs_local_matrix(): classical elasticity discretised on the
      /// same nodes, with the same Dirichlet constraints
      /// (Operators::LocalElasticityOperator).
      const TrilinosWrappers::SparseMatrix *local_matrix = nullptr;

      /// Where local_matrix_coarsening() > 1: the transfer between the PD
      /// DoFs and the rows of local_matrix, which then lives on a coarser
      /// grid (Operators::CoarseLattice).
      const Operators::GridTransfer *local_transfer = nullptr;

      /// Where needs_local_matrix(): changes whenever the caller assembles
      /// local_matrix again, so that a preconditioner that keeps what it
      /// built for the same matrix (ML's hierarchy holds the Trilinos
      /// matrix it was built on) builds anew.
      std::uint64_t local_matrix_version = 0;

      /// OperatorForm::matrix_free: the inverse of the operator's diagonal
      /// (every entry positive; the solver refuses zero rows before).
      const VectorType *inverse_diagonal = nullptr;

      /// OperatorForm::matrix_free: dst = A src, and the number of rows of
      /// A (all processes together).
      std::function<void(VectorType &, const VectorType &)> apply;
      types::global_dof_index                               n_rows = 0;

      /// The rigid translations, one mask over the locally owned rows per
      /// displacement component (the near-null space of AMG); for the
      /// matrix, or the local matrix where that is the one used.
      std::vector<std::vector<bool>> constant_modes;

      /// 'Linear solver/AMG ...'.
      AmgSettings amg;
    };

    /**
     * A number for PreconditionerSetup::local_matrix_version that no
     * earlier call returned (in this process; the callers call it the same
     * number of times on every process).
     */
    std::uint64_t
    new_local_matrix_version();


    /**
     * A preconditioner of the linear solver, selected by name in 'Linear
     * solver/Preconditioner' and registered with
     * PERIDEAL_REGISTER_PRECONDITIONER; its own parameters live in
     * 'Linear solver/<name>'. The built-in ones: 'AMG', 'Jacobi', 'SSOR',
     * 'ILU', 'Chebyshev', 'local elasticity' and 'none'.
     *
     * The linear solver checks supports() when the input is read, so that
     * a combination that cannot run is refused before any set-up. For each
     * solve it calls initialize() once, then the vmult of the form (or
     * hands trilinos_preconditioner() to the Trilinos methods; vmult() for
     * the matrix-free form, layer_vmult() for the layer form), then
     * clear(), which must release what initialize() built.
     */
    class Preconditioner
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      static std::string
      family_name()
      {
        return "preconditioner";
      }

      virtual ~Preconditioner() = default;

      /// Read the class's parameters (subsection 'Linear solver/<name>').
      virtual void
      parse_parameters(ParameterHandler &prm);

      /// Whether the class can precondition operators of @p form.
      virtual bool
      supports(const OperatorForm form) const = 0;

      /// Whether initialize() needs PreconditionerSetup::local_matrix: the
      /// caller then assembles the local elasticity operator.
      virtual bool
      needs_local_matrix() const;

      /// Where needs_local_matrix(): the stride of the lattice the local
      /// matrix is wanted on (1: the nodes themselves; 2: every second node
      /// in each direction, with PreconditionerSetup::local_transfer).
      virtual unsigned int
      local_matrix_coarsening() const;

      /// Whether this is the identity: the Krylov methods then take their
      /// unpreconditioned form (deal.II's CG reuses |r| instead of forming
      /// r.P^{-1}r), which saves a vector operation per iteration.
      virtual bool
      is_identity() const;

      /// Bytes per node that the set-up adds to the operator's own
      /// (the memory guard's estimate), in @p dim dimensions.
      virtual double
      bytes_per_node(const unsigned int dim) const;

      /// Build the preconditioner for one solve of an operator of @p form.
      virtual void
      initialize(const OperatorForm form, const PreconditionerSetup &setup) = 0;

      /// OperatorForm::assembled: the preconditioner as Trilinos' solvers
      /// take it. The default refuses (the class does not support the
      /// form).
      virtual const TrilinosWrappers::PreconditionBase &
      trilinos_preconditioner() const;

      /// OperatorForm::matrix_free: dst = P^{-1} src.
      virtual void
      vmult(VectorType &dst, const VectorType &src) const;

      /// OperatorForm::layer: dst = P^{-1} src, on the rows of the local
      /// matrix where needs_local_matrix(), else on the whole vector. (A
      /// name of its own, so that a class that overrides one of the two
      /// hides nothing.)
      virtual void
      layer_vmult(TrilinosWrappers::MPI::Vector       &dst,
                  const TrilinosWrappers::MPI::Vector &src) const;

      /// Release what initialize() built.
      virtual void
      clear() = 0;
    };

    /// The registry of preconditioners.
    using PreconditionerRegistry = PluginRegistry<Preconditioner>;
  } // namespace Solvers

  extern template class PluginRegistry<Solvers::Preconditioner>;
} // namespace PeriDEAL


/**
 * Register the preconditioner @p Class under @p name.
 */
#define PERIDEAL_REGISTER_PRECONDITIONER(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(PeriDEAL::Solvers::Preconditioner,       \
                          Class,                                   \
                          name,                                    \
                          description)

#endif
