#ifndef perideal_problems_explicit_dynamics_h
#define perideal_problems_explicit_dynamics_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/function_parser.h>
#include <deal.II/base/parsed_function.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/crack_geometry.h>
#include <perideal/io/crack_tip_tracker.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/problems/bond_failure.h>
#include <perideal/problems/explicit_dynamics/velocity_verlet.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>
#include <perideal/problems/time_loop.h>
#include <perideal/problems/time_stepping_problem.h>

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * Explicit dynamics with brittle fracture (problem type
     * `explicit dynamics`): the semi-discrete equation of motion
     * \f$\rho V_i \ddot u_i = F_i(u) + V_i b_i(t)\f$ integrated with velocity
     * Verlet (hybrid-collocation paper, Eq. 29),
     * \f[
     *   \dot u^{n+1/2} = \dot u^n + \tfrac{\Delta t}{2}\ddot u^n,\quad
     *   u^{n+1} = u^n + \Delta t\,\dot u^{n+1/2},\quad
     *   \dot u^{n+1} = \dot u^{n+1/2} + \tfrac{\Delta t}{2}\ddot u^{n+1},
     * \f]
     * with the internal forces \f$F_i\f$ of Operators::BondOperator (finite
     * or linearised kinematics) and bond failure at the model's critical
     * stretch (Models::Model::critical_stretch()); broken bonds stay broken
     * (Discretization::BondState).
     *
     * - **Time step.** Given, or the safety factor times the bound
     *   \f$\Delta t \le 2/\sqrt{\lambda_G}\f$, \f$\lambda_G\f$ Gershgorin's
     *   bound of the largest eigenvalue of \f$M^{-1}K\f$
     *   (BondOperator::gershgorin_eigenvalue_bound(); for bond-based models
     *   the bound of Silling & Askari 2005). A step above the bound is an
     *   error unless 'Allow unstable time step' is set. The power-method
     *   estimate of the actual limit (60 force passes) is printed next to
     *   it when the step may exceed the bound or does; it is information
     *   only and costs nothing otherwise.
     * - **Set-up.** Initial displacement and velocity (functions); the
     *   Dirichlet layers of 'Boundary conditions' prescribe the displacement
     *   or the velocity (function of x and t); body forces and tractions of
     *   'Boundary conditions', evaluated at each step's time when they use
     *   t (once otherwise), times the optional factor 'Load history' g(t);
     *   pre-cracks (Discretization::PreCracks) and no-fail boxes.
     * - **Checks** (Problems::TimeLoop and its companions): the step
     *   count in 64 bits and at most 'Maximum number of steps', every step
     *   taken within the bound, an 'Output interval' of at least one step;
     *   a non-finite initial field, prescribed value or load history named
     *   by its entry; the energy balance may not rise ('Energy balance
     *   tolerance').
     * - **Output.** PVTU every N steps or every interval of time with a PVD
     *   time series (displacement, velocity, damage, broken bonds); a CSV
     *   of time, kinetic and elastic energy, external work and broken bonds;
     *   a progress line on rank 0.
     *
     * Only the `none` boundary treatment is supported so far.
     */
    template <int dim>
    class ExplicitDynamics : public TimeSteppingProblem<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      /**
       * The solution records and time series, the energy file, and the
       * checkpoint directories (<Output/Directory>/checkpoint, .new, .old:
       * reserved whether or not this run writes checkpoints, since a
       * resumed run reads them).
       */
      std::vector<IO::OutputName>
      output_names(const Simulator<dim> &simulator) const override;
      /// The entries that have no effect on this run: those of
      /// 'Boundary conditions' (BoundaryConditions::unused_entries()), the
      /// 'Analytical solution', and own entries that the others switch off
      /// (e.g. 'Safety factor' with a given 'Time step').
      std::vector<UnusedEntry>
      unused_entries(const Simulator<dim> &simulator) const override;

      void
      run(Simulator<dim> &simulator) override;

      /// TimeSteppingProblem's checks, and with `Quadrature/Scheme =
      /// hybrid` a bond-based model.
      void
      check_input(const Simulator<dim> &simulator) const override;

      /// True: `Quadrature/Scheme = hybrid` (explicit_dynamics_hybrid.cc).
      bool
      supports_hybrid() const override
      {
        return true;
      }

      /**
       * Mesh, DoFs, nodes and the state vectors (about 2 KB a node in 3D,
       * 1 KB in 2D) plus 8 bytes a bond: the stencil index and bond-state
       * bit of a node's bonds once it is damaged, with room to spare.
       * Measured: 2.4 KB per added node for 3D PMB at m = 3
       * (bench/dynamics/run_memory.sh).
       */
      double
      estimated_bytes_per_node(const double coupled) const override;

    protected:
      std::string
      label() const override
      {
        return "explicit dynamics";
      }

    private:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// Bonds, operator, failure, pre-cracks, constraints, masses, loads.
      void
      setup(Simulator<dim> &simulator);

      /// Choose the time step from the stability bound (or check it).
      void
      choose_time_step(Simulator<dim> &simulator);

      /// With the hybrid scheme: the all-standard stability bounds, the
      /// fixed standard region, the collocation rows of the other nodes.
      void
      setup_hybrid(Simulator<dim> &simulator);

      /// With the hybrid scheme, at the end of a step (and of
      /// initialize()): scan the bonds of the collocation nodes when the
      /// displacement bound says one may have reached the threshold, and
      /// switch (adaptive) or stop (fixed).
      void
      update_hybrid(Simulator<dim> &simulator);

      /// With the hybrid scheme: standard nodes, scans and late switches.
      void
      print_hybrid_summary(Simulator<dim> &simulator);

      /// Initial fields, prescribed values at t = 0, initial forces.
      void
      initialize(Simulator<dim> &simulator);

      /// One velocity-Verlet step (the integrator's) from time to
      /// time + dt.
      void
      step(Simulator<dim> &simulator);

      /// Prescribed components at time @p t into u (and v).
      void
      apply_prescribed(Simulator<dim> &simulator,
                       const double    t,
                       const double    dt);

      /**
       * Evaluate the loads that depend on time at @p t into `load` (the
       * constant part plus the forces at the load sites), unless they are
       * already at @p t; stops with the entry, the time and the point named
       * where a force is not finite. Collective when there are such loads.
       */
      void
      update_load(Simulator<dim> &simulator, const double t);

      /// Forces at the current u, bond failure committed; the
      /// acceleration of the free DoFs. With @p with_energy the elastic
      /// energy of this state comes from the same pass over the bonds
      /// (BondOperator::apply_with_energy()), for record_energies().
      void
      compute_acceleration(Simulator<dim> &simulator,
                           const bool      with_energy = false);

      /// Whether run() records the energies after the current step (the
      /// last one, a stop for a restart, or every 'Energy every steps'):
      /// step() then asks for the energy with the forces.
      bool
      records_energies() const;

      /// Energies and broken bonds now: one CSV row (collective).
      void
      record_energies(Simulator<dim> &simulator);

      /// Add every process's own_work and own_broken_ends to
      /// external_work and broken_bonds (collective; one reduction).
      void
      sum_step_counters(const MPI_Comm comm);

      /**
       * On more than one process: per step of the loop, the time in the
       * ghost exchange and in the broken-bond exchange (mean and largest
       * over the processes), the ghost values a process receives, and the
       * share of the step (collective).
       */
      void
      print_communication_summary(Simulator<dim> &simulator) const;

      /// PVTU of the current state and the PVD series (collective).
      void
      write_output(Simulator<dim> &simulator);

      void
      print_progress_line(Simulator<dim> &simulator);

      /**
       * Write the state (per owned node, keyed by its position: u, v, a,
       * force and the neighbours of its broken bonds; time, counters,
       * energy rows and output records) to
       * <output>/checkpoint: into checkpoint.new, then renamed, so that a
       * run killed while writing keeps its last good checkpoint
       * (explicit_dynamics_checkpoint.cc). Collective.
       */
      void
      write_checkpoint(Simulator<dim> &simulator);

      /// Read what write_checkpoint() wrote (same input, any number of
      /// processes: nodes are keyed by position). Collective. Refuses a
      /// checkpoint written with another input (the entry that differs is
      /// named, with both values) and a corrupt one (checksum, sizes and
      /// counts checked against the file and the mesh before anything is
      /// allocated), on every process alike.
      void
      read_checkpoint(Simulator<dim> &simulator);

      /**
       * One quantity that defines the state a checkpoint holds: an input
       * entry ('Material model/bond-based/Young's modulus') with its value
       * as written, or a property of the discretisation ("number of nodes",
       * "hash of the node positions and volumes") with @p hint naming the
       * entries it comes from.
       */
      struct CheckpointKey
      {
        std::string name, value;
        bool        is_entry = true;
        std::string hint;
      };

      /// Read 'Overwrite checkpoint' and record the entries that define the
      /// state (CheckpointKey) from the whole parameter tree: the model and
      /// its constants, the horizon, the partial volumes, the mesh, the
      /// failure parameters and the columns of the energy file.
      void
      parse_checkpoint_parameters(ParameterHandler &prm);

      /// The entries of parse_checkpoint_parameters() and the properties of
      /// this run's discretisation (mesh, horizon, bonds, critical stretch,
      /// energy columns, time step). Collective (computed once).
      const std::vector<CheckpointKey> &
      checkpoint_keys(Simulator<dim> &simulator);

      /// Before a run without 'Resume from checkpoint' writes anything:
      /// refuse when its output directory holds a checkpoint further in
      /// time than the first one this run would write (which would replace
      /// it), unless 'Overwrite checkpoint' is set. Collective.
      void
      check_checkpoint_overwrite(Simulator<dim> &simulator) const;

      /// Stop with the step and node named when a value is not finite,
      /// or with the entry named when an input value was not
      /// (collective).
      void
      check_finite(Simulator<dim> &simulator);

      // Input.
      double       end_time            = 1;
      double       given_time_step     = 0;
      double       safety_factor       = 0.9;
      bool         allow_unstable      = false;
      bool         finite_kinematics   = true;
      bool         prescribe_velocity  = false;
      unsigned int output_every_steps  = 0;
      double       output_interval     = 0;
      unsigned int energy_every_steps  = 10;
      double       progress_interval_s = 5;
      std::string  energy_file;
      unsigned int checkpoint_every_steps = 0;
      double       checkpoint_minutes     = 0;
      bool         resume                 = false;
      bool         overwrite_checkpoint   = false;
      unsigned int steps_per_run          = 0;
      double       last_checkpoint        = 0;
      std::unique_ptr<Functions::ParsedFunction<dim>> initial_displacement;
      std::unique_ptr<Functions::ParsedFunction<dim>> initial_velocity;
      std::unique_ptr<FunctionParser<1>>              load_history;
      /// The function entries, for messages.
      FunctionEntry initial_displacement_entry, initial_velocity_entry,
        load_history_entry, dirichlet_entry;
      /// Step count and output schedule; non-finite values; the energy
      /// balance.
      TimeLoop             time_loop;
      FiniteCheck          finite_check{" s"};
      EnergyBalanceMonitor energy_monitor;
      /// Pre-cracks and no-fail regions.
      BondFailure<dim>         failure;
      IO::CrackTipTracker<dim> crack_tip;
      std::vector<Point<dim>>  probe_points;
      std::string              probe_text;
      /// Per probe: the local index of the nearest node if this process
      /// owns it, else invalid.
      std::vector<unsigned int> probe_nodes;

      // State.
      /// The time integrator (its step is dt, set when the loop starts).
      VelocityVerlet                 integrator;
      Discretization::BondState<dim> bond_state;
      Operators::BondOperator<dim>   bond_operator;
      AffineConstraints<double>      constraints;
      /// Prescribed DoFs: local vector index, node, component.
      struct Prescribed
      {
        unsigned int index, node, component;
      };
      std::vector<Prescribed> prescribed;
      std::vector<bool>       is_prescribed;     // per local vector index
      std::vector<double>     free_dof;          // 0 where prescribed, else 1
      bool                    with_load = false; // any load anywhere
      VectorType              u, v, a, force, previous_force, load, mass;
      /// Loads that depend on t: whether there are any (on any process),
      /// the part of `load` that does not, the sites of the others with
      /// the local indices of their DoFs (invalid: constrained), and the
      /// time `load` was last evaluated at (NaN: not yet).
      bool       time_dependent_load = false;
      VectorType constant_load;
      std::vector<typename Boundary::BoundaryConditions<dim>::LoadSite>
                                                 load_sites;
      std::vector<std::array<unsigned int, dim>> load_site_indices;
      double                                     load_time = 0;
      /// The prescribed values when they do not depend on t (evaluated
      /// once; empty until then).
      std::vector<double> prescribed_values;
      double              time = 0, dt = 0, dt_bound = 0, dt_estimate = 0;
      /// No step (64-bit step numbers: a count of steps never wraps).
      static constexpr std::uint64_t no_step =
        std::numeric_limits<std::uint64_t>::max();
      /// The elastic energy from the last compute_acceleration() with
      /// energy, and the step it belongs to (no_step: none).
      double        step_elastic_energy = 0;
      std::uint64_t elastic_energy_step = no_step;
      std::uint64_t step_number = 0, n_steps = 0;
      double        external_work = 0, load_factor = 0;
      std::size_t   broken_bonds = 0;
      /// On more than one process: this process's share of the external
      /// work and of the newly broken bond ends since sum_step_counters()
      /// last added them to external_work and broken_bonds, so that a step
      /// needs no reduction for them.
      double      own_work        = 0;
      std::size_t own_broken_ends = 0;
      /// Wall time of this process in the displacement's ghost exchange
      /// of the time loop (print_communication_summary()).
      double ghost_exchange_seconds = 0;
      /// BondState::exchange_statistics() when the loop started (the
      /// set-up's exchanges are not the loop's).
      std::pair<double, std::size_t> exchange_before_loop{0., 0};
      double                         last_progress = 0, next_output_time = 0;
      double                         loop_start      = 0;
      std::uint64_t                  loop_start_step = 0;
      /// The hybrid scheme's settings (nullptr: another scheme), the
      /// all-standard stability bounds (Gershgorin; the power method only
      /// when choose_time_step() prints its estimate, 0 otherwise), and the
      /// counts: all nodes, standard nodes now, scans of the bonds.
      const Quadrature::HybridSettings<dim> *hybrid = nullptr;
      double        standard_lambda = 0, standard_power = 0;
      std::size_t   n_total_nodes = 0, n_standard_nodes = 0;
      std::uint64_t n_switch_scans = 0;
      /// A late switch was reported (a warning once per run).
      bool                                        late_switch_warned = false;
      std::vector<std::vector<double>>            energy_rows;
      std::vector<std::pair<double, std::string>> records;
      /// The input entries that define the state (parse time), then, once
      /// checkpoint_keys() ran, the properties of the discretisation.
      std::vector<CheckpointKey> checkpoint_inputs, checkpoint_state_keys;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
