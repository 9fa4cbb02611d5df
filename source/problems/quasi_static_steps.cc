// The load-stepped quasi-static run: load steps with bond breaking, the
// step control, unstable growth and complete failure, the load-displacement
// CSV, the damage series and the progress line.

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/node_region.h>
#include <perideal/problems/quasi_static.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      std::string
      vector_text(const double *values, const unsigned int n)
      {
        std::ostringstream out;
        out << std::setprecision(4) << "(";
        for (unsigned int c = 0; c < n; ++c)
          out << (c > 0 ? ", " : "") << values[c];
        out << ")";
        return out.str();
      }
    } // namespace


    template <int dim>
    void
    QuasiStatic<dim>::run_load_steps(Simulator<dim> &simulator)
    {
      auto          &pcout    = simulator.get_pcout();
      const bool     breaking = bond_breaking != BondBreaking::off;
      const MPI_Comm comm     = simulator.get_communicator();

      Boundary::SystemContext<dim> context  = simulator.system_context();
      const std::vector<bool>      standard = hybrid_standard_region(simulator);
      context.hybrid_standard               = &standard;
      system = simulator.get_boundary_treatment().template make_system<dim>(
        simulator.get_boundary_treatment_name());
      system->setup(context);
      if (use_dynamic_relaxation)
        {
          AssertThrow(
            system->supports_dynamic_relaxation(),
            ExcInvalidInput("quasi-static/Nonlinear solver",
                            "dynamic relaxation",
                            "the boundary treatment '" +
                              simulator.get_boundary_treatment_name() +
                              "' does not offer it yet; use 'Newton'"));
          system->set_dynamic_relaxation(&dynamic_relaxation);
        }
      if (finite_deformation)
        system->set_finite_deformation(newton);
      if (breaking)
        {
          // The horizon is known from here on.
          const auto  &model = simulator.get_model();
          const double s0    = model.critical_stretch(simulator.get_horizon());
          AssertThrow(
            std::isfinite(s0),
            ExcInvalidInput("quasi-static/Bond breaking",
                            bond_breaking_name,
                            "the material model has no critical "
                            "stretch, so no bond can break; give '" +
                              model.input_path() + "Critical stretch' or '" +
                              model.input_path() +
                              "Fracture energy', or set 'Bond breaking "
                              "= off'"));
        }
      std::size_t broken = 0;
      if (breaking)
        broken = system->setup_failure(
          context,
          failure.critical_stretches(simulator),
          [&](const Discretization::NeighborList<dim> &lists,
              Discretization::BondState<dim>          &state) {
            return failure.cut_pre_cracks(simulator, lists, state);
          });
      const double largest_step = end_time / n_load_steps;
      {
        std::ostringstream line;
        line << "quasi-static load steps: t from 0 to "
             << format_number(end_time) << ", steps of at most "
             << format_number(largest_step) << " (at least "
             << format_number(minimum_step) << "), bond breaking '"
             << bond_breaking_name << "', "
             << (finite_deformation ? "finite deformation (modified Newton "
                                      "to a relative residual of " +
                                        format_number(newton.tolerance) + ")" :
                                      std::string("small strain"));
        if (breaking)
          line << ", critical stretch "
               << format_number(simulator.get_model().critical_stretch(
                    simulator.get_horizon()))
               << " (steps cut while a bond is past (1 + "
               << format_number(stretch_tolerance) << ") of it), " << broken
               << " bonds cut by pre-cracks";
        simulator.print_progress(line.str());
      }

      const auto       &output            = simulator.get_output();
      double            t                 = 0;
      double            dt                = largest_step;
      unsigned int      step              = 0;
      double            peak              = 0;
      bool              unstable_reported = false;
      bool              complete          = false;
      std::size_t       broken_by_load    = 0;
      std::vector<bool> flagged;
      rows.clear();
      records.clear();
      // Close to the end within round-off of the step arithmetic.
      const double t_tolerance = 1e-12 * end_time;
      while (t < end_time - t_tolerance && !complete)
        {
          const double t_try =
            t + dt >= end_time - t_tolerance ? end_time : t + dt;
          const double step_size = t_try - t;
          const bool   can_cut   = step_size > minimum_step * (1 + 1e-12);
          const auto   cut_step  = [&]() {
            dt = std::max(step_size / 2, minimum_step);
          };
          simulator.set_time(t_try);

          // The equilibrium with the bonds intact so far; a solve that
          // fails cuts the step.
          const auto solve = [&]() -> std::string {
            try
              {
                system->solve_step(context, displacement);
              }
            catch (const ExcNoConvergence &e)
              {
                std::ostringstream message;
                e.print_info(message);
                return message.str();
              }
            return "";
          };
          std::string error = solve();
          if (!error.empty())
            {
              AssertThrow(can_cut,
                          ExcInvalidInput(
                            "quasi-static/Minimum load step",
                            format_number(minimum_step),
                            "load step " + std::to_string(step + 1) +
                              " to t = " + format_number(t_try) +
                              " did not converge and cannot be cut "
                              "further; lower 'Minimum load step' (0: the "
                              "first step / 1024) or loosen the solver. The "
                              "solver said:\n" +
                              error));
              cut_step();
              continue;
            }
          unsigned int   iterations  = context.summary.solver.iterations;
          unsigned int   corrections = context.summary.solver.corrections;
          unsigned int   solves      = 1;
          std::size_t    new_bonds   = 0;
          std::size_t    over        = 0;
          Tensor<1, dim> reaction;
          // Found once, on the first converged step, by every process at
          // once (a process may own no node).
          if (!reaction_nodes_found && has_reaction())
            {
              flagged              = reaction_nodes(simulator);
              reaction_nodes_found = true;
            }
          if (has_reaction())
            reaction = system->holding_force(context, flagged);
          const Tensor<1, dim> load_before = reaction;

          if (breaking)
            {
              // Accuracy of the load at which bonds start to break: cut
              // the step while a bond is past its critical stretch by more
              // than the tolerance, or more bonds are over it than allowed.
              over                 = system->count_critical_bonds(1.);
              const bool overshoot = over > 0 && system->count_critical_bonds(
                                                   1 + stretch_tolerance) > 0;
              const bool too_many =
                max_bonds_per_step > 0 && over > max_bonds_per_step;
              if ((overshoot || too_many) && can_cut)
                {
                  cut_step();
                  continue;
                }
              // At the minimum step the load at which bonds break cannot
              // be resolved as asked: stop rather than go on with it
              // (over is a sum over all processes: all of them stop).
              AssertThrow(
                !overshoot && !too_many,
                ExcInvalidInput(
                  "quasi-static/Minimum load step",
                  format_number(minimum_step),
                  "load step " + std::to_string(step + 1) +
                    " to t = " + format_number(t_try) +
                    " cannot be cut further, and " + std::to_string(over) +
                    " bonds are past their critical stretch at its first "
                    "equilibrium (" +
                    (overshoot ?
                       "some by more than 'Critical stretch tolerance' = " +
                         format_number(stretch_tolerance) :
                       "more than 'Maximum bonds per step' = " +
                         std::to_string(max_bonds_per_step)) +
                    "). Lower 'Minimum load step' (0: the first step / "
                    "1024), or relax the tolerance"));
              // Sweeps at this load until no bond breaks.
              while (true)
                {
                  const std::size_t n = break_bonds();
                  if (n == 0)
                    break;
                  new_bonds += n;
                  error = solve();
                  ++solves;
                  AssertThrow(error.empty(),
                              ExcMessage(
                                "Load step " + std::to_string(step + 1) +
                                " at t = " + format_number(t_try) + ": after " +
                                std::to_string(new_bonds) +
                                " bonds broke at this load the solve did not "
                                "converge (a part of the body may have come "
                                "loose, or the crack has cut the last load "
                                "path). The solver said:\n" +
                                error));
                  iterations += context.summary.solver.iterations;
                  corrections += context.summary.solver.corrections;
                  if (has_reaction())
                    {
                      reaction = system->holding_force(context, flagged);
                      if (failure_fraction > 0 && peak > 0 &&
                          reaction.norm() < failure_fraction * peak)
                        {
                          complete = true;
                          break;
                        }
                    }
                }
              broken += new_bonds;
              broken_by_load += new_bonds;
              // Bonds that were not over their critical stretch at the
              // step's first equilibrium broke at this fixed load: the
              // crack grew without more load.
              if (new_bonds > over && !unstable_reported)
                {
                  unstable_reported = true;
                  pcout << "           unstable crack growth at t = "
                        << format_number(t_try) << " (step " << step + 1
                        << "): " << new_bonds - over
                        << " bonds broke at a fixed load after the " << over
                        << " over their critical stretch";
                  if (has_reaction())
                    pcout << "; critical load: reaction "
                          << vector_text(&load_before[0], dim)
                          << " (its magnitude "
                          << format_number(load_before.norm()) << ")";
                  pcout << std::endl;
                }
            }
          peak = std::max(peak, load_before.norm());
          t    = t_try;
          ++step;

          std::vector<double> row = {double(step), t};
          for (unsigned int c = 0; c < dim; ++c)
            row.push_back(reaction[c]);
          row.push_back(double(broken));
          row.push_back(iterations);
          rows.push_back(row);

          const bool last = complete || t >= end_time - t_tolerance;
          if (new_bonds > 0 && !last)
            {
              write_step_record(simulator, t);
              write_load_displacement(simulator);
            }

          // Progress: step, time, solves, iterations, residual, bonds,
          // reaction, rate and time left.
          std::ostringstream line;
          line << "step " << step << ", t = " << format_number(t) << " (dt "
               << format_number(step_size) << "), " << solves << " solve(s), "
               << iterations << " iteration(s), ";
          if (finite_deformation && !use_dynamic_relaxation)
            line << corrections << " Newton correction(s), ";
          line << "equilibrium residual " << std::scientific
               << std::setprecision(1) << context.summary.equilibrium_residual
               << std::defaultfloat;
          if (breaking)
            line << ", bonds broken +" << new_bonds << " (" << broken
                 << " in all)";
          if (system->n_isolated_nodes() > 0)
            line << ", " << system->n_isolated_nodes()
                 << " node(s) without bonds held";
          if (system->n_held_dofs_without_stiffness() > 0)
            line << ", " << system->n_held_dofs_without_stiffness()
                 << " direction(s) without stiffness held";
          if (has_reaction())
            line << ", reaction " << vector_text(&reaction[0], dim);
          const double elapsed = simulator.elapsed();
          if (!last)
            line << ", about " << std::setprecision(2) << std::fixed
                 << elapsed / t * (end_time - t) << std::defaultfloat
                 << " s left at this rate";
          simulator.print_progress(line.str());

          if (new_bonds == 0 && solves == 1 && step_size >= dt * (1 - 1e-12))
            dt = std::min(2 * dt, largest_step);
        }

      if (breaking && broken_by_load == 0)
        {
          // No bond reached its critical stretch: say how close the load
          // came instead of writing a result that looks like a fracture
          // run.
          const double ratio = largest_stretch_ratio(1e-3);
          AssertThrow(
            false,
            ExcInvalidInput("quasi-static/End time",
                            format_number(end_time),
                            "'Bond breaking = " + bond_breaking_name +
                              "', but no bond reached its critical stretch up "
                              "to t = " +
                              format_number(t) + ": the largest stretch is " +
                              (ratio > 0 ? format_number(ratio) :
                                           std::string("below 1e-12")) +
                              " of the critical one. Raise 'End time' or the "
                              "load, or set 'Bond breaking = off'"));
        }
      if (complete)
        pcout << "           complete failure at t = " << format_number(t)
              << " (step " << step << "): the reaction fell below "
              << format_number(failure_fraction) << " of its peak "
              << format_number(peak) << std::endl;

      // The final state: errors, node data, the last record and the series.
      std::vector<IO::NodeField> extra;
      if (breaking)
        extra.push_back({"damage", system->damage(context)});
      const std::string record = postprocess(simulator, extra, records.size());
      if (!record.empty())
        {
          records.emplace_back(t, record);
          output.write_time_series(records, comm);
        }
      write_load_displacement(simulator);
    }


    template <int dim>
    std::size_t
    QuasiStatic<dim>::break_bonds()
    {
      if (bond_breaking == BondBreaking::all_beyond_critical)
        return system->break_critical_bonds(1.);
      // The most critical: those within 0.1 % of the largest ratio.
      if (system->count_critical_bonds(1.) == 0)
        return 0;
      double lower = 1, upper = 2;
      while (system->count_critical_bonds(upper) > 0)
        {
          lower = upper;
          upper *= 2;
        }
      while (upper > lower * (1 + 1e-3))
        {
          const double middle = std::sqrt(lower * upper);
          (system->count_critical_bonds(middle) > 0 ? lower : upper) = middle;
        }
      return system->break_critical_bonds(lower);
    }


    template <int dim>
    double
    QuasiStatic<dim>::largest_stretch_ratio(const double precision)
    {
      double lower = 1, upper = 1;
      if (system->count_critical_bonds(1.) > 0)
        {
          upper = 2;
          while (system->count_critical_bonds(upper) > 0)
            {
              lower = upper;
              upper *= 2;
            }
        }
      else
        {
          lower = 0.5;
          while (system->count_critical_bonds(lower) == 0)
            {
              upper = lower;
              lower /= 2;
              if (lower < std::ldexp(1., -40))
                return 0;
            }
        }
      while (upper > lower * (1 + precision))
        {
          const double middle = std::sqrt(lower * upper);
          (system->count_critical_bonds(middle) > 0 ? lower : upper) = middle;
        }
      return lower;
    }


    template <int dim>
    std::vector<bool>
    QuasiStatic<dim>::reaction_nodes(const Simulator<dim> &simulator) const
    {
      const auto &nodes = simulator.get_nodes();
      const auto &bc    = simulator.get_boundary_conditions();
      const auto  layer =
        Boundary::BoundaryLayers<dim>(simulator.get_triangulation(),
                                      reaction_ids)
          .layer_of_nodes(nodes,
                          bc.dirichlet_layer_thickness() *
                            simulator.get_horizon());
      std::vector<bool> flagged(nodes.n_owned(), false);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        flagged[i] = layer[i] != numbers::invalid_unsigned_int &&
                     system->is_constrained(nodes[i]);
      // The boxes: each must hold a node and prescribed nodes, counted over
      // all processes, so that every process throws alike.
      Discretization::nodes_in_boxes(nodes,
                                     reaction_boxes,
                                     "quasi-static/Reaction boxes",
                                     reaction_boxes_text,
                                     "has no reaction");
      for (unsigned int k = 0; k < reaction_boxes.size(); ++k)
        {
          unsigned int n_held = 0;
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            if (reaction_boxes[k].point_inside(nodes[i].location) &&
                system->is_constrained(nodes[i]))
              {
                flagged[i] = true;
                ++n_held;
              }
          AssertThrow(Utilities::MPI::sum(n_held,
                                          simulator.get_communicator()) > 0,
                      ExcInvalidInput("quasi-static/Reaction boxes",
                                      reaction_boxes_text,
                                      "box " + std::to_string(k + 1) +
                                        " holds no prescribed node, so "
                                        "nothing holds it and it has no "
                                        "reaction; make each box cover nodes "
                                        "of 'Boundary conditions/Dirichlet "
                                        "boxes' or Dirichlet layers"));
        }
      return flagged;
    }


    template <int dim>
    void
    QuasiStatic<dim>::write_load_displacement(
      const Simulator<dim> &simulator) const
    {
      if (load_displacement_file.empty())
        return;
      const auto    &output = simulator.get_output();
      const MPI_Comm comm   = simulator.get_communicator();
      std::string    error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          const std::string path =
            output.directory() + "/" + load_displacement_file;
          std::error_code code;
          std::filesystem::create_directories(output.directory(), code);
          error = write_then_rename(path, [&](std::ostream &out) {
            out << "step,time";
            for (unsigned int c = 0; c < dim; ++c)
              out << ",reaction_"
                  << "xyz"[c];
            out << ",broken_bonds,iterations\n" << std::setprecision(12);
            for (const auto &row : rows)
              {
                for (unsigned int k = 0; k < row.size(); ++k)
                  out << (k > 0 ? "," : "") << row[k];
                out << '\n';
              }
          });
          if (!error.empty())
            error = "Invalid value '" + path +
                    "' for the parameter 'quasi-static/Load-displacement "
                    "file': " +
                    error + ".";
        }
      throw_on_any_rank(error, comm);
    }


    template <int dim>
    void
    QuasiStatic<dim>::write_step_record(Simulator<dim> &simulator,
                                        const double    time)
    {
      const auto &output = simulator.get_output();
      if (!output.enabled())
        return;
      const auto         context = simulator.system_context();
      TimerOutput::Scope scope(context.timer, "output");
      IO::NodeField      rank{"mpi_rank", {}};
      for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
        rank.values.push_back(
          Utilities::MPI::this_mpi_process(simulator.get_communicator()));
      const std::vector<IO::NodeField> fields = {{"damage",
                                                  system->damage(context)},
                                                 rank};
      const std::string record = output.write(context.dof_handler,
                                              context.nodes,
                                              displacement,
                                              fields,
                                              records.size());
      records.emplace_back(time, record);
      output.write_time_series(records, simulator.get_communicator());
    }


#define PERIDEAL_INSTANTIATE(dim)                                             \
  template void        QuasiStatic<dim>::run_load_steps(Simulator<dim> &);    \
  template std::size_t QuasiStatic<dim>::break_bonds();                       \
  template double      QuasiStatic<dim>::largest_stretch_ratio(const double); \
  template std::vector<bool> QuasiStatic<dim>::reaction_nodes(                \
    const Simulator<dim> &) const;                                            \
  template void QuasiStatic<dim>::write_load_displacement(                    \
    const Simulator<dim> &) const;                                            \
  template void QuasiStatic<dim>::write_step_record(Simulator<dim> &,         \
                                                    const double);
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
