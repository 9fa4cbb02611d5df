#ifndef perideal_problems_time_loop_h
#define perideal_problems_time_loop_h

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/point.h>

#include <perideal/boundary/boundary_treatment.h>
#include <perideal/discretization/node_set.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    using namespace dealii;

    /**
     * The checks of the time loop that every time-dependent problem type
     * (explicit dynamics, diffusion with or without corrosion; 1D, 2D, 3D)
     * shares, so that each is made once (doc/explicit-dynamics.md and
     * doc/diffusion.md, "Checks of the time loop"):
     *
     * - TimeLoop: the number of steps (64 bits) and the step from 'End
     *   time', 'Time step' or 'Safety factor' and the stability bound; a run
     *   that would need more than 'Maximum number of steps' is refused at
     *   set-up, and the step taken, End time / n, never exceeds the bound
     *   unless 'Allow unstable time step'; an 'Output interval' shorter than
     *   the step is refused, and the output schedule always advances.
     * - parse_function(): a function entry parsed and evaluated once, so that
     *   a syntax error names its subsection.
     * - FiniteCheck: a non-finite value of an input function names the entry
     *   (and the time) where it is evaluated; a non-finite solution names
     *   the step and the node.
     * - EnergyBalanceMonitor: kinetic + elastic energy - external work may
     *   not rise (explicit dynamics).
     */

    /// A function entry, for messages: its path ("explicit dynamics/Initial
    /// velocity/Function expression") and its expression as given.
    struct FunctionEntry
    {
      std::string name;
      std::string expression;
    };


    /**
     * Parse the function of the subsection @p name of the current subsection
     * of @p prm (declared by Functions::ParsedFunction::declare_parameters()
     * with @p n_components components), and evaluate it once at the origin
     * at t = 0: deal.II's parser reports a syntax error only at the first
     * evaluation, deep in the run and without the entry. A wrong number of
     * expressions or a syntax error throws ExcInvalidInput naming
     * '<section>/<name>/Function expression' and the parser's words.
     *
     * @param[in] section The path of the current subsection, for messages.
     * @param[out] entry If given: the entry and its expression.
     */
    template <int dim>
    std::unique_ptr<Functions::ParsedFunction<dim>>
    parse_function(ParameterHandler  &prm,
                   const std::string &name,
                   const std::string &section,
                   const unsigned int n_components,
                   FunctionEntry     *entry = nullptr);


    /// A point as "x, y[, z]" for messages.
    template <int dim>
    std::string
    point_text(const Point<dim> &p);


    /// What limits the time step: its value and, for messages, what it is
    /// and the input entry that sets it when one entry does (a model
    /// constant).
    struct StabilityBound
    {
      /// The largest stable step (+inf: none, e.g. implicit schemes).
      double value = std::numeric_limits<double>::infinity();
      /// E.g. "the stability bound 1.2e-07 s".
      std::string description;
      /// The entry that sets the bound ('diffusion/corrosion/Current
      /// density') and its value as given; empty: the mesh and constants.
      std::string entry, entry_value;
    };


    /// The number of steps of a run (64 bits: no count wraps) and the step,
    /// End time / n_steps.
    struct StepPlan
    {
      std::uint64_t n_steps = 0;
      double        dt      = 0;
    };


    /**
     * The schedule of a time-dependent run: reads the entries 'End time',
     * 'Time step', 'Safety factor', 'Allow unstable time step' (declared by
     * the problem type), 'Output interval' and 'Maximum number of steps'
     * (declared here) of the problem's subsection, plans the steps and
     * checks the output interval.
     */
    class TimeLoop
    {
    public:
      /// Declare 'Output every steps', 'Output interval' (the output
      /// schedule of every time-stepping problem) and 'Maximum number of
      /// steps' in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * Read the entries of the current subsection, whose path is
       * @p section (for messages); @p unit is the unit of time in messages
       * (" s", or "" where the problem has none).
       */
      void
      parse_parameters(ParameterHandler  &prm,
                       const std::string &section,
                       const std::string &unit);

      /**
       * The steps to 'End time': the wanted step is 'Time step' when it is
       * > 0, else 'Safety factor' times @p bound; n = ceil(End time /
       * wanted) in 64 bits, computed as a double first so that nothing
       * overflows. A run that needs more than 'Maximum number of steps' is
       * refused with the count and the entries that caused it (the step,
       * or the bound and its entry). Unless 'Allow unstable time step' is
       * set, the step taken, End time / n, is at most the bound (n is raised
       * by one where rounding would put it above). Same result on every
       * process (the inputs are).
       */
      StepPlan
      plan(const StabilityBound &bound) const;

      /**
       * Refuse an 'Output interval' > 0 shorter than the step @p dt:
       * output can only be written at steps, and such an interval is
       * almost always a slip of units (1e-22) that would otherwise write a
       * record at every step.
       */
      void
      check_output_interval(const double dt) const;

      /**
       * Whether output is due at @p time by 'Output interval': the time
       * has reached @p next_output_time (to round-off in @p dt).
       */
      bool
      output_due(const double time,
                 const double dt,
                 const double next_output_time) const;

      /**
       * Move @p next_output_time past @p time by whole intervals. It always
       * advances: the interval is at least the step, and the step count is
       * bounded, so t + interval > t; should it not, this throws instead of
       * looping.
       */
      void
      advance_output_time(double      &next_output_time,
                          const double time,
                          const double dt) const;

      /// 'Output interval' (0: none).
      double
      output_interval() const
      {
        return interval;
      }

      /// 'Maximum number of steps'.
      double
      maximum_steps() const
      {
        return max_steps;
      }

    private:
      std::string section, unit;
      double      end_time = 1, time_step = 0, safety_factor = 0.9;
      double      interval = 0, max_steps = 1e9;
      bool        allow_unstable = false;
      std::string end_time_text, time_step_text, safety_factor_text,
        interval_text, max_steps_text;
    };


    /**
     * Refuse what the time-stepping problem types do not support yet: a
     * 'Boundary treatment/Treatment' (@p treatment, named @p treatment_name
     * in the input) that adds nodes to the body's
     * (Boundary::BoundaryTreatment::body_nodes_only()), and an
     * 'Output/Node data file' @p node_data_file (written by the quasi-static
     * problem only). @p problem names the problem type in the message
     * ("explicit dynamics", "the diffusion problem").
     */
    void
    check_time_stepping_setup(const std::string                 &problem,
                              const Boundary::BoundaryTreatment &treatment,
                              const std::string                 &treatment_name,
                              const std::string &node_data_file);


    /**
     * Non-finite values, named by what made them. An input function (an
     * initial field, a prescribed value, a source, a load history) is
     * checked where it is evaluated: value() records the first non-finite
     * value on this process without communication, and the next collective
     * check (check_state() or throw_pending()) stops every process with the
     * entry, its expression, the node and, for a function of time, the
     * time. Only a state that turns non-finite from finite inputs is blamed
     * on the run itself (check_state(): the step and the node).
     */
    class FiniteCheck
    {
    public:
      /// @p unit: the unit of time in messages (" s", or "").
      explicit FiniteCheck(const std::string &unit = "")
        : unit(unit)
      {}

      /// Completes a reduction still in flight (an exception left the loop
      /// between start_state_check() and finish_state_check()), so that
      /// MPI does not write into freed memory; never throws.
      ~FiniteCheck()
      {
        if (in_flight.active)
          MPI_Wait(&in_flight.request, MPI_STATUS_IGNORE);
      }

      /**
       * Check a value of the function @p entry evaluated at @p x (and, when
       * @p with_time, at the time @p t). Cheap when finite; the step is
       * named by the check that reports it.
       */
      template <int dim>
      void
      value(const double         v,
            const FunctionEntry &entry,
            const Point<dim>    &x,
            const bool           with_time = false,
            const double         t         = 0)
      {
        if (std::isfinite(v) || pending.set)
          return;
        pending = {true, v, entry, point_text(x), with_time, t};
      }

      /**
       * Check a value of a function of time only (the same on every
       * process): throws at once on every process.
       */
      void
      scalar(const double         v,
             const FunctionEntry &entry,
             const double         t,
             const std::uint64_t  step) const;

      /// Throw on every process if a value was not finite on any
      /// (collective).
      void
      throw_pending(const MPI_Comm comm);

      /**
       * The collective check of the state after step @p step at @p time:
       * first a pending input error (on any process), then the values of
       * the owned nodes. @p arrays are the owned values (a fast vectorised
       * test: x * 0 is 0 for finite x and NaN otherwise); when that finds
       * one, @p finite_at(i) tells whether owned node i has finite values,
       * and the first such node (lowest DoF over all processes) is named:
       * "<quantity> is not finite at step <n> (t = <t><unit>) at the node
       * at (<x>). <advice> The output written before this step is
       * complete." One reduction when all is well.
       */
      template <int dim>
      void
      check_state(
        const Discretization::NodeSet<dim>                        &nodes,
        const std::vector<std::pair<const double *, std::size_t>> &arrays,
        const std::function<bool(unsigned int)>                   &finite_at,
        const std::uint64_t                                        step,
        const double                                               time,
        const std::string                                         &quantity,
        const std::string                                         &advice,
        const MPI_Comm                                             comm)
      {
        start_state_check(nodes,
                          arrays,
                          finite_at,
                          step,
                          time,
                          quantity,
                          advice,
                          comm);
        finish_state_check();
      }

      /**
       * check_state() in two halves, so that a time loop does not wait for
       * its reduction every step: start_state_check() finishes the check
       * started before (if any), tests this process's values now and
       * starts the reduction (MPI_Iallreduce) without waiting for it;
       * finish_state_check() waits for it and, if a value was not finite
       * anywhere, throws on every process with check_state()'s message for
       * the step the check was started at. Call finish_state_check()
       * before anything is written (energies, output, checkpoints) and at
       * the end of the loop: a run goes on for at most one step past a
       * state that is not finite, and writes nothing of it. Both
       * collective.
       */
      template <int dim>
      void
      start_state_check(
        const Discretization::NodeSet<dim>                        &nodes,
        const std::vector<std::pair<const double *, std::size_t>> &arrays,
        const std::function<bool(unsigned int)>                   &finite_at,
        const std::uint64_t                                        step,
        const double                                               time,
        const std::string                                         &quantity,
        const std::string                                         &advice,
        const MPI_Comm                                             comm);

      /// Complete the check start_state_check() started (nothing if none).
      void
      finish_state_check();

    private:
      /**
       * This process's part of check_state(): 0 for a pending input value
       * that was not finite, else the lowest DoF + 1 of an owned node with
       * a value that is not finite (and its message in @p message), else
       * the largest std::uint64_t.
       */
      template <int dim>
      std::uint64_t
      local_state_key(
        const Discretization::NodeSet<dim>                        &nodes,
        const std::vector<std::pair<const double *, std::size_t>> &arrays,
        const std::function<bool(unsigned int)>                   &finite_at,
        const std::uint64_t                                        step,
        const double                                               time,
        const std::string                                         &quantity,
        const std::string                                         &advice,
        std::string &message) const;

      /// Throw on every process for the reduced key @p first (collective).
      void
      throw_for_key(const std::uint64_t key,
                    const std::uint64_t first,
                    const std::uint64_t step,
                    const std::string  &message,
                    const MPI_Comm      comm) const;

      /// The check start_state_check() started.
      struct InFlight
      {
        bool          active = false;
        MPI_Request   request;
        MPI_Comm      comm;
        std::uint64_t key = 0, first = 0, step = 0;
        std::string   message;
      } in_flight;

      /// The message for the pending value, in step @p step (0: at set-up).
      std::string
      pending_message(const std::uint64_t step) const;

      std::string unit;
      /// The first non-finite input value of this process.
      struct Pending
      {
        bool          set = false;
        double        v   = 0;
        FunctionEntry entry;
        std::string   where;
        bool          with_time = false;
        double        t         = 0;
      } pending;
    };


    /**
     * The energy balance of explicit dynamics, kinetic + elastic energy -
     * external work: velocity Verlet keeps it constant up to an O(dt^2)
     * oscillation, and broken bonds can only lower it, so a rise beyond
     * that oscillation means energy made by the integrator (an unstable
     * step) or by the model. The monitor takes away the oscillation's known
     * part, dt^2/8 sum m |a|^2 (Verlet conserves the balance less that
     * term exactly for linear forces, and for any load history on a free
     * body), and checks each energy row against the lowest balance of the
     * rows before, relative to the largest kinetic + elastic energy or
     * |external work| so far: a rise above 'Energy balance tolerance' of it
     * stops the run (or, with 'Allow energy growth', prints one warning).
     * The inputs are sums over all processes, and the decision is reduced,
     * so every process decides alike.
     *
     * Energies at the level of round-off are not judged: the scale is at
     * least the round-off energy given by set_round_off_energy(), the
     * largest elastic energy a displacement of the size of the positions'
     * round-off can hold (before a delayed load starts, the energies are
     * that noise, and their relative rise is meaningless).
     */
    class EnergyBalanceMonitor
    {
    public:
      /// One energy row: sums over all processes.
      struct Row
      {
        double kinetic = 0, elastic = 0, external_work = 0;
        /// dt^2/8 sum m |a|^2 at the row's step (0: not known).
        double verlet_term = 0;
      };

      /// Declare 'Energy balance tolerance' and 'Allow energy growth'.
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm, const std::string &section);

      /// Forget the rows seen (a new run).
      void
      reset();

      /**
       * The energy below which a balance is round-off: the scale a rise is
       * judged against is never below it. ExplicitDynamics gives
       * (1/2) lambda_max sum m (100 eps |x|_max)^2 (round_off_energy()).
       */
      void
      set_round_off_energy(const double energy);

      /**
       * The largest elastic energy (1/2) u^T K u <= (1/2) lambda_max
       * sum_k m_k u_k^2 of a displacement whose every component is the
       * round-off of a position, 100 eps |x|_max (the factor 100 covers
       * the operations of a stretch or a fitted row), with lambda_max
       * = 4 / dt_bound^2 the bound of M^-1 K that the stability bound
       * comes from and @p total_mass the sum of the masses of all degrees
       * of freedom.
       */
      static double
      round_off_energy(const double total_mass,
                       const double largest_coordinate,
                       const double dt_bound);

      /// Take a row without checking it (rows restored from a checkpoint,
      /// which do not keep the Verlet term: 0, which can only hide a rise).
      void
      observe(const Row &row);

      /**
       * Check the @p row of step @p step at @p time, then take it. Throws
       * on every process, or with 'Allow energy growth' warns once on
       * @p pcout. Collective.
       */
      void
      check(const Row                &row,
            const std::uint64_t       step,
            const double              time,
            const double              dt_bound,
            const MPI_Comm            comm,
            const ConditionalOStream &pcout);

    private:
      std::string section;
      double      tolerance    = 0.1;
      bool        allow_growth = false, warned = false;
      /// Rows seen; the lowest balance; the largest kinetic + elastic.
      std::uint64_t n_rows = 0;
      double        lowest = 0, scale = 0;
      /// Energies below it are round-off (set_round_off_energy()).
      double round_off = 0;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
