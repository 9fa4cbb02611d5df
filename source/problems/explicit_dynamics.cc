#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/explicit_dynamics.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      std::string
      to_string(const double x)
      {
        std::ostringstream s;
        s << std::setprecision(6) << x;
        return s.str();
      }
    } // namespace


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
                        "(by about 1.5x); the printed power-method estimate "
                        "of the actual limit of velocity Verlet can be a few "
                        "per cent too large.");
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
      prm.declare_entry(
        "Pre-cracks",
        "",
        Patterns::Anything(),
        "Bonds that cross these start broken. 2D: segments 'x1, y1, x2, y2', "
        "3D: planar polygons 'x1, y1, z1, x2, y2, z2, x3, y3, z3, ...'; "
        "several separated by ';'. Empty: none.");
      prm.declare_entry(
        "No-fail boxes",
        "",
        Patterns::Anything(),
        "Bonds with an end node in one of these boxes never break. 'xmin, "
        "ymin[, zmin], xmax, ymax[, zmax]', several separated by ';'.");
      prm.declare_entry(
        "No-fail boundary ids",
        "",
        Patterns::List(Patterns::Integer(0, 254)),
        "Bonds with an end node closer than 'No-fail layer thickness' to a "
        "boundary face with one of these ids never break: keeps loaded or "
        "gripped edges from shattering.");
      prm.declare_entry("No-fail layer thickness",
                        "1",
                        Patterns::Double(0),
                        "Thickness of the no-fail layers along 'No-fail "
                        "boundary ids', in horizons.");
      IO::CrackTipTracker<dim>::declare_parameters(prm);
      prm.declare_entry("Probe points",
                        "",
                        Patterns::Anything(),
                        "Points 'x, y[, z]' separated by ';': the "
                        "displacement of the node nearest to each is added "
                        "to every row of the energy file (columns "
                        "probe<k>_u<c>).");
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
      pre_crack_text = prm.get("Pre-cracks");
      pre_cracks.parse(pre_crack_text, "explicit dynamics/Pre-cracks");
      no_fail_text = prm.get("No-fail boxes");
      no_fail_boxes =
        Discretization::parse_boxes<dim>(no_fail_text,
                                         "explicit dynamics/No-fail boxes");
      no_fail_ids_text       = prm.get("No-fail boundary ids");
      no_fail_ids            = Boundary::parse_boundary_ids(no_fail_ids_text);
      no_fail_thickness_text = prm.get("No-fail layer thickness");
      no_fail_thickness      = prm.get_double("No-fail layer thickness");
      AssertThrow(no_fail_ids.empty() || no_fail_thickness > 0,
                  ExcInvalidInput("explicit dynamics/No-fail layer thickness",
                                  no_fail_thickness_text,
                                  "give a thickness > 0 (in horizons), for "
                                  "instance 1"));
      crack_tip.parse_parameters(prm, "explicit dynamics");
      probe_text = prm.get("Probe points");
      probe_points =
        Discretization::parse_points<dim>(probe_text,
                                          "explicit dynamics/Probe points");
      parse_checkpoint_parameters(prm);
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::check_input(const Simulator<dim> &simulator) const
    {
      AssertThrow(simulator.get_boundary_treatment_name() == "none",
                  ExcInvalidInput("Boundary treatment/Treatment",
                                  simulator.get_boundary_treatment_name(),
                                  "explicit dynamics supports the 'none' "
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
      if (no_fail_ids.empty())
        unused.push_back({section + "No-fail layer thickness",
                          "it is the thickness of the layers along 'No-fail "
                          "boundary ids', and none are given; give them, or "
                          "remove the entry"});
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
    void
    ExplicitDynamics<dim>::run(Simulator<dim> &simulator)
    {
      setup(simulator);
      choose_time_step(simulator);
      energy_monitor.reset();
      if (resume)
        {
          read_checkpoint(simulator);
          for (const auto &row : energy_rows)
            energy_monitor.observe(row[2], row[3], row[4]);
        }
      else
        {
          check_checkpoint_overwrite(simulator);
          initialize(simulator);
          record_energies(simulator);
          write_output(simulator);
        }
      TimerOutput::Scope scope(simulator.get_timer(), "time steps");
      loop_start          = simulator.elapsed();
      loop_start_step     = step_number;
      last_progress       = loop_start;
      last_checkpoint     = loop_start;
      const MPI_Comm comm = simulator.get_communicator();
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
      auto &summary = simulator.get_summary();
      summary.n_bonds =
        Utilities::MPI::sum(simulator.get_neighbor_lists().n_owned_bonds(),
                            simulator.get_communicator());
    }


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
      // and layers (each of which must hold a node).
      const double        s0 = model.critical_stretch(horizon);
      std::vector<double> critical(nodes.size(), s0);
      const auto          in_no_fail_box =
        Discretization::nodes_in_boxes(nodes,
                                       no_fail_boxes,
                                       "explicit dynamics/No-fail boxes",
                                       no_fail_text,
                                       "keeps no bond from failing");
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (in_no_fail_box[i])
          critical[i] = std::numeric_limits<double>::infinity();
      if (!no_fail_ids.empty())
        {
          Boundary::check_boundary_ids(
            simulator.get_dof_handler().get_triangulation(),
            no_fail_ids,
            "explicit dynamics/No-fail boundary ids",
            no_fail_ids_text);
          std::vector<unsigned int> n_in_layer;
          const auto                layer =
            Boundary::BoundaryLayers<dim>(
              simulator.get_dof_handler().get_triangulation(),
              no_fail_ids)
              .layer_of_nodes(nodes, no_fail_thickness * horizon, &n_in_layer);
          for (unsigned int i = 0; i < nodes.size(); ++i)
            if (layer[i] != numbers::invalid_unsigned_int)
              critical[i] = std::numeric_limits<double>::infinity();
          for (unsigned int k = 0; k < no_fail_ids.size(); ++k)
            AssertThrow(
              n_in_layer[k] > 0,
              ExcInvalidInput("explicit dynamics/No-fail layer thickness",
                              no_fail_thickness_text,
                              "the no-fail layer of boundary id " +
                                std::to_string(no_fail_ids[k]) +
                                " holds no node centre; use a layer of at "
                                "least half a cell"));
        }
      bond_operator.set_kinematics(finite_kinematics, critical);

      double h = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        h = std::max(h, std::pow(nodes[i].volume(), 1. / dim));
      h = Utilities::MPI::max(h, comm);
      std::vector<std::size_t> cut_per_crack;
      const std::size_t        n_cut =
        pre_cracks.break_bonds(nodes,
                               lists,
                               bond_state,
                               horizon + 2 * std::sqrt(dim) * h,
                               &cut_per_crack);
      AssertThrow(pre_cracks.empty() || n_cut > 0,
                  ExcInvalidInput("explicit dynamics/Pre-cracks",
                                  pre_crack_text,
                                  "no bond crosses the pre-cracks: they lie "
                                  "outside the body"));
      for (std::size_t k = 0; k < cut_per_crack.size(); ++k)
        AssertThrow(cut_per_crack[k] > 0,
                    ExcInvalidInput("explicit dynamics/Pre-cracks",
                                    pre_crack_text,
                                    "pre-crack " + std::to_string(k + 1) +
                                      " crosses no bond (that another "
                                      "pre-crack does not cross already): it "
                                      "lies outside the body; move it onto "
                                      "the body, or remove it"));
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
      const double rho    = simulator.get_model().density();
      const double lambda = bond_operator.gershgorin_eigenvalue_bound(rho);
      const double power  = bond_operator.estimate_largest_eigenvalue(rho, 60);
      dt_bound            = 2 / std::sqrt(lambda);
      dt_estimate         = 2 / std::sqrt(power);
      check_stability_bound(simulator, bond_operator, lambda);
      if (given_time_step > 0)
        AssertThrow(
          given_time_step <= dt_bound || allow_unstable,
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
        << to_string(dt_bound)
        << " s, power-method estimate of the actual limit (may be a few per cent "
           "too large) "
        << to_string(dt_estimate) << " s" << std::endl;
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
      broken_bonds += bond_operator.commit_broken_bonds(bond_state);
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
      const unsigned int n        = u.locally_owned_size();
      const double       old_load = load_factor;
      double             work     = 0;
      double            *pu = u.begin(), *pv = v.begin(), *pa = a.begin();
      const double      *free = free_dof.data(), *pl = load.begin();
      // Half step of the velocity, full step of the displacement (of the
      // free DoFs).
      for (unsigned int k = 0; k < n; ++k)
        {
          const double half = pv[k] + 0.5 * dt * pa[k];
          const double next = pu[k] + dt * half;
          pv[k]             = free[k] != 0 ? half : pv[k];
          pu[k]             = free[k] != 0 ? next : pu[k];
        }
      if (with_load)
        for (unsigned int k = 0; k < n; ++k)
          work += 0.5 * old_load * pl[k] * dt * pv[k] * free[k];
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
      u.update_ghost_values();
      // The energy of this step comes with its forces when run() will
      // record it (the same test as there).
      compute_acceleration(simulator, records_energies());
      if (with_load)
        {
          // The load at the new time (update_load() may have rewritten it).
          const double *new_load = load.begin();
          for (unsigned int k = 0; k < n; ++k)
            work += 0.5 * load_factor * new_load[k] * dt * pv[k] * free[k];
        }
      for (unsigned int k = 0; k < n; ++k)
        {
          const double next = pv[k] + 0.5 * dt * pa[k];
          pv[k]             = free[k] != 0 ? next : pv[k];
        }
      for (unsigned int q = 0; q < prescribed.size(); ++q)
        {
          const unsigned int k = prescribed[q].index;
          const double       reaction =
            mass.local_element(k) * (v.local_element(k) - old_v[q]) / dt -
            0.5 * (old_f[q] + force.local_element(k));
          work += reaction * (u.local_element(k) - old_u[q]);
        }
      external_work += Utilities::MPI::sum(work, simulator.get_communicator());
      check_finite(simulator);
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


    template <int dim>
    void
    ExplicitDynamics<dim>::record_energies(Simulator<dim> &simulator)
    {
      TimerOutput::Scope scope(simulator.get_timer(), "energies");
      const MPI_Comm     comm    = simulator.get_communicator();
      double             kinetic = 0;
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
      energy_monitor.check(kinetic,
                           elastic,
                           external_work,
                           verlet_term,
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
            rank{"mpi_rank", {}};
          const double this_rank = Utilities::MPI::this_mpi_process(comm);
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            {
              damage.values.push_back(bond_state.damage(i));
              broken.values.push_back(bond_state.n_broken(i));
              rank.values.push_back(this_rank);
            }
          const std::string record = output.write(simulator.get_dof_handler(),
                                                  nodes,
                                                  ghosted_u,
                                                  {damage, broken, rank},
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
    ExplicitDynamics<dim>::check_finite(Simulator<dim> &simulator)
    {
      const auto &nodes = simulator.get_nodes();
      finite_check.check_state(
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
