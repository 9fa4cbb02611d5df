#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <perideal/base/exceptions.h>
#include <perideal/solvers/quasi_static_simulation.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Solvers
  {
    namespace
    {
      template <int dim>
      Point<dim>
      parse_point(const std::string &text)
      {
        const auto values =
          Utilities::string_to_double(Utilities::split_string_list(text));
        Point<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = values[d];
        return p;
      }

      std::string
      default_list(const int dim, const std::string &value)
      {
        std::string s = value;
        for (int d = 1; d < dim; ++d)
          s += "," + value;
        return s;
      }

      std::string
      to_string(const double value)
      {
        std::ostringstream s;
        s << std::setprecision(10) << value;
        return s.str();
      }
    } // namespace


    template <int dim>
    QuasiStaticSimulation<dim>::QuasiStaticSimulation(
      const MPI_Comm communicator)
      : communicator(communicator)
      , pcout(std::cout, Utilities::MPI::this_mpi_process(communicator) == 0)
      , timer(communicator, pcout, TimerOutput::never, TimerOutput::wall_times)
      , triangulation(communicator)
      , fe(FE_DGQ<dim>(0), dim)
      , dof_handler(triangulation)
    {}


    template <int dim>
    void
    QuasiStaticSimulation<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "3",
                        Patterns::Integer(2, 3),
                        "Space dimension of the problem: 2 or 3.");

      prm.enter_subsection("Geometry");
      {
        prm.declare_entry(
          "Mesh",
          "subdivided box",
          Patterns::Selection("subdivided box|file"),
          "'subdivided box': the box between 'Lower corner' and 'Upper "
          "corner' with 'Subdivisions' cells per direction (boundary ids 0/1 "
          "on x = min/max, 2/3 on y, 4/5 on z). 'file': the mesh in 'Mesh "
          "file', read with deal.II's GridIn; every cell must be an "
          "axis-aligned box.");
        prm.declare_entry("Lower corner",
                          default_list(dim, "0"),
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Lower corner of the box, one coordinate per "
                          "dimension.");
        prm.declare_entry("Upper corner",
                          default_list(dim, "1"),
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Upper corner of the box.");
        prm.declare_entry("Subdivisions",
                          default_list(dim, "10"),
                          Patterns::List(Patterns::Integer(1), dim, dim),
                          "Number of cells of the box in each direction, "
                          "before global refinement.");
        prm.declare_entry("Global refinements",
                          "0",
                          Patterns::Integer(0, 12),
                          "Number of times every cell is split into 2^dim.");
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "Mesh read when 'Mesh = file'; the format follows "
                          "the extension (.msh, .vtk, .inp/.ucd, ...).");
      }
      prm.leave_subsection();

      prm.enter_subsection("Horizon");
      {
        prm.declare_entry(
          "Specification",
          "m-ratio",
          Patterns::Selection("m-ratio|length"),
          "How the horizon is given: as the m-ratio (horizon over the "
          "smallest cell side h) or as a length.");
        prm.declare_entry("m-ratio",
                          "3",
                          Patterns::Double(),
                          "Horizon over the smallest cell side, > 0.");
        prm.declare_entry("Length",
                          "0.3",
                          Patterns::Double(),
                          "Horizon length, > 0 and smaller than the body.");
      }
      prm.leave_subsection();

      prm.enter_subsection("Partial volumes");
      {
        prm.declare_entry(
          "Algorithm",
          "exact",
          Patterns::Selection(
            Quadrature::PartialVolumeRegistry<dim>::pattern_string()),
          "How a neighbour cell's quadrature weight (the fraction of it "
          "inside the horizon) is computed. 'exact' is the closed-form "
          "volume of cell and ball.");
        Quadrature::PartialVolumeRegistry<dim>::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Material model");
      {
        prm.declare_entry("Model",
                          "linear peridynamic solid",
                          Patterns::Selection(
                            Models::ModelRegistry<dim>::pattern_string()),
                          "The PD material model; its constants are in the "
                          "subsection of the same name.");
        Models::ModelRegistry<dim>::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Boundary conditions");
      Boundary::BoundaryConditions<dim>::declare_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Analytical solution");
      {
        prm.declare_entry("Compare with analytical solution",
                          "false",
                          Patterns::Bool(),
                          "Whether to report the errors of the computed "
                          "displacement against the function in the "
                          "subsection 'Displacement'.");
        prm.enter_subsection("Displacement");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
      }
      prm.leave_subsection();

      prm.enter_subsection("Linear solver");
      LinearSolver::declare_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Output");
      {
        IO::SolutionOutput<dim>::declare_parameters(prm);
        prm.declare_entry(
          "Summary file",
          "",
          Patterns::FileName(),
          "CSV file to which one line per run is appended (sizes, solver, "
          "errors, phase timings, peak memory); the header is written when "
          "the file is new. Empty: no summary file.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::parse_parameters(ParameterHandler &prm)
    {
      AssertThrow(prm.get_integer("Dimension") == dim,
                  ExcInvalidInput("Dimension",
                                  prm.get("Dimension"),
                                  "this simulation is " + std::to_string(dim) +
                                    "D"));

      prm.enter_subsection("Geometry");
      {
        mesh_kind    = prm.get("Mesh");
        lower_corner = parse_point<dim>(prm.get("Lower corner"));
        upper_corner = parse_point<dim>(prm.get("Upper corner"));
        subdivisions.clear();
        for (const int n : Utilities::string_to_int(
               Utilities::split_string_list(prm.get("Subdivisions"))))
          subdivisions.push_back(n);
        global_refinements = prm.get_integer("Global refinements");
        mesh_file          = prm.get("Mesh file");
        if (mesh_kind == "subdivided box")
          {
            for (unsigned int d = 0; d < dim; ++d)
              AssertThrow(upper_corner[d] > lower_corner[d],
                          ExcInvalidInput("Geometry/Upper corner",
                                          prm.get("Upper corner"),
                                          "every coordinate of the upper "
                                          "corner must exceed that of the "
                                          "lower corner (" +
                                            prm.get("Lower corner") + ")"));
          }
        else
          AssertThrow(std::filesystem::is_regular_file(mesh_file) &&
                        std::ifstream(mesh_file).good(),
                      ExcInvalidInput("Geometry/Mesh file",
                                      mesh_file,
                                      "no readable file of this name; give "
                                      "the path of an existing mesh, "
                                      "relative to the working directory"));
      }
      prm.leave_subsection();

      prm.enter_subsection("Horizon");
      {
        horizon_specification = prm.get("Specification");
        m_ratio               = prm.get_double("m-ratio");
        horizon_length        = prm.get_double("Length");
        if (horizon_specification == "m-ratio")
          {
            AssertThrow(m_ratio > 0 && std::isfinite(m_ratio),
                        ExcInvalidInput("Horizon/m-ratio",
                                        prm.get("m-ratio"),
                                        "give a horizon-to-spacing ratio > "
                                        "0, typically between 2 and 5"));
          }
        else
          AssertThrow(horizon_length > 0 && std::isfinite(horizon_length),
                      ExcInvalidInput("Horizon/Length",
                                      prm.get("Length"),
                                      "give a horizon length > 0"));
      }
      prm.leave_subsection();

      prm.enter_subsection("Partial volumes");
      algorithm_name = prm.get("Algorithm");
      algorithm =
        Quadrature::PartialVolumeRegistry<dim>::create(algorithm_name, prm);
      prm.leave_subsection();

      prm.enter_subsection("Material model");
      model_name = prm.get("Model");
      model      = Models::ModelRegistry<dim>::create(model_name, prm);
      prm.leave_subsection();

      prm.enter_subsection("Boundary conditions");
      boundary_conditions.parse_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Analytical solution");
      {
        compare_with_analytical =
          prm.get_bool("Compare with analytical solution");
        prm.enter_subsection("Displacement");
        const std::string expression = prm.get("Function expression");
        AssertThrow(Utilities::split_string_list(expression, ';').size() == dim,
                    ExcInvalidInput(
                      "Analytical solution/Displacement/Function expression",
                      expression,
                      "give " + std::to_string(dim) +
                        " expressions separated by ';'"));
        analytical_solution =
          std::make_unique<Functions::ParsedFunction<dim>>(dim);
        analytical_solution->parse_parameters(prm);
        prm.leave_subsection();
      }
      prm.leave_subsection();

      prm.enter_subsection("Linear solver");
      linear_solver.parse_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Output");
      output.parse_parameters(prm);
      summary_file = prm.get("Summary file");
      prm.leave_subsection();
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::make_mesh()
    {
      TimerOutput::Scope scope(timer, "mesh");
      if (mesh_kind == "subdivided box")
        GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                  subdivisions,
                                                  lower_corner,
                                                  upper_corner,
                                                  true);
      else
        {
          GridIn<dim> grid_in;
          grid_in.attach_triangulation(triangulation);
          grid_in.read(mesh_file);
        }
      triangulation.refine_global(global_refinements);

      // The smallest cell side and the extent of the body.
      h = std::numeric_limits<double>::max();
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            // Every cell must be an axis-aligned box (a clear error
            // otherwise), before any size is derived from it.
            const BoundingBox<dim> box = Discretization::cell_box(*cell);
            for (unsigned int d = 0; d < dim; ++d)
              h = std::min(h, box.side_length(d));
            for (const unsigned int v : cell->vertex_indices())
              for (unsigned int d = 0; d < dim; ++d)
                {
                  lower[d] = std::min(lower[d], cell->vertex(v)[d]);
                  upper[d] = std::max(upper[d], cell->vertex(v)[d]);
                }
          }
      h                      = Utilities::MPI::min(h, communicator);
      double smallest_extent = std::numeric_limits<double>::max();
      for (unsigned int d = 0; d < dim; ++d)
        smallest_extent =
          std::min(smallest_extent,
                   Utilities::MPI::max(upper[d], communicator) -
                     Utilities::MPI::min(lower[d], communicator));

      if (horizon_specification == "m-ratio")
        horizon = m_ratio * h;
      else
        {
          horizon = horizon_length;
          m_ratio = horizon / h;
        }
      AssertThrow(
        horizon < smallest_extent,
        ExcInvalidInput(horizon_specification == "m-ratio" ? "Horizon/m-ratio" :
                                                             "Horizon/Length",
                        horizon_specification == "m-ratio" ?
                          to_string(m_ratio) :
                          to_string(horizon_length),
                        "the horizon " + to_string(horizon) +
                          " is not smaller than the smallest extent of the "
                          "body, " +
                          to_string(smallest_extent) +
                          "; use a smaller horizon or a larger body"));

      summary.h       = h;
      summary.horizon = horizon;
      summary.n_ranks = Utilities::MPI::n_mpi_processes(communicator);
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time()
            << " s] mesh: " << triangulation.n_global_active_cells()
            << " cells, h = " << std::defaultfloat << h
            << ", horizon = " << horizon << " (m-ratio " << m_ratio << "), "
            << Utilities::MPI::n_mpi_processes(communicator)
            << " MPI process(es)" << std::endl;
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::setup_nodes_and_bonds()
    {
      {
        TimerOutput::Scope scope(timer, "nodes and ghost exchange");
        dof_handler.distribute_dofs(fe);
        double diameter = 0;
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            diameter = std::max(diameter, cell->diameter());
        diameter = Utilities::MPI::max(diameter, communicator);
        // State-based forces of an owned node need the dilatations of its
        // neighbours, hence their neighbours: two horizons.
        const double coupling_range = model->is_state_based() ?
                                        2 * (horizon + diameter) :
                                        horizon + diameter;
        nodes.reinit(dof_handler, coupling_range);
      }
      summary.n_nodes = triangulation.n_global_active_cells();
      {
        TimerOutput::Scope scope(timer, "neighbour search and weights");
        neighbor_lists.reinit(nodes,
                              horizon,
                              *algorithm,
                              model->is_state_based());
      }
      summary.n_bonds =
        Utilities::MPI::sum(neighbor_lists.n_owned_bonds(), communicator);
      {
        TimerOutput::Scope scope(timer, "operator setup");
        pd_operator.reinit(nodes, neighbor_lists, *model, horizon);
      }
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time() << " s] nodes: " << summary.n_nodes
            << " (" << Utilities::MPI::sum(nodes.n_ghost(), communicator)
            << " ghost copies), bonds: " << summary.n_bonds << " ("
            << std::defaultfloat << std::setprecision(4)
            << double(summary.n_bonds) / summary.n_nodes
            << " per node), weights by '" << algorithm_name << "'"
            << (neighbor_lists.used_uniform_grid_table() ?
                  " from the uniform-grid table" :
                  " per bond")
            << std::endl;
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::assemble_and_solve()
    {
      const IndexSet &owned    = dof_handler.locally_owned_dofs();
      const IndexSet  relevant = nodes.relevant_dofs();
      {
        TimerOutput::Scope scope(timer, "assembly");
        boundary_conditions.make_constraints(dof_handler,
                                             nodes,
                                             horizon,
                                             constraints);
        load.reinit(owned, communicator);
        boundary_conditions.add_load(dof_handler, nodes, constraints, load);
        system_rhs = load;
        pd_operator.assemble(system_matrix, constraints, system_rhs);
      }
      summary.n_constrained_nodes = Utilities::MPI::sum(
        boundary_conditions.n_constrained_nodes(nodes, constraints),
        communicator);
      summary.n_nonzeros = system_matrix.n_nonzero_elements();
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time()
            << " s] assembled: " << dof_handler.n_dofs() << " DoFs, "
            << summary.n_nonzeros << " nonzeros, "
            << summary.n_constrained_nodes << " nodes in Dirichlet layers"
            << std::endl;

      // Symmetry of the system, measured: x^T A y against y^T A x.
      TrilinosWrappers::MPI::Vector x(owned, communicator),
        y(owned, communicator), ax(owned, communicator),
        ay(owned, communicator);
      for (const auto dof : owned)
        {
          x[dof] = std::sin(1.3 * dof + 0.2);
          y[dof] = std::cos(0.7 * dof + 1.1);
        }
      x.compress(VectorOperation::insert);
      y.compress(VectorOperation::insert);
      system_matrix.vmult(ax, x);
      system_matrix.vmult(ay, y);
      const double asymmetry = std::abs(y * ax - x * ay);
      const bool   symmetric = asymmetry <= 1e-12 * ax.l2_norm() * y.l2_norm();

      TrilinosWrappers::MPI::Vector solution(owned, communicator);
      {
        TimerOutput::Scope             scope(timer, "solve");
        std::vector<std::vector<bool>> constant_modes;
        DoFTools::extract_constant_modes(dof_handler,
                                         ComponentMask(dim, true),
                                         constant_modes);
        summary.solver = linear_solver.solve(system_matrix,
                                             solution,
                                             system_rhs,
                                             constant_modes,
                                             symmetric);
        constraints.distribute(solution);
      }
      displacement.reinit(owned, relevant, communicator);
      displacement = solution;
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time() << " s] solved with "
            << summary.solver.method << ": " << summary.solver.iterations
            << " iteration(s), relative residual " << std::scientific
            << std::setprecision(2) << summary.solver.relative_residual
            << std::defaultfloat << (symmetric ? "" : " (non-symmetric)")
            << std::endl;

      // Equilibrium with the matrix-free forces: F_int(u) + F_ext = 0 at
      // every free DoF.
      TrilinosWrappers::MPI::Vector internal(owned, communicator);
      pd_operator.apply(displacement, internal);
      double free_residual2 = 0;
      for (const auto dof : owned)
        if (!constraints.is_constrained(dof))
          free_residual2 += std::pow(internal[dof] + load[dof], 2);
      const double scale = internal.l2_norm();
      free_residual2     = Utilities::MPI::sum(free_residual2, communicator);
      summary.equilibrium_residual =
        scale > 0 ? std::sqrt(free_residual2) / scale : 0.;
      pcout << "           equilibrium check (matrix-free forces): "
            << "|F_int + F_ext| / |F_int| = " << std::scientific
            << std::setprecision(2) << summary.equilibrium_residual
            << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::postprocess()
    {
      std::vector<double> dilatation;
      pd_operator.compute_dilatation(displacement, dilatation);

      const unsigned int         n_owned = nodes.n_owned();
      std::vector<IO::NodeField> fields  = {{"dilatation", {}},
                                            {"weighted_volume", {}},
                                            {"node_volume", {}},
                                            {"n_neighbors", {}},
                                            {"mpi_rank", {}},
                                            {"constrained", {}}};
      const double rank = Utilities::MPI::this_mpi_process(communicator);
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          fields[0].values.push_back(dilatation[i]);
          fields[1].values.push_back(pd_operator.weighted_volumes()[i]);
          fields[2].values.push_back(nodes[i].volume());
          fields[3].values.push_back(neighbor_lists.bonds(i).size());
          fields[4].values.push_back(rank);
          bool constrained = false;
          for (const auto dof : nodes[i].dofs)
            constrained = constrained || constraints.is_constrained(dof);
          fields[5].values.push_back(constrained);
        }

      if (compare_with_analytical)
        {
          IO::NodeField  error{"displacement_error", {}};
          Vector<double> exact(dim);
          double         e2 = 0, u2 = 0, e_max = 0, u_max = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(nodes[i].location, exact);
              double e = 0, u = 0;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  e += std::pow(displacement[nodes[i].dofs[c]] - exact[c], 2);
                  u += exact[c] * exact[c];
                }
              e2 += nodes[i].volume() * e;
              u2 += nodes[i].volume() * u;
              e_max = std::max(e_max, std::sqrt(e));
              u_max = std::max(u_max, std::sqrt(u));
              error.values.push_back(std::sqrt(e));
            }
          e2                 = Utilities::MPI::sum(e2, communicator);
          u2                 = Utilities::MPI::sum(u2, communicator);
          e_max              = Utilities::MPI::max(e_max, communicator);
          u_max              = Utilities::MPI::max(u_max, communicator);
          summary.has_errors = true;
          summary.errors.l2  = u2 > 0 ? std::sqrt(e2 / u2) : std::sqrt(e2);
          summary.errors.max = u_max > 0 ? e_max / u_max : e_max;
          fields.push_back(error);
          pcout << "           error against the analytical solution: "
                << "relative L2 " << std::scientific << std::setprecision(3)
                << summary.errors.l2 << ", relative max " << summary.errors.max
                << std::defaultfloat << std::endl;
        }

      TimerOutput::Scope scope(timer, "output");
      const std::string  record =
        output.write(dof_handler, nodes, displacement, fields);
      if (!record.empty())
        pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
              << wall_clock.wall_time() << " s] wrote " << output.directory()
              << "/" << record << std::defaultfloat << std::endl;
    }


    template <int dim>
    RunSummary
    QuasiStaticSimulation<dim>::run()
    {
      wall_clock.restart();
      pcout << "PeriDEAL quasi-static " << dim << "D: model '" << model_name
            << "', partial volumes '" << algorithm_name << "', solver '"
            << linear_solver.method() << "'" << std::endl;
      make_mesh();
      setup_nodes_and_bonds();
      assemble_and_solve();
      postprocess();

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

      if (!summary_file.empty() &&
          Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          const bool    is_new = !std::filesystem::exists(summary_file);
          std::ofstream csv(summary_file, std::ios::app);
          AssertThrow(csv,
                      ExcInvalidInput("Output/Summary file",
                                      summary_file,
                                      "the file cannot be written; "
                                      "check the directory"));
          if (is_new)
            csv << "dim,model,algorithm,n_ranks,n_nodes,n_constrained_nodes,"
                   "h,horizon,m_ratio,n_bonds,nnz,solver,iterations,"
                   "relative_residual,equilibrium_residual,l2_error,"
                   "max_error,time_mesh,time_nodes,time_neighbors,"
                   "time_operator,time_assembly,time_solve,time_output,"
                   "time_total,peak_memory_mb\n";
          auto t = [&](const std::string &phase) {
            const auto it = summary.seconds.find(phase);
            return it == summary.seconds.end() ? 0. : it->second;
          };
          csv << std::setprecision(10) << dim << ",\"" << model_name << "\",\""
              << algorithm_name << "\"," << summary.n_ranks << ','
              << summary.n_nodes << ',' << summary.n_constrained_nodes << ','
              << h << ',' << horizon << ',' << horizon / h << ','
              << summary.n_bonds << ',' << summary.n_nonzeros << ",\""
              << summary.solver.method << "\"," << summary.solver.iterations
              << ',' << summary.solver.relative_residual << ','
              << summary.equilibrium_residual << ','
              << (summary.has_errors ? to_string(summary.errors.l2) : "") << ','
              << (summary.has_errors ? to_string(summary.errors.max) : "")
              << ',' << t("mesh") << ',' << t("nodes and ghost exchange") << ','
              << t("neighbour search and weights") << ',' << t("operator setup")
              << ',' << t("assembly") << ',' << t("solve") << ',' << t("output")
              << ',' << t("total") << ',' << summary.peak_memory_mb << '\n';
        }
      return summary;
    }


    template <int dim>
    const TrilinosWrappers::MPI::Vector &
    QuasiStaticSimulation<dim>::solution() const
    {
      return displacement;
    }


    template class QuasiStaticSimulation<2>;
    template class QuasiStaticSimulation<3>;
  } // namespace Solvers
} // namespace PeriDEAL
