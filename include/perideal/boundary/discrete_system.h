#ifndef perideal_boundary_discrete_system_h
#define perideal_boundary_discrete_system_h

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/lac/trilinos_vector.h>

#include <perideal/boundary/system_context.h>
#include <perideal/discretization/node_set.h>
#include <perideal/io/solution_output.h>
#include <perideal/solvers/linear_solver.h>

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
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
