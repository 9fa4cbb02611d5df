#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>

#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/tria.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <deal.II/base/multithread_info.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/base/input_checks.h>
#include <perideal/base/shared_libraries.h>
#include <perideal/models/diffusion_model.h>
#include <perideal/problems/simulator.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      /// The columns of the summary CSV.
      const std::string summary_header =
        "dim,model,algorithm,n_ranks,n_nodes,n_constrained_nodes,"
        "h,horizon,m_ratio,n_bonds,nnz,solver,iterations,"
        "relative_residual,equilibrium_residual,l2_error,"
        "max_error,time_mesh,time_nodes,time_neighbors,"
        "time_operator,time_assembly,time_solve,time_output,"
        "time_total,peak_memory_mb,treatment,taylor_order,"
        "n_unknowns,n_surface_nodes,n_fictitious_nodes,"
        "max_normalized_error,operator,preconditioner,"
        "time_preconditioner,n_threads,problem_type";

      const std::string summary_columns_differ =
        "the file exists with other columns (an older version or another "
        "program wrote it), and a row appended to it would be misread; name "
        "a new file, or move the old one away.";

      /// Whether @p file exists, is not empty and has other columns.
      bool
      summary_columns_mismatch(const std::string &file)
      {
        std::ifstream in(file);
        std::string   first_line;
        return in && std::getline(in, first_line) &&
               first_line != summary_header;
      }
    } // namespace


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


      /**
       * The mesh of a @p dim-dimensional run: p4est in 2D and 3D; in 1D,
       * where p4est has none, a shared triangulation (every process holds
       * the whole line) partitioned in z-order, which for a line is into
       * contiguous pieces.
       */
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
    } // namespace


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
    Simulator<dim>::declare_parameters(ParameterHandler &prm)
    {
      // The driver reads it and loads the libraries in a first pass
      // (load_shared_libraries()); declared here so that the full parse
      // accepts it.
      declare_shared_library_parameters(prm);
      prm.declare_entry("Dimension",
                        "3",
                        Patterns::Integer(1, 3),
                        "Space dimension of the problem: 1, 2 or 3. 1D runs "
                        "(a serial line, shared by the processes) have only "
                        "the problem type 'diffusion'.");
      prm.declare_entry(
        "Problem type",
        ProblemTypeRegistry<dim>::is_registered("quasi-static") ?
          "quasi-static" :
          ProblemTypeRegistry<dim>::names().front(),
        Patterns::Selection(ProblemTypeRegistry<dim>::pattern_string()),
        "What to solve on the PD nodes; the entries of each problem type "
        "are in the top-level subsection of the same name.");
      ProblemTypeRegistry<dim>::declare_parameters(prm);

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

      prm.enter_subsection("Boundary treatment");
      {
        prm.declare_entry(
          "Treatment",
          "none",
          Patterns::Selection(
            Boundary::BoundaryTreatmentRegistry::pattern_string()),
          "How the body's surface is treated: 'none' (incomplete "
          "neighbourhoods, conditions on the outermost nodes), 'fictitious "
          "layer' (completed neighbourhoods by Taylor extrapolation) or "
          "'surface nodes' (fictitious layer plus nodes on the external "
          "faces carrying the boundary conditions through the force flux; "
          "Scabbia et al. 2023). The last two need a uniform grid of cubes "
          "and give a non-symmetric matrix: use the direct solver or GMRES.");
        Boundary::BoundaryTreatmentRegistry::declare_parameters(prm);
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
        // 1D has no material model (its runs are diffusion runs).
        const bool has_models = !Models::ModelRegistry<dim>::names().empty();
        prm.declare_entry("Model",
                          has_models ? "linear peridynamic solid" : "none",
                          Patterns::Selection(
                            has_models ?
                              Models::ModelRegistry<dim>::pattern_string() :
                              std::string("none")),
                          has_models ?
                            "The PD material model; its constants are in the "
                            "subsection of the same name." :
                            "1D runs have no material model: the only "
                            "problem type in 1D is 'diffusion'.");
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
      Solvers::LinearSolver::declare_parameters(prm);
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
        prm.declare_entry(
          "Node data file",
          "",
          Patterns::FileName(),
          "CSV file with one line per node (body nodes, and surface nodes "
          "with the 'surface nodes' treatment): kind, position, computed "
          "and analytical displacement, normalized error (Scabbia et al. "
          "2023, Eq. 38). Written by process 0 for plots such as mid-plane "
          "error maps. Empty: not written.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    Simulator<dim>::check_input_file(const std::string &file,
                                     ParameterHandler  &prm)
    {
      const std::vector<InputEntry> entries = scan_input_file(file);

      struct Selection
      {
        std::string              section; // empty: top level
        std::string              selector;
        std::vector<std::string> names;
      };
      const std::vector<Selection> selections = {
        {"Material model", "Model", Models::ModelRegistry<dim>::names()},
        {"Partial volumes",
         "Algorithm",
         Quadrature::PartialVolumeRegistry<dim>::names()},
        {"Boundary treatment",
         "Treatment",
         Boundary::BoundaryTreatmentRegistry::names()},
        {"", "Problem type", ProblemTypeRegistry<dim>::names()},
        {"diffusion", "Model", Models::DiffusionModelRegistry<dim>::names()}};
      for (const auto &entry : entries)
        {
          AssertThrow(dim == 2 || entry.path.back() != "Plane model",
                      ExcMessage("The entry '" + entry.name() + "' (line " +
                                 std::to_string(entry.line) +
                                 ") applies to 2D only, and this run is " +
                                 std::to_string(dim) +
                                 "D. Remove it, or set 'Dimension = 2'."));
          for (const auto &selection : selections)
            {
              const unsigned int depth = selection.section.empty() ? 0 : 1;
              if (entry.path.size() < depth + 2 ||
                  (depth == 1 && entry.path[0] != selection.section))
                continue;
              const std::string &plugin = entry.path[depth];
              if (std::find(selection.names.begin(),
                            selection.names.end(),
                            plugin) == selection.names.end())
                continue;
              if (depth == 1)
                prm.enter_subsection(selection.section);
              const std::string selected = prm.get(selection.selector);
              if (depth == 1)
                prm.leave_subsection();
              const std::string selector =
                (depth == 1 ? selection.section + "/" : std::string()) +
                selection.selector;
              AssertThrow(plugin == selected,
                          ExcMessage(
                            "The entry '" + entry.name() + "' (line " +
                            std::to_string(entry.line) + ") belongs to '" +
                            plugin + "', but '" + selector + "' selects '" +
                            selected + "', so it would be ignored. Set '" +
                            selector + " = " + plugin +
                            "', or move the entry to the subsection '" +
                            selected + "'."));
            }
        }
    }


    template <int dim>
    void
    Simulator<dim>::parse_parameters(ParameterHandler &prm)
    {
      AssertThrow(prm.get_integer("Dimension") == dim,
                  ExcInvalidInput("Dimension",
                                  prm.get("Dimension"),
                                  "this simulation is " + std::to_string(dim) +
                                    "D"));
      problem_name = prm.get("Problem type");
      problem      = ProblemTypeRegistry<dim>::create(problem_name, prm);

      prm.enter_subsection("Geometry");
      {
        mesh_kind        = prm.get("Mesh");
        prm_subdivisions = prm.get("Subdivisions");
        lower_corner     = parse_point<dim>(prm.get("Lower corner"));
        upper_corner     = parse_point<dim>(prm.get("Upper corner"));
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
      if (model_name != "none")
        model = Models::ModelRegistry<dim>::create(model_name, prm);
      prm.leave_subsection();
      AssertThrow(model != nullptr || !problem->uses_material_model(),
                  ExcInvalidInput("Material model/Model",
                                  model_name,
                                  "the problem type '" + problem_name +
                                    "' needs a material model"));

      prm.enter_subsection("Boundary conditions");
      boundary_conditions.parse_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Boundary treatment");
      treatment_name = prm.get("Treatment");
      treatment =
        Boundary::BoundaryTreatmentRegistry::create(treatment_name, prm);
      prm.leave_subsection();
      summary.treatment    = treatment_name;
      summary.taylor_order = treatment->taylor_order();

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
      summary_file   = prm.get("Summary file");
      node_data_file = prm.get("Node data file");
      prm.leave_subsection();

      problem->check_input(*this);
      check_unused_entries(prm);
    }


    template <int dim>
    void
    Simulator<dim>::check_unused_entries(const ParameterHandler &prm) const
    {
      std::vector<UnusedEntry> unused = problem->unused_entries(*this);
      if (!problem->uses_material_model())
        unused.push_back({"Material model/",
                          "the problem type '" + problem_name +
                            "' uses no elastic material model; remove the "
                            "subsection 'Material model'"});
      else if (model != nullptr)
        for (const auto &rule : model->unused_entries())
          unused.push_back(
            {"Material model/" + model_name + "/" + rule.pattern, rule.why});
      if (!problem->uses_linear_solver())
        unused.push_back({"Linear solver/",
                          "the problem type '" + problem_name +
                            "' solves no linear system with it; remove the "
                            "subsection 'Linear solver'"});
      ParameterHandler defaults;
      declare_parameters(defaults);
      PeriDEAL::check_unused_entries(changed_entries(prm, defaults), unused);
    }


    template <int dim>
    void
    Simulator<dim>::check_memory_estimate() const
    {
      // Nodes of the box before anything is allocated, as a double (a
      // careless input can overflow any integer).
      double n_nodes = std::pow(2., dim * double(global_refinements));
      for (const auto n : subdivisions)
        n_nodes *= n;
      // Bytes per node, measured (doc/matrix-free-operator.md): about 2 KB
      // for mesh, DoF handler, node set, constraints and vectors with the
      // matrix-free operator, plus 6 KB for the AMG hierarchy of the local
      // elasticity preconditioner; an assembled matrix stores dim rows of
      // dim times the nodes within the coupling range, 12 bytes an entry,
      // and a direct solver's factors several times that.
      const double m =
        horizon_specification == "m-ratio" ?
          m_ratio :
          horizon_length /
            std::max(1e-300,
                     (upper_corner[0] - lower_corner[0]) / subdivisions[0]);
      // Calibrated on the 28^3 LPS case (110 KB per node assembled, m = 3).
      const double reach   = couples_two_horizons() ? 2 * m : m;
      const double coupled = dim == 3 ? 4. / 3. * M_PI * reach * reach * reach :
                             dim == 2 ? M_PI * reach * reach :
                                        2 * reach;
      // (2D: 1 KB and 1.5 KB; the 2000^2 run took 9.5 GB with local
      // elasticity.)
      double       per_node = dim == 3 ? 2048 : 1024;
      const double own      = problem->estimated_bytes_per_node(
        dim == 3 ? 4. / 3. * M_PI * m * m * m :
        dim == 2 ? M_PI * m * m :
                   2 * m);
      if (own >= 0)
        per_node = own;
      else if (linear_solver.is_matrix_free())
        {
          if (linear_solver.preconditioner_name() == "local elasticity")
            per_node += dim == 3 ? 6144 : 1536;
        }
      else
        per_node += dim * dim * coupled * 12 *
                    (linear_solver.method() == "direct" ? 2 : 1);
      const double needed = n_nodes * per_node;

      // Memory available to this job: MemAvailable of each host, shared
      // among the processes on it.
      double available = 0;
      {
        std::ifstream meminfo("/proc/meminfo");
        std::string   key;
        double        kb = 0;
        std::string   unit;
        while (meminfo >> key >> kb >> unit)
          if (key == "MemAvailable:")
            {
              available = kb * 1024;
              break;
            }
      }
      MPI_Comm host;
      MPI_Comm_split_type(communicator,
                          MPI_COMM_TYPE_SHARED,
                          0,
                          MPI_INFO_NULL,
                          &host);
      const unsigned int on_host = Utilities::MPI::n_mpi_processes(host);
      MPI_Comm_free(&host);
      available = Utilities::MPI::sum(available / on_host, communicator);
      if (available <= 0) // no /proc/meminfo: no guard
        return;
      AssertThrow(
        needed <= 0.9 * available,
        ExcInvalidInput(
          "Geometry/Subdivisions",
          prm_subdivisions,
          "with 'Global refinements = " + std::to_string(global_refinements) +
            "' this is " + format_number(n_nodes) +
            " nodes, which need an estimated " +
            format_number(needed / 1073741824.) + " GB, but only " +
            format_number(available / 1073741824.) +
            " GB are available; use fewer cells" +
            (linear_solver.is_matrix_free() || !problem->uses_linear_solver() ?
               std::string(", or more machines") :
               std::string(", 'Linear solver/Operator = matrix-free' (about "
                           "2 KB per node), or more machines"))));
    }


    template <int dim>
    void
    Simulator<dim>::make_mesh()
    {
      TimerOutput::Scope scope(timer, "mesh");
      if (mesh_kind == "subdivided box")
        check_memory_estimate();
      if (mesh_kind == "subdivided box")
        GridGenerator::subdivided_hyper_rectangle(*triangulation,
                                                  subdivisions,
                                                  lower_corner,
                                                  upper_corner,
                                                  true);
      else
        {
          // GridIn's own messages ("(none)", "No vertices given") name
          // neither the file nor the entry; every process reads the file, so
          // every process fails alike.
          GridIn<dim> grid_in;
          grid_in.attach_triangulation(*triangulation);
          std::string error;
          try
            {
              grid_in.read(mesh_file);
              if (triangulation->n_global_active_cells() == 0)
                error = "it holds no cells";
            }
          catch (const ExceptionBase &exc)
            {
              std::ostringstream info;
              exc.print_info(info);
              error = Utilities::trim(info.str());
            }
          catch (const std::exception &exc)
            {
              error = exc.what();
            }
          AssertThrow(
            error.empty(),
            ExcInvalidInput(
              "Geometry/Mesh file",
              mesh_file,
              "reading it as a " + std::to_string(dim) + "D mesh failed (" +
                (error.empty() ? "" : error) +
                "); check that the extension names its format (.msh, .vtk, "
                ".inp, .ucd, ...), that the file is complete, and that it "
                "holds " +
                std::to_string(dim) +
                "D cells ('Dimension = " + std::to_string(dim) + "')"));
        }
      triangulation->refine_global(global_refinements);

      // The smallest cell side and the extent of the body.
      h = std::numeric_limits<double>::max();
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      // Every cell must be an axis-aligned box (a clear error otherwise),
      // before any size is derived from it; the check fails on the process
      // that owns the cell, and all processes stop with its message.
      check_on_all_ranks(
        [&]() {
          for (const auto &cell : triangulation->active_cell_iterators())
            if (cell->is_locally_owned())
              {
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
        },
        communicator);
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
            << " s] mesh: " << triangulation->n_global_active_cells()
            << " cells, h = " << std::defaultfloat << std::setprecision(10) << h
            << ", horizon = " << horizon << " (m-ratio " << m_ratio << "), "
            << Utilities::MPI::n_mpi_processes(communicator)
            << " MPI process(es)" << std::endl;
    }


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
                  ExcInvalidInput(horizon_specification == "m-ratio" ?
                                    "Horizon/m-ratio" :
                                    "Horizon/Length",
                                  to_string(horizon_specification == "m-ratio" ?
                                              m_ratio :
                                              horizon_length),
                                  "the horizon " + to_string(horizon) +
                                    " reaches no neighbour, so there is no "
                                    "bond; give an m-ratio above 0.5 (above 1 "
                                    "for full volumes), typically 3"));
      std::ostringstream line;
      line << "nodes: " << summary.n_nodes << " ("
           << Utilities::MPI::sum(nodes.n_ghost(), communicator)
           << " ghost copies), bonds: " << summary.n_bonds << " ("
           << std::setprecision(4) << double(summary.n_bonds) / summary.n_nodes
           << " per node), weights by '" << algorithm_name << "'"
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
    RunSummary
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
                else if (entry == "Output/Summary file" &&
                         summary_columns_mismatch(file))
                  error = "Invalid value '" + file + "' for the parameter '" +
                          entry + "': " + summary_columns_differ;
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
                  ", solver '" + linear_solver.method() + "'" :
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

      write_summary_file();
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
      return {"Material model/" + model_name + "/" + entry.first,
              entry.second};
    }


    template <int dim>
    void
    Simulator<dim>::check_material_scale() const
    {
      if (model == nullptr || !problem->uses_material_model() ||
          model->stiffness_entry().first.empty())
        return;
      // The weighted volume m of a full ball, S_{d-1} int_0^delta omega r^{d+1}
      // dr (midpoint rule), the coefficients of the shortest and the longest
      // bond, and a row sum of the stiffness: the same on every process.
      const double sphere = dim == 1 ? 2. :
                            dim == 2 ? 2 * numbers::PI :
                                       4 * numbers::PI;
      const unsigned int n_r = 256;
      double             m   = 0;
      for (unsigned int k = 0; k < n_r; ++k)
        {
          const double r = (k + 0.5) / n_r * horizon;
          m += sphere * model->influence(r, horizon) * std::pow(r, dim + 1) *
               horizon / n_r;
        }
      const double volume = sphere / dim * std::pow(horizon, dim);
      bool         finite = std::isfinite(model->bulk_modulus()) &&
                    std::isfinite(model->shear_modulus()) &&
                    std::isfinite(m) && m > 0;
      for (const double r : {h, horizon})
        {
          const double a = model->dilatation_coefficient(m, r, horizon);
          const double b = model->extension_coefficient(m, r, horizon);
          const double row =
            (std::abs(a) * dim * horizon / m * volume + std::abs(b)) * volume;
          finite = finite && std::isfinite(a) && std::isfinite(b) &&
                   std::isfinite(row);
        }
      const auto [entry, value] = get_stiffness_entry();
      AssertThrow(finite,
                  ExcInvalidInput(
                    entry,
                    value,
                    "with the horizon " + to_string(horizon) +
                      " the bond stiffness of the model (the modulus over a "
                      "power of the horizon) overflows the range of double "
                      "precision numbers (about 1e308); give the modulus of "
                      "a real material, about 1e3 to 1e12 Pa (or of order 1 "
                      "in nondimensional units)"));
    }


    template <int dim>
    void
    Simulator<dim>::check_output_names() const
    {
      using Kind = IO::OutputName::Kind;
      std::vector<IO::OutputName> names;
      if (mesh_kind == "file")
        names.push_back(
          {"Geometry/Mesh file", mesh_file, mesh_file, Kind::input, "the mesh"});
      for (auto &name : problem->output_names(*this))
        names.push_back(std::move(name));
      if (!summary_file.empty())
        names.push_back({"Output/Summary file",
                         summary_file,
                         summary_file,
                         Kind::file,
                         "the summary file"});
      if (!node_data_file.empty())
        names.push_back({"Output/Node data file",
                         node_data_file,
                         node_data_file,
                         Kind::file,
                         "the node data file"});
      check_on_all_ranks([&]() { IO::check_output_names(names); },
                         communicator);
    }


    template <int dim>
    void
    Simulator<dim>::write_summary_file() const
    {
      if (summary_file.empty())
        return;
      // One row per run, appended: the file is rewritten under a temporary
      // name and renamed, so that a run killed while writing never
      // truncates the rows of earlier runs. Process 0 writes; its verdict
      // is shared.
      const std::string header = summary_header;
      std::string       error;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::string earlier;
          if (std::filesystem::exists(summary_file))
            {
              std::ifstream     in(summary_file);
              std::stringstream content;
              content << in.rdbuf();
              earlier = content.str();
              if (!earlier.empty() &&
                  earlier.substr(0, earlier.find('\n')) != header)
                error = "Invalid value '" + summary_file +
                        "' for the parameter 'Output/Summary file': " +
                        summary_columns_differ;
              if (!earlier.empty() && earlier.back() != '\n')
                earlier += '\n';
            }
          const std::filesystem::path parent =
            std::filesystem::path(summary_file).parent_path();
          std::error_code ignored;
          if (!parent.empty())
            std::filesystem::create_directories(parent, ignored);
          std::ostringstream csv;
          const auto         t = [&](const std::string &phase) {
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
              << ',' << t("total") << ',' << summary.peak_memory_mb << ",\""
              << summary.treatment << "\"," << summary.taylor_order << ','
              << summary.n_unknowns << ',' << summary.n_surface_nodes << ','
              << summary.n_fictitious_nodes << ','
              << (summary.has_errors ?
                    to_string(summary.errors.max_normalized) :
                    "")
              << ",\""
              << (linear_solver.is_matrix_free() ? "matrix-free" : "assembled")
              << "\",\"" << linear_solver.preconditioner_name() << "\","
              << t("preconditioner setup") << ','
              << MultithreadInfo::n_threads() << ",\"" << problem_name
              << "\"\n";
          if (error.empty())
            {
              const std::string written =
                write_then_rename(summary_file, [&](std::ostream &out) {
                  out << (earlier.empty() ? header + "\n" : earlier)
                      << csv.str();
                });
              if (!written.empty())
                error = "Invalid value '" + summary_file +
                        "' for the parameter 'Output/Summary file': " + written;
            }
        }
      throw_on_any_rank(error, communicator);
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
    RunSummary &
    Simulator<dim>::get_summary()
    {
      return summary;
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
