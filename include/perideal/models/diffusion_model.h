#ifndef perideal_models_diffusion_model_h
#define perideal_models_diffusion_model_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/base/input_checks.h>
#include <perideal/base/node_field.h>
#include <perideal/base/plugin_registry.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/diffusion_kernel.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Models
  {
    using namespace dealii;

    /**
     * Phases of the nodes and what they do to the bonds, as a model hands
     * them to the diffusion operator (the arguments of
     * Operators::DiffusionOperator::set_phases(), which says what each
     * means): a phase per node of the set, the symmetric factor table of
     * the conductances, the gate of interface bonds and the optional
     * antisymmetric table of fixed flows.
     */
    struct DiffusionPhases
    {
      const std::vector<unsigned char> &phase_of_node;
      unsigned int                      n_phases;
      const std::vector<double>        &factor;
      double                            gate;
      const std::vector<double>        &rate;
    };

    /**
     * What a diffusion model works on, filled by the diffusion problem
     * type: the nodes, their lists and the kernel, where each node's value
     * lies in the concentration vector, and the two things a model may ask
     * of the operator (models sit below operators/ and see none).
     */
    template <int dim>
    struct DiffusionSetup
    {
      const Discretization::NodeSet<dim>      &nodes;
      const Discretization::NeighborList<dim> &lists;
      const DiffusionKernel                   &kernel;
      /// The index of node i of the set (owned and ghosts) in the
      /// concentration vector: owned nodes below its locally_owned_size().
      const std::vector<unsigned int> &vector_index;
      /// Hand the operator new phases; call again whenever they change.
      std::function<void(const DiffusionPhases &)> set_phases;
      /// \f$\max_i\sum_j\mu_{ij}\f$ over all processes, without phase
      /// factors. Collective.
      std::function<double()> largest_row_sum;
      double                  horizon;
    };

    /**
     * The physics on top of plain diffusion, chosen with `diffusion/Model`
     * (registered by name; its entries live in the subsection
     * `diffusion/<name>`): `none` (plain diffusion) or `corrosion`. The
     * problem type calls the hooks below; a model changes the operator
     * through DiffusionSetup::set_phases and the state through the
     * concentration vector.
     */
    template <int dim>
    class DiffusionModel
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      virtual ~DiffusionModel() = default;

      /// Read the entries of the model's subsection.
      virtual void
      parse_parameters(ParameterHandler &prm);

      /**
       * Entries of the 'diffusion' subsection (paths relative to it, e.g.
       * 'Initial concentration/' or '<name>/Damage seed') that have no
       * effect with this model as configured; the simulator refuses them
       * when set (Problems::ProblemType::unused_entries()). Default: none.
       */
      virtual std::vector<UnusedEntry>
      unused_entries() const;

      /// Whether implicit time stepping and steady states apply.
      virtual bool
      supports_implicit() const;

      /**
       * Whether the model runs with the collocation quadrature
       * ('Quadrature/Scheme = collocation'): a model that sets phases on
       * the operator (corrosion) needs 'hybrid', whose nodes at an
       * interface keep their bonds. Default: false.
       */
      virtual bool
      supports_collocation() const;

      /**
       * Whether the model changes the phases of nodes during the run
       * (corrosion: metal dissolves): then the adaptive hybrid scheme
       * ('Quadrature/hybrid/Configuration = adaptive') switches the nodes
       * an interface reaches to the standard scheme; without, it would
       * switch none. The hybrid scheme runs with every model (a node at a
       * phase interface keeps its bonds). Default: false.
       */
      virtual bool
      changes_phases() const;

      /**
       * Set up the model once the operator and the initial concentration
       * (owned values of @p c) exist; may overwrite @p c and configure the
       * operator. Collective.
       */
      virtual void
      initialize(const DiffusionSetup<dim> &setup, VectorType &c);

      /// The largest explicit time step the model allows besides the
      /// stability bound (+inf by default). Collective.
      virtual double
      largest_time_step(const DiffusionSetup<dim> &setup) const;

      /// What sets largest_time_step(), for messages: why the model limits
      /// the step, and the entry ('diffusion/<model>/<Entry>') with its
      /// value as given that sets the limit (empty: none).
      struct TimeStepLimit
      {
        std::string reason, entry, value;
      };

      /// What sets largest_time_step() (empty by default).
      virtual TimeStepLimit
      time_step_limit() const;

      /**
       * After each time step, with the owned values of @p c at @p time;
       * @p record: a history row or an output follows. Collective. A model
       * that exchanges the ghost values may leave them valid (they are
       * then reused by the next step) but must not change owned values
       * afterwards without clearing them.
       */
      virtual void
      after_step(const DiffusionSetup<dim> &setup,
                 const double               time,
                 VectorType                &c,
                 const bool                 record);

      /// Names of the model's columns of the history file.
      virtual std::vector<std::string>
      history_columns() const;

      /// The values of those columns now. Collective.
      virtual std::vector<double>
      history_values(const DiffusionSetup<dim> &setup,
                     const VectorType          &c) const;

      /// Fields per owned node for the output.
      virtual std::vector<NodeField>
      node_fields(const DiffusionSetup<dim> &setup, const VectorType &c) const;

      /// Text for the progress line from history_values().
      virtual std::string
      progress_text(const std::vector<double> &values) const;

      static std::string
      family_name();
    };

    template <int dim>
    using DiffusionModelRegistry = PluginRegistry<DiffusionModel<dim>>;
  } // namespace Models

  extern template class PluginRegistry<Models::DiffusionModel<1>>;
  extern template class PluginRegistry<Models::DiffusionModel<2>>;
  extern template class PluginRegistry<Models::DiffusionModel<3>>;
} // namespace PeriDEAL

/// Register the diffusion model @p Class (a template over dim) as @p name.
#define PERIDEAL_REGISTER_DIFFUSION_MODEL(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::DiffusionModel<1>,    \
                          Class<1>,                                 \
                          name,                                     \
                          description)                              \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::DiffusionModel<2>,    \
                          Class<2>,                                 \
                          name,                                     \
                          description)                              \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::DiffusionModel<3>,    \
                          Class<3>,                                 \
                          name,                                     \
                          description)

#endif
