#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_dgq.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>

#include <deal.II/base/multithread_info.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/operators/local_elasticity_operator.h>
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
      // Every cell must be an axis-aligned box (a clear error otherwise),
      // before any size is derived from it; the check fails on the process
      // that owns the cell, and all processes stop with its message.
      check_on_all_ranks(
        [&]() {
          for (const auto &cell : triangulation.active_cell_iterators())
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
      if (treatment->uses_fictitious_layer())
        {
          {
            TimerOutput::Scope scope(timer, "operator setup");
            layer_operator.reinit(dof_handler,
                                  nodes,
                                  *model,
                                  horizon,
                                  *algorithm,
                                  treatment->uses_surface_nodes(),
                                  treatment->taylor_order());
          }
          summary.n_bonds = summary.n_nodes *
                            layer_operator.n_neighbours_per_node();
          summary.n_surface_nodes    = layer_operator.n_surface_nodes();
          summary.n_fictitious_nodes = layer_operator.n_fictitious_nodes();
          pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << wall_clock.wall_time() << " s] nodes: " << summary.n_nodes
                << " in the body, " << summary.n_fictitious_nodes
                << " fictitious, " << summary.n_surface_nodes
                << " surface nodes; " << layer_operator.n_neighbours_per_node()
                << " bonds per node, weights by '" << algorithm_name
                << "'; boundary treatment '" << treatment_name
                << "', Taylor order " << treatment->taylor_order()
                << std::defaultfloat << std::endl;
          return;
        }
      const bool matrix_free = linear_solver.is_matrix_free();
      {
        TimerOutput::Scope scope(timer, "neighbour search and weights");
        // The matrix-free operator evaluates full neighbourhoods with the
        // shared stencil: their lists need not be stored.
        neighbor_lists.reinit(nodes,
                              horizon,
                              *algorithm,
                              model->is_state_based(),
                              !matrix_free);
      }
      summary.n_bonds =
        Utilities::MPI::sum(neighbor_lists.n_owned_bonds(), communicator);
      {
        TimerOutput::Scope scope(timer, "operator setup");
        if (matrix_free)
          {
            bond_state.reinit(nodes, neighbor_lists);
            bond_operator.reinit(
              nodes, neighbor_lists, *model, horizon, &bond_state);
          }
        else
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
    QuasiStaticSimulation<dim>::assemble_and_solve_with_layer()
    {
      const IndexSet &owned_dofs = dof_handler.locally_owned_dofs();
      const IndexSet &owned      = layer_operator.owned_unknowns();
      std::map<types::global_dof_index, double> prescribed;
      {
        TimerOutput::Scope scope(timer, "assembly");
        system_rhs.reinit(owned, communicator);
        boundary_conditions.check_boundary_ids(triangulation);
        if (treatment->uses_surface_nodes())
          {
            // Body force on the body nodes, boundary conditions on the
            // surface nodes: Dirichlet values where prescribed, the traction
            // times the face area in the force-flux equation otherwise.
            for (unsigned int i = 0; i < nodes.n_owned(); ++i)
              {
                const Tensor<1, dim> b =
                  boundary_conditions.body_force_value(nodes[i].location);
                for (unsigned int c = 0; c < dim; ++c)
                  system_rhs[layer_operator.unknown_index(nodes[i], c)] =
                    nodes[i].volume() * b[c];
              }
            const auto &mask = boundary_conditions.dirichlet_component_mask();
            for (const auto &node : layer_operator.owned_surface_nodes())
              {
                const bool dirichlet =
                  boundary_conditions.is_dirichlet_boundary(node.boundary_id);
                const Tensor<1, dim> g =
                  dirichlet ? boundary_conditions.dirichlet_value(node.location) :
                              Tensor<1, dim>();
                const Tensor<1, dim> p =
                  boundary_conditions.is_traction_boundary(node.boundary_id) ?
                    boundary_conditions.traction_value(node.location,
                                                       node.normal()) :
                    Tensor<1, dim>();
                for (unsigned int c = 0; c < dim; ++c)
                  if (dirichlet && mask[c])
                    prescribed[node.first_unknown + c] = g[c];
                  else
                    system_rhs[node.first_unknown + c] = node.area * p[c];
              }
            summary.n_constrained_nodes = Utilities::MPI::sum(
              static_cast<unsigned int>(prescribed.size()), communicator);
          }
        else
          {
            // A completed neighbourhood makes every node a bulk node: a
            // homogeneous strain then costs nothing anywhere, and a free or
            // loaded face has no equation that could hold it. Only bodies
            // whose every face is fully prescribed are well posed.
            bool all_prescribed = true;
            for (const bool c : boundary_conditions.dirichlet_component_mask())
              all_prescribed = all_prescribed && c;
            for (const auto &cell : triangulation.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int f : cell->face_indices())
                  if (cell->at_boundary(f) &&
                      !boundary_conditions.is_dirichlet_boundary(
                        cell->face(f)->boundary_id()))
                    all_prescribed = false;
            AssertThrow(
              Utilities::MPI::min(all_prescribed ? 1 : 0, communicator) == 1,
              ExcInvalidInput(
                "Boundary treatment/Treatment",
                treatment_name,
                "a fictitious layer alone cannot carry free or loaded faces "
                "(with completed neighbourhoods homogeneous strains cost no "
                "energy, so the system is singular): list every boundary id "
                "under 'Dirichlet boundary ids' with all components, or use "
                "'surface nodes', whose force-flux equations carry "
                "tractions and free faces"));
            // Conditions as without treatment: Dirichlet layers. The
            // unknowns are the DoFs.
            boundary_conditions.make_constraints(dof_handler,
                                                 nodes,
                                                 horizon,
                                                 constraints);
            load.reinit(owned_dofs, communicator);
            boundary_conditions.add_load(dof_handler, nodes, constraints, load);
            for (const auto dof : owned_dofs)
              if (constraints.is_constrained(dof))
                prescribed[dof] = constraints.get_inhomogeneity(dof);
              else
                system_rhs[dof] = load[dof];
            summary.n_constrained_nodes = Utilities::MPI::sum(
              boundary_conditions.n_constrained_nodes(nodes, constraints),
              communicator);
          }
        system_rhs.compress(VectorOperation::insert);
        layer_operator.assemble(prescribed, system_matrix, system_rhs);
      }
      summary.n_unknowns = owned.size();
      summary.n_nonzeros = system_matrix.n_nonzero_elements();
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time()
            << " s] assembled: " << summary.n_unknowns << " unknowns, "
            << summary.n_nonzeros << " nonzeros, "
            << summary.n_constrained_nodes
            << (treatment->uses_surface_nodes() ?
                  " prescribed surface-node components" :
                  " nodes in Dirichlet layers")
            << " (non-symmetric)" << std::endl;

      TrilinosWrappers::MPI::Vector solution(owned, communicator);
      {
        TimerOutput::Scope scope(timer, "solve");
        // Rigid translations for AMG: the component of each unknown.
        std::vector<std::vector<bool>> constant_modes(
          dim, std::vector<bool>(owned.n_elements(), false));
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          for (unsigned int c = 0; c < dim; ++c)
            constant_modes[c][owned.index_within_set(
              layer_operator.unknown_index(nodes[i], c))] = true;
        for (const auto &node : layer_operator.owned_surface_nodes())
          for (unsigned int c = 0; c < dim; ++c)
            constant_modes[c][owned.index_within_set(node.first_unknown + c)] =
              true;
        summary.solver = linear_solver.solve(
          system_matrix, solution, system_rhs, constant_modes, false);
      }
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time() << " s] solved with "
            << summary.solver.method << ": " << summary.solver.iterations
            << " iteration(s), relative residual " << std::scientific
            << std::setprecision(2) << summary.solver.relative_residual
            << std::defaultfloat << std::endl;
      // Equilibrium of the assembled system (with a layer there is no
      // separate matrix-free form): |K u - f| / |K u| over the free rows.
      {
        TrilinosWrappers::MPI::Vector ku(owned, communicator);
        system_matrix.vmult(ku, solution);
        const double scale = ku.l2_norm();
        ku -= system_rhs;
        summary.equilibrium_residual = scale > 0 ? ku.l2_norm() / scale : 0.;
      }
      pcout << "           equilibrium check (assembled system): "
            << "|F_int + F_ext| / |F_int| = " << std::scientific
            << std::setprecision(2) << summary.equilibrium_residual
            << std::defaultfloat << std::endl;

      // Body displacements back to the DoF numbering, surface ones aside.
      TrilinosWrappers::MPI::Vector body(owned_dofs, communicator);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          body[nodes[i].dofs[c]] =
            solution[layer_operator.unknown_index(nodes[i], c)];
      body.compress(VectorOperation::insert);
      displacement.reinit(owned_dofs, nodes.relevant_dofs(), communicator);
      displacement = body;
      surface_displacement.clear();
      for (const auto &node : layer_operator.owned_surface_nodes())
        {
          Tensor<1, dim> u;
          for (unsigned int c = 0; c < dim; ++c)
            u[c] = solution[node.first_unknown + c];
          surface_displacement.push_back(u);
        }
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::solve_matrix_free()
    {
      using VectorType = LinearAlgebra::distributed::Vector<double>;
      summary.n_unknowns    = dof_handler.n_dofs();
      const IndexSet &owned = dof_handler.locally_owned_dofs();
      VectorType      load_vector, rhs, prescribed, solution;
      {
        TimerOutput::Scope scope(timer, "assembly");
        boundary_conditions.make_constraints(dof_handler,
                                             nodes,
                                             horizon,
                                             constraints);
        load.reinit(owned, communicator);
        boundary_conditions.add_load(dof_handler, nodes, constraints, load);
        constrained_operator.initialize(bond_operator, constraints);
        constrained_operator.initialize_dof_vector(load_vector);
        for (const auto dof : owned)
          load_vector[dof] = load[dof];
        constrained_operator.lift(load_vector, rhs, prescribed);
      }
      summary.n_constrained_nodes = Utilities::MPI::sum(
        boundary_conditions.n_constrained_nodes(nodes, constraints),
        communicator);
      const unsigned int n_stencil =
        Utilities::MPI::sum(bond_operator.n_stencil_nodes(), communicator);
      const std::size_t visits =
        Utilities::MPI::sum(bond_operator.n_bond_visits(), communicator);
      const double operator_mb =
        Utilities::MPI::sum(bond_operator.memory_consumption() / 1048576.,
                            communicator);
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time()
            << " s] matrix-free operator: " << dof_handler.n_dofs()
            << " DoFs, " << n_stencil << " nodes on the shared stencil, "
            << summary.n_nodes - n_stencil << " on lists, "
            << summary.n_constrained_nodes << " nodes in Dirichlet layers; "
            << visits << " bond visits per application, "
            << std::setprecision(1) << operator_mb << " MB, "
            << MultithreadInfo::n_threads() << " thread(s) per process"
            << std::defaultfloat << std::endl;

      std::vector<std::vector<bool>> constant_modes;
      if (linear_solver.preconditioner_name() == "local elasticity")
        {
          TimerOutput::Scope scope(timer, "preconditioner setup");
          Operators::LocalElasticityOperator<dim>::assemble(
            nodes, neighbor_lists.lattice(), *model, constraints, local_matrix);
          DoFTools::extract_constant_modes(dof_handler,
                                           ComponentMask(dim, true),
                                           constant_modes);
        }
      constrained_operator.initialize_dof_vector(solution);
      {
        TimerOutput::Scope scope(timer, "solve");
        summary.solver = linear_solver.solve(constrained_operator,
                                             solution,
                                             rhs,
                                             &local_matrix,
                                             constant_modes);
      }
      solution += prescribed;
      solution.update_ghost_values();
      pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
            << wall_clock.wall_time() << " s] solved with "
            << summary.solver.method << ": " << summary.solver.iterations
            << " iteration(s), relative residual " << std::scientific
            << std::setprecision(2) << summary.solver.relative_residual
            << std::defaultfloat << std::endl;

      // Equilibrium with the matrix-free forces at every free DoF.
      VectorType internal;
      bond_operator.initialize_dof_vector(internal);
      bond_operator.apply(solution, internal);
      double free_residual2 = 0, internal2 = 0;
      for (unsigned int k = 0; k < internal.locally_owned_size(); ++k)
        {
          internal2 += std::pow(internal.local_element(k), 2);
          if (!constrained_operator.is_prescribed(k))
            free_residual2 += std::pow(internal.local_element(k) +
                                         load_vector.local_element(k),
                                       2);
        }
      free_residual2 = Utilities::MPI::sum(free_residual2, communicator);
      internal2      = Utilities::MPI::sum(internal2, communicator);
      summary.equilibrium_residual =
        internal2 > 0 ? std::sqrt(free_residual2 / internal2) : 0.;
      pcout << "           equilibrium check (matrix-free forces): "
            << "|F_int + F_ext| / |F_int| = " << std::scientific
            << std::setprecision(2) << summary.equilibrium_residual
            << std::defaultfloat << std::endl;

      TrilinosWrappers::MPI::Vector owned_solution(owned, communicator);
      for (const auto dof : owned)
        owned_solution[dof] = solution[dof];
      owned_solution.compress(VectorOperation::insert);
      displacement.reinit(owned, nodes.relevant_dofs(), communicator);
      displacement = owned_solution;
    }


    template <int dim>
    void
    QuasiStaticSimulation<dim>::assemble_and_solve()
    {
      if (treatment->uses_fictitious_layer())
        {
          AssertThrow(!linear_solver.is_matrix_free(),
                      ExcInvalidInput(
                        "Linear solver/Operator",
                        "matrix-free",
                        "the boundary treatment '" + treatment_name +
                          "' is available with 'Operator = assembled' only "
                          "so far; set it, or use 'Boundary "
                          "treatment/Treatment = none'"));
          assemble_and_solve_with_layer();
          return;
        }
      if (linear_solver.is_matrix_free())
        {
          solve_matrix_free();
          return;
        }
      summary.n_unknowns = dof_handler.n_dofs();
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
      const unsigned int         n_owned = nodes.n_owned();
      const bool                 layer   = treatment->uses_fictitious_layer();
      std::vector<IO::NodeField> fields  = {{"node_volume", {}},
                                            {"mpi_rank", {}},
                                            {"constrained", {}}};
      const double rank = Utilities::MPI::this_mpi_process(communicator);
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          fields[0].values.push_back(nodes[i].volume());
          fields[1].values.push_back(rank);
          bool constrained = false;
          if (!(layer && treatment->uses_surface_nodes()))
            for (const auto dof : nodes[i].dofs)
              constrained = constrained || constraints.is_constrained(dof);
          fields[2].values.push_back(constrained);
        }
      if (!layer)
        {
          // Quantities of the operator without a layer.
          std::vector<double> dilatation;
          const bool          matrix_free = linear_solver.is_matrix_free();
          if (matrix_free)
            {
              LinearAlgebra::distributed::Vector<double> u;
              bond_operator.initialize_dof_vector(u);
              for (const auto dof : dof_handler.locally_owned_dofs())
                u[dof] = displacement[dof];
              u.update_ghost_values();
              bond_operator.compute_dilatation(u, dilatation);
            }
          else
            pd_operator.compute_dilatation(displacement, dilatation);
          const auto &weighted_volumes = matrix_free ?
                                           bond_operator.weighted_volumes() :
                                           pd_operator.weighted_volumes();
          IO::NodeField theta{"dilatation", {}}, m{"weighted_volume", {}},
            neighbours{"n_neighbors", {}};
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              theta.values.push_back(dilatation[i]);
              m.values.push_back(weighted_volumes[i]);
              neighbours.values.push_back(neighbor_lists.n_bonds(i));
            }
          fields.insert(fields.begin(), {theta, m, neighbours});
        }

      if (compare_with_analytical)
        {
          IO::NodeField  error{"displacement_error", {}};
          IO::NodeField  normalized{"normalized_error", {}};
          Vector<double> exact(dim);
          double         e2 = 0, u2 = 0, e_max = 0, u_max = 0;
          // Largest analytical magnitude of each component (Eq. 38).
          Tensor<1, dim> component_max;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(nodes[i].location, exact);
              for (unsigned int c = 0; c < dim; ++c)
                component_max[c] =
                  std::max(component_max[c], std::abs(exact[c]));
            }
          for (unsigned int c = 0; c < dim; ++c)
            component_max[c] =
              Utilities::MPI::max(component_max[c], communicator);
          double normalized_max = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(nodes[i].location, exact);
              double e = 0, u = 0, n2 = 0;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const double diff =
                    displacement[nodes[i].dofs[c]] - exact[c];
                  e += diff * diff;
                  u += exact[c] * exact[c];
                  if (component_max[c] > 0)
                    n2 += std::pow(diff / component_max[c], 2);
                }
              e2 += nodes[i].volume() * e;
              u2 += nodes[i].volume() * u;
              e_max = std::max(e_max, std::sqrt(e));
              u_max = std::max(u_max, std::sqrt(u));
              normalized_max = std::max(normalized_max, std::sqrt(n2));
              error.values.push_back(std::sqrt(e));
              normalized.values.push_back(std::sqrt(n2));
            }
          summary.errors.max_normalized =
            Utilities::MPI::max(normalized_max, communicator);
          if (!node_data_file.empty())
            write_node_data(component_max);
          fields.push_back(normalized);
          // Surface nodes: the same measure at the face centres.
          if (layer && treatment->uses_surface_nodes())
            {
              double surface_max = 0;
              const auto &surface = layer_operator.owned_surface_nodes();
              for (unsigned int k = 0; k < surface.size(); ++k)
                {
                  analytical_solution->vector_value(surface[k].location, exact);
                  double n2 = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    if (component_max[c] > 0)
                      n2 += std::pow((surface_displacement[k][c] - exact[c]) /
                                       component_max[c],
                                     2);
                  surface_max = std::max(surface_max, std::sqrt(n2));
                }
              surface_max = Utilities::MPI::max(surface_max, communicator);
              pcout << "           surface nodes: largest normalized error "
                    << std::scientific << std::setprecision(3) << surface_max
                    << std::defaultfloat << std::endl;
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
                << ", normalized max (Eq. 38) "
                << summary.errors.max_normalized << std::defaultfloat
                << std::endl;
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
    void
    QuasiStaticSimulation<dim>::write_node_data(
      const Tensor<1, dim> &component_max) const
    {
      // Rows: kind (0 body, 1 surface), x, u, exact, normalized error.
      std::vector<double> rows;
      Vector<double>      exact(dim);
      const auto add = [&](const int kind, const Point<dim> &x,
                           const Tensor<1, dim> &u) {
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
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          Tensor<1, dim> u;
          for (unsigned int c = 0; c < dim; ++c)
            u[c] = displacement[nodes[i].dofs[c]];
          add(0, nodes[i].location, u);
        }
      if (treatment->uses_fictitious_layer() && treatment->uses_surface_nodes())
        {
          const auto &surface = layer_operator.owned_surface_nodes();
          for (unsigned int k = 0; k < surface.size(); ++k)
            add(1, surface[k].location, surface_displacement[k]);
        }
      const auto all = Utilities::MPI::gather(communicator, rows, 0);
      if (Utilities::MPI::this_mpi_process(communicator) != 0)
        return;
      std::ofstream out(node_data_file);
      AssertThrow(out,
                  ExcInvalidInput("Output/Node data file",
                                  node_data_file,
                                  "the file cannot be written; check the "
                                  "directory"));
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
    }


    template <int dim>
    RunSummary
    QuasiStaticSimulation<dim>::run()
    {
      wall_clock.restart();
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
              }
        throw_on_any_rank(error, communicator);
      }
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
                   "time_total,peak_memory_mb,treatment,taylor_order,"
                   "n_unknowns,n_surface_nodes,n_fictitious_nodes,"
                   "max_normalized_error,operator,preconditioner,"
                   "time_preconditioner,n_threads\n";
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
              << ',' << t("total") << ',' << summary.peak_memory_mb << ",\""
              << summary.treatment << "\"," << summary.taylor_order << ','
              << summary.n_unknowns << ',' << summary.n_surface_nodes << ','
              << summary.n_fictitious_nodes << ','
              << (summary.has_errors ? to_string(summary.errors.max_normalized) :
                                       "")
              << ",\"" << (linear_solver.is_matrix_free() ? "matrix-free" : "assembled")
              << "\",\"" << linear_solver.preconditioner_name() << "\","
              << t("preconditioner setup") << ',' << MultithreadInfo::n_threads()
              << '\n';
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
