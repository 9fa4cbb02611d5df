/**
 * @file
 * The input of the diffusion problem type: its entries declared with their
 * patterns and help texts, read and checked (parse_parameters(); 'Time
 * stepping' into its integrator, the layer selections into values), and the
 * entries that this run leaves unused (unused_entries()); the checks against
 * the simulator's entries are TimeSteppingProblem::check_input().
 */

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>

#include <algorithm>
#include <string>
#include <vector>

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
      // The function subsections: scalar functions of x and t.
      const auto declare_function = [&](const std::string &name) {
        prm.enter_subsection(name);
        Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
        prm.leave_subsection();
      };
      // The boundary ids and the thickness of a kind of layer.
      const auto declare_layer = [&](const std::string &kind,
                                     const std::string &layers,
                                     const std::string &ids_help) {
        prm.declare_entry(kind + " boundary ids",
                          "",
                          Patterns::List(Patterns::Integer(0, 254)),
                          ids_help);
        prm.declare_entry(kind + " layer thickness",
                          "1",
                          Patterns::Double(),
                          "Thickness of the " + layers + ", in horizons.");
      };
      declare_function("Initial concentration");
      declare_function("Source");
      declare_layer("Dirichlet",
                    "Dirichlet layers",
                    "Boundaries along which 'Boundary concentration' is "
                    "prescribed in a layer of 'Dirichlet layer "
                    "thickness'.");
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
      declare_function("Boundary concentration");
      declare_layer("Flux",
                    "flux layers",
                    "Boundaries through which 'Boundary flux' enters, as "
                    "a source (flux / thickness) in a layer of 'Flux "
                    "layer thickness'.");
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
      declare_function("Boundary flux");
      prm.declare_entry("Compare with analytical solution",
                        "false",
                        Patterns::Bool(),
                        "Report the error against 'Analytical "
                        "concentration' (relative l2 norm over the free "
                        "nodes and the largest nodal error).");
      declare_function("Analytical concentration");
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
    void
    Diffusion<dim>::parse_parameters(ParameterHandler &prm)
    {
      kernel.parse_parameters(prm, section);
      const std::string stepping_text = prm.get("Time stepping");
      integrator                      = DiffusionIntegrators::create<dim>(
        stepping_text,
        prm.get("Implicit scheme") == "backward Euler" ? 1. : 0.5);
      model_name = prm.get("Model");
      model      = Models::DiffusionModelRegistry<dim>::create(model_name, prm);
      AssertThrow(!integrator->solves_linear_systems() ||
                    model->supports_implicit(),
                  ExcInvalidInput(section + "/Time stepping",
                                  stepping_text,
                                  "the model '" + model_name +
                                    "' runs with explicit time stepping "
                                    "only"));
      model_columns = model->history_columns();
      end_time      = prm.get_double("End time");
      AssertThrow(end_time > 0 || !integrator->takes_time_steps(),
                  ExcInvalidInput(section + "/End time",
                                  prm.get("End time"),
                                  "give a simulated time > 0"));
      given_time_step = prm.get_double("Time step");
      AssertThrow(given_time_step >= 0 &&
                    (given_time_step > 0 ||
                     !integrator->needs_given_time_step()),
                  ExcInvalidInput(section + "/Time step",
                                  prm.get("Time step"),
                                  integrator->needs_given_time_step() ?
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
      layer_values_text        = prm.get("Dirichlet layer values");
      flux_values_text         = prm.get("Flux layer values");
      layer_values =
        layer_values_text == "function"      ? LayerValues::function :
        layer_values_text == "surface value" ? LayerValues::surface_value :
                                               LayerValues::mirror;
      flux_values =
        flux_values_text == "source" ? FluxValues::source : FluxValues::mirror;
      flux_thickness_text = prm.get("Flux layer thickness");
      dirichlet_thickness = prm.get_double("Dirichlet layer thickness");
      flux_thickness      = prm.get_double("Flux layer thickness");
      // What every kind of layer needs: a thickness > 0; and for mirror
      // layers explicit stepping (their values depend on the solution) and
      // at most one horizon (an image lies up to two thicknesses away, and
      // the node set holds the off-process nodes within two horizons).
      const auto check_layer = [&](const std::string &kind,
                                   const bool         mirror,
                                   const std::string &values,
                                   const double       thickness,
                                   const std::string &thickness_text,
                                   const std::string &alternative) {
        AssertThrow(thickness > 0,
                    ExcInvalidInput(section + "/" + kind + " layer thickness",
                                    thickness_text,
                                    "give a thickness > 0 (in horizons)"));
        if (!mirror)
          return;
        AssertThrow(!integrator->solves_linear_systems(),
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
                  layer_values == LayerValues::mirror,
                  layer_values_text,
                  dirichlet_thickness,
                  dirichlet_thickness_text,
                  "'surface value' or 'function'");
      check_layer("Flux",
                  flux_values == FluxValues::mirror,
                  flux_values_text,
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
      AssertThrow(integrator->takes_time_steps() || !dirichlet_ids.empty(),
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
      TimeSteppingProblem<dim>::check_input(simulator);
      if (simulator.get_quadrature_scheme().collocation() == nullptr)
        return;
      const std::string &scheme = simulator.get_quadrature_scheme_name();
      AssertThrow(dim > 1 || simulator.get_node_perturbation() == 0,
                  ExcInvalidInput(
                    "Geometry/Node perturbation",
                    format_number(simulator.get_node_perturbation()),
                    "the diffusion operator's collocation rows on perturbed "
                    "nodes (a row per node) are built in 2D and 3D; in 1D "
                    "set 0, or 'Quadrature/Scheme = standard' (which runs on "
                    "perturbed nodes)"));
      const auto *hybrid = simulator.get_quadrature_scheme().hybrid();
      AssertThrow(hybrid == nullptr || dim > 1,
                  ExcInvalidInput("Quadrature/Scheme",
                                  scheme,
                                  "the hybrid scheme of the diffusion problem "
                                  "runs in 2D and 3D (its standard region is "
                                  "given by boxes and layers); in 1D use "
                                  "'Scheme = standard', or 'collocation' "
                                  "with a model that sets no phases"));
      AssertThrow(hybrid != nullptr || model->supports_collocation(),
                  ExcInvalidInput("Quadrature/Scheme",
                                  scheme,
                                  "the diffusion model '" + model_name +
                                    "' sets phases, and a collocation row "
                                    "has no phase factors: the nodes at an "
                                    "interface need the standard scheme; use "
                                    "'Scheme = standard'" +
                                    std::string(dim > 1 ?
                                                  ", or 'hybrid' (collocation "
                                                  "away from the interfaces)" :
                                                  "")));
      AssertThrow(hybrid == nullptr || !hybrid->adaptive ||
                    model->changes_phases(),
                  ExcInvalidInput("Quadrature/hybrid/Configuration",
                                  "adaptive",
                                  "the diffusion model '" + model_name +
                                    "' changes no phases, so no node would "
                                    "ever switch to the standard scheme; set "
                                    "'Configuration = fixed' (the standard "
                                    "boxes and layers, and the nodes whose "
                                    "ball is cut, are standard)"));
      AssertThrow(!kernel.calibrates_on_lattice(),
                  ExcInvalidInput(section + "/Micro-diffusivity calibration",
                                  "lattice",
                                  "the collocation quadrature integrates the "
                                  "kernel over the ball exactly and needs "
                                  "the continuum micro-diffusivity; set "
                                  "'continuum'"));
    }


    template <int dim>
    std::vector<UnusedEntry>
    Diffusion<dim>::unused_entries(const Simulator<dim> &simulator) const
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
      for (const auto &rule : integrator->unused_entries(given_time_step > 0))
        unused.push_back({prefix + rule.pattern, rule.why});
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
      const auto *hybrid = simulator.get_quadrature_scheme().hybrid();
      if (hybrid != nullptr && hybrid->adaptive)
        for (const char *entry :
             {"Critical stretch fraction", "Critical bond detection"})
          unused.push_back(
            {std::string("Quadrature/hybrid/") + entry,
             "the diffusion problem has no bond stretch: its adaptive "
             "hybrid switches the nodes a phase interface reaches, at the "
             "step the phase changes; remove the entry"});
      return unused;
    }


#define PERIDEAL_INSTANTIATE(dim)                                       \
  template void Diffusion<dim>::declare_parameters(ParameterHandler &); \
  template void Diffusion<dim>::parse_parameters(ParameterHandler &);   \
  template std::vector<UnusedEntry> Diffusion<dim>::unused_entries(     \
    const Simulator<dim> &) const;                                      \
  template void Diffusion<dim>::check_input(const Simulator<dim> &) const;
    PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
