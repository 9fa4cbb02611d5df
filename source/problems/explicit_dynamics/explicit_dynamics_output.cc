/**
 * @file
 * What an explicit dynamics run (ExplicitDynamics) records: the energy
 * rows with probes and crack tip, and the energy balance check; the
 * progress line; the PVTU records, PVD series and energy file; the check
 * that the state is finite.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_internal.h>

#include <cmath>
#include <filesystem>
#include <iomanip>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsImplementation::to_string;


    template <int dim>
    void
    ExplicitDynamics<dim>::record_energies(Simulator<dim> &simulator)
    {
      TimerOutput::Scope scope(simulator.get_timer(), "energies");
      const MPI_Comm     comm = simulator.get_communicator();
      // Nothing is recorded of a state that is not finite.
      finite_check.finish_state_check();
      sum_step_counters(comm);
      double kinetic = 0;
      for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
        kinetic +=
          0.5 * mass.local_element(k) * std::pow(v.local_element(k), 2);
      kinetic = Utilities::MPI::sum(kinetic, comm);
      // From this step's force pass when it was asked for; else its own
      // pass (initial state, resumed run).
      const double elastic = elastic_energy_step == step_number ?
                               step_elastic_energy :
                               bond_operator.elastic_energy(u);
      // Same values on every process: no hang.
      AssertThrow(std::isfinite(kinetic) && std::isfinite(elastic),
                  ExcMessage("The energy is not finite at step " +
                             std::to_string(step_number) +
                             " (t = " + to_string(time) +
                             " s): the run is unstable. Reduce 'explicit "
                             "dynamics/Time step' (stability bound " +
                             to_string(dt_bound) +
                             " s) or check the loads and material "
                             "constants. The output written before is "
                             "complete."));
      energy_rows.push_back({time,
                             double(step_number),
                             kinetic,
                             elastic,
                             external_work,
                             kinetic + elastic - external_work,
                             double(broken_bonds)});
      if (hybrid != nullptr)
        energy_rows.back().push_back(double(n_standard_nodes));
      if (!probe_points.empty())
        {
          const auto         &nodes = simulator.get_nodes();
          std::vector<double> probes(probe_points.size() * dim, 0.);
          for (unsigned int k = 0; k < probe_points.size(); ++k)
            if (probe_nodes[k] != numbers::invalid_unsigned_int)
              for (unsigned int c = 0; c < dim; ++c)
                probes[k * dim + c] = u[nodes[probe_nodes[k]].dofs[c]];
          Utilities::MPI::sum(probes, comm, probes);
          energy_rows.back().insert(energy_rows.back().end(),
                                    probes.begin(),
                                    probes.end());
        }
      if (crack_tip.enabled())
        {
          const auto tip = crack_tip.evaluate(
            simulator.get_nodes(),
            [this](const unsigned int i) { return bond_state.damage(i); },
            simulator.get_horizon(),
            comm);
          energy_rows.back().insert(energy_rows.back().end(),
                                    tip.begin(),
                                    tip.end());
        }
      // Velocity Verlet conserves K + E - W - dt^2/8 sum m |a|^2 (exactly
      // for linear forces, and for any load history on a free body), not
      // K + E - W: the monitor judges that form, so that the start of a
      // ramp, where the whole kinetic energy is this term, is not taken
      // for energy made. That form is an energy (positive) only for a
      // stable step: above the bound it falls as the run blows up, so there
      // the plain balance is judged.
      double verlet_term = 0;
      if (dt <= dt_bound)
        {
          for (unsigned int k = 0; k < a.locally_owned_size(); ++k)
            verlet_term +=
              mass.local_element(k) * a.local_element(k) * a.local_element(k);
          verlet_term = dt * dt / 8 * Utilities::MPI::sum(verlet_term, comm);
        }
      energy_monitor.check({kinetic, elastic, external_work, verlet_term},
                           step_number,
                           time,
                           dt_bound,
                           comm,
                           simulator.get_pcout());
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::print_progress_line(Simulator<dim> &simulator)
    {
      const double now = simulator.elapsed();
      last_progress    = now;
      const double rate =
        (step_number - loop_start_step) / std::max(now - loop_start, 1e-9);
      const auto &row = energy_rows.back();
      simulator.get_pcout()
        << "[" << std::setw(8) << std::fixed << std::setprecision(2) << now
        << " s] step " << step_number << "/" << n_steps
        << ", t = " << std::scientific << std::setprecision(4) << time
        << " s, kinetic " << row[2] << ", elastic " << row[3]
        << ", external work " << row[4] << ", broken bonds " << broken_bonds;
      if (hybrid != nullptr)
        simulator.get_pcout() << ", standard nodes " << n_standard_nodes;
      if (crack_tip.enabled())
        simulator.get_pcout()
          << ", crack tip at " << row[row.size() - 2] << " m from the origin";
      simulator.get_pcout() << ", " << std::fixed << std::setprecision(1)
                            << rate << " steps/s, " << std::setprecision(0)
                            << (n_steps - step_number) / std::max(rate, 1e-9)
                            << " s left" << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::write_output(Simulator<dim> &simulator)
    {
      const auto    &nodes = simulator.get_nodes();
      const MPI_Comm comm  = simulator.get_communicator();
      finite_check.finish_state_check();
      time_loop.advance_output_time(next_output_time, time, dt);
      const auto &output = simulator.get_output();
      if (output.enabled())
        {
          const IndexSet &owned =
            simulator.get_dof_handler().locally_owned_dofs();
          TrilinosWrappers::MPI::Vector owned_u(owned, comm),
            owned_v(owned, comm), ghosted_u, ghosted_v;
          for (const auto dof : owned)
            {
              owned_u[dof] = u[dof];
              owned_v[dof] = v[dof];
            }
          owned_u.compress(VectorOperation::insert);
          owned_v.compress(VectorOperation::insert);
          ghosted_u.reinit(owned, nodes.relevant_dofs(), comm);
          ghosted_v.reinit(owned, nodes.relevant_dofs(), comm);
          ghosted_u = owned_u;
          ghosted_v = owned_v;
          IO::NodeField damage{"damage", {}}, broken{"broken_bonds", {}},
            rank{"mpi_rank", {}}, scheme{"scheme", {}};
          const double this_rank = Utilities::MPI::this_mpi_process(comm);
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            {
              damage.values.push_back(bond_state.damage(i));
              broken.values.push_back(bond_state.n_broken(i));
              rank.values.push_back(this_rank);
              // 0 standard, 1 collocation (the hybrid scheme).
              scheme.values.push_back(bond_operator.is_collocation_node(i));
            }
          std::vector<IO::NodeField> fields = {damage, broken, rank};
          if (hybrid != nullptr)
            fields.push_back(scheme);
          const std::string record = output.write(simulator.get_dof_handler(),
                                                  nodes,
                                                  ghosted_u,
                                                  fields,
                                                  records.size(),
                                                  {{"velocity", &ghosted_v}});
          records.emplace_back(time, record);
          output.write_time_series(records, comm);
        }
      if (!energy_file.empty())
        {
          std::string error;
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            {
              const std::string path = output.directory() + "/" + energy_file;
              std::error_code   code;
              std::filesystem::create_directories(output.directory(), code);
              error = write_then_rename(path, [&](std::ostream &out) {
                out << "time,step,kinetic_energy,elastic_energy,"
                       "external_work,energy_balance,broken_bonds";
                if (hybrid != nullptr)
                  out << ",standard_nodes";
                for (unsigned int k = 0; k < probe_points.size(); ++k)
                  for (unsigned int c = 0; c < dim; ++c)
                    out << ",probe" << k << "_u"
                        << "xyz"[c];
                if (crack_tip.enabled())
                  for (const auto &name : crack_tip.column_names())
                    out << ',' << name;
                out << '\n' << std::setprecision(12);
                for (const auto &row : energy_rows)
                  {
                    for (unsigned int k = 0; k < row.size(); ++k)
                      out << (k > 0 ? "," : "") << row[k];
                    out << '\n';
                  }
              });
              if (!error.empty())
                error = "Invalid value '" + path +
                        "' for the parameter 'explicit dynamics/Energy "
                        "file': " +
                        error + ".";
            }
          throw_on_any_rank(error, comm);
        }
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::print_communication_summary(
      Simulator<dim> &simulator) const
    {
      const MPI_Comm      comm    = simulator.get_communicator();
      const unsigned int  n_procs = Utilities::MPI::n_mpi_processes(comm);
      const std::uint64_t steps   = step_number - loop_start_step;
      if (n_procs == 1 || steps == 0)
        return;
      const auto   statistics   = bond_state.exchange_statistics();
      const double bond_seconds = statistics.first - exchange_before_loop.first;
      const std::size_t pairs = statistics.second - exchange_before_loop.second;
      const double      loop  = simulator.elapsed() - loop_start;
      const auto        ghost =
        Utilities::MPI::min_max_avg(ghost_exchange_seconds / steps, comm);
      const auto bond = Utilities::MPI::min_max_avg(bond_seconds / steps, comm);
      const auto values =
        Utilities::MPI::min_max_avg(double(
                                      u.get_partitioner()->n_ghost_indices()),
                                    comm);
      const std::size_t all_pairs = Utilities::MPI::sum(pairs, comm);
      simulator.get_pcout()
        << "           MPI, per step of " << std::setprecision(3)
        << 1e3 * loop / steps << " ms: ghost exchange " << 1e3 * ghost.avg
        << " ms (largest " << 1e3 * ghost.max << "), " << values.avg
        << " ghost values received per process (largest " << values.max << ", "
        << 8e-3 * values.max << " kB); broken-bond exchange " << 1e3 * bond.avg
        << " ms (largest " << 1e3 * bond.max << "), "
        << double(all_pairs) / steps << " pairs sent" << std::defaultfloat
        << std::endl;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::check_finite(Simulator<dim> &simulator)
    {
      const auto &nodes = simulator.get_nodes();
      // Started here, finished at the next step's check or before anything
      // is written (FiniteCheck::start_state_check()).
      finite_check.start_state_check(
        nodes,
        {{u.begin(), u.locally_owned_size()},
         {v.begin(), v.locally_owned_size()}},
        [&](const unsigned int i) {
          for (unsigned int c = 0; c < dim; ++c)
            if (!std::isfinite(u[nodes[i].dofs[c]]) ||
                !std::isfinite(v[nodes[i].dofs[c]]))
              return false;
          return true;
        },
        step_number,
        time,
        "The displacement or velocity",
        "The run is unstable: reduce 'explicit dynamics/Time step' (stability "
        "bound " +
          to_string(dt_bound) +
          " s) or check the loads and material constants.",
        simulator.get_communicator());
    }


    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, record_energies, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, print_progress_line, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, write_output, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, check_finite, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void,
                                           print_communication_summary,
                                           const)
  } // namespace Problems
} // namespace PeriDEAL
