/**
 * @file
 * The entries of the explicit dynamics problem type (ExplicitDynamics):
 * their declaration and parsing, the checks of the input against the
 * simulator, the entries without effect on a run, the output names and
 * the memory estimate per node.
 */

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/explicit_dynamics.h>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    ExplicitDynamics<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("End time",
                        "1",
                        Patterns::Double(0),
                        "Simulated time (s), > 0.");
      prm.declare_entry(
        "Time step",
        "0",
        Patterns::Double(0),
        "Time step (s). 0: 'Safety factor' times the stability bound "
        "2/sqrt(lambda_G) (Gershgorin's bound of the largest eigenvalue of "
        "M^{-1} K; Silling & Askari 2005 for bond-based models). The step is "
        "shortened so that a whole number of steps reaches 'End time'.");
      prm.declare_entry("Safety factor",
                        "0.9",
                        Patterns::Double(0, 1),
                        "Fraction of the stability bound used when 'Time "
                        "step = 0'; in (0, 1].");
      prm.declare_entry("Allow unstable time step",
                        "false",
                        Patterns::Bool(),
                        "Accept a 'Time step' above the stability bound (it "
                        "is an error otherwise). The bound is conservative "
                        "(by about 1.5x). With 'true', or a 'Time step' "
                        "above the bound, the run also prints the "
                        "power-method estimate of the actual limit of "
                        "velocity Verlet (60 force passes; it can be a few "
                        "per cent too large).");
      prm.declare_entry("Kinematics",
                        "finite deformation",
                        Patterns::Selection("finite deformation|small strain"),
                        "finite deformation: bond forces along the deformed "
                        "bond, extension |y_j - y_i| - |x_j - x_i| (fracture "
                        "runs); small strain: the linearised kernel of the "
                        "quasi-static problem.");
      prm.declare_entry("Prescribed quantity",
                        "displacement",
                        Patterns::Selection("displacement|velocity"),
                        "What 'Boundary conditions/Dirichlet displacement' "
                        "prescribes on the nodes of the Dirichlet layers, as "
                        "a function of x and t: the displacement, or the "
                        "velocity (the displacement then follows by the "
                        "midpoint rule).");
      prm.declare_entry("Load history",
                        "1",
                        Patterns::Anything(),
                        "g(t): an extra factor on the body force and "
                        "traction of 'Boundary conditions', a function of t "
                        "alone (muparser syntax), e.g. '1' (none), 't < "
                        "1e-6 ? t / 1e-6 : 1' for a ramp. The functions of "
                        "'Boundary conditions' are themselves evaluated at "
                        "each step's time, so a load may as well use t "
                        "there (variables 'x,y,t').");
      prm.enter_subsection("Initial displacement");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();
      prm.enter_subsection("Initial velocity");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();
      BondFailure<dim>::declare_parameters(prm);
      IO::CrackTipTracker<dim>::declare_parameters(prm);
      prm.declare_entry("Probe points",
                        "",
                        Patterns::Anything(),
                        "Points 'x, y[, z]' separated by ';': the "
                        "displacement of the node nearest to each is added "
                        "to every row of the energy file (columns "
                        "probe<k>_u<c>).");
      prm.declare_entry("Energy every steps",
                        "10",
                        Patterns::Integer(1),
                        "Record kinetic and elastic energy, external work "
                        "and broken bonds every this many steps (a row of "
                        "the energy file; the progress line).");
      prm.declare_entry("Energy file",
                        "energies.csv",
                        Patterns::FileName(),
                        "CSV of time, kinetic energy, elastic energy, "
                        "external work, energy balance and broken bonds, in "
                        "'Output/Directory'. Empty: not written.");
      prm.declare_entry("Checkpoint every steps",
                        "0",
                        Patterns::Integer(0),
                        "Write a checkpoint (<Output/Directory>/checkpoint) "
                        "every this many steps. 0: not by steps.");
      prm.declare_entry("Checkpoint interval",
                        "0",
                        Patterns::Double(0),
                        "Write a checkpoint at most every this many minutes "
                        "of wall time (checked at energy rows). 0: not by "
                        "time.");
      prm.declare_entry("Steps per run",
                        "0",
                        Patterns::Integer(0),
                        "Stop after this many steps with a checkpoint, to "
                        "run a long simulation in chunks (resume with "
                        "'Resume from checkpoint = true'). 0: run to 'End "
                        "time'.");
      prm.declare_entry("Resume from checkpoint",
                        "false",
                        Patterns::Bool(),
                        "Continue from <Output/Directory>/checkpoint, "
                        "written by a run of the same input (on any number "
                        "of processes: bitwise the same result on the same "
                        "number, to round-off on another). The checkpoint "
                        "records the entries that define its state (model "
                        "and constants, horizon, mesh, partial volumes, "
                        "failure, probes and crack tip) and a checksum: a "
                        "change or a corrupt file is refused.");
      prm.declare_entry(
        "Overwrite checkpoint",
        "false",
        Patterns::Bool(),
        "Let a run without 'Resume from checkpoint' replace a checkpoint in "
        "'Output/Directory' that is further in time than the first one it "
        "writes (refused otherwise, to keep a long run from being lost by "
        "a forgotten 'Resume').");
      prm.declare_entry("Progress interval",
                        "5",
                        Patterns::Double(0),
                        "Print a progress line on rank 0 at most every this "
                        "many seconds of wall time (at energy rows).");
      TimeLoop::declare_parameters(prm);
      EnergyBalanceMonitor::declare_parameters(prm);
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::parse_parameters(ParameterHandler &prm)
    {
      end_time        = prm.get_double("End time");
      given_time_step = prm.get_double("Time step");
      safety_factor   = prm.get_double("Safety factor");
      AssertThrow(end_time > 0,
                  ExcInvalidInput("explicit dynamics/End time",
                                  prm.get("End time"),
                                  "give a simulated time > 0"));
      AssertThrow(safety_factor > 0,
                  ExcInvalidInput("explicit dynamics/Safety factor",
                                  prm.get("Safety factor"),
                                  "give a fraction in (0, 1]"));
      allow_unstable         = prm.get_bool("Allow unstable time step");
      finite_kinematics      = prm.get("Kinematics") == "finite deformation";
      prescribe_velocity     = prm.get("Prescribed quantity") == "velocity";
      output_every_steps     = prm.get_integer("Output every steps");
      output_interval        = prm.get_double("Output interval");
      energy_every_steps     = prm.get_integer("Energy every steps");
      energy_file            = prm.get("Energy file");
      progress_interval_s    = prm.get_double("Progress interval");
      checkpoint_every_steps = prm.get_integer("Checkpoint every steps");
      checkpoint_minutes     = prm.get_double("Checkpoint interval");
      steps_per_run          = prm.get_integer("Steps per run");
      resume                 = prm.get_bool("Resume from checkpoint");
      time_loop.parse_parameters(prm, "explicit dynamics", " s");
      energy_monitor.parse_parameters(prm, "explicit dynamics");
      load_history_entry = {"explicit dynamics/Load history",
                            prm.get("Load history")};
      load_history       = std::make_unique<FunctionParser<1>>(1);
      try
        {
          // FunctionParser<1> needs a space variable; one no user writes,
          // so that 'x' (or any other name but t) is an unknown variable
          // instead of a silent 0.
          load_history->initialize("perideal_unused_coordinate,t",
                                   prm.get("Load history"),
                                   std::map<std::string, double>(),
                                   true);
          // muparser parses at the first evaluation.
          load_history->value(Point<1>());
        }
      catch (...)
        {
          AssertThrow(false,
                      ExcInvalidInput("explicit dynamics/Load history",
                                      prm.get("Load history"),
                                      "give a function of t alone in "
                                      "muparser syntax (t is its only "
                                      "variable; a load that varies in space "
                                      "belongs in 'Boundary conditions')"));
        }
      initial_displacement = parse_function<dim>(prm,
                                                 "Initial displacement",
                                                 "explicit dynamics",
                                                 dim,
                                                 &initial_displacement_entry);
      initial_velocity     = parse_function<dim>(prm,
                                             "Initial velocity",
                                             "explicit dynamics",
                                             dim,
                                             &initial_velocity_entry);
      // The prescribed displacement or velocity is parsed by the boundary
      // conditions; its expression, for messages about its values, lives
      // outside this subsection (which PluginRegistry::create() entered
      // from the top level).
      prm.leave_subsection();
      prm.enter_subsection("Boundary conditions");
      prm.enter_subsection("Dirichlet displacement");
      dirichlet_entry = {"Boundary conditions/Dirichlet displacement/Function "
                         "expression",
                         prm.get("Function expression")};
      prm.leave_subsection();
      prm.leave_subsection();
      prm.enter_subsection("explicit dynamics");
      failure.parse_parameters(prm, "explicit dynamics");
      crack_tip.parse_parameters(prm, "explicit dynamics");
      probe_text = prm.get("Probe points");
      probe_points =
        Discretization::parse_points<dim>(probe_text,
                                          "explicit dynamics/Probe points");
      parse_checkpoint_parameters(prm);
    }


    template <int dim>
    std::vector<UnusedEntry>
    ExplicitDynamics<dim>::unused_entries(const Simulator<dim> &simulator) const
    {
      const std::string        section = "explicit dynamics/";
      const auto              &bc      = simulator.get_boundary_conditions();
      std::vector<UnusedEntry> unused  = bc.unused_entries();
      unused.push_back({"Analytical solution/",
                        "explicit dynamics compares with no analytical "
                        "solution (it records energies, 'Probe points' and "
                        "the crack tip); remove the subsection 'Analytical "
                        "solution'"});
      if (given_time_step > 0)
        unused.push_back({section + "Safety factor",
                          "'Time step' is given, so no fraction of the "
                          "stability bound is taken; set 'Time step = 0' "
                          "to use it, or remove the entry"});
      else
        unused.push_back({section + "Allow unstable time step",
                          "with 'Time step = 0' the step is 'Safety factor' "
                          "(at most 1) times the stability bound, never "
                          "above it; remove the entry"});
      for (auto &entry : failure.unused_entries())
        unused.push_back(entry);
      if (!crack_tip.enabled())
        for (const char *entry : {"Crack tip region", "Crack tip damage"})
          unused.push_back({section + entry,
                            "no 'Crack tip origin' is given, so no crack tip "
                            "is tracked; give the origin too, or remove the "
                            "entry"});
      if (!bc.has_load())
        unused.push_back({section + "Load history",
                          "'Boundary conditions' gives no body force and no "
                          "'Traction boundary ids', so there is no load to "
                          "scale; give the load, or remove the entry"});
      if (!bc.has_dirichlet())
        unused.push_back({section + "Prescribed quantity",
                          "neither 'Boundary conditions/Dirichlet boundary "
                          "ids' nor 'Dirichlet boxes' is given, so nothing "
                          "is prescribed; give them, or remove the entry"});
      return unused;
    }


    template <int dim>
    std::vector<IO::OutputName>
    ExplicitDynamics<dim>::output_names(const Simulator<dim> &simulator) const
    {
      const auto &output = simulator.get_output();
      auto        names  = output.output_names(true);
      for (const std::string suffix : {"", ".new", ".old"})
        names.push_back(
          {"Output/Directory",
           output.directory(),
           output.directory() + "/checkpoint" + suffix,
           IO::OutputName::Kind::directory,
           "the checkpoint directory 'checkpoint" + suffix + "'"});
      if (!energy_file.empty())
        names.push_back({"explicit dynamics/Energy file",
                         energy_file,
                         output.directory() + "/" + energy_file,
                         IO::OutputName::Kind::file,
                         "the energy file"});
      return names;
    }


    template <int dim>
    double
    ExplicitDynamics<dim>::estimated_bytes_per_node(const double coupled) const
    {
      return (dim == 3 ? 2048 : 1024) + 8 * coupled;
    }


    template void
    ExplicitDynamics<2>::declare_parameters(ParameterHandler &);
    template void
    ExplicitDynamics<3>::declare_parameters(ParameterHandler &);
    template void
    ExplicitDynamics<2>::parse_parameters(ParameterHandler &);
    template void
    ExplicitDynamics<3>::parse_parameters(ParameterHandler &);
    template std::vector<UnusedEntry>
    ExplicitDynamics<2>::unused_entries(const Simulator<2> &) const;
    template std::vector<UnusedEntry>
    ExplicitDynamics<3>::unused_entries(const Simulator<3> &) const;
    template std::vector<IO::OutputName>
    ExplicitDynamics<2>::output_names(const Simulator<2> &) const;
    template std::vector<IO::OutputName>
    ExplicitDynamics<3>::output_names(const Simulator<3> &) const;
    template double
    ExplicitDynamics<2>::estimated_bytes_per_node(const double) const;
    template double
    ExplicitDynamics<3>::estimated_bytes_per_node(const double) const;
  } // namespace Problems
} // namespace PeriDEAL
