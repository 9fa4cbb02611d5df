#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/time_loop.h>

#include <algorithm>
#include <iomanip>
#include <limits>

namespace PeriDEAL
{
  namespace Problems
  {
    void
    check_time_stepping_setup(const std::string                 &problem,
                              const Boundary::BoundaryTreatment &treatment,
                              const std::string                 &treatment_name,
                              const std::string                 &node_data_file)
    {
      AssertThrow(treatment.body_nodes_only(),
                  ExcInvalidInput("Boundary treatment/Treatment",
                                  treatment_name,
                                  problem + " steps the body's own nodes only "
                                            "so far: use a treatment that "
                                            "adds no nodes ('none')"));
      AssertThrow(node_data_file.empty(),
                  ExcInvalidInput("Output/Node data file",
                                  node_data_file,
                                  "the node data file is written by the "
                                  "quasi-static problem only; leave it "
                                  "empty"));
    }


    namespace
    {
      /// The text of ExcInvalidInput, for errors that travel as strings
      /// (throw_on_any_rank()).
      std::string
      invalid_input(const std::string &entry,
                    const std::string &value,
                    const std::string &fix)
      {
        return "Invalid value '" + value + "' for the parameter '" + entry +
               "': " + fix + '.';
      }


      std::string
      trimmed(const std::string &text)
      {
        const auto first = text.find_first_not_of(" \t\n");
        if (first == std::string::npos)
          return "";
        const auto last = text.find_last_not_of(" \t\n");
        return text.substr(first, last - first + 1);
      }


      std::string
      number(const double x)
      {
        std::ostringstream s;
        s << x;
        return s.str();
      }
    } // namespace


    template <int dim>
    std::string
    point_text(const Point<dim> &p)
    {
      std::ostringstream s;
      s << p;
      return s.str();
    }


    template <int dim>
    std::unique_ptr<Functions::ParsedFunction<dim>>
    parse_function(ParameterHandler  &prm,
                   const std::string &name,
                   const std::string &section,
                   const unsigned int n_components,
                   FunctionEntry     *entry)
    {
      prm.enter_subsection(name);
      const std::string expression = prm.get("Function expression");
      const std::string variables  = prm.get("Variable names");
      const std::string path = section + "/" + name + "/Function expression";
      if (entry != nullptr)
        *entry = {path, expression};
      const std::string what =
        n_components == 1 ?
          std::string("one expression") :
          std::to_string(n_components) +
            " expressions separated by ';', one per component,";
      std::string error;
      if (Utilities::split_string_list(expression, ';').size() != n_components)
        error = "give " + what + " in the variables '" + variables + "'";
      auto function =
        std::make_unique<Functions::ParsedFunction<dim>>(n_components);
      if (error.empty())
        {
          // deal.II's parser reads the expression at its first evaluation:
          // one now, so that a syntax error is reported here, with the
          // entry, instead of in the middle of the run.
          std::string parser_said;
          try
            {
              function->parse_parameters(prm);
              function->set_time(0);
              Vector<double> values(n_components);
              function->vector_value(Point<dim>(), values);
            }
          catch (const ExceptionBase &exc)
            {
              std::ostringstream info;
              exc.print_info(info);
              parser_said = trimmed(info.str());
            }
          catch (const std::exception &exc)
            {
              parser_said = trimmed(exc.what());
            }
          if (!parser_said.empty())
            error = "it cannot be parsed (" + parser_said + "); give " + what +
                    " in muparser syntax in the variables '" + variables +
                    "' ('Variable names')";
        }
      prm.leave_subsection();
      AssertThrow(error.empty(), ExcInvalidInput(path, expression, error));
      return function;
    }


    // TimeLoop.

    void
    TimeLoop::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Output every steps",
                        "0",
                        Patterns::Integer(0),
                        "Write PVTU output every this many steps (and at the "
                        "first and last step). 0: use 'Output interval'.");
      prm.declare_entry("Output interval",
                        "0",
                        Patterns::Double(0),
                        "Write PVTU output every this much simulated time. "
                        "0 (and 'Output every steps = 0'): only at the first "
                        "and last step.");
      prm.declare_entry(
        "Maximum number of steps",
        "1e9",
        Patterns::Double(1, 1e15),
        "The most time steps a run may take, at most 1e15. A run that would "
        "need more (a tiny 'Time step' or 'Safety factor', a long 'End "
        "time', a constant that makes the stability bound tiny) is refused "
        "before it starts, with the number of steps and the entries that "
        "set it. 1e9 steps are days of wall time even for a small problem; "
        "raise it for a run that really needs more.");
    }


    void
    TimeLoop::parse_parameters(ParameterHandler  &prm,
                               const std::string &section_,
                               const std::string &unit_)
    {
      section            = section_;
      unit               = unit_;
      end_time_text      = prm.get("End time");
      time_step_text     = prm.get("Time step");
      safety_factor_text = prm.get("Safety factor");
      interval_text      = prm.get("Output interval");
      max_steps_text     = prm.get("Maximum number of steps");
      end_time           = prm.get_double("End time");
      time_step          = prm.get_double("Time step");
      safety_factor      = prm.get_double("Safety factor");
      interval           = prm.get_double("Output interval");
      max_steps          = prm.get_double("Maximum number of steps");
      allow_unstable     = prm.get_bool("Allow unstable time step");
    }


    StepPlan
    TimeLoop::plan(const StabilityBound &bound) const
    {
      const bool   given  = time_step > 0;
      const double wanted = given ? time_step : safety_factor * bound.value;
      // As a double first: End time / wanted can be 1e300, or infinite
      // when the step underflows to 0, and no integer may wrap.
      const double steps = end_time / wanted;
      double       n     = std::max(1., std::ceil(steps - 1e-9));
      // End time / n may exceed the wanted step by the 1e-9 of a step that
      // the count forgives; where that would cross the bound, one more
      // step puts it below.
      if (!allow_unstable && wanted <= bound.value &&
          end_time / n > bound.value)
        n += 1;
      if (!(n <= max_steps))
        {
          const std::string count =
            std::isfinite(n) ? number(n) : "infinitely many";
          const std::string to_end = " takes " + count + " steps to '" +
                                     section + "/End time' = " + end_time_text +
                                     unit;
          const std::string more =
            ", more than '" + section +
            "/Maximum number of steps' = " + max_steps_text + "; ";
          const std::string raise =
            ", or raise 'Maximum number of steps' if the run really needs "
            "that many steps";
          std::string entry, value, text;
          if (given)
            {
              entry = section + "/Time step";
              value = time_step_text;
              text =
                "a step of " + time_step_text + unit + to_end + more +
                "give a larger step" +
                (std::isfinite(bound.value) ? " (" + bound.description + ")" :
                                              std::string()) +
                " or a shorter 'End time'" + raise;
            }
          else
            {
              text = "a step of " + number(wanted) + unit +
                     " ('Safety factor' " + safety_factor_text + " times " +
                     bound.description + ")" + to_end + more;
              if (!bound.entry.empty())
                {
                  entry = bound.entry;
                  value = bound.entry_value;
                  text += "check '" + bound.entry + "'";
                }
              else if (end_time / bound.value <= max_steps)
                {
                  entry = section + "/Safety factor";
                  value = safety_factor_text;
                  text += "give a 'Safety factor' near 1 (0.9 is usual)";
                }
              else
                {
                  entry = section + "/End time";
                  value = end_time_text;
                  text += "give a shorter 'End time'";
                }
              text += raise;
            }
          AssertThrow(false, ExcInvalidInput(entry, value, text));
        }
      StepPlan plan;
      plan.n_steps = static_cast<std::uint64_t>(n);
      plan.dt      = end_time / static_cast<double>(plan.n_steps);
      // Every step taken must respect the bound, not only the one asked
      // for.
      AssertThrow(
        allow_unstable || plan.dt <= bound.value,
        ExcInvalidInput(section + (given ? "/Time step" : "/Safety factor"),
                        given ? time_step_text : safety_factor_text,
                        "the step taken, 'End time' / " + format_number(n) +
                          " = " + number(plan.dt) + unit + ", exceeds " +
                          bound.description +
                          "; give a smaller step, or set 'Allow unstable time "
                          "step = true'"));
      return plan;
    }


    void
    TimeLoop::check_output_interval(const double dt) const
    {
      // (1 - 1e-9): End time / n may round a step given equal to the
      // interval up by an ulp.
      AssertThrow(!(interval > 0 && interval < dt * (1 - 1e-9)),
                  ExcInvalidInput(
                    section + "/Output interval",
                    interval_text,
                    "it is shorter than the time step, " + number(dt) + unit +
                      ", and output is written at steps only; give an "
                      "interval of at least one step, 0 for none, or "
                      "'Output every steps = 1' for output at every step"));
    }


    bool
    TimeLoop::output_due(const double time,
                         const double dt,
                         const double next_output_time) const
    {
      return interval > 0 && time >= next_output_time - 1e-12 * dt;
    }


    void
    TimeLoop::advance_output_time(double      &next_output_time,
                                  const double time,
                                  const double dt) const
    {
      if (!(interval > 0))
        return;
      while (next_output_time <= time + 1e-12 * dt)
        {
          const double next = next_output_time + interval;
          AssertThrow(next > next_output_time,
                      ExcInvalidInput(section + "/Output interval",
                                      interval_text,
                                      "at t = " + number(time) + unit +
                                        " the next output time no longer "
                                        "advances; give a longer interval"));
          next_output_time = next;
        }
    }


    // FiniteCheck.

    std::string
    FiniteCheck::pending_message(const std::uint64_t step) const
    {
      if (!pending.set)
        return "";
      std::ostringstream s;
      s << "its value, " << pending.v << ", is not finite";
      if (pending.with_time)
        {
          if (step > 0)
            s << " at step " << step << " (evaluated at t = " << pending.t
              << unit << ")";
          else
            s << " at t = " << pending.t << unit;
        }
      s << " at the node at (" << pending.where
        << "); give an expression that is finite wherever"
        << (pending.with_time ? " and whenever" : "")
        << " the run evaluates it";
      return invalid_input(pending.entry.name,
                           pending.entry.expression,
                           s.str());
    }


    void
    FiniteCheck::scalar(const double         v,
                        const FunctionEntry &entry,
                        const double         t,
                        const std::uint64_t  step) const
    {
      if (std::isfinite(v))
        return;
      std::ostringstream s;
      s << "its value, " << v << ", is not finite at step " << step
        << " (evaluated at t = " << t << unit
        << "); give an expression that is finite whenever the run evaluates "
           "it";
      AssertThrow(false,
                  ExcInvalidInput(entry.name, entry.expression, s.str()));
    }


    void
    FiniteCheck::throw_pending(const MPI_Comm comm)
    {
      throw_on_any_rank(pending_message(0), comm);
    }


    template <int dim>
    std::uint64_t
    FiniteCheck::local_state_key(
      const Discretization::NodeSet<dim>                        &nodes,
      const std::vector<std::pair<const double *, std::size_t>> &arrays,
      const std::function<bool(unsigned int)>                   &finite_at,
      const std::uint64_t                                        step,
      const double                                               time,
      const std::string                                         &quantity,
      const std::string                                         &advice,
      std::string                                               &message) const
    {
      // A fast test first: x * 0 is 0 for a finite x and NaN otherwise, so
      // the sum is 0 exactly when every owned value is finite (one
      // vectorised pass instead of a look-up per value; four partial sums,
      // so that the loop is not one chain of adds).
      double partial[4] = {0, 0, 0, 0};
      for (const auto &[values, n] : arrays)
        {
          std::size_t k = 0;
          for (; k + 4 <= n; k += 4)
            for (unsigned int q = 0; q < 4; ++q)
              partial[q] += values[k + q] * 0.;
          for (; k < n; ++k)
            partial[0] += values[k] * 0.;
        }
      const double probe = partial[0] + partial[1] + partial[2] + partial[3];
      // The first owned node (lowest DoF) with a value that is not finite.
      constexpr std::uint64_t none = std::numeric_limits<std::uint64_t>::max();
      std::uint64_t           bad  = none;
      unsigned int            bad_node = 0;
      for (unsigned int i = 0; probe != 0. && i < nodes.n_owned(); ++i)
        if (!finite_at(i))
          {
            bad      = nodes[i].dofs[0];
            bad_node = i;
            break;
          }
      message.clear();
      if (bad != none)
        {
          std::ostringstream s;
          s << quantity << " is not finite at step " << step << " (t = " << time
            << unit << ") at the node at (" << nodes[bad_node].location << "). "
            << advice << " The output written before this step is complete.";
          message = s.str();
        }
      // One reduction for both: 0 when an input value was not finite on
      // this process (it caused whatever followed), else the lowest bad
      // DoF + 1.
      return pending.set ? 0 : (bad == none ? none : bad + 1);
    }


    void
    FiniteCheck::throw_for_key(const std::uint64_t key,
                               const std::uint64_t first,
                               const std::uint64_t step,
                               const std::string  &message,
                               const MPI_Comm      comm) const
    {
      if (first == std::numeric_limits<std::uint64_t>::max())
        return;
      if (first == 0)
        throw_on_any_rank(pending_message(step), comm);
      throw_on_any_rank(key == first ? message : std::string(), comm);
    }


    template <int dim>
    void
    FiniteCheck::start_state_check(
      const Discretization::NodeSet<dim>                        &nodes,
      const std::vector<std::pair<const double *, std::size_t>> &arrays,
      const std::function<bool(unsigned int)>                   &finite_at,
      const std::uint64_t                                        step,
      const double                                               time,
      const std::string                                         &quantity,
      const std::string                                         &advice,
      const MPI_Comm                                             comm)
    {
      finish_state_check();
      in_flight.key = local_state_key(nodes,
                                      arrays,
                                      finite_at,
                                      step,
                                      time,
                                      quantity,
                                      advice,
                                      in_flight.message);
      // MPI_UINT64_T, not Utilities::MPI::min(): that one (deal.II 9.4)
      // returned the largest value on 2 processes for a key of 0 against
      // 2^64 - 1, and a bad input value went unreported.
      in_flight.first = std::numeric_limits<std::uint64_t>::max();
      in_flight.step  = step;
      in_flight.comm  = comm;
      const int ierr  = MPI_Iallreduce(&in_flight.key,
                                      &in_flight.first,
                                      1,
                                      MPI_UINT64_T,
                                      MPI_MIN,
                                      comm,
                                      &in_flight.request);
      AssertThrowMPI(ierr);
      in_flight.active = true;
    }


    void
    FiniteCheck::finish_state_check()
    {
      if (!in_flight.active)
        return;
      const int ierr = MPI_Wait(&in_flight.request, MPI_STATUS_IGNORE);
      AssertThrowMPI(ierr);
      in_flight.active = false;
      throw_for_key(in_flight.key,
                    in_flight.first,
                    in_flight.step,
                    in_flight.message,
                    in_flight.comm);
    }


    // EnergyBalanceMonitor.

    void
    EnergyBalanceMonitor::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Energy balance tolerance",
        "0.1",
        Patterns::Double(0),
        "Largest rise of the energy balance (kinetic + elastic energy - "
        "external work, the column energy_balance, less velocity Verlet's "
        "own term dt^2/8 sum m |a|^2) above its lowest value so far, as a "
        "fraction of the largest kinetic + elastic energy or |external work| "
        "so far; checked at every energy row ('Energy every steps'). Broken "
        "bonds only lower the balance, and velocity Verlet keeps it up to an "
        "O(dt^2) oscillation (doc/explicit-dynamics.md, 'The energy "
        "balance'), so a larger rise is energy made by an unstable step or "
        "by the model: the run stops, unless 'Allow energy growth' is set. "
        "Energies below the round-off energy (1/2) lambda_max sum m (100 "
        "eps |x|_max)^2 (lambda_max = 4/dt_bound^2) are not judged against "
        "each other: that is the noise of a run whose loads have not "
        "started. > 0.");
      prm.declare_entry("Allow energy growth",
                        "false",
                        Patterns::Bool(),
                        "Only warn (once) when the energy balance rises "
                        "beyond 'Energy balance tolerance', and go on.");
    }


    void
    EnergyBalanceMonitor::parse_parameters(ParameterHandler  &prm,
                                           const std::string &section_)
    {
      section      = section_;
      tolerance    = prm.get_double("Energy balance tolerance");
      allow_growth = prm.get_bool("Allow energy growth");
      AssertThrow(tolerance > 0,
                  ExcInvalidInput(section + "/Energy balance tolerance",
                                  prm.get("Energy balance tolerance"),
                                  "give a fraction > 0 of the energy, for "
                                  "instance 0.1"));
    }


    void
    EnergyBalanceMonitor::reset()
    {
      n_rows = 0;
      lowest = scale = 0;
      warned         = false;
    }


    void
    EnergyBalanceMonitor::set_round_off_energy(const double energy)
    {
      round_off = energy;
    }


    double
    EnergyBalanceMonitor::round_off_energy(const double total_mass,
                                           const double largest_coordinate,
                                           const double dt_bound)
    {
      const double u =
        100 * std::numeric_limits<double>::epsilon() * largest_coordinate;
      // (1/2) lambda_max M u^2 with lambda_max = 4 / dt_bound^2.
      return 2 * total_mass * (u / dt_bound) * (u / dt_bound);
    }


    void
    EnergyBalanceMonitor::observe(const Row &row)
    {
      const auto &[kinetic, elastic, external_work, verlet_term] = row;
      const double balance = kinetic + elastic - external_work - verlet_term;
      lowest               = n_rows == 0 ? balance : std::min(lowest, balance);
      // The energy put in by the loads belongs to the scale: the run's
      // energies start from nothing, and under a load they are of the
      // order of its work.
      scale = std::max({scale, kinetic + elastic, std::abs(external_work)});
      ++n_rows;
    }


    void
    EnergyBalanceMonitor::check(const Row                &row,
                                const std::uint64_t       step,
                                const double              time,
                                const double              dt_bound,
                                const MPI_Comm            comm,
                                const ConditionalOStream &pcout)
    {
      const auto &[kinetic, elastic, external_work, verlet_term] = row;
      const double balance = kinetic + elastic - external_work - verlet_term;
      // The round-off floor: below it, the energies are the noise of the
      // positions' round-off (the run before a delayed load starts).
      const double energy = std::max(
        {scale, kinetic + elastic, std::abs(external_work), round_off});
      const double rise = balance - lowest;
      // The sums are the same on every process; the decision is reduced
      // all the same, so that no process can go on alone.
      const bool grew =
        Utilities::MPI::max(n_rows > 0 && rise > tolerance * energy ? 1 : 0,
                            comm) == 1;
      const double before = lowest;
      observe(row);
      if (!grew || (allow_growth && warned))
        return;
      std::ostringstream s;
      s << "The energy balance (kinetic + elastic energy - external work) "
           "rose to "
        << balance << " at step " << step << " (t = " << time << " s), " << rise
        << " above its lowest value " << before
        << " (both less velocity Verlet's own dt^2/8 sum m|a|^2): "
        << rise / energy
        << " of the largest kinetic + elastic energy or external work so "
           "far ("
        << energy << (energy == round_off ? ", the round-off energy" : "")
        << "), more than '" << section
        << "/Energy balance tolerance' = " << tolerance
        << ". Broken bonds only lower the balance, so the run made energy: "
           "a time step that is not stable ('"
        << section << "/Time step'; stability bound " << dt_bound
        << " s), or a model that makes energy when bonds break (a "
           "state-based model near incompressibility; "
           "doc/explicit-dynamics.md).";
      if (allow_growth)
        {
          warned = true;
          pcout << "Warning: " << s.str()
                << " Going on ('Allow energy growth = true'); this warning "
                   "is not repeated."
                << std::endl;
          return;
        }
      s << " Reduce the time step, or set '" << section
        << "/Allow energy growth = true' to go on with a warning. The output "
           "written before is complete.";
      AssertThrow(false, ExcMessage(s.str()));
    }


    template std::string
    point_text(const Point<1> &);
    template std::string
    point_text(const Point<2> &);
    template std::string
    point_text(const Point<3> &);
    template std::unique_ptr<Functions::ParsedFunction<1>>
    parse_function(ParameterHandler &,
                   const std::string &,
                   const std::string &,
                   const unsigned int,
                   FunctionEntry *);
    template std::unique_ptr<Functions::ParsedFunction<2>>
    parse_function(ParameterHandler &,
                   const std::string &,
                   const std::string &,
                   const unsigned int,
                   FunctionEntry *);
    template std::unique_ptr<Functions::ParsedFunction<3>>
    parse_function(ParameterHandler &,
                   const std::string &,
                   const std::string &,
                   const unsigned int,
                   FunctionEntry *);
#define PERIDEAL_INSTANTIATE(dim)                                \
  template void FiniteCheck::start_state_check(                  \
    const Discretization::NodeSet<dim> &,                        \
    const std::vector<std::pair<const double *, std::size_t>> &, \
    const std::function<bool(unsigned int)> &,                   \
    const std::uint64_t,                                         \
    const double,                                                \
    const std::string &,                                         \
    const std::string &,                                         \
    const MPI_Comm);
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
  } // namespace Problems
} // namespace PeriDEAL
