#ifndef perideal_boundary_discrete_system_h
#define perideal_boundary_discrete_system_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/system_context.h>
#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/solution_output.h>
#include <perideal/solvers/dynamic_relaxation.h>
#include <perideal/solvers/linear_solver.h>

#include <functional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Boundary
  {
    using namespace dealii;

    /**
     * What a boundary treatment hands to a problem type: the discrete
     * system of the body with the treatment applied (its own nodes and
     * unknowns, its operators, how the boundary conditions enter). The
     * problem type drives it and never asks which treatment made it.
     *
     * The `none` treatment builds a NodalSystem (BondOperator, matrix-free
     * or assembled); `fictitious layer` and `surface nodes` build a
     * LayerSystem (FictitiousLayerOperator). A new treatment registers a
     * BoundaryTreatment whose make_system() returns its own class.
     *
     * The system sees the run through a SystemContext (filled by the
     * problem type from its simulator), never through the simulator.
     */
    template <int dim>
    class DiscreteSystem
    {
    public:
      virtual ~DiscreteSystem() = default;

      /**
       * Refuse settings of @p linear_solver that the system cannot honour
       * (naming the entries), before anything is built. Collective.
       */
      virtual void
      check_input(const Solvers::LinearSolver &linear_solver) const;

      /// Build neighbour lists, operators, layers (timer "operator setup").
      virtual void
      setup(const SystemContext<dim> &context) = 0;

      /**
       * Solve the linear quasi-static problem \f$K u = f\f$ with the
       * context's boundary conditions and linear solver; check
       * equilibrium; fill the run summary. @p displacement receives the
       * body nodes' displacements in the DoFHandler numbering, with ghost
       * values of every node of the node set.
       */
      virtual void
      solve_linear(const SystemContext<dim>      &context,
                   TrilinosWrappers::MPI::Vector &displacement) = 0;

      /// Per-node fields of the operator for the owned nodes (dilatation,
      /// weighted volume, ...), for output.
      virtual std::vector<IO::NodeField>
      node_fields(const SystemContext<dim>            &context,
                  const TrilinosWrappers::MPI::Vector &displacement) const;

      /// Whether owned node @p i has a prescribed component.
      virtual bool
      is_constrained(const Discretization::Node<dim> &node) const = 0;

      /// A node of the system that is not a body node (a surface node).
      struct ExtraNode
      {
        Point<dim>     location;
        Tensor<1, dim> displacement;
      };

      /// The owned nodes that carry unknowns besides the body nodes, after
      /// solve_linear().
      virtual std::vector<ExtraNode>
      extra_nodes() const;

      /// Their name in the log ("surface nodes").
      virtual std::string
      extra_nodes_name() const;

      /**
       * @name Bond failure in load-stepped static runs
       *
       * Problems::QuasiStatic drives the load steps and asks the system for
       * equilibria with the bonds intact so far, for the bonds over their
       * critical stretch, and breaks them; a system that cannot break
       * bonds says so in supports_bond_breaking() and the problem type
       * refuses the input before anything is built.
       */
      /// @{

      /// Whether the functions of this group work (default false).
      virtual bool
      supports_bond_breaking() const;

      /// Breaks the bonds that cross the pre-cracks in the given bond
      /// state and returns how many it broke on all processes.
      using CutBonds =
        std::function<std::size_t(const Discretization::NeighborList<dim> &,
                                  Discretization::BondState<dim> &)>;

      /**
       * After setup(): bond failure at @p critical_stretch (one value per
       * node of the set, owned and ghost; +inf: never fails), and the bonds
       * that @p cut breaks broken from the start. Returns the number cut.
       * Collective.
       */
      virtual std::size_t
      setup_failure(const SystemContext<dim>  &context,
                    const std::vector<double> &critical_stretch,
                    const CutBonds            &cut);

      /// Whether solve_step() can use adaptive dynamic relaxation (false by
      /// default).
      virtual bool
      supports_dynamic_relaxation() const;

      /**
       * Let solve_step() relax with @p solver (owned by the caller; nullptr:
       * back to the linear solver of the context). Only where
       * supports_dynamic_relaxation().
       */
      virtual void
      set_dynamic_relaxation(const Solvers::DynamicRelaxation *solver);

      /**
       * Whether solve_step() can solve with finite-deformation kinematics
       * (false by default).
       */
      virtual bool
      supports_finite_deformation() const;

      /**
       * The equilibrium of a finite-deformation step (set_finite_deformation())
       * is solved by a modified Newton method: the residual
       * \f$r = f_{\rm ext} + F(u)\f$ with the bond forces along the deformed
       * bonds, and corrections \f$K\,\delta u = r\f$ with the linearised
       * stiffness K of the intact bonds (the linear solver of the context,
       * or dynamic relaxation of the nonlinear residual), until
       * \f$\|r\| \le\f$ @p tolerance \f$\|b\|\f$ (b the right-hand side
       * of the lifted linear system of the same step, the scale of the
       * Krylov solvers' test), at most @p max_iterations corrections.
       */
      struct NewtonControl
      {
        double       tolerance      = 1e-8;
        unsigned int max_iterations = 50;
      };

      /**
       * Solve every later solve_step() with finite-deformation kinematics
       * (the bond extension \f$|\xi + \eta| - |\xi|\f$, the forces along the
       * deformed bond) and count and break bonds by their finite stretch.
       * Only where supports_finite_deformation().
       */
      virtual void
      set_finite_deformation(const NewtonControl &control);

      /**
       * Equilibrium with the bonds intact now, at the boundary conditions
       * of the context's current time, warm-started from the last
       * solution; no log line (the solver report and the equilibrium
       * residual go into the run summary). A node whose bonds are all
       * broken is held at its last displacement (its load, if any, is
       * dropped). Throws on a solve that does not converge; the state is
       * then as before the call. Collective.
       */
      virtual void
      solve_step(const SystemContext<dim>      &context,
                 TrilinosWrappers::MPI::Vector &displacement);

      /**
       * The intact bonds whose stretch under the last solution reaches
       * @p factor times their critical stretch, on all processes
       * (nothing breaks). Collective.
       */
      virtual std::size_t
      count_critical_bonds(const double factor);

      /// Break the bonds count_critical_bonds() counts; returns how many
      /// broke on all processes. Collective.
      virtual std::size_t
      break_critical_bonds(const double factor);

      /// The damage (broken share of the bonds) of each owned body node.
      virtual std::vector<double>
      damage(const SystemContext<dim> &context) const;

      /// The nodes held because all their bonds broke, on all processes.
      virtual unsigned int
      n_isolated_nodes() const;

      /// The DoFs of other nodes held because no intact bond gives them
      /// stiffness (the bonds left all lie across that direction), on all
      /// processes.
      virtual unsigned int
      n_held_dofs_without_stiffness() const;

      /**
       * The force that holds the owned body nodes flagged in @p flagged
       * (one flag per owned node) in the last solution: minus the sum of
       * the body's internal forces on them, on all processes (in 2D per
       * unit thickness). Collective.
       */
      virtual Tensor<1, dim>
      holding_force(const SystemContext<dim> &context,
                    const std::vector<bool>  &flagged) const;
      /// @}
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
