#ifndef perideal_problems_diffusion_h
#define perideal_problems_diffusion_h

#include <deal.II/base/parsed_function.h>

#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/models/diffusion_kernel.h>
#include <perideal/models/diffusion_model.h>
#include <perideal/operators/diffusion_operator.h>
#include <perideal/problems/diffusion/integrators.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>
#include <perideal/problems/time_loop.h>
#include <perideal/problems/time_stepping_problem.h>
#include <perideal/solvers/amg.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * Nonlocal diffusion (problem type `diffusion`): the semi-discrete
     * bond-based PD diffusion equation (hybrid-collocation paper, Eqs. 22
     * and 27)
     * \f[
     *   \dot C_i = (LC)_i + S_i(t),\qquad
     *   (LC)_i = \sum_j \mu_{ij}(C_j - C_i),
     * \f]
     * with the kernel of Models::DiffusionKernel (micro-diffusivity from K
     * by flux matching) and the exact partial volumes of the simulator,
     * applied by Operators::DiffusionOperator.
     *
     * - **Time stepping.** `explicit`: forward Euler (Eq. 31), the step
     *   given or the safety factor times the bound \f$2/\lambda_G\f$
     *   (\f$\lambda_G\f$ Gershgorin's bound of the spectral radius of L); a
     *   step above the bound is an error unless 'Allow unstable time step'.
     *   `implicit`: backward Euler or Crank-Nicolson, each step a linear
     *   solve with \f$A = I - \theta\Delta t L\f$ on the free nodes by CG
     *   (GMRES off a uniform lattice) without a matrix, preconditioned by
     *   Jacobi or by the local Laplacian (a cell-centred finite-volume
     *   Laplacian on the same nodes with algebraic multigrid). `steady
     *   state`: \f$-LC = S\f$, the limit of long times, one solve.
     * - **Boundary conditions.** Dirichlet values in volumetric layers
     *   along listed boundary ids ('Boundary concentration', a function of
     *   x and t); fluxes through listed boundaries as sources in a layer
     *   (flux divided by the layer thickness); a source S(x, t).
     * - **Checks** (Problems::TimeLoop and its companions): the step
     *   count in 64 bits and at most 'Maximum number of steps', every
     *   explicit step within the bound (the model's too), an 'Output
     *   interval' of at least one step; a non-finite initial
     *   concentration, source, flux or boundary value named by its entry.
     * - **Output.** PVTU with a PVD time series (concentration, error);
     *   a CSV of time, total amount, extrema and the error against an
     *   analytical solution (relative l2 norm, paper Eq. 66, over the free
     *   nodes); a progress line on rank 0.
     *
     * The sources by job: diffusion.cc (run, set-up, time step choice,
     * the explicit instantiation and the registration),
     * diffusion_integrators.cc (forward Euler, θ-scheme, steady state:
     * DiffusionIntegrators), diffusion_parameters.cc (the input),
     * diffusion_layers.cc (the layers and sources),
     * diffusion_solve.cc (the linear solves and the local Laplacian),
     * diffusion_checks.cc (non-finite states and solves) and
     * diffusion_output.cc (history, progress line, PVTU and CSV).
     */
    template <int dim>
    class Diffusion : public TimeSteppingProblem<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      /// The solution records and time series, and the history file.
      std::vector<IO::OutputName>
      output_names(const Simulator<dim> &simulator) const override;
      /**
       * The sections the diffusion problem never reads ('Boundary
       * conditions', 'Analytical solution': it has its own), entries that
       * its other entries switch off (the solver with explicit stepping,
       * the time step of a steady state, layer settings without layers,
       * ...), and the model's (Models::DiffusionModel::unused_entries()).
       */
      std::vector<UnusedEntry>
      unused_entries(const Simulator<dim> &simulator) const override;

      /// TimeSteppingProblem's checks, and with the collocation
      /// quadrature a model that supports it
      /// (Models::DiffusionModel::supports_collocation()) and the
      /// continuum calibration of the micro-diffusivity.
      void
      check_input(const Simulator<dim> &simulator) const override;

      /// True: the bulk nodes take the collocation row where
      /// 'Quadrature/Scheme' asks for it.
      bool
      supports_collocation() const override
      {
        return true;
      }

      /// True: 'Quadrature/Scheme = hybrid' (2D and 3D): collocation rows
      /// outside the standard region; nodes at a phase interface
      /// (corrosion) are standard (doc/collocation.md, "Hybrid diffusion").
      bool
      supports_hybrid() const override
      {
        return true;
      }

      void
      run(Simulator<dim> &simulator) override;

      /// Mesh, DoFs, nodes and a few scalar vectors; lists (16 bytes a
      /// bond) only near boundaries and interfaces of a uniform grid,
      /// counted as 4 bytes per coupled neighbour on average.
      double
      estimated_bytes_per_node(const double coupled) const override;

      /// The kernel is the diffusion subsection's, not a material model.
      bool
      uses_material_model() const override
      {
        return false;
      }

      /// 'diffusion/Model' selects a diffusion model.
      std::vector<PluginSelection>
      plugin_selections() const override
      {
        return {
          {"diffusion", "Model", Models::DiffusionModelRegistry<dim>::names()}};
      }

      /// Diffusion bonds couple over one horizon; mirror layers reach
      /// their mirror images up to two layer thicknesses away.
      bool
      couples_two_horizons(const Models::Model<dim> *) const override
      {
        return layer_values == LayerValues::mirror ||
               flux_values == FluxValues::mirror;
      }

    protected:
      std::string
      label() const override
      {
        return "the diffusion problem";
      }

    private:
      // The time integrators take the steps on this problem's state.
      friend class DiffusionIntegrators::ForwardEuler<dim>;
      friend class DiffusionIntegrators::ThetaScheme<dim>;
      friend class DiffusionIntegrators::SteadyState<dim>;

      /// The input subsection, which error messages name entries by.
      static inline const std::string section = "diffusion";

      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// 'Dirichlet layer values', parsed once in parse_parameters().
      enum class LayerValues
      {
        function,
        surface_value,
        mirror
      };

      /// 'Flux layer values', parsed once in parse_parameters().
      enum class FluxValues
      {
        source,
        mirror
      };

      void
      setup(Simulator<dim> &simulator);

      void
      choose_time_step(Simulator<dim> &simulator);

      /// The Dirichlet and flux layers and which nodes are prescribed
      /// (diffusion_layers.cc, as the three functions below).
      void
      setup_layers(Simulator<dim> &simulator);

      /// Surface points of the Dirichlet layers and the reflections of
      /// mirror layers.
      void
      setup_layer_values(Simulator<dim> &simulator);

      /// Values of the prescribed nodes (Dirichlet layers, mirror flux
      /// layers) at time @p t into @p c.
      void
      apply_layer_values(const double t, VectorType &c) const;

      /// The source S(t) of the owned nodes (volume source and fluxes).
      void
      evaluate_source(const double t, VectorType &s) const;

      /**
       * Solve \f$(\alpha I - \beta L)\,x = b\f$ on the free nodes, x given at
       * the Dirichlet nodes (initial guess elsewhere). Returns the
       * iterations (diffusion_solve.cc, as setup_local_laplacian()).
       */
      unsigned int
      solve(Simulator<dim>   &simulator,
            const double      alpha,
            const double      beta,
            const VectorType &rhs,
            VectorType       &x);

      /// The step count by one and the time with it (the last step ends
      /// at 'End time' exactly).
      void
      advance_time();

      /// Assemble the local Laplacian preconditioner for alpha, beta.
      void
      setup_local_laplacian(Simulator<dim> &simulator,
                            const double    alpha,
                            const double    beta);

      /// A row of the history (diffusion_output.cc, as the two functions
      /// below).
      void
      record_history(Simulator<dim> &simulator);

      void
      write_output(Simulator<dim> &simulator);

      void
      print_progress_line(Simulator<dim> &simulator);

      /// Stop naming the step and node when a value is not finite, or the
      /// entry when an input value was not (collective; diffusion_checks.cc,
      /// as the three functions below).
      void
      check_finite(Simulator<dim> &simulator);

      /// "the linear solve of step 3 (t = 0.003)", or "the steady-state
      /// solve".
      std::string
      solve_label() const;

      /**
       * Before a linear solve: stop, on every process, when its right-hand
       * side @p lifted (@p b with the prescribed values lifted) or its
       * initial guess @p x is not finite, naming the entry that made it so
       * (the source, the boundary flux or concentration, the initial
       * concentration) with the node and the time, or else the step. A
       * Krylov method would otherwise "converge" on it: deal.II's SolverCG
       * returns without an error when the first residual is NaN, and the
       * field would stay as it was.
       */
      void
      check_solve_input(Simulator<dim>   &simulator,
                        const VectorType &b,
                        const VectorType &lifted,
                        const VectorType &x) const;

      /**
       * After a linear solve from finite data: stop, on every process, when
       * the solver did not reach @p converged (with the last residual
       * @p residual, NaN: it stopped at its first check) or the solution
       * @p x is not finite; the system overflowed.
       */
      void
      check_solve_result(Simulator<dim>   &simulator,
                         const bool        converged,
                         const double      residual,
                         const VectorType &x) const;

      /// What the diffusion model works on (after setup()).
      const Models::DiffusionSetup<dim> &
      model_setup() const;

      // Input.
      Models::DiffusionKernel kernel;
      std::string             model_name   = "none";
      LayerValues             layer_values = LayerValues::function;
      FluxValues              flux_values  = FluxValues::source;
      /// The two selections as given, for messages.
      std::string layer_values_text, flux_values_text;
      std::unique_ptr<Models::DiffusionModel<dim>> model;
      /// 'Time stepping', chosen once in parse_parameters().
      std::unique_ptr<DiffusionIntegrators::Integrator<dim>> integrator;
      double                          end_time = 1, given_time_step = 0;
      double                          safety_factor   = 0.9;
      bool                            allow_unstable  = false;
      bool                            local_laplacian = false;
      Solvers::AmgSettings            amg_settings;
      double                          tolerance      = 1e-10;
      unsigned int                    max_iterations = 1000;
      std::vector<types::boundary_id> dirichlet_ids, flux_ids;
      std::string dirichlet_ids_text, flux_ids_text, dirichlet_thickness_text,
        flux_thickness_text;
      double dirichlet_thickness = 1, flux_thickness = 1;
      std::unique_ptr<Functions::ParsedFunction<dim>> initial, source,
        boundary_value, boundary_flux, analytical;
      /// The 'Function expression' of each function subsection, for
      /// messages.
      std::map<std::string, std::string> expressions;
      bool with_source = true, with_flux = false, compare = false;
      /// The function entries, for messages.
      FunctionEntry initial_entry, source_entry, boundary_value_entry,
        boundary_flux_entry, analytical_entry;
      /// Step count and output schedule; non-finite values (the
      /// evaluations of const functions record into it).
      TimeLoop            time_loop;
      mutable FiniteCheck finite_check;
      unsigned int        output_every_steps  = 0;
      double              output_interval     = 0;
      unsigned int        history_every_steps = 10;
      std::string         history_file;
      double              progress_interval_s = 5;

      // State.
      const Discretization::NodeSet<dim> *nodes = nullptr;
      Discretization::BondState<dim>      bond_state;
      Operators::DiffusionOperator<dim>   op;
      double                              horizon = 0;
      /// Node i of the set's index in the vectors, for the model.
      std::vector<unsigned int>                  vector_index;
      std::optional<Models::DiffusionSetup<dim>> model_view;
      std::vector<unsigned int>                  dirichlet_nodes; // owned
      /// Per Dirichlet node: the nearest point of the physical surface (the
      /// inner face of the layer).
      std::vector<Point<dim>> surface_points;
      /// An owned layer node whose value is reflected through the surface:
      /// from the node of the set at its mirror image, after the images of
      /// lower levels (edges, corners).
      struct Reflection
      {
        unsigned int node = 0, image = 0, level = 0;
        /// Odd (Dirichlet) or even (flux) reflection.
        bool odd = true;
        /// The surface point x_b and |x - x_m| = 2 |x - x_b|.
        Point<dim> surface;
        double     distance = 0;
      };
      std::vector<Reflection> reflections;
      /// Passes over the reflections per fill, the same on every process
      /// (the longest chain of reflections, 0 without mirror layers).
      unsigned int reflection_passes = 0;
      /// Per reflection, the data part of its value (2 g or |x - x_m| q/K),
      /// evaluated once per fill.
      mutable std::vector<double> reflection_shift;
      /// Owned nodes whose values are prescribed: the Dirichlet layers,
      /// and the flux layers with 'Flux layer values = mirror'.
      std::vector<unsigned int> prescribed_nodes;
      std::vector<unsigned int> flux_nodes;    // owned
      std::vector<bool>         is_prescribed; // per owned index
      VectorType                c, lc, s, rhs, row_sum;
      std::unique_ptr<TrilinosWrappers::SparseMatrix>    laplacian;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
      double        time = 0, dt = 0, dt_bound = 0, radius_estimate = 0;
      std::uint64_t step_number = 0, n_steps = 0;
      unsigned int  last_iterations = 0, total_iterations = 0;
      double        last_progress = 0, next_output_time = 0, loop_start = 0;
      std::vector<std::string> model_columns;
      /// 'Quadrature/Scheme = hybrid': the standard nodes (all processes)
      /// go into the history and the progress line.
      bool                                        hybrid = false;
      std::vector<std::vector<double>>            history;
      std::vector<std::pair<double, std::string>> records;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
