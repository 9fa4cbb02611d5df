/**
 * @file
 * The explicit dynamics problem type (ExplicitDynamics): the time loop of
 * run() (output, energy rows, checkpoints) and one step (the integrator's
 * VelocityVerlet) with its forces, loads, prescribed values and external
 * work. The class
 * is instantiated here and registers itself as 'explicit dynamics'; its
 * entries, set-up, output and checkpoints are in the
 * explicit_dynamics_*.cc files.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/problems/explicit_dynamics.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    ExplicitDynamics<dim>::run(Simulator<dim> &simulator)
    {
      setup(simulator);
      choose_time_step(simulator);
      energy_monitor.reset();
      {
        // The round-off floor of the energy monitor: the largest
        // coordinate and the total mass, over all processes.
        const auto &nodes              = simulator.get_nodes();
        double      largest_coordinate = 0;
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          largest_coordinate =
            std::max(largest_coordinate, nodes[i].location.norm());
        energy_monitor.set_round_off_energy(
          EnergyBalanceMonitor::round_off_energy(
            mass.l1_norm(),
            Utilities::MPI::max(largest_coordinate,
                                simulator.get_communicator()),
            dt_bound));
      }
      if (resume)
        {
          read_checkpoint(simulator);
          for (const auto &row : energy_rows)
            energy_monitor.observe({row[2], row[3], row[4]});
        }
      else
        {
          check_checkpoint_overwrite(simulator);
          initialize(simulator);
          record_energies(simulator);
          write_output(simulator);
        }
      TimerOutput::Scope scope(simulator.get_timer(), "time steps");
      integrator.set_time_step(dt);
      loop_start           = simulator.elapsed();
      exchange_before_loop = bond_state.exchange_statistics();
      loop_start_step      = step_number;
      last_progress        = loop_start;
      last_checkpoint      = loop_start;
      const MPI_Comm comm  = simulator.get_communicator();
      while (step_number < n_steps)
        {
          step(simulator);
          const bool last = step_number == n_steps;
          const bool stop = !last && steps_per_run > 0 &&
                            step_number - loop_start_step == steps_per_run;
          bool by_wall_time = false;
          if (records_energies())
            {
              record_energies(simulator);
              if (last ||
                  simulator.elapsed() - last_progress >= progress_interval_s)
                print_progress_line(simulator);
              // The same decision on every process.
              by_wall_time =
                checkpoint_minutes > 0 &&
                Utilities::MPI::max(simulator.elapsed() - last_checkpoint,
                                    comm) >= 60 * checkpoint_minutes;
            }
          const bool by_steps =
            output_every_steps > 0 && step_number % output_every_steps == 0;
          const bool by_time = time_loop.output_due(time, dt, next_output_time);
          if (last || by_steps || by_time)
            {
              TimerOutput::Scope out(simulator.get_timer(), "output");
              write_output(simulator);
            }
          if (!last && (stop || by_wall_time ||
                        (checkpoint_every_steps > 0 &&
                         step_number % checkpoint_every_steps == 0)))
            {
              TimerOutput::Scope out(simulator.get_timer(), "checkpoint");
              write_checkpoint(simulator);
              last_checkpoint = simulator.elapsed();
            }
          if (stop)
            {
              simulator.get_pcout()
                << "           stopped after " << steps_per_run
                << " steps ('Steps per run') at step " << step_number << "/"
                << n_steps << "; continue with 'Resume from checkpoint = true'."
                << std::endl;
              break;
            }
        }
      finite_check.finish_state_check();
      sum_step_counters(comm);
      print_hybrid_summary(simulator);
      print_communication_summary(simulator);
      auto &summary = simulator.get_summary();
      summary.n_bonds =
        Utilities::MPI::sum(simulator.get_neighbor_lists().n_owned_bonds(),
                            simulator.get_communicator());
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::sum_step_counters(const MPI_Comm comm)
    {
      if (Utilities::MPI::n_mpi_processes(comm) == 1)
        return;
      // The ends as a double: exact below 2^53.
      std::array<double, 2> shares = {{own_work, double(own_broken_ends)}};
      Utilities::MPI::sum(ArrayView<const double>(shares.data(), 2),
                          comm,
                          ArrayView<double>(shares.data(), 2));
      external_work += shares[0];
      broken_bonds += static_cast<std::size_t>(shares[1]) / 2;
      own_work        = 0;
      own_broken_ends = 0;
    }


    template <int dim>
    bool
    ExplicitDynamics<dim>::records_energies() const
    {
      const bool last = step_number == n_steps;
      const bool stop = !last && steps_per_run > 0 &&
                        step_number - loop_start_step == steps_per_run;
      return last || stop || step_number % energy_every_steps == 0;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::compute_acceleration(Simulator<dim> &simulator,
                                                const bool      with_energy)
    {
      if (with_energy)
        {
          step_elastic_energy = bond_operator.apply_with_energy(u, force);
          elastic_energy_step = step_number;
        }
      else
        {
          bond_operator.apply(u, force);
          elastic_energy_step = no_step;
        }
      // The count without a reduction (sum_step_counters() adds the
      // processes' shares when it is read).
      const std::size_t ends =
        bond_operator.commit_broken_bond_ends(bond_state);
      if (Utilities::MPI::n_mpi_processes(simulator.get_communicator()) == 1)
        broken_bonds += ends / 2;
      else
        own_broken_ends += ends;
      update_load(simulator, time);
      load_history->set_time(time);
      load_factor = load_history->value(Point<1>());
      finite_check.scalar(load_factor, load_history_entry, time, step_number);
      const unsigned int n = u.locally_owned_size();
      const double *pf = force.begin(), *pl = load.begin(), *pm = mass.begin(),
                   *free = free_dof.data();
      double *pa         = a.begin();
      for (unsigned int k = 0; k < n; ++k)
        {
          const double acceleration = (pf[k] + load_factor * pl[k]) / pm[k];
          pa[k]                     = free[k] != 0 ? acceleration : 0.;
        }
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::update_load(Simulator<dim> &simulator,
                                       const double    t)
    {
      if (!time_dependent_load || t == load_time)
        return;
      auto &conditions = simulator.get_boundary_conditions();
      conditions.set_time(t);
      for (const auto &indices : load_site_indices)
        for (const unsigned int k : indices)
          if (k != numbers::invalid_unsigned_int)
            load.local_element(k) = constant_load.local_element(k);
      std::string non_finite;
      for (std::size_t s = 0; s < load_sites.size(); ++s)
        {
          const Tensor<1, dim> f = conditions.load_at(load_sites[s]);
          for (unsigned int c = 0; c < dim; ++c)
            {
              const unsigned int k = load_site_indices[s][c];
              if (k != numbers::invalid_unsigned_int)
                load.local_element(k) += f[c];
              if (!std::isfinite(f[c]) && non_finite.empty())
                {
                  std::ostringstream text;
                  text << "The load is not finite at t = " << t
                       << " s: component " << c << " of '"
                       << conditions.load_entry(load_sites[s]) << "' is "
                       << f[c] << " at (" << load_sites[s].point
                       << "); give an expression that is finite on the "
                          "whole body and its loaded faces for every t up "
                          "to 'End time'. The output written before is "
                          "complete.";
                  non_finite = text.str();
                }
            }
        }
      throw_on_any_rank(non_finite, simulator.get_communicator());
      load_time = t;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::step(Simulator<dim> &simulator)
    {
      // The load at the current time (after a resume: not yet evaluated).
      update_load(simulator, time);
      const double old_load = load_factor;
      double       work     = 0;
      integrator.advance_first_half(u, v, a, free_dof);
      if (with_load)
        work = integrator.add_load_work(work, old_load, load, v, free_dof);
      // Prescribed components at the new time; their old values and forces
      // for the work of the reactions.
      std::vector<double> old_u(prescribed.size()), old_v(prescribed.size()),
        old_f(prescribed.size());
      for (unsigned int q = 0; q < prescribed.size(); ++q)
        {
          old_u[q] = u.local_element(prescribed[q].index);
          old_v[q] = v.local_element(prescribed[q].index);
          old_f[q] = force.local_element(prescribed[q].index);
        }
      time += dt;
      ++step_number;
      apply_prescribed(simulator, time, dt);
      {
        const auto start = std::chrono::steady_clock::now();
        u.update_ghost_values();
        ghost_exchange_seconds += std::chrono::duration<double>(
                                    std::chrono::steady_clock::now() - start)
                                    .count();
      }
      // The energy of this step comes with its forces when run() will
      // record it (the same test as there).
      compute_acceleration(simulator, records_energies());
      // The load at the new time (update_load() may have rewritten it).
      if (with_load)
        work = integrator.add_load_work(work, load_factor, load, v, free_dof);
      integrator.advance_second_half(v, a, free_dof);
      // The work of the reactions R = m a - f on the prescribed
      // components: the change of their kinetic energy, m a v dt summed
      // exactly, less the trapezoidal work of the bond forces. The
      // inertial part as m (v1 - v0) / dt * (u1 - u0) was this only where
      // u1 - u0 = dt (v0 + v1) / 2: a prescribed velocity that jumps
      // (a load that starts late) moves the node by dt v(t - dt/2), so the
      // kinetic energy of the jump came with no work, or with twice it,
      // and the energy monitor stopped a correct run.
      for (unsigned int q = 0; q < prescribed.size(); ++q)
        {
          const unsigned int k  = prescribed[q].index;
          const double       v1 = v.local_element(k);
          work +=
            0.5 * mass.local_element(k) * (v1 - old_v[q]) * (v1 + old_v[q]) -
            0.5 * (old_f[q] + force.local_element(k)) *
              (u.local_element(k) - old_u[q]);
        }
      // On one process as before, step by step; else summed when read.
      if (Utilities::MPI::n_mpi_processes(simulator.get_communicator()) == 1)
        external_work += work;
      else
        own_work += work;
      check_finite(simulator);
      // The hybrid scheme's scan reads the state: it waits for the check.
      if (hybrid != nullptr)
        finite_check.finish_state_check();
      update_hybrid(simulator);
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::apply_prescribed(Simulator<dim> &simulator,
                                            const double    t,
                                            const double    h)
    {
      // Only the owned prescribed nodes: no communication.
      auto       &conditions = simulator.get_boundary_conditions();
      const auto &nodes      = simulator.get_nodes();
      const auto  values_at  = [&](const double when) {
        // Values that do not depend on t are evaluated once.
        if (!conditions.dirichlet_depends_on_time() &&
            prescribed_values.size() == prescribed.size() &&
            !prescribed.empty())
          return prescribed_values;
        conditions.set_time(when);
        std::vector<double> values(prescribed.size());
        unsigned int        node = numbers::invalid_unsigned_int;
        Tensor<1, dim>      g;
        for (unsigned int q = 0; q < prescribed.size(); ++q)
          {
            if (prescribed[q].node != node)
              {
                node = prescribed[q].node;
                g    = conditions.dirichlet_value(nodes[node].location);
              }
            values[q] = g[prescribed[q].component];
            finite_check.value(values[q],
                               dirichlet_entry,
                               nodes[node].location,
                               true,
                               when);
          }
        if (!conditions.dirichlet_depends_on_time())
          prescribed_values = values;
        return values;
      };
      if (prescribe_velocity)
        {
          const auto middle = values_at(t - 0.5 * h);
          const auto end    = values_at(t);
          for (unsigned int q = 0; q < prescribed.size(); ++q)
            {
              u.local_element(prescribed[q].index) += h * middle[q];
              v.local_element(prescribed[q].index) = end[q];
            }
        }
      else
        {
          const auto end = values_at(t);
          for (unsigned int q = 0; q < prescribed.size(); ++q)
            {
              const unsigned int k = prescribed[q].index;
              v.local_element(k)   = (end[q] - u.local_element(k)) / h;
              u.local_element(k)   = end[q];
            }
        }
    }


    template class ExplicitDynamics<2>;
    template class ExplicitDynamics<3>;
  } // namespace Problems
} // namespace PeriDEAL

PERIDEAL_REGISTER_PROBLEM_TYPE(
  PeriDEAL::Problems::ExplicitDynamics,
  "explicit dynamics",
  "Explicit dynamics with brittle fracture: velocity Verlet on the PD "
  "bond forces (finite or linearised kinematics), bond failure at a "
  "critical stretch, pre-cracks, PVD time series and energy CSV.")
