#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/operators/local_elasticity_operator.h>
#include <perideal/problems/quasi_static.h>

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
    namespace
    {
      /**
       * What the phases of the quasi-static problem read from the
       * simulator, gathered once per phase.
       */
      template <int dim>
      struct Context
      {
        const MPI_Comm                                   communicator;
        ConditionalOStream                              &pcout;
        TimerOutput                                     &timer;
        RunSummary                                      &summary;
        const DoFHandler<dim>                           &dof_handler;
        const parallel::distributed::Triangulation<dim> &triangulation;
        const Discretization::NodeSet<dim>              &nodes;
        const Discretization::NeighborList<dim>         &neighbor_lists;
        const Models::Model<dim>                        &model;
        const double                                     horizon;
        const Boundary::BoundaryConditions<dim>         &boundary_conditions;
        const Boundary::BoundaryTreatment               &treatment;
        const std::string                               &treatment_name;
        const Solvers::LinearSolver                     &linear_solver;
        const Functions::ParsedFunction<dim>            *analytical_solution;
        const IO::SolutionOutput<dim>                   &output;
        const std::string                               &node_data_file;
      };

      template <int dim>
      Context<dim>
      context_of(Simulator<dim> &s)
      {
        return {s.get_communicator(),
                s.get_pcout(),
                s.get_timer(),
                s.get_summary(),
                s.get_dof_handler(),
                s.get_triangulation(),
                s.get_nodes(),
                s.get_neighbor_lists(),
                s.get_model(),
                s.get_horizon(),
                s.get_boundary_conditions(),
                s.get_boundary_treatment(),
                s.get_boundary_treatment_name(),
                s.get_linear_solver(),
                s.get_analytical_solution(),
                s.get_output(),
                s.get_node_data_file()};
      }
    } // namespace


    template <int dim>
    void
    QuasiStatic<dim>::declare_parameters(ParameterHandler &)
    {}


    template <int dim>
    void
    QuasiStatic<dim>::parse_parameters(ParameterHandler &)
    {}


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
      const auto &name = simulator.get_boundary_treatment_name();
      AssertThrow(
        !simulator.get_boundary_treatment().uses_fictitious_layer() ||
          !simulator.get_linear_solver().is_matrix_free(),
        ExcInvalidInput("Linear solver/Operator",
                        "matrix-free",
                        "the boundary treatment '" + name +
                          "' is available with 'Operator = assembled' only so "
                          "far; set it, or use 'Boundary treatment/Treatment = "
                          "none'"));
    }


    template <int dim>
    void
    QuasiStatic<dim>::run(Simulator<dim> &simulator)
    {
      if (simulator.get_boundary_treatment().uses_fictitious_layer())
        setup_layer_operator(simulator);
      else
        {
          // Both operators evaluate full neighbourhoods with the shared
          // stencil: their lists need not be stored.
          simulator.setup_neighbor_lists(false);
          TimerOutput::Scope scope(simulator.get_timer(), "operator setup");
          const auto        &nodes = simulator.get_nodes();
          const auto        &lists = simulator.get_neighbor_lists();
          bond_state.reinit(nodes, lists);
          bond_operator.reinit(nodes,
                               lists,
                               simulator.get_model(),
                               simulator.get_horizon(),
                               &bond_state);
        }
      assemble_and_solve(simulator);
      postprocess(simulator);
    }


    template <int dim>
    void
    QuasiStatic<dim>::setup_layer_operator(Simulator<dim> &simulator)
    {
      auto       &summary   = simulator.get_summary();
      const auto &treatment = simulator.get_boundary_treatment();
      {
        TimerOutput::Scope scope(simulator.get_timer(), "operator setup");
        layer_operator.reinit(simulator.get_dof_handler(),
                              simulator.get_nodes(),
                              simulator.get_model(),
                              simulator.get_horizon(),
                              simulator.get_partial_volume(),
                              treatment.uses_surface_nodes(),
                              treatment.taylor_order());
      }
      summary.n_bonds =
        summary.n_nodes * layer_operator.n_neighbours_per_node();
      summary.n_surface_nodes    = layer_operator.n_surface_nodes();
      summary.n_fictitious_nodes = layer_operator.n_fictitious_nodes();
      std::ostringstream line;
      line << "nodes: " << summary.n_nodes << " in the body, "
           << summary.n_fictitious_nodes << " fictitious, "
           << summary.n_surface_nodes << " surface nodes; "
           << layer_operator.n_neighbours_per_node()
           << " bonds per node, weights by '"
           << simulator.get_partial_volume_name() << "'; boundary treatment '"
           << simulator.get_boundary_treatment_name() << "', Taylor order "
           << treatment.taylor_order();
      simulator.print_progress(line.str());
    }


    template <int dim>
    void
    QuasiStatic<dim>::assemble_and_solve_with_layer(Simulator<dim> &simulator)
    {
      const auto      ctx        = context_of(simulator);
      const IndexSet &owned_dofs = ctx.dof_handler.locally_owned_dofs();
      const IndexSet &owned      = layer_operator.owned_unknowns();
      std::map<types::global_dof_index, double> prescribed;
      {
        TimerOutput::Scope scope(ctx.timer, "assembly");
        system_rhs.reinit(owned, ctx.communicator);
        ctx.boundary_conditions.check_boundary_ids(ctx.triangulation);
        if (ctx.treatment.uses_surface_nodes())
          {
            // Body force on the body ctx.nodes, boundary conditions on the
            // surface ctx.nodes: Dirichlet values where prescribed, the
            // traction times the face area in the force-flux equation
            // otherwise.
            for (unsigned int i = 0; i < ctx.nodes.n_owned(); ++i)
              {
                const Tensor<1, dim> b =
                  ctx.boundary_conditions.body_force_value(
                    ctx.nodes[i].location);
                for (unsigned int c = 0; c < dim; ++c)
                  system_rhs[layer_operator.unknown_index(ctx.nodes[i], c)] =
                    ctx.nodes[i].volume() * b[c];
              }
            const auto &mask =
              ctx.boundary_conditions.dirichlet_component_mask();
            for (const auto &node : layer_operator.owned_surface_nodes())
              {
                const bool dirichlet =
                  ctx.boundary_conditions.is_dirichlet_boundary(
                    node.boundary_id);
                const Tensor<1, dim> g =
                  dirichlet ?
                    ctx.boundary_conditions.dirichlet_value(node.location) :
                    Tensor<1, dim>();
                const Tensor<1, dim> p =
                  ctx.boundary_conditions.is_traction_boundary(
                    node.boundary_id) ?
                    ctx.boundary_conditions.traction_value(node.location,
                                                           node.normal()) :
                    Tensor<1, dim>();
                for (unsigned int c = 0; c < dim; ++c)
                  if (dirichlet && mask[c])
                    prescribed[node.first_unknown + c] = g[c];
                  else
                    system_rhs[node.first_unknown + c] = node.area * p[c];
              }
            ctx.summary.n_constrained_nodes =
              Utilities::MPI::sum(static_cast<unsigned int>(prescribed.size()),
                                  ctx.communicator);
          }
        else
          {
            // A completed neighbourhood makes every node a bulk node: a
            // homogeneous strain then costs nothing anywhere, and a free or
            // loaded face has no equation that could hold it. Only bodies
            // whose every face is fully prescribed are well posed.
            bool all_prescribed = true;
            for (const bool c :
                 ctx.boundary_conditions.dirichlet_component_mask())
              all_prescribed = all_prescribed && c;
            for (const auto &cell : ctx.triangulation.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int f : cell->face_indices())
                  if (cell->at_boundary(f) &&
                      !ctx.boundary_conditions.is_dirichlet_boundary(
                        cell->face(f)->boundary_id()))
                    all_prescribed = false;
            AssertThrow(
              Utilities::MPI::min(all_prescribed ? 1 : 0, ctx.communicator) ==
                1,
              ExcInvalidInput(
                "Boundary treatment/Treatment",
                ctx.treatment_name,
                "a fictitious layer alone cannot carry free or loaded faces "
                "(with completed neighbourhoods homogeneous strains cost no "
                "energy, so the system is singular): list every boundary id "
                "under 'Dirichlet boundary ids' with all components, or use "
                "'surface nodes', whose force-flux equations carry "
                "tractions and free faces"));
            // Conditions as without ctx.treatment: Dirichlet layers. The
            // unknowns are the DoFs.
            ctx.boundary_conditions.make_constraints(ctx.dof_handler,
                                                     ctx.nodes,
                                                     ctx.horizon,
                                                     constraints);
            load.reinit(owned_dofs, ctx.communicator);
            ctx.boundary_conditions.add_load(ctx.dof_handler,
                                             ctx.nodes,
                                             constraints,
                                             load);
            for (const auto dof : owned_dofs)
              if (constraints.is_constrained(dof))
                prescribed[dof] = constraints.get_inhomogeneity(dof);
              else
                system_rhs[dof] = load[dof];
            ctx.summary.n_constrained_nodes = Utilities::MPI::sum(
              ctx.boundary_conditions.n_constrained_nodes(ctx.nodes,
                                                          constraints),
              ctx.communicator);
          }
        system_rhs.compress(VectorOperation::insert);
        layer_operator.assemble(prescribed, system_matrix, system_rhs);
      }
      ctx.summary.n_unknowns = owned.size();
      ctx.summary.n_nonzeros = system_matrix.n_nonzero_elements();
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed()
                << " s] assembled: " << ctx.summary.n_unknowns << " unknowns, "
                << ctx.summary.n_nonzeros << " nonzeros, "
                << ctx.summary.n_constrained_nodes
                << (ctx.treatment.uses_surface_nodes() ?
                      " prescribed surface-node components" :
                      " nodes in Dirichlet layers")
                << " (non-symmetric)" << std::endl;

      TrilinosWrappers::MPI::Vector solution(owned, ctx.communicator);
      {
        TimerOutput::Scope scope(ctx.timer, "solve");
        // Rigid translations for AMG: the component of each unknown.
        std::vector<std::vector<bool>> constant_modes(
          dim,
          std::vector<bool>(owned.n_elements(), false));
        for (unsigned int i = 0; i < ctx.nodes.n_owned(); ++i)
          for (unsigned int c = 0; c < dim; ++c)
            constant_modes[c][owned.index_within_set(
              layer_operator.unknown_index(ctx.nodes[i], c))] = true;
        for (const auto &node : layer_operator.owned_surface_nodes())
          for (unsigned int c = 0; c < dim; ++c)
            constant_modes[c][owned.index_within_set(node.first_unknown + c)] =
              true;
        ctx.summary.solver = ctx.linear_solver.solve(system_matrix,
                                                     solution,
                                                     system_rhs,
                                                     constant_modes,
                                                     false);
      }
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed() << " s] solved with "
                << ctx.summary.solver.method << ": "
                << ctx.summary.solver.iterations
                << " iteration(s), relative residual " << std::scientific
                << std::setprecision(2) << ctx.summary.solver.relative_residual
                << std::defaultfloat << std::endl;
      // Equilibrium of the assembled system (with a layer there is no
      // separate matrix-free form): |K u - f| / |K u| over the free rows.
      {
        TrilinosWrappers::MPI::Vector ku(owned, ctx.communicator);
        system_matrix.vmult(ku, solution);
        const double scale = ku.l2_norm();
        ku -= system_rhs;
        ctx.summary.equilibrium_residual =
          scale > 0 ? ku.l2_norm() / scale : 0.;
      }
      ctx.pcout << "           equilibrium check (assembled system): "
                << "|F_int + F_ext| / |F_int| = " << std::scientific
                << std::setprecision(2) << ctx.summary.equilibrium_residual
                << std::defaultfloat << std::endl;

      // Body displacements back to the DoF numbering, surface ones aside.
      TrilinosWrappers::MPI::Vector body(owned_dofs, ctx.communicator);
      for (unsigned int i = 0; i < ctx.nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          body[ctx.nodes[i].dofs[c]] =
            solution[layer_operator.unknown_index(ctx.nodes[i], c)];
      body.compress(VectorOperation::insert);
      displacement.reinit(owned_dofs,
                          ctx.nodes.relevant_dofs(),
                          ctx.communicator);
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
    QuasiStatic<dim>::make_constraints_and_load(Simulator<dim> &simulator)
    {
      const auto ctx = context_of(simulator);
      ctx.boundary_conditions.make_constraints(ctx.dof_handler,
                                               ctx.nodes,
                                               ctx.horizon,
                                               constraints);
      check_rigid_motions(simulator);
      load.reinit(ctx.dof_handler.locally_owned_dofs(), ctx.communicator);
      ctx.boundary_conditions.add_load(ctx.dof_handler,
                                       ctx.nodes,
                                       constraints,
                                       load);
    }


    template <int dim>
    void
    QuasiStatic<dim>::solve_matrix_free(Simulator<dim> &simulator)
    {
      const auto ctx         = context_of(simulator);
      using VectorType       = LinearAlgebra::distributed::Vector<double>;
      ctx.summary.n_unknowns = ctx.dof_handler.n_dofs();
      const IndexSet &owned  = ctx.dof_handler.locally_owned_dofs();
      VectorType      load_vector, rhs, prescribed, solution;
      {
        TimerOutput::Scope scope(ctx.timer, "assembly");
        make_constraints_and_load(simulator);
        constrained_operator.initialize(bond_operator, constraints);
        constrained_operator.initialize_dof_vector(load_vector);
        for (const auto dof : owned)
          load_vector[dof] = load[dof];
        constrained_operator.lift(load_vector, rhs, prescribed);
      }
      ctx.summary.n_constrained_nodes = Utilities::MPI::sum(
        ctx.boundary_conditions.n_constrained_nodes(ctx.nodes, constraints),
        ctx.communicator);
      const unsigned int n_stencil =
        Utilities::MPI::sum(bond_operator.n_stencil_nodes(), ctx.communicator);
      const std::size_t visits =
        Utilities::MPI::sum(bond_operator.n_bond_visits(), ctx.communicator);
      const double operator_mb =
        Utilities::MPI::sum(bond_operator.memory_consumption() / 1048576.,
                            ctx.communicator);
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed()
                << " s] matrix-free operator: " << ctx.dof_handler.n_dofs()
                << " DoFs, " << n_stencil << " nodes on the shared stencil, "
                << ctx.summary.n_nodes - n_stencil << " on lists, "
                << ctx.summary.n_constrained_nodes
                << " nodes in Dirichlet layers; " << visits
                << " bond visits per application, " << std::setprecision(1)
                << operator_mb << " MB, " << MultithreadInfo::n_threads()
                << " thread(s) per process" << std::defaultfloat << std::endl;

      std::vector<std::vector<bool>> constant_modes;
      if (ctx.linear_solver.preconditioner_name() == "local elasticity")
        {
          TimerOutput::Scope scope(ctx.timer, "preconditioner setup");
          Operators::LocalElasticityOperator<dim>::assemble(
            ctx.nodes,
            ctx.neighbor_lists.lattice(),
            ctx.model,
            constraints,
            local_matrix);
          DoFTools::extract_constant_modes(ctx.dof_handler,
                                           ComponentMask(dim, true),
                                           constant_modes);
        }
      constrained_operator.initialize_dof_vector(solution);
      {
        TimerOutput::Scope scope(ctx.timer, "solve");
        ctx.summary.solver = ctx.linear_solver.solve(constrained_operator,
                                                     solution,
                                                     rhs,
                                                     &local_matrix,
                                                     constant_modes);
      }
      solution += prescribed;
      solution.update_ghost_values();
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed() << " s] solved with "
                << ctx.summary.solver.method << ": "
                << ctx.summary.solver.iterations
                << " iteration(s), relative residual " << std::scientific
                << std::setprecision(2) << ctx.summary.solver.relative_residual
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
            free_residual2 +=
              std::pow(internal.local_element(k) + load_vector.local_element(k),
                       2);
        }
      free_residual2 = Utilities::MPI::sum(free_residual2, ctx.communicator);
      internal2      = Utilities::MPI::sum(internal2, ctx.communicator);
      ctx.summary.equilibrium_residual =
        internal2 > 0 ? std::sqrt(free_residual2 / internal2) : 0.;
      ctx.pcout << "           equilibrium check (matrix-free forces): "
                << "|F_int + F_ext| / |F_int| = " << std::scientific
                << std::setprecision(2) << ctx.summary.equilibrium_residual
                << std::defaultfloat << std::endl;

      TrilinosWrappers::MPI::Vector owned_solution(owned, ctx.communicator);
      for (const auto dof : owned)
        owned_solution[dof] = solution[dof];
      owned_solution.compress(VectorOperation::insert);
      displacement.reinit(owned, ctx.nodes.relevant_dofs(), ctx.communicator);
      displacement = owned_solution;
    }


    template <int dim>
    void
    QuasiStatic<dim>::assemble_and_solve(Simulator<dim> &simulator)
    {
      const auto ctx = context_of(simulator);
      if (ctx.treatment.uses_fictitious_layer())
        {
          assemble_and_solve_with_layer(simulator);
          return;
        }
      if (ctx.linear_solver.is_matrix_free())
        {
          solve_matrix_free(simulator);
          return;
        }
      ctx.summary.n_unknowns   = ctx.dof_handler.n_dofs();
      const IndexSet &owned    = ctx.dof_handler.locally_owned_dofs();
      const IndexSet  relevant = ctx.nodes.relevant_dofs();
      {
        TimerOutput::Scope scope(ctx.timer, "assembly");
        make_constraints_and_load(simulator);
        system_rhs = load;
        bond_operator.assemble(system_matrix, &constraints, &system_rhs);
      }
      ctx.summary.n_constrained_nodes = Utilities::MPI::sum(
        ctx.boundary_conditions.n_constrained_nodes(ctx.nodes, constraints),
        ctx.communicator);
      ctx.summary.n_nonzeros = system_matrix.n_nonzero_elements();
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed()
                << " s] assembled: " << ctx.dof_handler.n_dofs() << " DoFs, "
                << ctx.summary.n_nonzeros << " nonzeros, "
                << ctx.summary.n_constrained_nodes
                << " nodes in Dirichlet layers" << std::endl;

      // Symmetry of the system, measured: x^T A y against y^T A x.
      TrilinosWrappers::MPI::Vector x(owned, ctx.communicator),
        y(owned, ctx.communicator), ax(owned, ctx.communicator),
        ay(owned, ctx.communicator);
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

      TrilinosWrappers::MPI::Vector solution(owned, ctx.communicator);
      {
        TimerOutput::Scope             scope(ctx.timer, "solve");
        std::vector<std::vector<bool>> constant_modes;
        DoFTools::extract_constant_modes(ctx.dof_handler,
                                         ComponentMask(dim, true),
                                         constant_modes);
        ctx.summary.solver = ctx.linear_solver.solve(system_matrix,
                                                     solution,
                                                     system_rhs,
                                                     constant_modes,
                                                     symmetric);
        constraints.distribute(solution);
      }
      displacement.reinit(owned, relevant, ctx.communicator);
      displacement = solution;
      ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                << simulator.elapsed() << " s] solved with "
                << ctx.summary.solver.method << ": "
                << ctx.summary.solver.iterations
                << " iteration(s), relative residual " << std::scientific
                << std::setprecision(2) << ctx.summary.solver.relative_residual
                << std::defaultfloat << (symmetric ? "" : " (non-symmetric)")
                << std::endl;

      // Equilibrium with the matrix-free forces: F_int(u) + F_ext = 0 at
      // every free DoF.
      // (The apply() loops of BondOperator, not its assembly.)
      LinearAlgebra::distributed::Vector<double> u, internal;
      bond_operator.initialize_dof_vector(u);
      bond_operator.initialize_dof_vector(internal);
      for (const auto dof : owned)
        u[dof] = displacement[dof];
      u.update_ghost_values();
      bond_operator.apply(u, internal);
      double free_residual2 = 0;
      for (const auto dof : owned)
        if (!constraints.is_constrained(dof))
          free_residual2 += std::pow(internal[dof] + load[dof], 2);
      const double scale = internal.l2_norm();
      free_residual2 = Utilities::MPI::sum(free_residual2, ctx.communicator);
      ctx.summary.equilibrium_residual =
        scale > 0 ? std::sqrt(free_residual2) / scale : 0.;
      ctx.pcout << "           equilibrium check (matrix-free forces): "
                << "|F_int + F_ext| / |F_int| = " << std::scientific
                << std::setprecision(2) << ctx.summary.equilibrium_residual
                << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    QuasiStatic<dim>::postprocess(Simulator<dim> &simulator)
    {
      const auto                 ctx     = context_of(simulator);
      const unsigned int         n_owned = ctx.nodes.n_owned();
      const bool                 layer  = ctx.treatment.uses_fictitious_layer();
      std::vector<IO::NodeField> fields = {{"node_volume", {}},
                                           {"mpi_rank", {}},
                                           {"constrained", {}}};
      const double rank = Utilities::MPI::this_mpi_process(ctx.communicator);
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          fields[0].values.push_back(ctx.nodes[i].volume());
          fields[1].values.push_back(rank);
          bool constrained = false;
          if (!(layer && ctx.treatment.uses_surface_nodes()))
            for (const auto dof : ctx.nodes[i].dofs)
              constrained = constrained || constraints.is_constrained(dof);
          fields[2].values.push_back(constrained);
        }
      if (!layer)
        {
          // Quantities of the operator without a layer.
          std::vector<double>                        dilatation;
          LinearAlgebra::distributed::Vector<double> u;
          bond_operator.initialize_dof_vector(u);
          for (const auto dof : ctx.dof_handler.locally_owned_dofs())
            u[dof] = displacement[dof];
          u.update_ghost_values();
          bond_operator.compute_dilatation(u, dilatation);
          const auto &weighted_volumes = bond_operator.weighted_volumes();
          IO::NodeField theta{"dilatation", {}}, m{"weighted_volume", {}},
            neighbours{"n_neighbors", {}};
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              theta.values.push_back(dilatation[i]);
              m.values.push_back(weighted_volumes[i]);
              neighbours.values.push_back(ctx.neighbor_lists.n_bonds(i));
            }
          fields.insert(fields.begin(), {theta, m, neighbours});
        }

      if (ctx.analytical_solution != nullptr)
        {
          IO::NodeField  error{"displacement_error", {}};
          IO::NodeField  normalized{"normalized_error", {}};
          Vector<double> exact(dim);
          double         e2 = 0, u2 = 0, e_max = 0, u_max = 0;
          // Largest analytical magnitude of each component (Eq. 38).
          Tensor<1, dim> component_max;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              ctx.analytical_solution->vector_value(ctx.nodes[i].location,
                                                    exact);
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
              ctx.analytical_solution->vector_value(ctx.nodes[i].location,
                                                    exact);
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
          if (!ctx.node_data_file.empty())
            write_node_data(simulator, component_max);
          fields.push_back(normalized);
          // Surface ctx.nodes: the same measure at the face centres.
          if (layer && ctx.treatment.uses_surface_nodes())
            {
              double      surface_max = 0;
              const auto &surface     = layer_operator.owned_surface_nodes();
              for (unsigned int k = 0; k < surface.size(); ++k)
                {
                  ctx.analytical_solution->vector_value(surface[k].location,
                                                        exact);
                  double n2 = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    if (component_max[c] > 0)
                      n2 += std::pow((surface_displacement[k][c] - exact[c]) /
                                       component_max[c],
                                     2);
                  surface_max = std::max(surface_max, std::sqrt(n2));
                }
              surface_max = Utilities::MPI::max(surface_max, ctx.communicator);
              ctx.pcout << "           surface nodes: largest normalized error "
                        << std::scientific << std::setprecision(3)
                        << surface_max << std::defaultfloat << std::endl;
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

      TimerOutput::Scope scope(ctx.timer, "output");
      const std::string  record =
        ctx.output.write(ctx.dof_handler, ctx.nodes, displacement, fields);
      if (!record.empty())
        ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                  << simulator.elapsed() << " s] wrote "
                  << ctx.output.directory() << "/" << record
                  << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    QuasiStatic<dim>::write_node_data(Simulator<dim>       &simulator,
                                      const Tensor<1, dim> &component_max) const
    {
      const auto ctx = context_of(simulator);
      // Rows: kind (0 body, 1 surface), x, u, exact, normalized error.
      std::vector<double> rows;
      Vector<double>      exact(dim);
      const auto          add =
        [&](const int kind, const Point<dim> &x, const Tensor<1, dim> &u) {
          ctx.analytical_solution->vector_value(x, exact);
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
      if (ctx.treatment.uses_fictitious_layer() &&
          ctx.treatment.uses_surface_nodes())
        {
          const auto &surface = layer_operator.owned_surface_nodes();
          for (unsigned int k = 0; k < surface.size(); ++k)
            add(1, surface[k].location, surface_displacement[k]);
        }
      const auto all = Utilities::MPI::gather(ctx.communicator, rows, 0);
      // Written by process 0 under a temporary name; the verdict is shared
      // so that a failure there does not leave the others waiting.
      std::string error;
      if (Utilities::MPI::this_mpi_process(ctx.communicator) == 0)
        error = write_then_rename(ctx.node_data_file, [&](std::ostream &out) {
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
                          "Invalid value '" + ctx.node_data_file +
                            "' for the parameter 'Output/Node data file': " +
                            error + ".",
                        ctx.communicator);
    }


    template <int dim>
    void
    QuasiStatic<dim>::check_rigid_motions(Simulator<dim> &simulator) const
    {
      // The rigid motions (translations, rotations about the body's centre
      // in units of its size) restricted to the prescribed DoFs: the Gram
      // matrix M^T M adds up over processes, and a (near) null vector is a
      // rigid motion that no Dirichlet condition holds. A direct solver
      // would return one of infinitely many solutions without complaint.
      const auto        &nodes   = simulator.get_nodes();
      const MPI_Comm     comm    = simulator.get_communicator();
      constexpr unsigned n_modes = dim * (dim + 1) / 2;
      Point<dim>         lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int d = 0; d < dim; ++d)
          {
            lower[d] = std::min(lower[d], nodes[i].location[d]);
            upper[d] = std::max(upper[d], nodes[i].location[d]);
          }
      double     size = 0;
      Point<dim> centre;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d]  = Utilities::MPI::min(lower[d], comm);
          upper[d]  = Utilities::MPI::max(upper[d], comm);
          centre[d] = 0.5 * (lower[d] + upper[d]);
          size      = std::max(size, upper[d] - lower[d]);
        }
      auto mode = [&](const unsigned int r,
                      const Point<dim>  &p,
                      const unsigned int c) -> double {
        if (r < dim)
          return r == c ? 1. : 0.;
        const Tensor<1, dim> x = (p - centre) / size;
        if constexpr (dim == 2)
          return c == 0 ? -x[1] : x[0];
        else
          {
            // Rotations about the x, y and z axes.
            const unsigned int a = r - dim, b = (a + 1) % 3, e = (a + 2) % 3;
            return c == b ? -x[e] : (c == e ? x[b] : 0.);
          }
      };
      std::vector<double> gram(n_modes * n_modes, 0.);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          if (constraints.is_constrained(nodes[i].dofs[c]))
            for (unsigned int p = 0; p < n_modes; ++p)
              for (unsigned int q = 0; q < n_modes; ++q)
                gram[p * n_modes + q] +=
                  mode(p, nodes[i].location, c) * mode(q, nodes[i].location, c);
      Utilities::MPI::sum(gram, comm, gram);
      LAPACKFullMatrix<double> matrix(n_modes, n_modes);
      for (unsigned int p = 0; p < n_modes; ++p)
        for (unsigned int q = 0; q < n_modes; ++q)
          matrix(p, q) = gram[p * n_modes + q];
      Vector<double>     eigenvalues;
      FullMatrix<double> eigenvectors;
      matrix.compute_eigenvalues_symmetric(-1.,
                                           1e300,
                                           0.,
                                           eigenvalues,
                                           eigenvectors);
      const double largest = eigenvalues.linfty_norm();
      const char  *axes[]  = {"x", "y", "z"};
      std::string  free_modes;
      for (unsigned int k = 0; k < eigenvalues.size(); ++k)
        if (!(eigenvalues[k] > 1e-10 * largest) || largest == 0)
          {
            unsigned int dominant = 0;
            for (unsigned int p = 1; p < n_modes; ++p)
              if (std::abs(eigenvectors(p, k)) >
                  std::abs(eigenvectors(dominant, k)))
                dominant = p;
            free_modes += std::string(free_modes.empty() ? "" : ", ") +
                          (dominant < dim ?
                             std::string("translation in ") + axes[dominant] :
                           dim == 2 ? std::string("rotation in the x-y plane") :
                                      std::string("rotation about ") +
                                        axes[dominant - dim]);
          }
      AssertThrow(
        free_modes.empty(),
        ExcInvalidInput(
          "Boundary conditions/Dirichlet boundary ids",
          simulator.get_boundary_conditions().dirichlet_ids_string(),
          "the Dirichlet layers leave a rigid motion free (" + free_modes +
            "), so the system is singular; prescribe the missing "
            "components ('Dirichlet components') or more boundaries"));
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
