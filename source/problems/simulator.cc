/**
 * @file
 * The Simulator's run(): the output checks, the shared set-up (mesh, nodes,
 * neighbour lists) and the problem type's loop, the timings and the summary;
 * and the getters through which problem types reach the shared set-up. The
 * parameters, the input checks and the mesh are in simulator_parameters.cc,
 * simulator_checks.cc and simulator_mesh.cc.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/fe/fe_dgq.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/tria.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/make_triangulation.h>
#include <perideal/problems/simulator.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    std::unique_ptr<parallel::TriangulationBase<dim>>
    make_triangulation(const MPI_Comm communicator)
    {
      if constexpr (dim == 1)
        return std::make_unique<parallel::shared::Triangulation<1>>(
          communicator,
          Triangulation<1>::none,
          false,
          parallel::shared::Triangulation<1>::partition_zorder);
      else
        return std::make_unique<parallel::distributed::Triangulation<dim>>(
          communicator);
    }

    template std::unique_ptr<parallel::TriangulationBase<1>>
    make_triangulation<1>(const MPI_Comm);
    template std::unique_ptr<parallel::TriangulationBase<2>>
    make_triangulation<2>(const MPI_Comm);
    template std::unique_ptr<parallel::TriangulationBase<3>>
    make_triangulation<3>(const MPI_Comm);


    template <int dim>
    Simulator<dim>::Simulator(const MPI_Comm communicator)
      : communicator(communicator)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
      , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
      , triangulation(make_triangulation<dim>(communicator))
      , fe(FE_DGQ<dim>(0), dim)
      , dof_handler(*triangulation)
    {}


    template <int dim>
    void
    Simulator<dim>::setup_nodes()
    {
      TimerOutput::Scope scope(timer, "nodes and ghost exchange");
      dof_handler.distribute_dofs(fe);
      double diameter = 0;
      for (const auto &cell : triangulation->active_cell_iterators())
        if (cell->is_locally_owned())
          diameter = std::max(diameter, cell->diameter());
      diameter = Utilities::MPI::max(diameter, communicator);
      // State-based forces of an owned node need the dilatations of its
      // neighbours, hence their neighbours: two horizons.
      const double coupling_range =
        couples_two_horizons() ? 2 * (horizon + diameter) : horizon + diameter;
      nodes.set_perturbation(node_perturbation, random_seed);
      nodes.reinit(dof_handler, coupling_range);
      summary.n_nodes = triangulation->n_global_active_cells();
    }


    template <int dim>
    void
    Simulator<dim>::setup_neighbor_lists(const bool store_full_lists)
    {
      {
        TimerOutput::Scope scope(timer, "neighbour search and weights");
        neighbor_lists.reinit(nodes,
                              horizon,
                              *algorithm,
                              couples_two_horizons(),
                              store_full_lists);
      }
      summary.n_bonds =
        Utilities::MPI::sum(neighbor_lists.n_owned_bonds(), communicator);
      AssertThrow(summary.n_bonds > 0,
                  ExcInvalidInput(horizon_entry().first,
                                  horizon_entry().second,
                                  "the horizon " + format_number(horizon) +
                                    " reaches no neighbour, so there is no "
                                    "bond; give an m-ratio above 0.5 (above 1 "
                                    "for full volumes), typically 3"));
      std::ostringstream line;
      line << "nodes: " << summary.n_nodes << " ("
           << Utilities::MPI::sum(nodes.n_ghost(), communicator)
           << " ghost copies), bonds: " << summary.n_bonds << " ("
           << std::setprecision(4) << double(summary.n_bonds) / summary.n_nodes
           << " per node)";
      if (node_perturbation > 0)
        line << ", nodes perturbed by up to " << node_perturbation
             << " h (seed " << random_seed << ")";
      line << ", weights by '" << algorithm_name << "'"
           << (neighbor_lists.used_uniform_grid_table() ?
                 " from the uniform-grid table" :
                 " per bond");
      print_progress(line.str());
    }


    template <int dim>
    double
    Simulator<dim>::elapsed() const
    {
      return wall_clock.wall_time();
    }


    template <int dim>
    void
    Simulator<dim>::print_progress(const std::string &text)
    {
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time() << " s] " << text << std::defaultfloat
            << std::endl;
    }


    template <int dim>
    IO::RunSummary
    Simulator<dim>::run()
    {
      wall_clock.restart();
      check_output_names();
      // Output paths are checked before any work, on every process that
      // writes, and the verdict is shared: a failure on one process must
      // not leave the others waiting.
      {
        std::string error;
        if (output.enabled())
          {
            const std::string why =
              check_writable_directory(output.directory());
            if (!why.empty())
              error = "Invalid value '" + output.directory() +
                      "' for the parameter 'Output/Directory': " + why +
                      "; give a directory that exists or can be created.";
          }
        if (error.empty() &&
            Utilities::MPI::this_mpi_process(communicator) == 0)
          for (const auto &[entry, file] :
               {std::make_pair(std::string("Output/Summary file"),
                               summary_file),
                std::make_pair(std::string("Output/Node data file"),
                               node_data_file)})
            if (!file.empty() && error.empty())
              {
                const std::string why = check_writable_file(file);
                if (!why.empty())
                  error = "Invalid value '" + file + "' for the parameter '" +
                          entry + "': " + why +
                          "; give a writable file in an existing directory.";
                else if (entry == "Output/Summary file")
                  {
                    const std::string columns =
                      IO::check_run_summary_columns(file);
                    if (!columns.empty())
                      error = "Invalid value '" + file +
                              "' for the parameter '" + entry + "': " + columns;
                  }
              }
        throw_on_any_rank(error, communicator);
      }
      // The linear solver only where the problem type solves with it.
      pcout << "PeriDEAL " << problem_name << " " << dim << "D: "
            << (problem->uses_material_model() ?
                  "model '" + model_name + "', " :
                  std::string())
            << "partial volumes '" << algorithm_name << "'"
            << (problem->uses_linear_solver() ?
                  ", solver '" + linear_solver.method_name() + "'" :
                  std::string())
            << std::endl;
      make_mesh();
      check_material_scale();
      setup_nodes();
      problem->run(*this);

      summary.seconds = timer.get_summary_data(TimerOutput::total_wall_time);
      summary.seconds["total"] = wall_clock.wall_time();
      Utilities::System::MemoryStats stats;
      Utilities::System::get_memory_stats(stats);
      summary.peak_memory_mb =
        Utilities::MPI::sum(stats.VmHWM / 1024., communicator);
      timer.print_wall_time_statistics(communicator);
      pcout << "total wall time " << std::setprecision(4)
            << summary.seconds["total"] << " s, peak memory (all processes) "
            << std::setprecision(4) << summary.peak_memory_mb << " MB"
            << std::endl;

      if (!summary_file.empty())
        IO::append_run_summary(summary_file, summary, communicator);
      return summary;
    }


    template <int dim>
    std::pair<std::string, std::string>
    Simulator<dim>::get_stiffness_entry() const
    {
      AssertThrow(model != nullptr, ExcInternalError());
      const auto entry = model->stiffness_entry();
      if (entry.first.empty())
        return {"Material model/Model", model_name};
      return {"Material model/" + model_name + "/" + entry.first, entry.second};
    }


    template <int dim>
    MPI_Comm
    Simulator<dim>::get_communicator() const
    {
      return communicator;
    }


    template <int dim>
    ConditionalOStream &
    Simulator<dim>::get_pcout()
    {
      return pcout;
    }


    template <int dim>
    TimerOutput &
    Simulator<dim>::get_timer()
    {
      return timer;
    }


    template <int dim>
    const parallel::TriangulationBase<dim> &
    Simulator<dim>::get_triangulation() const
    {
      return *triangulation;
    }


    template <int dim>
    const DoFHandler<dim> &
    Simulator<dim>::get_dof_handler() const
    {
      return dof_handler;
    }


    template <int dim>
    const Discretization::NodeSet<dim> &
    Simulator<dim>::get_nodes() const
    {
      return nodes;
    }


    template <int dim>
    const Discretization::NeighborList<dim> &
    Simulator<dim>::get_neighbor_lists() const
    {
      return neighbor_lists;
    }


    template <int dim>
    const Models::Model<dim> &
    Simulator<dim>::get_model() const
    {
      AssertThrow(model != nullptr,
                  ExcMessage("This run has no material model ('Material "
                             "model/Model = none')."));
      return *model;
    }


    template <int dim>
    const Quadrature::PartialVolume<dim> &
    Simulator<dim>::get_partial_volume() const
    {
      return *algorithm;
    }


    template <int dim>
    const std::string &
    Simulator<dim>::get_partial_volume_name() const
    {
      return algorithm_name;
    }


    template <int dim>
    const Quadrature::QuadratureScheme<dim> &
    Simulator<dim>::get_quadrature_scheme() const
    {
      return *quadrature_scheme;
    }


    template <int dim>
    const std::string &
    Simulator<dim>::get_quadrature_scheme_name() const
    {
      return quadrature_scheme_name;
    }


    template <int dim>
    double
    Simulator<dim>::get_horizon() const
    {
      return horizon;
    }


    template <int dim>
    const Boundary::BoundaryConditions<dim> &
    Simulator<dim>::get_boundary_conditions() const
    {
      return boundary_conditions;
    }


    template <int dim>
    Boundary::BoundaryConditions<dim> &
    Simulator<dim>::get_boundary_conditions()
    {
      return boundary_conditions;
    }


    template <int dim>
    const Boundary::BoundaryTreatment &
    Simulator<dim>::get_boundary_treatment() const
    {
      return *treatment;
    }


    template <int dim>
    const std::string &
    Simulator<dim>::get_boundary_treatment_name() const
    {
      return treatment_name;
    }


    template <int dim>
    const Solvers::LinearSolver &
    Simulator<dim>::get_linear_solver() const
    {
      return linear_solver;
    }


    template <int dim>
    const Functions::ParsedFunction<dim> *
    Simulator<dim>::get_analytical_solution() const
    {
      return compare_with_analytical ? analytical_solution.get() : nullptr;
    }


    template <int dim>
    void
    Simulator<dim>::set_time(const double t)
    {
      boundary_conditions.set_time(t);
      if (analytical_solution != nullptr)
        analytical_solution->set_time(t);
    }


    template <int dim>
    const IO::SolutionOutput<dim> &
    Simulator<dim>::get_output() const
    {
      return output;
    }


    template <int dim>
    const std::string &
    Simulator<dim>::get_node_data_file() const
    {
      return node_data_file;
    }


    template <int dim>
    IO::RunSummary &
    Simulator<dim>::get_summary()
    {
      return summary;
    }


    template <int dim>
    Boundary::SystemContext<dim>
    Simulator<dim>::system_context()
    {
      return {communicator,
              pcout,
              timer,
              summary,
              dof_handler,
              *triangulation,
              nodes,
              neighbor_lists,
              get_model(),
              *algorithm,
              algorithm_name,
              *quadrature_scheme,
              quadrature_scheme_name,
              horizon,
              boundary_conditions,
              treatment_name,
              linear_solver,
              [this](const bool store_full_lists) {
                setup_neighbor_lists(store_full_lists);
              },
              [this]() { return elapsed(); },
              [this](const std::string &text) { print_progress(text); }};
    }


    template <int dim>
    bool
    Simulator<dim>::couples_two_horizons() const
    {
      return problem->couples_two_horizons(model.get());
    }


    template class Simulator<1>;
    template class Simulator<2>;
    template class Simulator<3>;
  } // namespace Problems
} // namespace PeriDEAL
