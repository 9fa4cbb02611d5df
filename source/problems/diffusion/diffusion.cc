/**
 * @file
 * The run of the diffusion problem type: the set-up (kernel, bond state,
 * operator, layers), the initial state, the time step against the
 * stability bound, the time loop whose steps (or the one solve of a
 * steady state) its integrator takes, the memory estimate; the explicit
 * instantiation of Diffusion and its registration as the problem type
 * 'diffusion'. The input is in diffusion_parameters.cc, the layers in
 * diffusion_layers.cc, the linear solves in diffusion_solve.cc, their
 * checks in diffusion_checks.cc and the output in diffusion_output.cc.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <perideal/base/exceptions.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/node_region.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <sstream>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    const Models::DiffusionSetup<dim> &
    Diffusion<dim>::model_setup() const
    {
      Assert(model_view.has_value(), ExcInternalError());
      return *model_view;
    }


    template <int dim>
    void
    Diffusion<dim>::run(Simulator<dim> &simulator)
    {
      setup(simulator);
      {
        TimerOutput::Scope scope(simulator.get_timer(), "initial state");
        initial->set_time(0);
        for (unsigned int i = 0; i < simulator.get_nodes().n_owned(); ++i)
          {
            const auto  &x     = simulator.get_nodes()[i].location;
            const double value = initial->value(x);
            finite_check.value(value, initial_entry, x);
            c.local_element(op.vector_index(i)) = value;
          }
        model->initialize(model_setup(), c);
        apply_layer_values(0, c);
        finite_check.throw_pending(simulator.get_communicator());
      }
      if (hybrid)
        {
          // With the model's phases (the interface nodes are standard).
          const std::uint64_t n_total = simulator.get_summary().n_nodes;
          const std::uint64_t n_standard =
            n_total -
            Utilities::MPI::sum(std::uint64_t(op.n_collocation_nodes_now()),
                                simulator.get_communicator());
          simulator.get_pcout()
            << "           hybrid: " << n_standard << " of " << n_total
            << " nodes standard (" << std::fixed << std::setprecision(1)
            << 100. * n_standard / std::max<std::uint64_t>(n_total, 1)
            << " %: the standard region, cut balls, phase interfaces"
            << (simulator.get_quadrature_scheme().hybrid()->adaptive ?
                  ", and for good every node an interface reaches)" :
                  "; a node returns to its row once an interface has "
                  "passed)")
            << std::defaultfloat << std::endl;
        }
      if (!integrator->takes_time_steps())
        {
          TimerOutput::Scope scope(simulator.get_timer(), "steady solve");
          integrator->step(*this, simulator);
          check_finite(simulator);
          record_history(simulator);
          print_progress_line(simulator);
          write_output(simulator);
          return;
        }
      choose_time_step(simulator);
      integrator->initialize(*this, simulator);
      record_history(simulator);
      write_output(simulator);
      TimerOutput::Scope scope(simulator.get_timer(), "time steps");
      loop_start    = simulator.elapsed();
      last_progress = loop_start;
      while (step_number < n_steps)
        {
          integrator->step(*this, simulator);
          check_finite(simulator);
          const bool last = step_number == n_steps;
          const bool by_steps =
            output_every_steps > 0 && step_number % output_every_steps == 0;
          const bool by_time = time_loop.output_due(time, dt, next_output_time);
          const bool row     = last || step_number % history_every_steps == 0;
          {
            TimerOutput::Scope model_scope(simulator.get_timer(),
                                           "model (" + model_name + ")");
            model->after_step(model_setup(),
                              time,
                              c,
                              row || by_steps || by_time);
          }
          if (row)
            {
              record_history(simulator);
              if (last ||
                  simulator.elapsed() - last_progress >= progress_interval_s)
                print_progress_line(simulator);
            }
          if (last || by_steps || by_time)
            {
              TimerOutput::Scope out(simulator.get_timer(), "output");
              write_output(simulator);
            }
        }
      if (integrator->solves_linear_systems())
        simulator.get_pcout()
          << "           " << total_iterations << " solver iterations in "
          << n_steps << " steps (" << std::fixed << std::setprecision(1)
          << double(total_iterations) / std::max<std::uint64_t>(n_steps, 1)
          << " per step)" << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    Diffusion<dim>::setup(Simulator<dim> &simulator)
    {
      simulator.setup_neighbor_lists(false);
      TimerOutput::Scope scope(simulator.get_timer(), "operator setup");
      nodes                = &simulator.get_nodes();
      const auto    &nodes = simulator.get_nodes();
      const MPI_Comm comm  = simulator.get_communicator();
      horizon              = simulator.get_horizon();
      kernel.reinit(dim, horizon);
      if (kernel.calibrates_on_lattice())
        {
          const auto &lists = simulator.get_neighbor_lists();
          AssertThrow(lists.lattice().is_uniform() && !lists.stencil().empty(),
                      ExcInvalidInput(section +
                                        "/Micro-diffusivity calibration",
                                      "lattice",
                                      "the mesh is not a uniform grid; use "
                                      "'continuum'"));
          std::vector<std::array<int, dim>> offsets;
          std::vector<double>               fractions;
          for (const auto &o : lists.stencil())
            {
              offsets.push_back(o.offset);
              fractions.push_back(o.beta);
            }
          kernel.calibrate_on_lattice<dim>(lists.lattice().spacing(),
                                           offsets,
                                           fractions);
        }
      bond_state.reinit(nodes, simulator.get_neighbor_lists());
      op.reinit(nodes, simulator.get_neighbor_lists(), kernel, &bond_state);
      if (const auto *hybrid_settings =
            simulator.get_quadrature_scheme().hybrid())
        {
          // The fixed standard region (check_input() refuses 1D). Nodes at
          // a phase interface are standard anyway (the operator finds
          // them; with 'adaptive' for good).
          hybrid = true;
          std::vector<bool> standard(nodes.n_owned(), false);
          if constexpr (dim > 1)
            {
              const std::vector<bool> region =
                hybrid_standard_region(simulator);
              for (unsigned int i = 0; i < nodes.n_owned(); ++i)
                standard[i] = region[i];
            }
          op.set_standard_nodes(standard, hybrid_settings->adaptive);
        }
      if (const auto *settings =
            simulator.get_quadrature_scheme().collocation())
        {
          std::ostringstream line;
          line << "quadrature '" << simulator.get_quadrature_scheme_name()
               << "': order " << settings->order << ", ";
          if (simulator.get_node_perturbation() > 0)
            {
              // Irregular nodes: a row per node. Without a shared row there
              // is no symbol to check. A row whose diagonal is not negative
              // falls back (or stops the run); growing modes that a row's
              // diagonal does not show are not checked at set-up
              // (doc/collocation.md Sect. 11.2): the power-method estimate
              // below bounds the largest |eigenvalue|, not the largest real
              // part. The stabilised order-2 rows per node (the default)
              // had none in the bond-based study of Sect. 7.2.
              const Operators::CollocationReport report =
                op.use_collocation_per_node(*settings);
              line << "a row per node (irregular nodes), ";
              if (report.n_collocation_nodes > 0)
                line << report.n_collocation_min << " to "
                     << report.n_collocation << " collocation nodes (";
              else
                line << "none fitted (";
              line << report.n_monomials << " monomials), cond(A) up to "
                   << std::setprecision(2) << std::scientific
                   << report.condition << std::defaultfloat << "; "
                   << report.n_collocation_nodes << " nodes by collocation"
                   << (report.n_lower_order > 0 ?
                         " (" + std::to_string(report.n_lower_order) +
                           " of them by order 2: bad order-4 cloud)" :
                         std::string())
                   << ", " << report.n_fixed_standard
                   << " standard (insulating bond), " << report.n_cut_nodes
                   << " standard (ball cut by the surface), "
                   << report.n_ill_conditioned
                   << " standard (ill-conditioned or indefinite cloud)";
            }
          else
            {
              const double condition = op.use_collocation(*settings);
              // Growing modes (doc/collocation.md Sect. 7) blow up any
              // explicit step.
              AssertThrow(
                op.collocation_symbol() <= 1e-10 ||
                  integrator->solves_linear_systems(),
                ExcInvalidInput(
                  "Quadrature/collocation/Order",
                  std::to_string(settings->order),
                  "the bulk collocation row of this order at this "
                  "m-ratio has growing modes (largest symbol "
                  "eigenvalue " +
                    format_number(op.collocation_symbol()) +
                    " of the most negative; doc/collocation.md Sect. "
                    "7), which explicit time stepping amplifies at "
                    "any step; use 'Order = 2'" +
                    (settings->stabilisation_mode ==
                         Quadrature::CollocationSettings::Stabilisation::none ?
                       std::string(", 'Stabilisation = automatic'") :
                       std::string()) +
                    " or implicit time stepping"));
              line << (op.uses_collocation() ?
                         std::to_string(op.n_collocation_nodes()) +
                           " collocation nodes, cond(A) " :
                         std::string("the bulk stays standard: cond(A) "))
                   << std::setprecision(2) << std::scientific << condition
                   << std::defaultfloat;
            }
          simulator.print_progress(line.str());
        }
      for (auto *v : {&c, &lc, &s, &rhs, &row_sum})
        op.initialize_vector(*v);
      op.row_sums(row_sum);
      // Before any model sets phases (with fixed flows the operator is
      // affine).
      radius_estimate = op.estimate_spectral_radius(60);
      vector_index.resize(nodes.size());
      for (unsigned int i = 0; i < nodes.size(); ++i)
        vector_index[i] = op.vector_index(i);
      model_view.emplace(Models::DiffusionSetup<dim>{
        nodes,
        simulator.get_neighbor_lists(),
        kernel,
        vector_index,
        [this](const Models::DiffusionPhases &phases) {
          op.set_phases(phases.phase_of_node,
                        phases.n_phases,
                        phases.factor,
                        phases.gate,
                        phases.rate);
        },
        [this]() { return op.largest_row_sum(); },
        horizon});

      setup_layers(simulator);

      const unsigned int n_stencil =
        Utilities::MPI::sum(op.n_stencil_nodes(), comm);
      const std::size_t visits = Utilities::MPI::sum(op.n_bond_visits(), comm);
      simulator.get_pcout()
        << "[" << std::setw(8) << std::fixed << std::setprecision(2)
        << simulator.elapsed()
        << " s] diffusion: " << simulator.get_summary().n_nodes << " nodes ("
        << n_stencil << " on the shared stencil), " << visits
        << " bond visits per evaluation, K = " << std::scientific
        << std::setprecision(4) << kernel.diffusivity() << std::defaultfloat
        << ", q = " << kernel.flux_exponent() << ", " << kernel.influence_name()
        << " influence, micro-diffusivity " << std::scientific
        << std::setprecision(6) << kernel.micro_diffusivity()
        << std::defaultfloat
        << (kernel.calibrates_on_lattice() ? " (on the lattice)" :
                                             " (continuum)")
        << ", " << Utilities::MPI::sum(dirichlet_nodes.size(), comm)
        << " Dirichlet nodes, " << Utilities::MPI::sum(flux_nodes.size(), comm)
        << " flux nodes, " << integrator->name() << ", "
        << MultithreadInfo::n_threads() << " thread(s) per process"
        << std::endl;
    }


    template <int dim>
    void
    Diffusion<dim>::choose_time_step(Simulator<dim> &simulator)
    {
      const double bound = op.gershgorin_bound();
      // The simulator refuses a run without bonds: a bound out of range is
      // the diffusivity's scale (over the squared spacing) overflowing.
      AssertThrow(std::isfinite(bound) && bound > 0 && std::isfinite(2 / bound),
                  ExcInvalidInput(section + "/Diffusivity",
                                  format_number(kernel.diffusivity()),
                                  "the stable time step 2 / lambda_G is " +
                                    format_number(2 / bound) +
                                    ": Gershgorin's bound lambda_G of the "
                                    "operator, about the diffusivity over "
                                    "the squared node spacing, is " +
                                    format_number(bound) +
                                    ", out of the range of double precision "
                                    "numbers (about 1e-308 to 1e308); give "
                                    "the diffusivity of a real medium, about "
                                    "1e-12 to 1e-3 m^2/s (or of order 1 in "
                                    "nondimensional units)"));
      dt_bound                      = 2 / bound;
      const double model_bound      = model->largest_time_step(model_setup());
      const bool   limited_by_model = model_bound < dt_bound;
      if (limited_by_model)
        {
          dt_bound = model_bound;
          simulator.get_pcout()
            << "           the model '" << model_name
            << "' limits the time step to " << model_bound << std::endl;
        }
      if (integrator->is_conditionally_stable() && given_time_step > 0)
        AssertThrow(given_time_step <= dt_bound || allow_unstable,
                    ExcInvalidInput(
                      section + "/Time step",
                      format_number(given_time_step),
                      "forward Euler is stable only up to " +
                        format_number(dt_bound) +
                        (limited_by_model ?
                           " (the limit of the model '" + model_name + "')" :
                           std::string(" (2 / Gershgorin's bound of the "
                                       "operator)")) +
                        "; give a smaller step, 0 for "
                        "the bound, or set 'Allow unstable "
                        "time step = true'"));
      // Implicit schemes are stable at any step: no bound (only the count).
      StabilityBound step_bound;
      if (integrator->is_conditionally_stable())
        {
          step_bound.value = dt_bound;
          step_bound.description =
            limited_by_model ?
              "the limit " + format_number(dt_bound) + " of the model '" +
                model_name + "' (" + model->time_step_limit().reason + ")" :
              "the forward Euler bound " + format_number(dt_bound);
          if (limited_by_model)
            {
              step_bound.entry       = model->time_step_limit().entry;
              step_bound.entry_value = model->time_step_limit().value;
            }
        }
      const auto plan = time_loop.plan(step_bound);
      n_steps         = plan.n_steps;
      dt              = plan.dt;
      time_loop.check_output_interval(dt);
      simulator.get_pcout()
        << "[" << std::setw(8) << std::fixed << std::setprecision(2)
        << simulator.elapsed() << " s] time step " << std::scientific
        << std::setprecision(4) << dt << " (" << n_steps
        << " steps); forward Euler bound " << dt_bound
        << " (power-method estimate of the limit " << 2 / radius_estimate << ")"
        << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    Diffusion<dim>::advance_time()
    {
      ++step_number;
      time = step_number == n_steps ? end_time : step_number * dt;
    }


    template <int dim>
    double
    Diffusion<dim>::estimated_bytes_per_node(const double coupled) const
    {
      return (dim == 3 ? 2048 : 1024) + 4 * coupled;
    }


    template class Diffusion<1>;
    template class Diffusion<2>;
    template class Diffusion<3>;
  } // namespace Problems
} // namespace PeriDEAL

PERIDEAL_REGISTER_PROBLEM_TYPE_1D_2D_3D(
  PeriDEAL::Problems::Diffusion,
  "diffusion",
  "Nonlocal (bond-based PD) diffusion: forward Euler within its stability "
  "bound, backward Euler or Crank-Nicolson with CG on the matrix-free "
  "operator, or the steady state; Dirichlet layers, fluxes, sources, PVD "
  "time series and a history CSV.")
