// NodalSystem's bond failure for load-stepped static runs
// (Problems::QuasiStatic): failure set-up, quiet warm-started solves, the
// bonds over a multiple of their critical stretch, breaking them, and the
// force that holds a set of nodes.

#include <deal.II/base/mpi.h>

#include <perideal/boundary/nodal_system.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace PeriDEAL
{
  namespace Boundary
  {
    namespace
    {
      // One evaluation of the forces with failure at factor times the
      // critical stretches: the bonds over it are recorded in the operator
      // (BondOperator::count_exceeded_bonds(), commit_broken_bonds()).
      template <int dim>
      void
      find_bonds_over(
        Operators::BondOperator<dim>                     &bond_operator,
        const std::vector<double>                        &critical_stretch,
        const double                                      factor,
        const LinearAlgebra::distributed::Vector<double> &displacement,
        const bool                                        finite)
      {
        std::vector<double> scaled(critical_stretch);
        for (double &s0 : scaled)
          s0 *= factor;
        bond_operator.set_kinematics(finite, scaled);
        LinearAlgebra::distributed::Vector<double> force;
        bond_operator.initialize_dof_vector(force);
        bond_operator.apply(displacement, force);
      }
    } // namespace


    template <int dim>
    bool
    NodalSystem<dim>::supports_bond_breaking() const
    {
      return true;
    }


    template <int dim>
    std::size_t
    NodalSystem<dim>::setup_failure(
      const SystemContext<dim>                     &context,
      const std::vector<double>                    &critical,
      const typename DiscreteSystem<dim>::CutBonds &cut)
    {
      TimerOutput::Scope scope(context.timer, "operator setup");
      AssertThrow(critical.size() == context.nodes.size(), ExcInternalError());
      critical_stretch        = critical;
      const std::size_t n_cut = cut(context.neighbor_lists, bond_state);
      bond_operator.update_bond_state();
      return n_cut;
    }


    template <int dim>
    void
    NodalSystem<dim>::hold_isolated_nodes(const SystemContext<dim> &context)
    {
      // A node whose bonds all broke has a zero row: it is held where it
      // was (zero before the first solve). Its load, if any, is dropped.
      // So is a direction in which no intact bond gives a node stiffness
      // (its bonds left all lie across it, e.g. one row along x): a zero
      // diagonal entry of K, exactly zero on a lattice, so the threshold
      // (relative to the node's stiffest direction) only guards round-off.
      // In that direction the bonds exert no force (small strain), so the
      // hold costs no reaction.
      const auto               &nodes = context.nodes;
      AffineConstraints<double> held;
      held.reinit(nodes.relevant_dofs());
      for (const auto &line : constraints.get_lines())
        {
          held.add_line(line.index);
          held.set_inhomogeneity(line.index, line.inhomogeneity);
        }
      const bool has_last = last_displacement.size() > 0;
      held_dofs.clear();
      const auto hold = [&](const types::global_dof_index dof) {
        if (held.is_constrained(dof))
          return false;
        held_dofs.push_back(dof);
        held.add_line(dof);
        held.set_inhomogeneity(dof, has_last ? last_displacement[dof] : 0.);
        return true;
      };
      bond_operator.initialize_dof_vector(diagonal);
      bond_operator.compute_diagonal(diagonal);
      n_isolated  = 0;
      n_held_dofs = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          const unsigned int n_bonds = context.neighbor_lists.n_bonds(i);
          if (n_bonds == 0)
            continue;
          if (bond_state.n_broken(i) == n_bonds)
            {
              ++n_isolated;
              for (const auto dof : nodes[i].dofs)
                hold(dof);
              continue;
            }
          double stiffest = 0;
          for (const auto dof : nodes[i].dofs)
            stiffest = std::max(stiffest, diagonal[dof]);
          for (const auto dof : nodes[i].dofs)
            if (!(diagonal[dof] > 1e-12 * stiffest) && hold(dof))
              ++n_held_dofs;
        }
      held.close();
      boundary_constraints.copy_from(constraints);
      constraints.copy_from(held);
      n_isolated  = Utilities::MPI::sum(n_isolated, context.communicator);
      n_held_dofs = Utilities::MPI::sum(n_held_dofs, context.communicator);
    }


    template <int dim>
    void
    NodalSystem<dim>::solve_step(const SystemContext<dim>      &context,
                                 TrilinosWrappers::MPI::Vector &displacement)
    {
      context.summary.n_unknowns = context.dof_handler.n_dofs();
      if (dynamic_relaxation != nullptr ||
          context.linear_solver.is_matrix_free())
        {
          assemble_matrix_free_step(context);
          if (dynamic_relaxation == nullptr)
            prepare_preconditioner(context);
          solve_matrix_free_step(context, displacement);
          check_equilibrium(context, displacement, false);
        }
      else
        solve_assembled(context, displacement, false);
      context.summary.n_constrained_nodes = Utilities::MPI::sum(
        context.boundary_conditions.n_constrained_nodes(context.nodes,
                                                        constraints),
        context.communicator);
    }


    template <int dim>
    void
    NodalSystem<dim>::set_finite_deformation(
      const typename DiscreteSystem<dim>::NewtonControl &control)
    {
      AssertThrow(collocation.n_collocation_nodes == 0, ExcInternalError());
      finite = true;
      newton = control;
      bond_operator.set_kinematics(true);
    }


    template <int dim>
    Solvers::SolverReport
    NodalSystem<dim>::solve_newton(const SystemContext<dim> &context,
                                   VectorType               &x)
    {
      // r = b - A(x) with the finite kinematics, corrections K dx = r with
      // the linearised stiffness: a modified Newton (chord) method, whose
      // rate is about the distance of the tangent from K (the strains and
      // rotations); each correction a Krylov solve to the linear solver's
      // tolerance relative to |r|.
      Timer                 timer;
      Solvers::SolverReport report;
      VectorType            r, dx;
      constrained_operator.initialize_dof_vector(r);
      constrained_operator.initialize_dof_vector(dx);
      const double b_norm = step_rhs.l2_norm();
      const double goal   = newton.tolerance * b_norm;
      double       r_norm = 0;
      unsigned int it     = 0;
      for (;; ++it)
        {
          constrained_operator.residual(r, x, step_rhs);
          r_norm = r.l2_norm();
          AssertThrow(std::isfinite(r_norm),
                      ExcNoConvergence(
                        "the finite-deformation residual is not finite after " +
                        std::to_string(it) + " Newton correction(s)"));
          if (r_norm <= goal || it == newton.max_iterations)
            break;
          dx                = 0;
          const auto linear = context.linear_solver.solve(constrained_operator,
                                                          dx,
                                                          r,
                                                          &local_matrix,
                                                          constant_modes,
                                                          local_transfer,
                                                          local_matrix_version);
          report.iterations += linear.iterations;
          report.method = linear.method;
          x += dx;
        }
      report.relative_residual = b_norm > 0 ? r_norm / b_norm : r_norm;
      report.corrections       = it;
      report.seconds           = timer.wall_time();
      report.method            = "modified Newton (" + std::to_string(it) +
                      " correction(s) by " + report.method + ")";
      if (r_norm > goal)
        {
          std::ostringstream message;
          message << "the modified Newton iteration of finite deformation did "
                     "not converge in "
                  << it << " corrections: relative residual "
                  << report.relative_residual << " against the tolerance "
                  << newton.tolerance
                  << " ('quasi-static/Newton/Relative tolerance', 'Maximum "
                     "iterations')";
          AssertThrow(false, ExcNoConvergence(message.str()));
        }
      return report;
    }


    template <int dim>
    std::size_t
    NodalSystem<dim>::count_critical_bonds(const double factor)
    {
      AssertThrow(!critical_stretch.empty() && last_displacement.size() > 0,
                  ExcInternalError());
      find_bonds_over(bond_operator,
                      critical_stretch,
                      factor,
                      last_displacement,
                      finite);
      const std::size_t n = bond_operator.count_exceeded_bonds();
      bond_operator.set_kinematics(finite);
      return n;
    }


    template <int dim>
    std::size_t
    NodalSystem<dim>::break_critical_bonds(const double factor)
    {
      AssertThrow(!critical_stretch.empty() && last_displacement.size() > 0,
                  ExcInternalError());
      find_bonds_over(bond_operator,
                      critical_stretch,
                      factor,
                      last_displacement,
                      finite);
      const std::size_t n = bond_operator.commit_broken_bonds(bond_state);
      bond_operator.set_kinematics(finite);
      return n;
    }


    template <int dim>
    std::vector<double>
    NodalSystem<dim>::damage(const SystemContext<dim> &context) const
    {
      std::vector<double> values;
      for (unsigned int i = 0; i < context.nodes.n_owned(); ++i)
        values.push_back(bond_state.damage(i));
      return values;
    }


    template <int dim>
    unsigned int
    NodalSystem<dim>::n_isolated_nodes() const
    {
      return n_isolated;
    }


    template <int dim>
    unsigned int
    NodalSystem<dim>::n_held_dofs_without_stiffness() const
    {
      return n_held_dofs;
    }


    template <int dim>
    Tensor<1, dim>
    NodalSystem<dim>::holding_force(const SystemContext<dim> &context,
                                    const std::vector<bool>  &flagged) const
    {
      Tensor<1, dim> force;
      for (unsigned int i = 0; i < flagged.size(); ++i)
        if (flagged[i])
          for (unsigned int c = 0; c < dim; ++c)
            force[c] -= last_force[context.nodes[i].dofs[c]];
      for (unsigned int c = 0; c < dim; ++c)
        force[c] = Utilities::MPI::sum(force[c], context.communicator);
      return force;
    }


    template class NodalSystem<2>;
    template class NodalSystem<3>;
  } // namespace Boundary
} // namespace PeriDEAL
