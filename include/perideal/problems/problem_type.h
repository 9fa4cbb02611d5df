#ifndef perideal_problems_problem_type_h
#define perideal_problems_problem_type_h

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/input_checks.h>
#include <perideal/base/plugin_registry.h>
#include <perideal/io/output_names.h>

#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  /**
   * The simulator and the problem types it runs.
   */
  namespace Models
  {
    template <int dim>
    class Model;
  }

  namespace Problems
  {
    using namespace dealii;

    template <int dim>
    class Simulator;

    /**
     * An entry that selects one plugin of a registry whose plugins keep
     * their entries in subsections named after them (as 'Material
     * model/Model' and 'Material model/<model>/...'), for the check that
     * the input sets no entry of a plugin it does not select
     * (Simulator::check_input_file()).
     */
    struct PluginSelection
    {
      /// The subsection of the selecting entry; empty: the top level.
      std::string section;
      /// The selecting entry, inside @p section.
      std::string selector;
      /// The registered names it selects among.
      std::vector<std::string> names;
      /// Plugins that also read another plugin's subsection: (subsection,
      /// plugin) pairs, e.g. ("collocation", "hybrid"); such entries are
      /// not refused when that plugin is selected.
      std::vector<std::pair<std::string, std::string>> shared = {};
    };

    /**
     * What a run does once the shared set-up (mesh, PD nodes, model,
     * boundary conditions and treatment, output settings) is in place: a
     * quasi-static solve, a time loop, a diffusion problem. Each problem type
     * registers itself by name with PERIDEAL_REGISTER_PROBLEM_TYPE and is
     * chosen with the top-level entry `Problem type`; its own entries live in
     * the top-level subsection of the same name. Adding one touches no
     * central switch.
     */
    template <int dim>
    class ProblemType
    {
    public:
      virtual ~ProblemType() = default;

      /// Read the entries of the problem type's own subsection.
      virtual void
      parse_parameters(ParameterHandler &prm) = 0;

      /**
       * Check entries of the whole input against each other (called after
       * the simulator has parsed everything); throw ExcInvalidInput naming
       * the entries otherwise.
       */
      virtual void
      check_input(const Simulator<dim> &simulator) const;

      /**
       * Every name under which a run of this problem type writes, besides
       * the simulator's own ('Output/Summary file', 'Output/Node data
       * file'), so that the simulator can refuse two outputs that meet
       * before the run starts (IO::check_output_names()). Default: the
       * solution records of 'Output'.
       */
      virtual std::vector<IO::OutputName>
      output_names(const Simulator<dim> &simulator) const;

      /**
       * The entries of the whole input that have no effect on this run as
       * configured (called after check_input()), e.g. a time step's safety
       * factor when the step is given, or a section the problem type never
       * reads. The simulator refuses a run whose input sets one of them to
       * a value other than its default, naming the entry, its value and
       * the reason given here. The material model's own rules and the
       * sections of 'Material model' and 'Linear solver' (by
       * uses_material_model() and uses_linear_solver()) are added by the
       * simulator. Default: none.
       */
      virtual std::vector<UnusedEntry>
      unused_entries(const Simulator<dim> &simulator) const;

      /**
       * Run the problem on the set-up of @p simulator: the mesh and the
       * node set exist; the problem builds bonds, operators, solves or
       * steps, and writes its output and its part of the run summary.
       */
      virtual void
      run(Simulator<dim> &simulator) = 0;

      /**
       * Estimated peak memory per node of a run of this problem type, for
       * the check before the mesh is built, given @p coupled, the number of
       * nodes within one horizon of a node. A negative value (the default)
       * means: the linear solve's estimate of the simulator (matrix-free or
       * assembled, with its preconditioner).
       */
      virtual double
      estimated_bytes_per_node(const double coupled) const;

      /// Whether runs solve with the simulator's 'Linear solver'.
      virtual bool
      uses_linear_solver() const;

      /**
       * Whether the problem type evaluates nodes with the collocation
       * quadrature where 'Quadrature/Scheme' asks for it
       * (Quadrature::QuadratureScheme::collocation()). Default: false; the
       * simulator refuses the scheme otherwise.
       */
      virtual bool
      supports_collocation() const;

      /**
       * Whether the problem type runs the hybrid scheme (`Quadrature/Scheme
       * = hybrid`: collocation nodes beside standard ones, which bonds near
       * failure switch to standard). Default: false.
       */
      virtual bool
      supports_hybrid() const;

      /**
       * Refuse, naming `Quadrature/Scheme`, a state-based material model
       * with a scheme that has collocation nodes (their LPS rows run in
       * quasi-static problems only, linear and without failure); nothing
       * for the standard scheme. For check_input() of the other problem
       * types.
       */
      static void
      check_collocation_model(const Simulator<dim> &simulator);

      /// Whether runs use the simulator's 'Material model' (elasticity).
      virtual bool
      uses_material_model() const;

      /**
       * Whether nodes couple over two horizons (state-based forces need the
       * dilatations of the neighbours): the node set then holds the
       * off-process nodes within two horizons and neighbour lists of the
       * off-process neighbours are built. Default: whether the material
       * model @p model is state-based (false without one: null).
       */
      virtual bool
      couples_two_horizons(const Models::Model<dim> *model) const;

      /**
       * The plugin selections in the problem type's own entries (e.g.
       * 'diffusion/Model'), which Simulator::check_input_file() checks
       * besides the simulator's own. Called on an object created with
       * default parameters. Default: none.
       */
      virtual std::vector<PluginSelection>
      plugin_selections() const;

      static std::string
      family_name();
    };

    template <int dim>
    using ProblemTypeRegistry = PluginRegistry<ProblemType<dim>>;
  } // namespace Problems

  extern template class PluginRegistry<Problems::ProblemType<1>>;
  extern template class PluginRegistry<Problems::ProblemType<2>>;
  extern template class PluginRegistry<Problems::ProblemType<3>>;
} // namespace PeriDEAL

/// Register the problem type @p Class (a template over dim) under @p name.
#define PERIDEAL_REGISTER_PROBLEM_TYPE(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::ProblemType<2>,  \
                          Class<2>,                              \
                          name,                                  \
                          description)                           \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::ProblemType<3>,  \
                          Class<3>,                              \
                          name,                                  \
                          description)

/**
 * Register a problem type that also runs in 1D (on the shared line mesh of
 * Simulator<1>), in addition to 2D and 3D.
 */
#define PERIDEAL_REGISTER_PROBLEM_TYPE_1D_2D_3D(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::ProblemType<1>,           \
                          Class<1>,                                       \
                          name,                                           \
                          description)                                    \
  PERIDEAL_REGISTER_PROBLEM_TYPE(Class, name, description)

#endif
