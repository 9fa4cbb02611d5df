#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_tools.h>

#include <perideal/base/exceptions.h>
#include <perideal/boundary/layer_system.h>
#include <perideal/boundary/system_context.h>
#include <perideal/discretization/lattice.h>
#include <perideal/operators/local_elasticity_operator.h>

#include <iomanip>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  namespace Boundary
  {
    template <int dim>
    LayerSystem<dim>::LayerSystem(const std::string &treatment_name,
                                  const bool         with_surface_nodes,
                                  const unsigned int taylor_order)
      : treatment_name(treatment_name)
      , with_surface_nodes(with_surface_nodes)
      , taylor_order(taylor_order)
    {}


    template <int dim>
    void
    LayerSystem<dim>::check_input(
      const Solvers::LinearSolver &linear_solver) const
    {
      if (!linear_solver.is_matrix_free())
        return;
      // Without a matrix: the factored operator is not symmetric and has
      // no diagonal.
      linear_solver.check_form(Solvers::OperatorForm::layer,
                               false,
                               "the boundary treatment '" + treatment_name +
                                 "'");
    }


    template <int dim>
    bool
    LayerSystem<dim>::is_constrained(
      const Discretization::Node<dim> &node) const
    {
      // With surface nodes the conditions act on the surface nodes.
      if (with_surface_nodes)
        return false;
      for (const auto dof : node.dofs)
        if (constraints.is_constrained(dof))
          return true;
      return false;
    }


    template <int dim>
    std::vector<typename DiscreteSystem<dim>::ExtraNode>
    LayerSystem<dim>::extra_nodes() const
    {
      std::vector<typename DiscreteSystem<dim>::ExtraNode> extra;
      const auto &surface = layer_operator.owned_surface_nodes();
      for (unsigned int k = 0; k < surface_displacement.size(); ++k)
        extra.push_back({surface[k].location, surface_displacement[k]});
      return extra;
    }


    template <int dim>
    std::string
    LayerSystem<dim>::extra_nodes_name() const
    {
      return with_surface_nodes ? "surface nodes" : "";
    }


    template <int dim>
    void
    LayerSystem<dim>::setup(const SystemContext<dim> &context)
    {
      auto &summary = context.summary;
      {
        TimerOutput::Scope scope(context.timer, "operator setup");
        layer_operator.reinit(context.dof_handler,
                              context.nodes,
                              context.model,
                              context.horizon,
                              context.partial_volume,
                              with_surface_nodes,
                              taylor_order);
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
           << " bonds per node, weights by '" << context.partial_volume_name
           << "'; boundary treatment '" << context.treatment_name
           << "', Taylor order " << taylor_order;
      context.print_progress(line.str());
    }


    template <int dim>
    void
    LayerSystem<dim>::solve_linear(const SystemContext<dim>      &context,
                                   TrilinosWrappers::MPI::Vector &displacement)
    {
      const IndexSet &owned_dofs  = context.dof_handler.locally_owned_dofs();
      const IndexSet &owned       = layer_operator.owned_unknowns();
      const bool      matrix_free = context.linear_solver.is_matrix_free();
      std::map<types::global_dof_index, double> prescribed;
      {
        TimerOutput::Scope scope(context.timer, "assembly");
        system_rhs.reinit(owned, context.communicator);
        context.boundary_conditions.check_boundary_ids(context.triangulation);
        if (with_surface_nodes)
          {
            // Body force on the body nodes, boundary conditions on the
            // surface nodes: Dirichlet values where prescribed, the
            // traction times the face area in the force-flux equation
            // otherwise.
            for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
              {
                const Tensor<1, dim> b =
                  context.boundary_conditions.body_force_value(
                    context.nodes[i].location);
                for (unsigned int c = 0; c < dim; ++c)
                  system_rhs[layer_operator.unknown_index(context.nodes[i],
                                                          c)] =
                    context.nodes[i].volume() * b[c];
              }
            const auto &mask =
              context.boundary_conditions.dirichlet_component_mask();
            for (const auto &node : layer_operator.owned_surface_nodes())
              {
                const bool dirichlet =
                  context.boundary_conditions.is_dirichlet_boundary(
                    node.boundary_id);
                const Tensor<1, dim> g =
                  dirichlet ?
                    context.boundary_conditions.dirichlet_value(node.location) :
                    Tensor<1, dim>();
                const Tensor<1, dim> p =
                  context.boundary_conditions.is_traction_boundary(
                    node.boundary_id) ?
                    context.boundary_conditions.traction_value(node.location,
                                                               node.normal()) :
                    Tensor<1, dim>();
                for (unsigned int c = 0; c < dim; ++c)
                  if (dirichlet && mask[c])
                    prescribed[node.first_unknown + c] = g[c];
                  else
                    system_rhs[node.first_unknown + c] = node.area * p[c];
              }
            context.summary.n_constrained_nodes =
              Utilities::MPI::sum(static_cast<unsigned int>(prescribed.size()),
                                  context.communicator);
          }
        else
          {
            // A completed neighbourhood makes every node a bulk node: a
            // homogeneous strain then costs nothing anywhere, and a free or
            // loaded face has no equation that could hold it. Only bodies
            // whose every face is fully prescribed are well posed.
            bool all_prescribed = true;
            for (const bool c :
                 context.boundary_conditions.dirichlet_component_mask())
              all_prescribed = all_prescribed && c;
            for (const auto &cell :
                 context.triangulation.active_cell_iterators())
              if (cell->is_locally_owned())
                for (const unsigned int f : cell->face_indices())
                  if (cell->at_boundary(f) &&
                      !context.boundary_conditions.is_dirichlet_boundary(
                        cell->face(f)->boundary_id()))
                    all_prescribed = false;
            AssertThrow(
              Utilities::MPI::min(all_prescribed ? 1 : 0,
                                  context.communicator) == 1,
              ExcInvalidInput(
                "Boundary treatment/Treatment",
                context.treatment_name,
                "a fictitious layer alone cannot carry free or loaded faces "
                "(with completed neighbourhoods homogeneous strains cost no "
                "energy, so the system is singular): list every boundary id "
                "under 'Dirichlet boundary ids' with all components, or use "
                "'surface nodes', whose force-flux equations carry "
                "tractions and free faces"));
            // Conditions as without treatment: Dirichlet layers. The
            // unknowns are the DoFs.
            context.boundary_conditions.make_constraints(context.dof_handler,
                                                         context.nodes,
                                                         context.horizon,
                                                         constraints);
            load.reinit(owned_dofs, context.communicator);
            context.boundary_conditions.add_load(context.dof_handler,
                                                 context.nodes,
                                                 constraints,
                                                 load);
            for (const auto dof : owned_dofs)
              if (constraints.is_constrained(dof))
                prescribed[dof] = constraints.get_inhomogeneity(dof);
              else
                system_rhs[dof] = load[dof];
            context.summary.n_constrained_nodes = Utilities::MPI::sum(
              context.boundary_conditions.n_constrained_nodes(context.nodes,
                                                              constraints),
              context.communicator);
          }
        system_rhs.compress(VectorOperation::insert);
        load = system_rhs; // the external loads, before elimination
        if (matrix_free)
          layer_operator.build_factors();
        else
          layer_operator.assemble(prescribed, system_matrix, system_rhs);
      }
      context.summary.n_unknowns = owned.size();
      context.summary.n_nonzeros =
        matrix_free ? 0 : system_matrix.n_nonzero_elements();
      context.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                    << context.elapsed() << " s] "
                    << (matrix_free ?
                          "factored operator (no product matrix): " :
                          "assembled: ")
                    << context.summary.n_unknowns << " unknowns, "
                    << context.summary.n_nonzeros << " nonzeros, "
                    << context.summary.n_constrained_nodes
                    << (with_surface_nodes ?
                          " prescribed surface-node components" :
                          " nodes in Dirichlet layers")
                    << " (non-symmetric)" << std::endl;

      TrilinosWrappers::MPI::Vector solution(owned, context.communicator);
      if (matrix_free)
        solve_matrix_free(context, prescribed, solution);
      else
        {
          TimerOutput::Scope scope(context.timer, "solve");
          // Rigid translations for AMG: the component of each unknown.
          std::vector<std::vector<bool>> constant_modes(
            dim,
            std::vector<bool>(owned.n_elements(), false));
          for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
            for (unsigned int c = 0; c < dim; ++c)
              constant_modes[c][owned.index_within_set(
                layer_operator.unknown_index(context.nodes[i], c))] = true;
          for (const auto &node : layer_operator.owned_surface_nodes())
            for (unsigned int c = 0; c < dim; ++c)
              constant_modes[c]
                            [owned.index_within_set(node.first_unknown + c)] =
                              true;
          context.summary.solver = context.linear_solver.solve(system_matrix,
                                                               solution,
                                                               system_rhs,
                                                               constant_modes,
                                                               false);
        }
      print_solve(context, "");
      // Equilibrium with the factored operator (bond forces of the
      // completed neighbourhoods, K = A E + B X D E applied factor by
      // factor), not with the assembled and eliminated matrix that the
      // solver used: |K u - f| over the free unknowns, relative to
      // |K| |u| (|K| estimated as |K r| / |r| for a fixed oscillating r):
      // with completed neighbourhoods a linear field has K u = 0
      // everywhere, so |K u| is no scale.
      {
        TrilinosWrappers::MPI::Vector ku(owned, context.communicator),
          r(owned, context.communicator), kr(owned, context.communicator);
        layer_operator.apply(solution, ku);
        for (const auto k : owned)
          r[k] = std::sin(1.3 * k + 0.2);
        r.compress(VectorOperation::insert);
        layer_operator.apply(r, kr);
        const double scale =
          std::max(ku.l2_norm(),
                   kr.l2_norm() / r.l2_norm() * solution.l2_norm());
        double residual2 = 0;
        for (const auto k : owned)
          if (prescribed.find(k) == prescribed.end())
            residual2 += std::pow(ku[k] - load[k], 2);
        residual2 = Utilities::MPI::sum(residual2, context.communicator);
        context.summary.equilibrium_residual =
          scale > 0 ? std::sqrt(residual2) / scale : 0.;
      }
      print_equilibrium(context, "factored operator");

      // Body displacements back to the DoF numbering, surface ones aside.
      TrilinosWrappers::MPI::Vector body(owned_dofs, context.communicator);
      for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          body[context.nodes[i].dofs[c]] =
            solution[layer_operator.unknown_index(context.nodes[i], c)];
      body.compress(VectorOperation::insert);
      displacement.reinit(owned_dofs,
                          context.nodes.relevant_dofs(),
                          context.communicator);
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
    LayerSystem<dim>::solve_matrix_free(
      const SystemContext<dim>                        &context,
      const std::map<types::global_dof_index, double> &prescribed,
      TrilinosWrappers::MPI::Vector                   &solution)
    {
      const IndexSet &owned = layer_operator.owned_unknowns();
      const MPI_Comm  comm  = context.communicator;
      using Vector          = TrilinosWrappers::MPI::Vector;
      TimerOutput::Scope scope(context.timer, "solve");

      // Prescribed unknowns eliminated: x = g + y with y = 0 there; the
      // operator is K on free rows and the identity on prescribed ones.
      std::vector<bool> is_prescribed(owned.n_elements(), false);
      Vector            g(owned, comm), kg(owned, comm), rhs(owned, comm);
      for (const auto &p : prescribed)
        {
          g[p.first]                                     = p.second;
          is_prescribed[owned.index_within_set(p.first)] = true;
        }
      g.compress(VectorOperation::insert);
      layer_operator.apply(g, kg);
      rhs = load;
      rhs -= kg;
      const auto zero_prescribed = [&](Vector &v) {
        double *values = v.trilinos_vector()[0];
        for (unsigned int l = 0; l < is_prescribed.size(); ++l)
          if (is_prescribed[l])
            values[l] = 0;
      };
      zero_prescribed(rhs);
      Vector     free_part(owned, comm);
      const auto op = [&](Vector &dst, const Vector &src) {
        free_part = src;
        zero_prescribed(free_part);
        layer_operator.apply(free_part, dst);
        double       *out = dst.trilinos_vector()[0];
        const double *in  = src.trilinos_vector()[0];
        for (unsigned int l = 0; l < is_prescribed.size(); ++l)
          if (is_prescribed[l])
            out[l] = in[l];
      };

      // A preconditioner on the local elasticity matrix (Q1 on the dual grid
      // of the body nodes, with the Dirichlet layers of the boundary
      // conditions) acts on the body unknowns, the surface unknowns scaled
      // by the mean body diagonal; any other acts on all unknowns.
      Solvers::LinearSolver::TrilinosMap precondition;
      Vector                             body_residual, body_correction;
      double                             surface_scale = 1;
      std::vector<std::pair<unsigned int, unsigned int>> body_positions;
      if (context.linear_solver.preconditioner().needs_local_matrix())
        {
          TimerOutput::Scope inner(context.timer, "preconditioner setup");
          Discretization::Lattice<dim> lattice;
          lattice.reinit(context.nodes);
          AffineConstraints<double> layers;
          if (!with_surface_nodes)
            layers.copy_from(constraints);
          else
            context.boundary_conditions.make_constraints(context.dof_handler,
                                                         context.nodes,
                                                         context.horizon,
                                                         layers);
          Operators::LocalElasticityOperator<dim>::assemble(context.nodes,
                                                            lattice,
                                                            context.model,
                                                            layers,
                                                            local_matrix);
          Solvers::PreconditionerSetup setup;
          setup.local_matrix         = &local_matrix;
          setup.local_matrix_version = Solvers::new_local_matrix_version();
          DoFTools::extract_constant_modes(context.dof_handler,
                                           ComponentMask(dim, true),
                                           setup.constant_modes);
          const Solvers::Preconditioner &body_preconditioner =
            context.linear_solver.setup_preconditioner(
              Solvers::OperatorForm::layer,
              std::move(setup));
          double diagonal_sum = 0;
          for (const auto dof : context.dof_handler.locally_owned_dofs())
            diagonal_sum += local_matrix.diag_element(dof);
          const double n_dofs = context.dof_handler.n_dofs();
          surface_scale = n_dofs / Utilities::MPI::sum(diagonal_sum, comm);
          body_residual.reinit(context.dof_handler.locally_owned_dofs(), comm);
          body_correction.reinit(body_residual);
          // Local positions of the body unknowns and of their DoFs, found
          // once: the preconditioner runs every iteration.
          for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
            for (unsigned int c = 0; c < dim; ++c)
              body_positions.emplace_back(
                owned.index_within_set(
                  layer_operator.unknown_index(context.nodes[i], c)),
                context.dof_handler.locally_owned_dofs().index_within_set(
                  context.nodes[i].dofs[c]));
          precondition = [&](Vector &dst, const Vector &src) {
            const double *in       = src.trilinos_vector()[0];
            double       *residual = body_residual.trilinos_vector()[0];
            for (const auto &[unknown, dof] : body_positions)
              residual[dof] = in[unknown];
            body_preconditioner.layer_vmult(body_correction, body_residual);
            dst = src;
            dst *= surface_scale;
            double       *out        = dst.trilinos_vector()[0];
            const double *correction = body_correction.trilinos_vector()[0];
            for (const auto &[unknown, dof] : body_positions)
              out[unknown] = correction[dof];
          };
        }
      else if (!context.linear_solver.preconditioner().is_identity())
        {
          const Solvers::Preconditioner &preconditioner =
            context.linear_solver.setup_preconditioner(
              Solvers::OperatorForm::layer,
              Solvers::PreconditionerSetup());
          precondition = [&preconditioner](Vector &dst, const Vector &src) {
            preconditioner.layer_vmult(dst, src);
          };
        }
      context.summary.solver = context.linear_solver.solve(
        op,
        precondition,
        solution,
        rhs,
        context.linear_solver.preconditioner_name());
      context.linear_solver.release_preconditioner();
      solution += g;
    }


    template class LayerSystem<2>;
    template class LayerSystem<3>;
  } // namespace Boundary
} // namespace PeriDEAL
