#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/boundary/nodal_system.h>
#include <perideal/boundary/system_context.h>
#include <perideal/operators/local_elasticity_operator.h>

#include <iomanip>
#include <limits>
#include <sstream>

namespace PeriDEAL
{
  namespace Boundary
  {
    template <int dim>
    void
    NodalSystem<dim>::setup(const SystemContext<dim> &context)
    {
      // Both operator paths evaluate full neighbourhoods with the shared
      // stencil: their lists need not be stored.
      context.setup_neighbor_lists(false);
      TimerOutput::Scope scope(context.timer, "operator setup");
      const auto        &nodes = context.nodes;
      const auto        &lists = context.neighbor_lists;
      bond_state.reinit(nodes, lists);
      bond_operator.reinit(nodes,
                           lists,
                           context.model,
                           context.horizon,
                           &bond_state);
      collocation = {};
      if (const auto *settings = context.quadrature_scheme.collocation())
        {
          // The hybrid scheme's fixed standard region (no node switches
          // in a static solve; QuasiStatic refuses 'adaptive').
          const bool hybrid = context.quadrature_scheme.hybrid() != nullptr;
          AssertThrow(!hybrid || context.hybrid_standard != nullptr,
                      ExcInternalError());
          collocation =
            bond_operator.use_collocation(*settings,
                                          hybrid ? *context.hybrid_standard :
                                                   std::vector<bool>());
          std::ostringstream line;
          line << "quadrature '" << context.quadrature_scheme_name
               << "': order " << settings->order << ", ";
          if (collocation.per_node && collocation.n_collocation_nodes == 0)
            line << "a row per node (irregular nodes), none fitted ("
                 << collocation.n_monomials << " monomials), cond(A) up to ";
          else if (collocation.per_node)
            line << "a row per node (irregular nodes), "
                 << collocation.n_collocation_min << " to "
                 << collocation.n_collocation << " collocation nodes ("
                 << collocation.n_monomials << " monomials), cond(A) up to ";
          else
            line << collocation.n_collocation << " collocation nodes ("
                 << collocation.n_monomials << " monomials), cond(A) ";
          line << std::setprecision(2) << std::scientific
               << collocation.condition << std::defaultfloat << "; "
               << collocation.n_collocation_nodes << " nodes by collocation"
               << (collocation.n_lower_order > 0 ?
                     " (" + std::to_string(collocation.n_lower_order) +
                       " of them by order 2: bad order-" +
                       std::to_string(settings->order) + " cloud)" :
                     std::string())
               << ", ";
          if (hybrid)
            line << collocation.n_fixed_standard
                 << " standard (fixed region), ";
          line << collocation.n_cut_nodes
               << " standard (ball cut by the surface), "
               << collocation.n_ill_conditioned
               << (collocation.per_node ?
                     " standard (ill-conditioned or indefinite cloud)" :
                     " standard (ill-conditioned cloud)");
          context.print_progress(line.str());
          if (collocation.symbol > 1e-10)
            context.pcout
              << "           warning: the bulk collocation row has growing "
                 "modes (largest symbol eigenvalue "
              << std::setprecision(2) << collocation.symbol << std::defaultfloat
              << " of the most negative): the static operator is "
                 "indefinite, see doc/collocation.md Sect. 7"
              << std::endl;
        }
    }


    template <int dim>
    void
    NodalSystem<dim>::solve_linear(const SystemContext<dim>      &context,
                                   TrilinosWrappers::MPI::Vector &displacement)
    {
      if (context.linear_solver.is_matrix_free())
        solve_matrix_free(context, displacement);
      else
        solve_assembled(context, displacement, true);
    }


    template <int dim>
    std::vector<IO::NodeField>
    NodalSystem<dim>::node_fields(
      const SystemContext<dim>            &context,
      const TrilinosWrappers::MPI::Vector &displacement) const
    {
      const auto         &nodes = context.nodes;
      std::vector<double> dilatation;
      VectorType          u;
      bond_operator.initialize_dof_vector(u);
      for (const auto dof : context.dof_handler.locally_owned_dofs())
        u[dof] = displacement[dof];
      u.update_ghost_values();
      bond_operator.compute_dilatation(u, dilatation);
      const auto   &weighted_volumes = bond_operator.weighted_volumes();
      IO::NodeField theta{"dilatation", {}}, m{"weighted_volume", {}},
        neighbours{"n_neighbors", {}}, scheme{"scheme", {}};
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          theta.values.push_back(dilatation[i]);
          m.values.push_back(weighted_volumes[i]);
          neighbours.values.push_back(context.neighbor_lists.n_bonds(i));
          // 0: standard, 1: collocation.
          scheme.values.push_back(bond_operator.is_collocation_node(i) ? 1 : 0);
        }
      if (context.quadrature_scheme.collocation() == nullptr)
        return {theta, m, neighbours};
      return {theta, m, neighbours, scheme};
    }


    template <int dim>
    bool
    NodalSystem<dim>::is_constrained(
      const Discretization::Node<dim> &node) const
    {
      for (const auto dof : node.dofs)
        if (constraints.is_constrained(dof))
          return true;
      return false;
    }


    template <int dim>
    void
    NodalSystem<dim>::make_constraints_and_load(
      const SystemContext<dim> &context)
    {
      context.boundary_conditions.make_constraints(context.dof_handler,
                                                   context.nodes,
                                                   context.horizon,
                                                   constraints);
      if (!critical_stretch.empty())
        hold_isolated_nodes(context);
      check_rigid_motions(context);
      load.reinit(context.dof_handler.locally_owned_dofs(),
                  context.communicator);
      context.boundary_conditions.add_load(context.dof_handler,
                                           context.nodes,
                                           constraints,
                                           load);
    }


    template <int dim>
    void
    NodalSystem<dim>::assemble_matrix_free_step(
      const SystemContext<dim> &context)
    {
      TimerOutput::Scope scope(context.timer, "assembly");
      make_constraints_and_load(context);
      constrained_operator.initialize(bond_operator,
                                      constraints,
                                      critical_stretch.empty() ? nullptr :
                                                                 &diagonal);
      VectorType load_vector;
      constrained_operator.initialize_dof_vector(load_vector);
      for (const auto dof : context.dof_handler.locally_owned_dofs())
        load_vector[dof] = load[dof];
      constrained_operator.lift(load_vector, step_rhs, step_prescribed);
    }


    template <int dim>
    void
    NodalSystem<dim>::prepare_preconditioner(const SystemContext<dim> &context)
    {
      const bool fracture = !critical_stretch.empty();
      if (preconditioner_ready && !fracture)
        return;
      if (!context.linear_solver.preconditioner().needs_local_matrix())
        {
          preconditioner_ready = true;
          return;
        }
      TimerOutput::Scope scope(context.timer, "preconditioner setup");
      // Nodes perturbed in their cells: the preconditioner's finite
      // elements live on the cells, whose centres may still form a
      // lattice.
      const bool uniform = context.neighbor_lists.lattice().is_uniform();
      if (!uniform && !preconditioner_ready)
        preconditioner_cells.reinit(context.nodes, true);
      const auto &lattice =
        uniform ? context.neighbor_lists.lattice() : preconditioner_cells;
      // With bond failure the local matrix has the cracks too (its dual
      // cubes cut where a bond between their corners is broken): the
      // intact one misses the crack-opening modes, which then cost CG
      // iterations. It is assembled again (and the multigrid hierarchy
      // rebuilt) when the cut cubes have grown by a tenth, not at every
      // broken bond: a run to failure re-solves hundreds of times; and
      // whenever new DoFs are held (the local matrix and the coarse
      // lattice leave them out).
      std::vector<std::uint32_t> broken_masks;
      std::size_t                n_cut = 0;
      if (fracture)
        {
          broken_masks =
            Operators::LocalElasticityOperator<dim>::broken_neighbor_masks(
              context.nodes,
              lattice,
              context.neighbor_lists,
              bond_state);
          n_cut =
            Operators::LocalElasticityOperator<dim>::n_cut_cubes(context.nodes,
                                                                 lattice,
                                                                 broken_masks);
          // Collective on every process, before any test that decides.
          const bool holds_changed =
            Utilities::MPI::logical_or(held_dofs != held_dofs_built,
                                       context.communicator);
          if (preconditioner_ready && n_cut <= cut_cubes_built * 11 / 10 &&
              !holds_changed)
            return;
        }
      preconditioner_ready = true;
      cut_cubes_built      = n_cut;
      held_dofs_built      = held_dofs;
      // On a coarser lattice ('local elasticity/Coarsening'): its own
      // DoFs, reached through the interpolation.
      const unsigned int coarsening =
        context.linear_solver.preconditioner().local_matrix_coarsening();
      local_transfer = nullptr;
      if (coarsening > 1)
        {
          coarse_lattice.reinit(context.nodes,
                                lattice,
                                constraints,
                                coarsening,
                                fracture ? &boundary_constraints : nullptr);
          local_transfer = &coarse_lattice;
        }
      Operators::LocalElasticityOperator<dim>::assemble(
        context.nodes,
        lattice,
        context.model,
        constraints,
        local_matrix,
        fracture ? &broken_masks : nullptr,
        coarsening > 1 ? &coarse_lattice : nullptr);
      local_matrix_version = Solvers::new_local_matrix_version();
      constant_modes.clear();
      if (coarsening > 1)
        constant_modes = coarse_lattice.constant_modes();
      else
        DoFTools::extract_constant_modes(context.dof_handler,
                                         ComponentMask(dim, true),
                                         constant_modes);
    }


    template <int dim>
    void
    NodalSystem<dim>::solve_matrix_free_step(
      const SystemContext<dim>      &context,
      TrilinosWrappers::MPI::Vector &displacement)
    {
      const IndexSet &owned = context.dof_handler.locally_owned_dofs();
      VectorType      solution;
      constrained_operator.initialize_dof_vector(solution);
      // Warm start from the last solution's free part (prescribed entries
      // are zero in the lifted system).
      if (free_solution.size() == solution.size())
        for (unsigned int k = 0; k < solution.locally_owned_size(); ++k)
          solution.local_element(k) = constrained_operator.is_prescribed(k) ?
                                        0. :
                                        free_solution.local_element(k);
      {
        TimerOutput::Scope scope(context.timer, "solve");
        context.summary.solver =
          dynamic_relaxation != nullptr ?
            dynamic_relaxation->solve(constrained_operator,
                                      solution,
                                      step_rhs,
                                      context.communicator) :
          finite ? solve_newton(context, solution) :
                   context.linear_solver.solve(constrained_operator,
                                               solution,
                                               step_rhs,
                                               &local_matrix,
                                               constant_modes,
                                               local_transfer,
                                               local_matrix_version);
      }
      free_solution = solution;
      solution += step_prescribed;
      TrilinosWrappers::MPI::Vector owned_solution(owned, context.communicator);
      for (const auto dof : owned)
        owned_solution[dof] = solution[dof];
      owned_solution.compress(VectorOperation::insert);
      displacement.reinit(owned,
                          context.nodes.relevant_dofs(),
                          context.communicator);
      displacement = owned_solution;
    }


    template <int dim>
    void
    NodalSystem<dim>::solve_matrix_free(
      const SystemContext<dim>      &context,
      TrilinosWrappers::MPI::Vector &displacement)
    {
      context.summary.n_unknowns = context.dof_handler.n_dofs();
      assemble_matrix_free_step(context);
      context.summary.n_constrained_nodes = Utilities::MPI::sum(
        context.boundary_conditions.n_constrained_nodes(context.nodes,
                                                        constraints),
        context.communicator);
      print_operator(context);
      prepare_preconditioner(context);
      solve_matrix_free_step(context, displacement);
      print_solve(context, "");
      check_equilibrium(context, displacement);
    }


    template <int dim>
    void
    NodalSystem<dim>::print_operator(const SystemContext<dim> &context) const
    {
      const unsigned int n_stencil =
        Utilities::MPI::sum(bond_operator.n_stencil_nodes(),
                            context.communicator) +
        collocation.n_collocation_nodes;
      const std::size_t visits =
        Utilities::MPI::sum(bond_operator.n_bond_visits(),
                            context.communicator);
      const double operator_mb =
        Utilities::MPI::sum(bond_operator.memory_consumption() / 1048576.,
                            context.communicator);
      context.pcout
        << "[" << std::setw(8) << std::fixed << std::setprecision(2)
        << context.elapsed()
        << " s] matrix-free operator: " << context.dof_handler.n_dofs()
        << " DoFs, "
        << (collocation.per_node ?
              std::to_string(n_stencil) +
                " nodes by a collocation row of their own" :
              std::to_string(n_stencil) + " nodes on the shared stencil" +
                (collocation.n_collocation_nodes > 0 ?
                   " (" + std::to_string(collocation.n_collocation_nodes) +
                     " of them by collocation)" :
                   std::string()))
        << ", " << context.summary.n_nodes - n_stencil << " on lists, "
        << context.summary.n_constrained_nodes << " nodes in Dirichlet layers; "
        << visits << " bond visits per application, " << std::setprecision(1)
        << operator_mb << " MB, " << MultithreadInfo::n_threads()
        << " thread(s) per process" << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    NodalSystem<dim>::solve_assembled(
      const SystemContext<dim>      &context,
      TrilinosWrappers::MPI::Vector &displacement,
      const bool                     verbose)
    {
      context.summary.n_unknowns = context.dof_handler.n_dofs();
      const IndexSet &owned      = context.dof_handler.locally_owned_dofs();
      const IndexSet  relevant   = context.nodes.relevant_dofs();
      {
        TimerOutput::Scope scope(context.timer, "assembly");
        make_constraints_and_load(context);
        system_rhs = load;
        bond_operator.assemble(system_matrix, &constraints, &system_rhs);
      }
      context.summary.n_constrained_nodes = Utilities::MPI::sum(
        context.boundary_conditions.n_constrained_nodes(context.nodes,
                                                        constraints),
        context.communicator);
      context.summary.n_nonzeros = system_matrix.n_nonzero_elements();
      if (verbose)
        context.pcout << "[" << std::setw(8) << std::fixed
                      << std::setprecision(2) << context.elapsed()
                      << " s] assembled: " << context.dof_handler.n_dofs()
                      << " DoFs, " << context.summary.n_nonzeros
                      << " nonzeros, " << context.summary.n_constrained_nodes
                      << " nodes in Dirichlet layers" << std::endl;

      // Symmetry of the system, measured: x^T A y against y^T A x.
      TrilinosWrappers::MPI::Vector x(owned, context.communicator),
        y(owned, context.communicator), ax(owned, context.communicator),
        ay(owned, context.communicator);
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

      TrilinosWrappers::MPI::Vector solution(owned, context.communicator);
      {
        TimerOutput::Scope             scope(context.timer, "solve");
        std::vector<std::vector<bool>> constant_modes;
        DoFTools::extract_constant_modes(context.dof_handler,
                                         ComponentMask(dim, true),
                                         constant_modes);
        context.summary.solver = context.linear_solver.solve(system_matrix,
                                                             solution,
                                                             system_rhs,
                                                             constant_modes,
                                                             symmetric);
        constraints.distribute(solution);
      }
      displacement.reinit(owned, relevant, context.communicator);
      displacement = solution;
      if (verbose)
        print_solve(context, symmetric ? "" : " (non-symmetric)");
      check_equilibrium(context, displacement, verbose);
    }


    template <int dim>
    void
    NodalSystem<dim>::check_rigid_motions(
      const SystemContext<dim> &context) const
    {
      // The rigid motions (translations, rotations about the body's centre
      // in units of its size) restricted to the prescribed DoFs: the Gram
      // matrix M^T M adds up over processes, and a (near) null vector is a
      // rigid motion that no Dirichlet condition holds. A direct solver
      // would return one of infinitely many solutions without complaint.
      const auto        &nodes   = context.nodes;
      const MPI_Comm     comm    = context.communicator;
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
          context.boundary_conditions.dirichlet_ids_string(),
          "the Dirichlet layers leave a rigid motion free (" + free_modes +
            "), so the system is singular; prescribe the missing "
            "components ('Dirichlet components') or more boundaries"));
    }


    template <int dim>
    void
    NodalSystem<dim>::check_equilibrium(
      const SystemContext<dim>            &context,
      const TrilinosWrappers::MPI::Vector &displacement,
      const bool                           verbose)
    {
      // F_int(u) + F_ext = 0 at every free DoF, with the forces of
      // BondOperator::apply() (not of its assembly).
      const IndexSet &owned = context.dof_handler.locally_owned_dofs();
      VectorType     &u = last_displacement, &internal = last_force;
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
      // With finite kinematics a rigid motion leaves no internal force at
      // all, and the residual is measured against the step's lifted
      // right-hand side as well (the scale of the Newton test).
      const double scale = finite ?
                             std::max(internal.l2_norm(), step_rhs.l2_norm()) :
                             internal.l2_norm();
      free_residual2 =
        Utilities::MPI::sum(free_residual2, context.communicator);
      context.summary.equilibrium_residual =
        scale > 0 ? std::sqrt(free_residual2) / scale : 0.;
      if (verbose)
        print_equilibrium(context, "matrix-free forces");
    }


    template class NodalSystem<2>;
    template class NodalSystem<3>;
  } // namespace Boundary
} // namespace PeriDEAL
