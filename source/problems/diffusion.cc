#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/diffusion.h>
#include <perideal/solvers/amg.h>
#include <perideal/solvers/krylov.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    Diffusion<dim>::declare_parameters(ParameterHandler &prm)
    {
      Models::DiffusionKernel::declare_parameters(prm);
      prm.declare_entry(
        "Model",
        "none",
        Patterns::Selection(
          Models::DiffusionModelRegistry<dim>::pattern_string()),
        "The physics on top of diffusion: none, or corrosion (its entries in "
        "the subsection of that name).");
      Models::DiffusionModelRegistry<dim>::declare_parameters(prm);
      prm.declare_entry(
        "Time stepping",
        "explicit",
        Patterns::Selection("explicit|implicit|steady state"),
        "explicit: forward Euler with the step below the stability bound; "
        "implicit: 'Implicit scheme' with a linear solve per step; steady "
        "state: -L C = S (source and boundary values at t = 0), one solve.");
      prm.declare_entry("Implicit scheme",
                        "backward Euler",
                        Patterns::Selection("backward Euler|Crank-Nicolson"),
                        "The implicit scheme: theta = 1 or 1/2.");
      prm.declare_entry("End time", "1", Patterns::Double(), "> 0.");
      prm.declare_entry(
        "Time step",
        "0",
        Patterns::Double(),
        "Time step. 0 (explicit only): 'Safety factor' times the stability "
        "bound 2 / lambda_G of forward Euler (lambda_G: Gershgorin's bound "
        "of the spectral radius of the discrete operator). The step is "
        "shortened so that a whole number of steps reaches 'End time'.");
      prm.declare_entry("Safety factor",
                        "0.9",
                        Patterns::Double(),
                        "Fraction of the stability bound used when 'Time "
                        "step = 0'; in (0, 1].");
      prm.declare_entry("Allow unstable time step",
                        "false",
                        Patterns::Bool(),
                        "Accept an explicit 'Time step' above the stability "
                        "bound (an error otherwise).");
      prm.declare_entry("Preconditioner",
                        "local laplacian",
                        Patterns::Selection("jacobi|local laplacian"),
                        "Implicit and steady solves: Jacobi on the exact "
                        "diagonal, or algebraic multigrid on the local "
                        "Laplacian (cell-centred finite volumes on the same "
                        "nodes; uniform grids).");
      Solvers::AmgSettings::declare_parameters(prm, "0.02");
      prm.declare_entry("Solver tolerance",
                        "1e-10",
                        Patterns::Double(),
                        "Relative residual of the implicit solves; in (0, "
                        "1).");
      prm.declare_entry("Maximum iterations",
                        "1000",
                        Patterns::Integer(1),
                        "Iterations of an implicit solve before it fails.");
      prm.enter_subsection("Initial concentration");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.enter_subsection("Source");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.declare_entry("Dirichlet boundary ids",
                        "",
                        Patterns::List(Patterns::Integer(0, 254)),
                        "Boundaries along which 'Boundary concentration' is "
                        "prescribed in a layer of 'Dirichlet layer "
                        "thickness'.");
      prm.declare_entry("Dirichlet layer thickness",
                        "1",
                        Patterns::Double(),
                        "Thickness of the Dirichlet layers, in horizons.");
      prm.declare_entry(
        "Dirichlet layer values",
        "function",
        Patterns::Selection("function|surface value|mirror"),
        "How the Dirichlet layers get their values. function: 'Boundary "
        "concentration' at each layer node (needs the solution in the "
        "layer, e.g. a manufactured one); surface value: its value at the "
        "nearest point of the physical surface (the inner face of the "
        "layer), extended as a constant; mirror: 2 g(x_b) - C(x_m), the "
        "odd reflection through the surface point x_b of the value at the "
        "mirror node x_m (second order for a smooth solution; explicit time "
        "stepping, uniform grids).");
      prm.enter_subsection("Boundary concentration");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.declare_entry("Flux boundary ids",
                        "",
                        Patterns::List(Patterns::Integer(0, 254)),
                        "Boundaries through which 'Boundary flux' enters, as "
                        "a source (flux / thickness) in a layer of 'Flux "
                        "layer thickness'.");
      prm.declare_entry("Flux layer thickness",
                        "1",
                        Patterns::Double(),
                        "Thickness of the flux layers, in horizons.");
      prm.declare_entry(
        "Flux layer values",
        "source",
        Patterns::Selection("source|mirror"),
        "How a flux enters. source: the layer is part of the body and "
        "'Boundary flux' q enters as the source q / thickness in its nodes. "
        "mirror: the layer is a fictitious layer outside the body (the "
        "physical surface is its inner face, as for Dirichlet layers) whose "
        "values are C(x_m) + |x - x_m| q(x_b) / K, the even reflection of "
        "the mirror node x_m through the surface point x_b with the normal "
        "gradient the flux gives (zero flux: a plain even reflection); "
        "second order for a smooth solution; explicit time stepping, "
        "uniform grids.");
      prm.enter_subsection("Boundary flux");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.declare_entry("Compare with analytical solution",
                        "false",
                        Patterns::Bool(),
                        "Report the error against 'Analytical "
                        "concentration' (relative l2 norm over the free "
                        "nodes and the largest nodal error).");
      prm.enter_subsection("Analytical concentration");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.declare_entry("Output every steps",
                        "0",
                        Patterns::Integer(0),
                        "Write PVTU output every this many steps (and at the "
                        "first and last step). 0: use 'Output interval'.");
      prm.declare_entry("Output interval",
                        "0",
                        Patterns::Double(0),
                        "Write PVTU output every this much simulated time; 0 "
                        "(with 'Output every steps = 0'): first and last "
                        "step only.");
      prm.declare_entry("History every steps",
                        "10",
                        Patterns::Integer(1),
                        "A row of the history file (and a progress check) "
                        "every this many steps.");
      prm.declare_entry("History file",
                        "history.csv",
                        Patterns::FileName(),
                        "CSV of time, step, total amount, minimum, maximum, "
                        "solver iterations and errors, in "
                        "'Output/Directory'. Empty: not written.");
      prm.declare_entry("Progress interval",
                        "5",
                        Patterns::Double(0),
                        "Print a progress line on rank 0 at most every this "
                        "many seconds of wall time.");
      TimeLoop::declare_parameters(prm);
    }


    template <int dim>
    std::string
    Diffusion<dim>::stepping_name(const Stepping value)
    {
      switch (value)
        {
          case Stepping::explicit_euler:
            return "explicit";
          case Stepping::implicit:
            return "implicit";
          case Stepping::steady_state:
            return "steady state";
        }
      Assert(false, ExcInternalError());
      return "";
    }


    template <int dim>
    void
    Diffusion<dim>::parse_parameters(ParameterHandler &prm)
    {
      kernel.parse_parameters(prm, section);
      const std::string stepping_text = prm.get("Time stepping");
      for (const auto value : {Stepping::explicit_euler,
                               Stepping::implicit,
                               Stepping::steady_state})
        if (stepping_name(value) == stepping_text)
          stepping = value;
      Assert(stepping_name(stepping) == stepping_text,
             ExcInternalError()); // the pattern admits these three only
      model_name = prm.get("Model");
      model      = Models::DiffusionModelRegistry<dim>::create(model_name, prm);
      AssertThrow(stepping == Stepping::explicit_euler ||
                    model->supports_implicit(),
                  ExcInvalidInput(section + "/Time stepping",
                                  stepping_text,
                                  "the model '" + model_name +
                                    "' runs with explicit time stepping "
                                    "only"));
      model_columns = model->history_columns();
      theta         = prm.get("Implicit scheme") == "backward Euler" ? 1. : 0.5;
      end_time      = prm.get_double("End time");
      AssertThrow(end_time > 0 || stepping == Stepping::steady_state,
                  ExcInvalidInput(section + "/End time",
                                  prm.get("End time"),
                                  "give a simulated time > 0"));
      given_time_step = prm.get_double("Time step");
      AssertThrow(given_time_step >= 0 &&
                    (given_time_step > 0 || stepping != Stepping::implicit),
                  ExcInvalidInput(section + "/Time step",
                                  prm.get("Time step"),
                                  stepping == Stepping::implicit ?
                                    "implicit time stepping needs a time "
                                    "step > 0" :
                                    "give a step > 0, or 0 for the "
                                    "stability bound"));
      safety_factor = prm.get_double("Safety factor");
      AssertThrow(safety_factor > 0 && safety_factor <= 1,
                  ExcInvalidInput(section + "/Safety factor",
                                  prm.get("Safety factor"),
                                  "give a fraction in (0, 1]"));
      allow_unstable  = prm.get_bool("Allow unstable time step");
      local_laplacian = prm.get("Preconditioner") == "local laplacian";
      amg_settings.parse_parameters(prm);
      tolerance = prm.get_double("Solver tolerance");
      AssertThrow(tolerance > 0 && tolerance < 1,
                  ExcInvalidInput(section + "/Solver tolerance",
                                  prm.get("Solver tolerance"),
                                  "give a relative tolerance in (0, 1)"));
      max_iterations = prm.get_integer("Maximum iterations");

      const auto parse =
        [&](const std::string &name, auto &function, FunctionEntry &entry) {
          function = parse_function<dim>(prm, name, section, 1, &entry);
          expressions[name] = entry.expression;
          return entry.expression;
        };
      parse("Initial concentration", initial, initial_entry);
      with_source = parse("Source", source, source_entry) != "0";
      parse("Boundary concentration", boundary_value, boundary_value_entry);
      with_flux =
        parse("Boundary flux", boundary_flux, boundary_flux_entry) != "0";
      parse("Analytical concentration", analytical, analytical_entry);
      compare = prm.get_bool("Compare with analytical solution");

      dirichlet_ids_text = prm.get("Dirichlet boundary ids");
      flux_ids_text      = prm.get("Flux boundary ids");
      dirichlet_ids      = Boundary::parse_boundary_ids(dirichlet_ids_text);
      flux_ids           = Boundary::parse_boundary_ids(flux_ids_text);
      dirichlet_thickness_text = prm.get("Dirichlet layer thickness");
      layer_values             = prm.get("Dirichlet layer values");
      flux_values              = prm.get("Flux layer values");
      flux_thickness_text      = prm.get("Flux layer thickness");
      dirichlet_thickness      = prm.get_double("Dirichlet layer thickness");
      flux_thickness           = prm.get_double("Flux layer thickness");
      // What every kind of layer needs: a thickness > 0; and for mirror
      // layers explicit stepping (their values depend on the solution) and
      // at most one horizon (an image lies up to two thicknesses away, and
      // the node set holds the off-process nodes within two horizons).
      const auto check_layer = [&](const std::string &kind,
                                   const std::string &values,
                                   const double       thickness,
                                   const std::string &thickness_text,
                                   const std::string &alternative) {
        AssertThrow(thickness > 0,
                    ExcInvalidInput(section + "/" + kind + " layer thickness",
                                    thickness_text,
                                    "give a thickness > 0 (in horizons)"));
        if (values != "mirror")
          return;
        AssertThrow(stepping == Stepping::explicit_euler,
                    ExcInvalidInput(section + "/" + kind + " layer values",
                                    values,
                                    "mirror layers need 'Time stepping = "
                                    "explicit' (their values depend on the "
                                    "solution); use " +
                                      alternative));
        AssertThrow(thickness <= 1,
                    ExcInvalidInput(section + "/" + kind + " layer thickness",
                                    thickness_text,
                                    "mirror layers reach nodes up to two "
                                    "layer thicknesses away: give at most 1 "
                                    "(horizon)"));
      };
      check_layer("Dirichlet",
                  layer_values,
                  dirichlet_thickness,
                  dirichlet_thickness_text,
                  "'surface value' or 'function'");
      check_layer("Flux",
                  flux_values,
                  flux_thickness,
                  flux_thickness_text,
                  "'source'");
      for (const auto id : flux_ids)
        AssertThrow(std::find(dirichlet_ids.begin(), dirichlet_ids.end(), id) ==
                      dirichlet_ids.end(),
                    ExcInvalidInput(section + "/Flux boundary ids",
                                    flux_ids_text,
                                    "boundary id " + std::to_string(id) +
                                      " is also in 'Dirichlet boundary ids'; a "
                                      "face carries either a value or a flux"));
      AssertThrow(stepping != Stepping::steady_state || !dirichlet_ids.empty(),
                  ExcInvalidInput(section + "/Dirichlet boundary ids",
                                  dirichlet_ids_text,
                                  "a steady state needs prescribed values "
                                  "somewhere (otherwise it is not unique): "
                                  "list at least one boundary id"));

      output_every_steps  = prm.get_integer("Output every steps");
      output_interval     = prm.get_double("Output interval");
      history_every_steps = prm.get_integer("History every steps");
      history_file        = prm.get("History file");
      progress_interval_s = prm.get_double("Progress interval");
      time_loop.parse_parameters(prm, section, "");
    }


    template <int dim>
    void
    Diffusion<dim>::check_input(const Simulator<dim> &simulator) const
    {
      AssertThrow(simulator.get_boundary_treatment_name() == "none",
                  ExcInvalidInput("Boundary treatment/Treatment",
                                  simulator.get_boundary_treatment_name(),
                                  "the diffusion problem supports the 'none' "
                                  "treatment only so far"));
      AssertThrow(simulator.get_node_data_file().empty(),
                  ExcInvalidInput("Output/Node data file",
                                  simulator.get_node_data_file(),
                                  "the node data file is written by the "
                                  "quasi-static problem only; leave it "
                                  "empty"));
    }


    template <int dim>
    std::vector<UnusedEntry>
    Diffusion<dim>::unused_entries(const Simulator<dim> &) const
    {
      const std::string        prefix = section + "/";
      std::vector<UnusedEntry> unused = {
        {"Boundary conditions/",
         "the diffusion problem takes its boundary values and fluxes from "
         "'diffusion/Dirichlet boundary ids', 'Boundary concentration', "
         "'Flux boundary ids' and 'Boundary flux'; remove the subsection "
         "'Boundary conditions'"},
        {"Analytical solution/",
         "the diffusion problem compares with 'diffusion/Analytical "
         "concentration' when 'diffusion/Compare with analytical solution' "
         "is true; remove the subsection 'Analytical solution'"}};
      const auto add = [&](const std::vector<std::string> &entries,
                           const std::string              &why) {
        for (const auto &entry : entries)
          unused.push_back({prefix + entry, why});
      };
      if (stepping != Stepping::implicit)
        add({"Implicit scheme"},
            "'Time stepping = " + stepping_name(stepping) +
              "' uses no implicit scheme; set 'Time stepping = implicit' to "
              "use it, or remove the entry");
      if (stepping == Stepping::explicit_euler)
        add({"Preconditioner", "Solver tolerance", "Maximum iterations"},
            "'Time stepping = explicit' solves no linear system; remove the "
            "entry, or choose 'implicit' or 'steady state'");
      if (stepping == Stepping::steady_state)
        add({"Time step",
             "End time",
             "Output every steps",
             "Output interval",
             "History every steps"},
            "'Time stepping = steady state' takes no time steps (one solve, "
            "one output, sources and boundary values at t = 0); remove the "
            "entry, or choose 'explicit' or 'implicit'");
      if (stepping != Stepping::explicit_euler || given_time_step > 0)
        add({"Safety factor"},
            stepping != Stepping::explicit_euler ?
              "the time step of 'Time stepping = " + stepping_name(stepping) +
                "' is 'Time step' itself; remove the entry" :
              std::string("'Time step' is given, so no fraction of the "
                          "stability bound is taken; set 'Time step = 0' to "
                          "use it, or remove the entry"));
      if (stepping != Stepping::explicit_euler || given_time_step == 0)
        add({"Allow unstable time step"},
            stepping != Stepping::explicit_euler ?
              "'Time stepping = " + stepping_name(stepping) +
                "' has no stability bound to exceed; remove the entry" :
              std::string("with 'Time step = 0' the step is 'Safety "
                          "factor' (at most 1) times the stability bound, "
                          "never above it; remove the entry"));
      if (dirichlet_ids.empty())
        add({"Dirichlet layer thickness",
             "Dirichlet layer values",
             "Boundary concentration/"},
            "no 'Dirichlet boundary ids' are given, so there is no "
            "Dirichlet layer; give them, or remove the entry");
      if (flux_ids.empty())
        add({"Flux layer thickness", "Flux layer values", "Boundary flux/"},
            "no 'Flux boundary ids' are given, so no flux enters; give "
            "them, or remove the entry");
      if (!compare)
        add({"Analytical concentration/"},
            "'diffusion/Compare with analytical solution' is false; set it "
            "to true to compare, or remove the entry");
      for (const auto &rule : model->unused_entries())
        unused.push_back({prefix + rule.pattern, rule.why});
      return unused;
    }


    template <int dim>
    Models::DiffusionSetup<dim>
    Diffusion<dim>::model_setup(Simulator<dim> &simulator)
    {
      return {simulator.get_nodes(),
              simulator.get_neighbor_lists(),
              kernel,
              op,
              horizon};
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
        model->initialize(model_setup(simulator), c);
        apply_layer_values(0, c);
        finite_check.throw_pending(simulator.get_communicator());
      }
      if (stepping == Stepping::steady_state)
        {
          TimerOutput::Scope scope(simulator.get_timer(), "steady solve");
          evaluate_source(0, rhs);
          if (local_laplacian)
            setup_local_laplacian(simulator, 0, 1);
          last_iterations = solve(simulator, 0, 1, rhs, c);
          total_iterations += last_iterations;
          check_finite(simulator);
          record_history(simulator);
          print_progress_line(simulator);
          write_output(simulator);
          return;
        }
      choose_time_step(simulator);
      if (stepping == Stepping::implicit && local_laplacian)
        setup_local_laplacian(simulator, 1, theta * dt);
      record_history(simulator);
      write_output(simulator);
      TimerOutput::Scope scope(simulator.get_timer(), "time steps");
      loop_start    = simulator.elapsed();
      last_progress = loop_start;
      while (step_number < n_steps)
        {
          if (stepping == Stepping::explicit_euler)
            explicit_step(simulator);
          else
            implicit_step(simulator);
          check_finite(simulator);
          const bool last = step_number == n_steps;
          const bool by_steps =
            output_every_steps > 0 && step_number % output_every_steps == 0;
          const bool by_time = time_loop.output_due(time, dt, next_output_time);
          const bool row     = last || step_number % history_every_steps == 0;
          {
            TimerOutput::Scope model_scope(simulator.get_timer(),
                                           "model (" + model_name + ")");
            model->after_step(model_setup(simulator),
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
      if (stepping == Stepping::implicit)
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
      for (auto *v : {&c, &lc, &s, &rhs, &row_sum})
        op.initialize_vector(*v);
      op.row_sums(row_sum);
      // Before any model sets phases (with fixed flows the operator is
      // affine).
      radius_estimate = op.estimate_spectral_radius(60);

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
        << " flux nodes, " << stepping_name(stepping) << ", "
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
      dt_bound = 2 / bound;
      const double model_bound =
        model->largest_time_step(model_setup(simulator));
      const bool limited_by_model = model_bound < dt_bound;
      if (limited_by_model)
        {
          dt_bound = model_bound;
          simulator.get_pcout()
            << "           the model '" << model_name
            << "' limits the time step to " << model_bound << std::endl;
        }
      if (stepping == Stepping::explicit_euler && given_time_step > 0)
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
      if (stepping == Stepping::explicit_euler)
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
    Diffusion<dim>::explicit_step(Simulator<dim> &)
    {
      // C^{n+1} = C^n + dt (L C^n + S^n) (paper Eq. 31); prescribed values
      // at t^{n+1}.
      // A diffusion model may have left the ghost values of this state up
      // to date (corrosion exchanges them after each step): not twice.
      if (!c.has_ghost_elements())
        c.update_ghost_values();
      op.apply(c, lc);
      evaluate_source(time, s);
      c.zero_out_ghost_values();
      const unsigned int n = c.locally_owned_size();
      for (unsigned int k = 0; k < n; ++k)
        if (!is_prescribed[k])
          c.local_element(k) += dt * (lc.local_element(k) + s.local_element(k));
      ++step_number;
      time = step_number == n_steps ? end_time : step_number * dt;
      apply_layer_values(time, c);
    }


    namespace
    {
      /**
       * alpha x - beta L x on the free nodes, the identity on the
       * prescribed ones (whose values do not enter the free rows: they are
       * lifted to the right-hand side).
       */
      template <int dim>
      struct SystemOperator
      {
        using VectorType = LinearAlgebra::distributed::Vector<double>;
        const Operators::DiffusionOperator<dim> &op;
        const std::vector<bool>                 &is_prescribed;
        double                                   alpha, beta;
        mutable VectorType                       tmp, result;

        void
        vmult(VectorType &dst, const VectorType &src) const
        {
          const unsigned int n = src.locally_owned_size();
          for (unsigned int k = 0; k < n; ++k)
            tmp.local_element(k) = is_prescribed[k] ? 0. : src.local_element(k);
          tmp.update_ghost_values();
          op.apply(tmp, result);
          tmp.zero_out_ghost_values();
          for (unsigned int k = 0; k < n; ++k)
            dst.local_element(k) =
              is_prescribed[k] ?
                src.local_element(k) :
                alpha * src.local_element(k) - beta * result.local_element(k);
        }
      };


    } // namespace


    template <int dim>
    unsigned int
    Diffusion<dim>::solve(Simulator<dim>   &simulator,
                          const double      alpha,
                          const double      beta,
                          const VectorType &b,
                          VectorType       &x)
    {
      // Lift the prescribed values: b_free += beta (L g)_free, g the
      // prescribed values (zero elsewhere).
      VectorType lifted(b), g;
      op.initialize_vector(g);
      const unsigned int n = x.locally_owned_size();
      for (unsigned int k = 0; k < n; ++k)
        if (is_prescribed[k])
          g.local_element(k) = x.local_element(k);
      g.update_ghost_values();
      op.apply(g, lc);
      for (unsigned int k = 0; k < n; ++k)
        lifted.local_element(k) =
          is_prescribed[k] ? x.local_element(k) :
                             b.local_element(k) + beta * lc.local_element(k);

      SystemOperator<dim> system{op, is_prescribed, alpha, beta, {}, {}};
      op.initialize_vector(system.tmp);
      op.initialize_vector(system.result);
      x.zero_out_ghost_values();
      check_solve_input(simulator, b, lifted, x);
      const double  norm = lifted.l2_norm();
      SolverControl control(max_iterations, std::max(tolerance * norm, 1e-300));
      const MPI_Comm comm = simulator.get_communicator();
      try
        {
          if (norm == 0)
            x = 0;
          else
            {
              // CG where the operator is symmetric, GMRES (deal.II's
              // defaults: left-preconditioned, 30 vectors) where not.
              const Solvers::Method method = op.is_symmetric() ?
                                               Solvers::Method::cg :
                                               Solvers::Method::gmres;
              const typename SolverGMRES<VectorType>::AdditionalData gmres;
              if (local_laplacian)
                Solvers::run_krylov(method,
                                    gmres,
                                    control,
                                    system,
                                    x,
                                    lifted,
                                    *amg);
              else
                {
                  VectorType inverse_diagonal;
                  op.initialize_vector(inverse_diagonal);
                  for (unsigned int k = 0; k < n; ++k)
                    inverse_diagonal.local_element(k) =
                      is_prescribed[k] ?
                        1. :
                        1. / (alpha + beta * row_sum.local_element(k));
                  const DiagonalMatrix<VectorType> jacobi(inverse_diagonal);
                  Solvers::run_krylov(method,
                                      gmres,
                                      control,
                                      system,
                                      x,
                                      lifted,
                                      jacobi);
                }
            }
        }
      catch (const SolverControl::NoConvergence &e)
        {
          if (!std::isfinite(e.last_residual))
            check_solve_result(simulator, false, e.last_residual, x);
          AssertThrow(false,
                      ExcMessage(
                        "The linear solve of step " +
                        std::to_string(step_number + 1) + " (t = " +
                        format_number(time) + ") did not converge: residual " +
                        format_number(e.last_residual) + " after " +
                        std::to_string(e.last_step) + " iterations, " +
                        "target " + format_number(control.tolerance()) +
                        ". Raise 'diffusion/Maximum iterations', use "
                        "'Preconditioner = local laplacian', or a shorter "
                        "'Time step'. The output written before is "
                        "complete."));
        }
      (void)comm;
      if (norm == 0)
        return 0; // no iteration: last_step() would be invalid_unsigned_int
      check_solve_result(simulator,
                         control.last_check() == SolverControl::success,
                         control.last_value(),
                         x);
      return control.last_step();
    }


    template <int dim>
    void
    Diffusion<dim>::implicit_step(Simulator<dim> &simulator)
    {
      // (I - theta dt L) C^{n+1} = C^n + (1 - theta) dt (L C^n + S^n)
      //                           + theta dt S^{n+1}.
      const unsigned int n = c.locally_owned_size();
      rhs                  = c;
      if (theta < 1)
        {
          c.update_ghost_values();
          op.apply(c, lc);
          c.zero_out_ghost_values();
          evaluate_source(time, s);
          for (unsigned int k = 0; k < n; ++k)
            rhs.local_element(k) +=
              (1 - theta) * dt * (lc.local_element(k) + s.local_element(k));
        }
      ++step_number;
      time = step_number == n_steps ? end_time : step_number * dt;
      evaluate_source(time, s);
      rhs.add(theta * dt, s);
      apply_layer_values(time, c);
      last_iterations = solve(simulator, 1, theta * dt, rhs, c);
      total_iterations += last_iterations;
    }


    template <int dim>
    void
    Diffusion<dim>::setup_local_laplacian(Simulator<dim> &simulator,
                                          const double    alpha,
                                          const double    beta)
    {
      // alpha I - beta K Delta_h on the free nodes, Delta_h the cell-centred
      // finite-volume Laplacian (2 dim + 1 points, no flux across the
      // outer boundary); identity rows and no columns for the prescribed
      // nodes, so that the matrix stays symmetric. At wavelengths above
      // the horizon L behaves like K Delta (flux matching), below it the
      // PD symbol saturates: spectrally equivalent at fixed m-ratio.
      TimerOutput::Scope scope(simulator.get_timer(), "local Laplacian");
      const auto        &lattice = simulator.get_neighbor_lists().lattice();
      const MPI_Comm     comm    = simulator.get_communicator();
      AssertThrow(lattice.is_uniform(),
                  ExcInvalidInput(section + "/Preconditioner",
                                  "local laplacian",
                                  "the local Laplacian needs a uniform grid; "
                                  "use 'jacobi' on this mesh"));
      // Whether each node of the set (ghosts too) is prescribed.
      VectorType flag;
      op.initialize_vector(flag);
      for (const auto i : prescribed_nodes)
        flag.local_element(op.vector_index(i)) = 1;
      flag.update_ghost_values();
      const auto prescribed = [&](const unsigned int i) {
        return flag.local_element(op.vector_index(i)) != 0;
      };
      const auto global = [&](const unsigned int i) {
        return (*nodes)[i].dofs[0] / dim;
      };
      const IndexSet &owned = op.get_partitioner()->locally_owned_range();
      const double    a =
        beta * kernel.diffusivity() / (lattice.spacing() * lattice.spacing());
      TrilinosWrappers::SparsityPattern pattern(owned, comm, 2 * dim + 1);
      std::vector<std::vector<std::pair<types::global_dof_index, double>>> rows(
        nodes->n_owned());
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          auto &row = rows[i];
          if (prescribed(i))
            {
              row.emplace_back(global(i), 1.);
              continue;
            }
          double diagonal = alpha;
          for (unsigned int d = 0; d < dim; ++d)
            for (const int side : {-1, 1})
              {
                auto y = lattice.coordinates(i);
                y[d] += side;
                const int j = lattice.node_at(y);
                if (j < 0)
                  continue;
                diagonal += a;
                if (!prescribed(j))
                  row.emplace_back(global(j), -a);
              }
          row.emplace_back(global(i), diagonal);
        }
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        for (const auto &entry : rows[i])
          pattern.add(global(i), entry.first);
      pattern.compress();
      laplacian = std::make_unique<TrilinosWrappers::SparseMatrix>();
      laplacian->reinit(pattern);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        for (const auto &entry : rows[i])
          laplacian->set(global(i), entry.first, entry.second);
      laplacian->compress(VectorOperation::insert);
      amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      Solvers::initialize_amg(*amg, *laplacian, amg_settings, {});
    }


    template <int dim>
    void
    Diffusion<dim>::record_history(Simulator<dim> &simulator)
    {
      const MPI_Comm comm    = simulator.get_communicator();
      double         total   = 0;
      double         lowest  = std::numeric_limits<double>::max();
      double         highest = std::numeric_limits<double>::lowest();
      double         error2 = 0, exact2 = 0, max_error = 0;
      if (compare)
        analytical->set_time(time);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const unsigned int k     = op.vector_index(i);
          const double       value = c.local_element(k);
          total += (*nodes)[i].volume() * value;
          lowest  = std::min(lowest, value);
          highest = std::max(highest, value);
          if (compare && !is_prescribed[k])
            {
              const double exact = analytical->value((*nodes)[i].location);
              error2 += (value - exact) * (value - exact);
              exact2 += exact * exact;
              max_error = std::max(max_error, std::abs(value - exact));
            }
        }
      total                   = Utilities::MPI::sum(total, comm);
      lowest                  = Utilities::MPI::min(lowest, comm);
      highest                 = Utilities::MPI::max(highest, comm);
      std::vector<double> row = {time,
                                 double(step_number),
                                 total,
                                 lowest,
                                 highest,
                                 double(last_iterations)};
      if (compare)
        {
          error2    = Utilities::MPI::sum(error2, comm);
          exact2    = Utilities::MPI::sum(exact2, comm);
          max_error = Utilities::MPI::max(max_error, comm);
          row.push_back(exact2 > 0 ? std::sqrt(error2 / exact2) :
                                     std::sqrt(error2));
          row.push_back(max_error);
        }
      const auto values = model->history_values(model_setup(simulator), c);
      row.insert(row.end(), values.begin(), values.end());
      history.push_back(row);
    }


    template <int dim>
    void
    Diffusion<dim>::print_progress_line(Simulator<dim> &simulator)
    {
      const double now = simulator.elapsed();
      last_progress    = now;
      const auto &row  = history.back();
      auto       &out  = simulator.get_pcout();
      out << "[" << std::setw(8) << std::fixed << std::setprecision(2) << now
          << " s] ";
      if (stepping == Stepping::steady_state)
        out << "steady state";
      else
        out << "step " << step_number << "/" << n_steps
            << ", t = " << std::scientific << std::setprecision(4) << time;
      out << std::scientific << std::setprecision(4) << ", total " << row[2]
          << ", min " << row[3] << ", max " << row[4];
      if (stepping != Stepping::explicit_euler)
        out << ", " << last_iterations << " iterations";
      if (compare)
        out << ", relative l2 error " << row[6] << ", max error " << row[7];
      if (!model_columns.empty())
        out << ", "
            << model->progress_text(
                 std::vector<double>(row.end() - model_columns.size(),
                                     row.end()));
      if (stepping != Stepping::steady_state)
        {
          const double rate = step_number / std::max(now - loop_start, 1e-9);
          out << ", " << std::fixed << std::setprecision(1) << rate
              << " steps/s, " << std::setprecision(0)
              << (n_steps - step_number) / std::max(rate, 1e-9) << " s left";
        }
      out << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    Diffusion<dim>::write_output(Simulator<dim> &simulator)
    {
      const MPI_Comm comm = simulator.get_communicator();
      time_loop.advance_output_time(next_output_time,
                                    time,
                                    std::max(dt, 1e-300));
      const auto &output = simulator.get_output();
      if (output.enabled())
        {
          IO::NodeField concentration{"concentration", {}}, error{"error", {}},
            rank{"mpi_rank", {}};
          if (compare)
            analytical->set_time(time);
          const double this_rank = Utilities::MPI::this_mpi_process(comm);
          for (unsigned int i = 0; i < nodes->n_owned(); ++i)
            {
              const double value = c.local_element(op.vector_index(i));
              concentration.values.push_back(value);
              if (compare)
                error.values.push_back(value -
                                       analytical->value((*nodes)[i].location));
              rank.values.push_back(this_rank);
            }
          std::vector<IO::NodeField> fields = {concentration, rank};
          if (compare)
            fields.push_back(error);
          for (auto &field : model->node_fields(model_setup(simulator), c))
            fields.push_back(std::move(field));
          const std::string record = output.write(simulator.get_dof_handler(),
                                                  *nodes,
                                                  fields,
                                                  records.size());
          records.emplace_back(time, record);
          output.write_time_series(records, comm);
        }
      if (!history_file.empty())
        {
          std::string error;
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            {
              const std::string path = output.directory() + "/" + history_file;
              std::error_code   code;
              std::filesystem::create_directories(output.directory(), code);
              error = write_then_rename(path, [&](std::ostream &out) {
                out << "time,step,total,minimum,maximum,iterations";
                if (compare)
                  out << ",relative_l2_error,max_error";
                for (const auto &name : model_columns)
                  out << ',' << name;
                out << '\n' << std::setprecision(12);
                for (const auto &row : history)
                  {
                    for (unsigned int k = 0; k < row.size(); ++k)
                      out << (k > 0 ? "," : "") << row[k];
                    out << '\n';
                  }
              });
              if (!error.empty())
                error =
                  "Invalid value '" + path +
                  "' for the parameter 'diffusion/History file': " + error +
                  ".";
            }
          throw_on_any_rank(error, comm);
        }
    }


    template <int dim>
    void
    Diffusion<dim>::check_finite(Simulator<dim> &simulator)
    {
      // The sources and boundary values were finite where they were
      // evaluated (else their entry would be named): the solution diverged.
      std::ostringstream advice;
      if (stepping == Stepping::explicit_euler)
        advice << "The run is unstable: reduce 'diffusion/Time step' "
                  "(forward Euler bound "
               << dt_bound << ") or check the constants.";
      else
        advice << "Check the constants and the solver settings.";
      finite_check.check_state(
        *nodes,
        {{c.begin(), c.locally_owned_size()}},
        [&](const unsigned int i) {
          return std::isfinite(c.local_element(op.vector_index(i)));
        },
        step_number,
        time,
        "The concentration",
        advice.str(),
        simulator.get_communicator());
    }


    template <int dim>
    std::vector<IO::OutputName>
    Diffusion<dim>::output_names(const Simulator<dim> &simulator) const
    {
      const auto &output = simulator.get_output();
      auto        names  = output.output_names(true);
      if (!history_file.empty())
        names.push_back({section + "/History file",
                         history_file,
                         output.directory() + "/" + history_file,
                         IO::OutputName::Kind::file,
                         "the history file"});
      return names;
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
