/**
 * @file
 * The set-up of an explicit dynamics run (ExplicitDynamics): bonds,
 * operator, failure (no-fail boxes and layers), pre-cracks, constraints,
 * masses, loads and probes; the time step from the stability bound; the
 * initial state.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_internal.h>
#include <perideal/problems/node_region.h>

#include <array>
#include <cmath>
#include <iomanip>
#include <limits>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsImplementation::to_string;


    template <int dim>
    void
    ExplicitDynamics<dim>::setup(Simulator<dim> &simulator)
    {
      simulator.setup_neighbor_lists(false);
      TimerOutput::Scope scope(simulator.get_timer(), "operator setup");
      const auto        &nodes   = simulator.get_nodes();
      const auto        &lists   = simulator.get_neighbor_lists();
      const auto        &model   = simulator.get_model();
      const double       horizon = simulator.get_horizon();
      const MPI_Comm     comm    = simulator.get_communicator();
      bond_state.reinit(nodes, lists);
      bond_operator.reinit(nodes, lists, model, horizon, &bond_state);

      // Failure: the model's critical stretch, none in the no-fail boxes
      // and layers; the pre-cracks.
      const double s0 = model.critical_stretch(horizon);
      bond_operator.set_kinematics(finite_kinematics,
                                   failure.critical_stretches(simulator));
      const std::size_t n_cut =
        failure.cut_pre_cracks(simulator, lists, bond_state);
      bond_operator.update_bond_state();
      broken_bonds = n_cut;

      // Constraints, masses and loads.
      simulator.get_boundary_conditions().make_constraints(
        simulator.get_dof_handler(),
        nodes,
        horizon,
        constraints);
      bond_operator.initialize_dof_vector(u);
      for (auto *vector : {&v, &a, &force, &previous_force, &load, &mass})
        bond_operator.initialize_dof_vector(*vector);
      const auto &partitioner = bond_operator.get_partitioner();
      is_prescribed.assign(u.locally_owned_size(), false);
      prescribed.clear();
      const double rho = model.density();
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          {
            const unsigned int index =
              partitioner->global_to_local(nodes[i].dofs[c]);
            mass.local_element(index) = rho * nodes[i].volume();
            if (constraints.is_constrained(nodes[i].dofs[c]))
              {
                prescribed.push_back({index, i, c});
                is_prescribed[index] = true;
              }
          }
      TrilinosWrappers::MPI::Vector nodal_load(
        simulator.get_dof_handler().locally_owned_dofs(),
        comm);
      // Loads that depend on t: the constant part once, the others at
      // their sites at each step (update_load()).
      auto &conditions    = simulator.get_boundary_conditions();
      time_dependent_load = conditions.load_depends_on_time();
      load_sites.clear();
      load_site_indices.clear();
      if (time_dependent_load)
        load_sites = conditions.add_constant_load(simulator.get_dof_handler(),
                                                  nodes,
                                                  constraints,
                                                  nodal_load);
      else
        conditions.add_load(simulator.get_dof_handler(),
                            nodes,
                            constraints,
                            nodal_load);
      for (const auto dof : simulator.get_dof_handler().locally_owned_dofs())
        load[dof] = nodal_load[dof];
      if (time_dependent_load)
        constant_load = load;
      for (const auto &site : load_sites)
        {
          std::array<unsigned int, dim> indices;
          for (unsigned int c = 0; c < dim; ++c)
            indices[c] = site.dofs[c] == numbers::invalid_dof_index ?
                           numbers::invalid_unsigned_int :
                           partitioner->global_to_local(site.dofs[c]);
          load_site_indices.push_back(indices);
        }
      load_time = std::numeric_limits<double>::quiet_NaN();
      // The update loops blend with a 0/1 mask (they vectorise), and skip
      // the work of the loads when there are none anywhere.
      free_dof.resize(u.locally_owned_size());
      for (unsigned int k = 0; k < free_dof.size(); ++k)
        free_dof[k] = is_prescribed[k] ? 0. : 1.;
      with_load = time_dependent_load ||
                  Utilities::MPI::max(load.linfty_norm(), comm) > 0;
      prescribed_values.clear();

      // Points that would silently stand for the nearest node: on the
      // body, or an error.
      Discretization::check_points_in_body(nodes,
                                           probe_points,
                                           "explicit dynamics/Probe points",
                                           probe_text);
      crack_tip.check_on_body(nodes, "explicit dynamics");

      // Probes: the nearest node over all processes (ties: lowest DoF).
      probe_nodes.assign(probe_points.size(), numbers::invalid_unsigned_int);
      for (unsigned int k = 0; k < probe_points.size(); ++k)
        {
          double       best = std::numeric_limits<double>::max();
          unsigned int node = numbers::invalid_unsigned_int;
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            {
              const double d = nodes[i].location.distance(probe_points[k]);
              if (d < best)
                {
                  best = d;
                  node = i;
                }
            }
          const double closest = Utilities::MPI::min(best, comm);
          const types::global_dof_index mine =
            best == closest ? nodes[node].dofs[0] : numbers::invalid_dof_index;
          const auto winner = Utilities::MPI::min(mine, comm);
          if (mine == winner && mine != numbers::invalid_dof_index)
            probe_nodes[k] = node;
        }

      setup_hybrid(simulator);
      const unsigned int n_stencil =
        Utilities::MPI::sum(bond_operator.n_stencil_nodes(), comm);
      const unsigned int n_runs =
        Utilities::MPI::sum(bond_operator.n_run_nodes(), comm);
      const std::size_t visits =
        Utilities::MPI::sum(bond_operator.n_bond_visits(), comm);
      simulator.get_pcout()
        << "[" << std::setw(8) << std::fixed << std::setprecision(2)
        << simulator.elapsed()
        << " s] explicit dynamics: " << simulator.get_summary().n_nodes
        << " nodes (" << n_stencil << " on the shared stencil, " << n_runs
        << " near the surface in runs along x), " << visits
        << " bond visits per step, "
        << (finite_kinematics ? "finite deformation" : "small strain")
        << ", critical stretch "
        << (std::isfinite(s0) ? to_string(s0) :
                                std::string("none (no failure)"))
        << ", " << n_cut << " bonds cut by pre-cracks, "
        << Utilities::MPI::sum(prescribed.size(), comm) << " prescribed DoFs, "
        << MultithreadInfo::n_threads() << " thread(s) per process"
        << std::defaultfloat << std::endl;
      if (time_dependent_load)
        simulator.get_pcout()
          << "           the body force or traction depends on t: evaluated "
             "at every step's time at "
          << Utilities::MPI::sum(load_sites.size(), comm) << " load sites"
          << std::endl;
    }


    namespace
    {
      /**
       * Stop when the stable step 2 / sqrt(lambda) is not a finite positive
       * number. The simulator refuses a run without bonds, so Gershgorin's
       * bound lambda of M^{-1} K has left the range of doubles; it is the
       * stiffness over the density: name the one that is out of range.
       * Collective (the same lambda on every process).
       */
      template <int dim>
      void
      check_stability_bound(const Simulator<dim>               &simulator,
                            const Operators::BondOperator<dim> &op,
                            const double                        lambda)
      {
        const double bound = 2 / std::sqrt(lambda);
        if (std::isfinite(bound) && bound > 0)
          return;
        const double      stiffness = op.gershgorin_eigenvalue_bound(1.);
        const double      rho       = simulator.get_model().density();
        const std::string why =
          "the stable time step 2 / sqrt(lambda) is " + format_number(bound) +
          ": Gershgorin's bound lambda of M^{-1} K, the bond stiffness (" +
          format_number(stiffness) +
          " per unit density) over the density, "
          "is " +
          format_number(lambda) +
          ", out of the range of double precision numbers (about 1e-308 to "
          "1e308); give ";
        const bool by_stiffness = !std::isfinite(stiffness) || stiffness <= 0 ||
                                  !std::isfinite(2 / std::sqrt(stiffness));
        if (by_stiffness)
          {
            const auto [entry, value] = simulator.get_stiffness_entry();
            AssertThrow(false,
                        ExcInvalidInput(entry,
                                        value,
                                        why +
                                          "the modulus of a real material, "
                                          "about 1e3 to 1e12 Pa (or of order "
                                          "1 in nondimensional units)"));
          }
        const std::string entry = simulator.get_stiffness_entry().first;
        AssertThrow(
          false,
          ExcInvalidInput(entry.substr(0, entry.rfind('/') + 1) + "Density",
                          format_number(rho),
                          why + "the density of a real material, about "
                                "1 to 2e4 kg/m^3 (or of order 1 in "
                                "nondimensional units)"));
      }
    } // namespace


    template <int dim>
    void
    ExplicitDynamics<dim>::choose_time_step(Simulator<dim> &simulator)
    {
      TimerOutput::Scope scope(simulator.get_timer(), "time step bound");
      const double       rho = simulator.get_model().density();
      // With the hybrid scheme, the larger of the bounds with the
      // collocation rows and with none (setup_hybrid()): any node may
      // switch.
      const double lambda =
        std::max(bond_operator.gershgorin_eigenvalue_bound(rho),
                 hybrid != nullptr ? standard_lambda : 0.);
      dt_bound = 2 / std::sqrt(lambda);
      check_stability_bound(simulator, bond_operator, lambda);
      // The power-method estimate of the actual limit is information only
      // (60 force passes, as many as a few dozen steps): it is computed
      // where someone looks at it, that is when the step may exceed the
      // bound ('Allow unstable time step') or does (the error below).
      const bool above_bound = given_time_step > dt_bound;
      dt_estimate            = 0;
      if (allow_unstable || above_bound)
        {
          // setup_hybrid() estimated the all-standard operator whenever a
          // step is given or may be unstable.
          const double power =
            std::max(bond_operator.estimate_largest_eigenvalue(rho, 60),
                     hybrid != nullptr ? standard_power : 0.);
          dt_estimate = 2 / std::sqrt(power);
        }
      if (given_time_step > 0)
        AssertThrow(
          !above_bound || allow_unstable,
          ExcInvalidInput("explicit dynamics/Time step",
                          to_string(given_time_step),
                          "the step exceeds the stability bound " +
                            to_string(dt_bound) +
                            " s (the power-method estimate of the limit is " +
                            to_string(dt_estimate) +
                            " s); give a smaller step, 0 for the bound times "
                            "'Safety factor', or set 'Allow unstable time "
                            "step = true'"));
      StabilityBound bound;
      bound.value       = dt_bound;
      bound.description = "the stability bound " + to_string(dt_bound) + " s";
      const auto plan   = time_loop.plan(bound);
      n_steps           = plan.n_steps;
      dt                = plan.dt;
      time_loop.check_output_interval(dt);
      next_output_time = output_interval;
      simulator.get_pcout()
        << "           time step " << to_string(dt) << " s (" << n_steps
        << " steps to " << to_string(end_time) << " s); stability bound "
        << to_string(dt_bound) << " s";
      if (dt_estimate > 0)
        simulator.get_pcout()
          << ", power-method estimate of the actual limit (may be a few per "
             "cent too large) "
          << to_string(dt_estimate) << " s";
      simulator.get_pcout() << std::endl;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::initialize(Simulator<dim> &simulator)
    {
      const auto    &nodes = simulator.get_nodes();
      Vector<double> value(dim);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          initial_displacement->vector_value(nodes[i].location, value);
          for (unsigned int c = 0; c < dim; ++c)
            {
              finite_check.value(value[c],
                                 initial_displacement_entry,
                                 nodes[i].location);
              u[nodes[i].dofs[c]] = value[c];
            }
          initial_velocity->vector_value(nodes[i].location, value);
          for (unsigned int c = 0; c < dim; ++c)
            {
              finite_check.value(value[c],
                                 initial_velocity_entry,
                                 nodes[i].location);
              v[nodes[i].dofs[c]] = value[c];
            }
        }
      time = 0;
      simulator.get_boundary_conditions().set_time(0);
      for (const auto &p : prescribed)
        {
          const double g = simulator.get_boundary_conditions().dirichlet_value(
            nodes[p.node].location)[p.component];
          finite_check.value(g, dirichlet_entry, nodes[p.node].location, true);
          (prescribe_velocity ? v : u).local_element(p.index) = g;
        }
      // Before the first force pass: it would only spread the bad values.
      finite_check.throw_pending(simulator.get_communicator());
      u.update_ghost_values();
      // run() records the energies of the initial state next.
      compute_acceleration(simulator, true);
      check_finite(simulator);
      finite_check.finish_state_check();
      update_hybrid(simulator);
    }


    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, setup, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, choose_time_step, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, initialize, )
  } // namespace Problems
} // namespace PeriDEAL
