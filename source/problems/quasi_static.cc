#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/node_region.h>
#include <perideal/problems/quasi_static.h>
#include <perideal/solvers/dynamic_relaxation.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    QuasiStatic<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "End time",
        "1",
        Patterns::Double(),
        "The (pseudo-)time t at the end of the load path: the functions of "
        "'Boundary conditions' (Dirichlet displacement, Body force, "
        "Traction, Boundary stress) and 'Analytical solution' are functions "
        "of t, and the run goes from t = 0 to this time in 'Load steps' "
        "steps. With one step and no bond breaking the loads are evaluated "
        "once, at this time; the default 1 is the end of a unit ramp, so a "
        "load 'p*t' acts in full.");
      prm.declare_entry("Load steps",
                        "1",
                        Patterns::Integer(),
                        "The number of load steps from t = 0 to 'End time' "
                        "(the largest step; the step control may cut it). "
                        "1 with 'Bond breaking = off': one solve at 'End "
                        "time'.");
      prm.declare_entry(
        "Bond breaking",
        "off",
        Patterns::Selection("off|all beyond critical|most critical"),
        "After the equilibrium of a load step: 'off' breaks nothing; 'all "
        "beyond critical' breaks every bond whose stretch reached its "
        "critical stretch (the material model's 'Critical stretch' or "
        "'Fracture energy'), 'most critical' only those within 0.1 % of the "
        "largest ratio of stretch to critical stretch; either way the same "
        "load is solved again until no bond breaks. Pre-cracks and no-fail "
        "regions as in explicit dynamics.");
      prm.declare_entry(
        "Nonlinear solver",
        "Newton",
        Patterns::Selection("Newton|dynamic relaxation"),
        "The solver of each equilibrium. 'Newton': with small-strain "
        "kinematics the problem with the current bonds is linear, so "
        "Newton's method is one linear solve ('Linear solver'), "
        "warm-started from the last step. 'dynamic relaxation': adaptive "
        "dynamic relaxation (Kilic & Madenci 2010) on the matrix-free "
        "operator, warm-started too, with its own test of convergence "
        "(subsection 'dynamic relaxation'); it solves no linear system, so "
        "'Linear solver' has no effect.");
      prm.enter_subsection("dynamic relaxation");
      Solvers::DynamicRelaxation::declare_parameters(prm);
      prm.leave_subsection();
      prm.declare_entry(
        "Kinematics",
        "small strain",
        Patterns::Selection("small strain|finite deformation"),
        "The bond kinematics: 'small strain' (the bond extension linearised "
        "in u, n.(u_j - u_i), and the force along the undeformed bond: each "
        "equilibrium is linear) or 'finite deformation' (the extension "
        "|xi + eta| - |xi| and the force along the deformed bond, as in "
        "explicit dynamics: rigid rotations of any size leave no force; the "
        "critical stretch is compared with the finite stretch). Finite "
        "deformation is solved by a modified Newton method (subsection "
        "'Newton': the corrections by 'Linear solver' on the matrix-free "
        "operator with the stiffness of the reference configuration) or by "
        "dynamic relaxation of the nonlinear residual; it needs 'Quadrature/"
        "Scheme = standard' and 'Boundary treatment/Treatment = none'.");
      prm.enter_subsection("Newton");
      {
        prm.declare_entry(
          "Relative tolerance",
          "1e-8",
          Patterns::Double(0),
          "With 'Kinematics = finite deformation': the equilibrium of a "
          "load step is reached when the residual |f_ext + F(u)| (free "
          "DoFs) is at most this times the norm of the step's lifted "
          "right-hand side (the scale of the Krylov solvers' test).");
        prm.declare_entry(
          "Maximum iterations",
          "50",
          Patterns::Integer(1),
          "With 'Kinematics = finite deformation': the most Newton "
          "corrections of one solve; a solve that needs more fails and the "
          "step control cuts the load step.");
      }
      prm.leave_subsection();
      prm.declare_entry(
        "Reaction boundary ids",
        "",
        Patterns::List(Patterns::Integer(0, 254)),
        "Boundary ids with Dirichlet layers whose reaction is written to "
        "'Load-displacement file': the force that holds the layer's "
        "prescribed nodes, i.e. minus the sum of the body's internal forces "
        "on them (per unit thickness in 2D). Each id must be one of "
        "'Boundary conditions/Dirichlet boundary ids'.");
      prm.declare_entry(
        "Reaction boxes",
        "",
        Patterns::Anything(),
        "Boxes 'xmin, ymin[, zmin], xmax, ymax[, zmax]' (several separated "
        "by ';') whose prescribed nodes (those of 'Boundary "
        "conditions/Dirichlet boxes' or Dirichlet layers) add their "
        "reaction to that of the 'Reaction boundary ids': the load point "
        "of a beam in bending, say. Empty: none.");
      prm.declare_entry(
        "Load-displacement file",
        "load_displacement.csv",
        Patterns::FileName(Patterns::FileName::output),
        "CSV in 'Output/Directory' with one row per load step: "
        "step,time,reaction_x,reaction_y[,reaction_z],broken_bonds,"
        "iterations (broken bonds: all broken so far, pre-cracks included; "
        "iterations: the linear solver's, summed over the step's solves). "
        "Written when the load is stepped. Empty: none.");
      prm.declare_entry("Minimum load step",
                        "0",
                        Patterns::Double(0),
                        "The step control does not cut a step below this; "
                        "0: ('End time' / 'Load steps') / 1024. A solve that "
                        "fails at the minimum stops the run with the step "
                        "and the load named.");
      prm.declare_entry(
        "Critical stretch tolerance",
        "0.01",
        Patterns::Double(0),
        "A load step is cut (down to 'Minimum load step') while some bond's "
        "stretch exceeds (1 + this) times its critical stretch at the "
        "step's equilibrium: the load at which bonds start to break is "
        "then found to about this relative precision.");
      prm.declare_entry("Maximum bonds per step",
                        "0",
                        Patterns::Integer(0),
                        "A load step is also cut while more bonds than this "
                        "are over their critical stretch at its first "
                        "equilibrium; 0: no limit.");
      prm.declare_entry("Complete failure fraction",
                        "0.01",
                        Patterns::Double(0, 1),
                        "With bond breaking and 'Reaction boundary ids': "
                        "the run stops, complete, when the magnitude of the "
                        "reaction falls below this fraction of its peak "
                        "after bonds broke. 0: run to 'End time'.");
      BondFailure<dim>::declare_parameters(prm);
    }


    template <int dim>
    void
    QuasiStatic<dim>::parse_parameters(ParameterHandler &prm)
    {
      end_time = prm.get_double("End time");
      AssertThrow(std::isfinite(end_time) && end_time > 0,
                  ExcInvalidInput("quasi-static/End time",
                                  prm.get("End time"),
                                  "give a time > 0 (the load path runs from "
                                  "t = 0 to it)"));
      const long steps = prm.get_integer("Load steps");
      AssertThrow(steps >= 1,
                  ExcInvalidInput("quasi-static/Load steps",
                                  prm.get("Load steps"),
                                  "give at least 1 step"));
      n_load_steps        = static_cast<unsigned int>(steps);
      bond_breaking_name  = prm.get("Bond breaking");
      bond_breaking       = bond_breaking_name == "off" ?
                              BondBreaking::off :
                            bond_breaking_name == "most critical" ?
                              BondBreaking::most_critical :
                              BondBreaking::all_beyond_critical;
      reaction_ids_text   = prm.get("Reaction boundary ids");
      reaction_ids        = Boundary::parse_boundary_ids(reaction_ids_text);
      reaction_boxes_text = prm.get("Reaction boxes");
      reaction_boxes =
        Discretization::parse_boxes<dim>(reaction_boxes_text,
                                         "quasi-static/Reaction boxes");
      load_displacement_file = prm.get("Load-displacement file");
      minimum_step           = prm.get_double("Minimum load step");
      const double largest   = end_time / n_load_steps;
      AssertThrow(minimum_step <= largest,
                  ExcInvalidInput("quasi-static/Minimum load step",
                                  prm.get("Minimum load step"),
                                  "give at most 'End time' / 'Load steps' = " +
                                    format_number(largest) +
                                    ", or 0 for a 1024th of it"));
      if (minimum_step == 0)
        minimum_step = largest / 1024;
      stretch_tolerance  = prm.get_double("Critical stretch tolerance");
      max_bonds_per_step = prm.get_integer("Maximum bonds per step");
      failure_fraction   = prm.get_double("Complete failure fraction");
      failure.parse_parameters(prm, "quasi-static");
      use_dynamic_relaxation =
        prm.get("Nonlinear solver") == "dynamic relaxation";
      finite_deformation = prm.get("Kinematics") == "finite deformation";
      prm.enter_subsection("Newton");
      newton.tolerance = prm.get_double("Relative tolerance");
      AssertThrow(newton.tolerance > 0 && newton.tolerance < 1,
                  ExcInvalidInput("quasi-static/Newton/Relative tolerance",
                                  prm.get("Relative tolerance"),
                                  "give a tolerance between 0 and 1, e.g. "
                                  "1e-8"));
      newton.max_iterations = prm.get_integer("Maximum iterations");
      prm.leave_subsection();
      prm.enter_subsection("dynamic relaxation");
      dynamic_relaxation.parse_parameters(prm,
                                          "quasi-static/dynamic relaxation/");
      prm.leave_subsection();
    }


    template <int dim>
    std::vector<IO::OutputName>
    QuasiStatic<dim>::output_names(const Simulator<dim> &simulator) const
    {
      const auto &output = simulator.get_output();
      auto        names  = output.output_names(steps_load());
      if (steps_load() && !load_displacement_file.empty())
        names.push_back({"quasi-static/Load-displacement file",
                         load_displacement_file,
                         output.directory() + "/" + load_displacement_file,
                         IO::OutputName::Kind::file,
                         "the load-displacement file"});
      return names;
    }


    template <int dim>
    void
    QuasiStatic<dim>::check_input(const Simulator<dim> &simulator) const
    {
      AssertThrow(
        simulator.get_node_data_file().empty() ||
          simulator.get_analytical_solution() != nullptr,
        ExcInvalidInput("Output/Node data file",
                        simulator.get_node_data_file(),
                        "the node data file holds the errors against the "
                        "analytical solution: set 'Analytical solution/Compare "
                        "with analytical solution = true', or leave the entry "
                        "empty"));
      const auto probe =
        simulator.get_boundary_treatment().template make_system<dim>(
          simulator.get_boundary_treatment_name());
      probe->check_input(simulator.get_linear_solver());
      if (simulator.get_quadrature_scheme().collocation() != nullptr)
        check_collocation_input(simulator);
      const auto &bc = simulator.get_boundary_conditions();
      for (const auto id : reaction_ids)
        AssertThrow(bc.is_dirichlet_boundary(id),
                    ExcInvalidInput("quasi-static/Reaction boundary ids",
                                    reaction_ids_text,
                                    "boundary id " + std::to_string(id) +
                                      " has no Dirichlet layer, so nothing "
                                      "holds it and it has no reaction; list "
                                      "ids of 'Boundary conditions/Dirichlet "
                                      "boundary ids' (" +
                                      bc.dirichlet_ids_string() + ")"));
      if (finite_deformation)
        {
          AssertThrow(
            probe->supports_finite_deformation(),
            ExcInvalidInput("quasi-static/Kinematics",
                            "finite deformation",
                            "the boundary treatment '" +
                              simulator.get_boundary_treatment_name() +
                              "' solves small strains only; use 'Boundary "
                              "treatment/Treatment = none', or 'Kinematics = "
                              "small strain'"));
          AssertThrow(
            simulator.get_quadrature_scheme().collocation() == nullptr,
            ExcInvalidInput("quasi-static/Kinematics",
                            "finite deformation",
                            "the collocation rows are linear in u; set "
                            "'Quadrature/Scheme = standard', or 'Kinematics = "
                            "small strain'"));
          AssertThrow(
            use_dynamic_relaxation ||
              simulator.get_linear_solver().is_matrix_free(),
            ExcInvalidInput("quasi-static/Kinematics",
                            "finite deformation",
                            "its Newton corrections run on the matrix-free "
                            "operator; set 'Linear solver/Operator = "
                            "matrix-free' (with a Krylov 'Method'), or "
                            "'Nonlinear solver = dynamic relaxation'"));
        }
      // Load stepping (solve_step()) belongs to the same group of functions
      // as bond breaking.
      AssertThrow(n_load_steps == 1 || probe->supports_bond_breaking(),
                  ExcInvalidInput("quasi-static/Load steps",
                                  std::to_string(n_load_steps),
                                  "the boundary treatment '" +
                                    simulator.get_boundary_treatment_name() +
                                    "' solves one load only; set 'Load steps "
                                    "= 1', or use 'Boundary treatment/"
                                    "Treatment = none'"));
      if (bond_breaking == BondBreaking::off)
        return;
      AssertThrow(probe->supports_bond_breaking(),
                  ExcInvalidInput("quasi-static/Bond breaking",
                                  bond_breaking_name,
                                  "the boundary treatment '" +
                                    simulator.get_boundary_treatment_name() +
                                    "' does not break bonds; use 'Boundary "
                                    "treatment/Treatment = none', or 'Bond "
                                    "breaking = off'"));
      AssertThrow(simulator.get_quadrature_scheme().collocation() == nullptr,
                  ExcInvalidInput("quasi-static/Bond breaking",
                                  bond_breaking_name,
                                  "quasi-static bond breaking runs with "
                                  "'Quadrature/Scheme = standard' so far "
                                  "(the collocation rows hold no bonds to "
                                  "break); set it, or 'Bond breaking = off'"));
    }


    template <int dim>
    bool
    QuasiStatic<dim>::supports_collocation() const
    {
      return true;
    }


    template <int dim>
    bool
    QuasiStatic<dim>::supports_hybrid() const
    {
      return true;
    }


    template <int dim>
    void
    QuasiStatic<dim>::check_collocation_input(
      const Simulator<dim> &simulator) const
    {
      const std::string &scheme = simulator.get_quadrature_scheme_name();
      AssertThrow(simulator.get_boundary_treatment().body_nodes_only(),
                  ExcInvalidInput("Quadrature/Scheme",
                                  scheme,
                                  "the collocation rows are built for the "
                                  "body's own nodes, and the boundary "
                                  "treatment '" +
                                    simulator.get_boundary_treatment_name() +
                                    "' adds others; use 'Boundary "
                                    "treatment/Treatment = none' or 'Scheme "
                                    "= standard'"));
      AssertThrow(
        !simulator.get_model().is_state_based() ||
          simulator.get_node_perturbation() == 0,
        ExcInvalidInput("Geometry/Node perturbation",
                        format_number(simulator.get_node_perturbation()),
                        "the collocation rows of the state-based model are "
                        "built for nodes at the cell centres so far (perturbed "
                        "nodes take bond-based rows); set 0, use a bond-based "
                        "model, or 'Quadrature/Scheme = standard'"));
      const auto *hybrid = simulator.get_quadrature_scheme().hybrid();
      AssertThrow(hybrid == nullptr || !hybrid->adaptive,
                  ExcInvalidInput("Quadrature/hybrid/Configuration",
                                  "adaptive",
                                  "a quasi-static solve breaks no bonds, so "
                                  "no node would ever switch to the standard "
                                  "scheme; set 'Configuration = fixed' (the "
                                  "standard boxes and layers, and the nodes "
                                  "whose ball is cut, are standard)"));
      const auto &solver = simulator.get_linear_solver();
      solver.check_form(solver.is_matrix_free() ?
                          Solvers::OperatorForm::matrix_free :
                          Solvers::OperatorForm::assembled,
                        false,
                        "the quadrature scheme '" + scheme + "'");
    }


    template <int dim>
    std::vector<UnusedEntry>
    QuasiStatic<dim>::unused_entries(const Simulator<dim> &simulator) const
    {
      std::vector<UnusedEntry> unused =
        simulator.get_boundary_conditions().unused_entries();
      const std::string section = "quasi-static/";
      unused.push_back({"Material model/*/Density",
                        "the quasi-static problem has no inertia (the entry "
                        "acts in 'Problem type = explicit dynamics'); "
                        "remove it"});
      if (bond_breaking == BondBreaking::off)
        {
          for (const char *entry : {"Critical stretch", "Fracture energy"})
            unused.push_back({std::string("Material model/*/") + entry,
                              "'quasi-static/Bond breaking = off': no bond "
                              "breaks; set 'Bond breaking', or remove the "
                              "entry"});
          for (const char *entry : {"Pre-cracks",
                                    "No-fail boxes",
                                    "No-fail boundary ids",
                                    "No-fail layer thickness",
                                    "Critical stretch tolerance",
                                    "Maximum bonds per step",
                                    "Complete failure fraction"})
            unused.push_back({section + entry,
                              "'Bond breaking = off': no bond breaks; set "
                              "'Bond breaking', or remove the entry"});
        }
      else
        {
          for (auto &entry : failure.unused_entries())
            unused.push_back(entry);
          if (!has_reaction())
            unused.push_back({section + "Complete failure fraction",
                              "complete failure is told by the reaction, and "
                              "no 'Reaction boundary ids' or 'Reaction "
                              "boxes' are given; give them, or remove the "
                              "entry"});
        }
      if (!steps_load())
        for (const char *entry : {"Load-displacement file",
                                  "Minimum load step",
                                  "Reaction boundary ids",
                                  "Reaction boxes"})
          unused.push_back({section + entry,
                            "one solve at 'End time' ('Load steps = 1', "
                            "'Bond breaking = off') writes no "
                            "load-displacement file; give more 'Load "
                            "steps', or remove the entry"});
      if (!finite_deformation || use_dynamic_relaxation)
        unused.push_back(
          {section + "Newton/",
           finite_deformation ?
             "'Nonlinear solver = dynamic relaxation' has its own test of "
             "convergence ('quasi-static/dynamic relaxation'); remove the "
             "entry, or use 'Newton'" :
             "with 'Kinematics = small strain' each equilibrium is one "
             "linear solve ('Linear solver'); set 'Kinematics = finite "
             "deformation', or remove the entry"});
      if (use_dynamic_relaxation)
        unused.push_back({"Linear solver/",
                          "'quasi-static/Nonlinear solver = dynamic "
                          "relaxation' solves no linear system (its test of "
                          "convergence is in 'quasi-static/dynamic "
                          "relaxation'); remove the entry, or use 'Newton'"});
      else
        unused.push_back({section + "dynamic relaxation/",
                          "'Nonlinear solver = Newton' does not relax; set "
                          "'Nonlinear solver = dynamic relaxation', or "
                          "remove the entry"});
      if (simulator.get_analytical_solution() == nullptr)
        unused.push_back({"Analytical solution/Displacement/",
                          "'Analytical solution/Compare with analytical "
                          "solution' is false; set it to true to compare, "
                          "or remove the entry"});
      return unused;
    }


    template <int dim>
    void
    QuasiStatic<dim>::run(Simulator<dim> &simulator)
    {
      if (steps_load())
        {
          run_load_steps(simulator);
          return;
        }
      // Every function of the set-up at the one time of this problem.
      simulator.set_time(end_time);
      simulator.get_pcout()
        << "           boundary conditions evaluated at t = "
        << format_number(end_time) << " ('quasi-static/End time')"
        << (simulator.get_boundary_conditions().load_depends_on_time() ||
                simulator.get_boundary_conditions()
                  .dirichlet_depends_on_time() ?
              "; they depend on t" :
              "; they do not depend on t")
        << std::endl;
      Boundary::SystemContext<dim> context = simulator.system_context();
      // The hybrid scheme's fixed standard region (empty without it).
      const std::vector<bool> standard = hybrid_standard_region(simulator);
      context.hybrid_standard          = &standard;
      system = simulator.get_boundary_treatment().template make_system<dim>(
        simulator.get_boundary_treatment_name());
      system->setup(context);
      system->solve_linear(context, displacement);
      postprocess(simulator);
    }


    template <int dim>
    std::string
    QuasiStatic<dim>::postprocess(Simulator<dim>                   &simulator,
                                  const std::vector<IO::NodeField> &extra,
                                  const unsigned int                index)
    {
      const auto  ctx                    = simulator.system_context();
      const auto *analytical_solution    = simulator.get_analytical_solution();
      const unsigned int         n_owned = ctx.nodes.n_owned();
      std::vector<IO::NodeField> fields  = {{"node_volume", {}},
                                            {"mpi_rank", {}},
                                            {"constrained", {}}};
      const double rank = Utilities::MPI::this_mpi_process(ctx.communicator);
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          fields[0].values.push_back(ctx.nodes[i].volume());
          fields[1].values.push_back(rank);
          fields[2].values.push_back(system->is_constrained(ctx.nodes[i]));
        }
      const auto operator_fields = system->node_fields(ctx, displacement);
      fields.insert(fields.begin(),
                    operator_fields.begin(),
                    operator_fields.end());

      if (analytical_solution != nullptr)
        {
          IO::NodeField  error{"displacement_error", {}};
          IO::NodeField  normalized{"normalized_error", {}};
          Vector<double> exact(dim);
          double         e2 = 0, u2 = 0, e_max = 0, u_max = 0;
          // Largest analytical magnitude of each component (Eq. 38).
          Tensor<1, dim> component_max;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(ctx.nodes[i].location, exact);
              for (unsigned int c = 0; c < dim; ++c)
                component_max[c] =
                  std::max(component_max[c], std::abs(exact[c]));
            }
          for (unsigned int c = 0; c < dim; ++c)
            component_max[c] =
              Utilities::MPI::max(component_max[c], ctx.communicator);
          double normalized_max = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(ctx.nodes[i].location, exact);
              double e = 0, u = 0, n2 = 0;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const double diff =
                    displacement[ctx.nodes[i].dofs[c]] - exact[c];
                  e += diff * diff;
                  u += exact[c] * exact[c];
                  if (component_max[c] > 0)
                    n2 += std::pow(diff / component_max[c], 2);
                }
              e2 += ctx.nodes[i].volume() * e;
              u2 += ctx.nodes[i].volume() * u;
              e_max          = std::max(e_max, std::sqrt(e));
              u_max          = std::max(u_max, std::sqrt(u));
              normalized_max = std::max(normalized_max, std::sqrt(n2));
              error.values.push_back(std::sqrt(e));
              normalized.values.push_back(std::sqrt(n2));
            }
          ctx.summary.errors.max_normalized =
            Utilities::MPI::max(normalized_max, ctx.communicator);
          if (!simulator.get_node_data_file().empty())
            write_node_data(simulator, component_max);
          fields.push_back(normalized);
          // Nodes of the system besides the body's (surface nodes): the
          // same measure at their locations.
          const auto extra = system->extra_nodes();
          if (!system->extra_nodes_name().empty())
            {
              double surface_max = 0;
              for (const auto &node : extra)
                {
                  analytical_solution->vector_value(node.location, exact);
                  double n2 = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    if (component_max[c] > 0)
                      n2 += std::pow((node.displacement[c] - exact[c]) /
                                       component_max[c],
                                     2);
                  surface_max = std::max(surface_max, std::sqrt(n2));
                }
              surface_max = Utilities::MPI::max(surface_max, ctx.communicator);
              ctx.pcout << "           " << system->extra_nodes_name()
                        << ": largest normalized error " << std::scientific
                        << std::setprecision(3) << surface_max
                        << std::defaultfloat << std::endl;
            }
          e2                     = Utilities::MPI::sum(e2, ctx.communicator);
          u2                     = Utilities::MPI::sum(u2, ctx.communicator);
          e_max                  = Utilities::MPI::max(e_max, ctx.communicator);
          u_max                  = Utilities::MPI::max(u_max, ctx.communicator);
          ctx.summary.has_errors = true;
          ctx.summary.errors.l2  = u2 > 0 ? std::sqrt(e2 / u2) : std::sqrt(e2);
          ctx.summary.errors.max = u_max > 0 ? e_max / u_max : e_max;
          fields.push_back(error);
          ctx.pcout << "           error against the analytical solution: "
                    << "relative L2 " << std::scientific << std::setprecision(3)
                    << ctx.summary.errors.l2 << ", relative max "
                    << ctx.summary.errors.max << ", normalized max (Eq. 38) "
                    << ctx.summary.errors.max_normalized << std::defaultfloat
                    << std::endl;
        }

      fields.insert(fields.end(), extra.begin(), extra.end());
      const auto        &output = simulator.get_output();
      TimerOutput::Scope scope(ctx.timer, "output");
      const std::string  record =
        output.write(ctx.dof_handler, ctx.nodes, displacement, fields, index);
      if (!record.empty())
        ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                  << simulator.elapsed() << " s] wrote " << output.directory()
                  << "/" << record << std::defaultfloat << std::endl;
      return record;
    }


    template <int dim>
    void
    QuasiStatic<dim>::write_node_data(Simulator<dim>       &simulator,
                                      const Tensor<1, dim> &component_max) const
    {
      const auto  ctx                   = simulator.system_context();
      const auto *analytical_solution   = simulator.get_analytical_solution();
      const std::string &node_data_file = simulator.get_node_data_file();
      // Rows: kind (0 body, 1 surface), x, u, exact, normalized error.
      std::vector<double> rows;
      Vector<double>      exact(dim);
      const auto          add =
        [&](const int kind, const Point<dim> &x, const Tensor<1, dim> &u) {
          analytical_solution->vector_value(x, exact);
          rows.push_back(kind);
          double n2 = 0;
          for (unsigned int c = 0; c < dim; ++c)
            rows.push_back(x[c]);
          for (unsigned int c = 0; c < dim; ++c)
            rows.push_back(u[c]);
          for (unsigned int c = 0; c < dim; ++c)
            {
              rows.push_back(exact[c]);
              if (component_max[c] > 0)
                n2 += std::pow((u[c] - exact[c]) / component_max[c], 2);
            }
          rows.push_back(std::sqrt(n2));
        };
      for (unsigned int i = 0; i < ctx.nodes.n_owned(); ++i)
        {
          Tensor<1, dim> u;
          for (unsigned int c = 0; c < dim; ++c)
            u[c] = displacement[ctx.nodes[i].dofs[c]];
          add(0, ctx.nodes[i].location, u);
        }
      for (const auto &node : system->extra_nodes())
        add(1, node.location, node.displacement);
      const auto all = Utilities::MPI::gather(ctx.communicator, rows, 0);
      // Written by process 0 under a temporary name; the verdict is shared
      // so that a failure there does not leave the others waiting.
      std::string error;
      if (Utilities::MPI::this_mpi_process(ctx.communicator) == 0)
        error = write_then_rename(node_data_file, [&](std::ostream &out) {
          const char *const names[] = {"x", "y", "z"};
          out << "kind";
          for (unsigned int c = 0; c < dim; ++c)
            out << ',' << names[c];
          for (unsigned int c = 0; c < dim; ++c)
            out << ",u_" << names[c];
          for (unsigned int c = 0; c < dim; ++c)
            out << ",exact_" << names[c];
          out << ",normalized_error\n" << std::setprecision(12);
          const unsigned int width = 3 * dim + 2;
          for (const auto &part : all)
            for (std::size_t r = 0; r < part.size(); r += width)
              {
                out << (part[r] == 0 ? "body" : "surface");
                for (unsigned int k = 1; k < width; ++k)
                  out << ',' << part[r + k];
                out << '\n';
              }
        });
      throw_on_any_rank(error.empty() ?
                          error :
                          "Invalid value '" + node_data_file +
                            "' for the parameter 'Output/Node data file': " +
                            error + ".",
                        ctx.communicator);
    }


    template class QuasiStatic<2>;
    template class QuasiStatic<3>;
  } // namespace Problems
} // namespace PeriDEAL

PERIDEAL_REGISTER_PROBLEM_TYPE(
  PeriDEAL::Problems::QuasiStatic,
  "quasi-static",
  "The linear quasi-static PD problem K u = V b with volumetric Dirichlet "
  "layers, body forces and tractions; assembled or matrix-free.")
