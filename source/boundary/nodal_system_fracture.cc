// NodalSystem's bond failure for load-stepped static runs
// (Problems::QuasiStatic): failure set-up, quiet warm-started solves, the
// bonds over a multiple of their critical stretch, breaking them, and the
// force that holds a set of nodes.

#include <deal.II/base/mpi.h>

#include <perideal/boundary/nodal_system.h>

#include <algorithm>
#include <cmath>

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
        const LinearAlgebra::distributed::Vector<double> &displacement)
      {
        std::vector<double> scaled(critical_stretch);
        for (double &s0 : scaled)
          s0 *= factor;
        bond_operator.set_kinematics(false, scaled);
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
      const auto               &nodes = context.nodes;
      AffineConstraints<double> held;
      held.reinit(nodes.relevant_dofs());
      for (const auto &line : constraints.get_lines())
        {
          held.add_line(line.index);
          held.set_inhomogeneity(line.index, line.inhomogeneity);
        }
      const bool has_last = last_displacement.size() > 0;
      n_isolated          = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        if (context.neighbor_lists.n_bonds(i) > 0 &&
            bond_state.n_broken(i) == context.neighbor_lists.n_bonds(i))
          {
            ++n_isolated;
            for (const auto dof : nodes[i].dofs)
              if (!held.is_constrained(dof))
                {
                  held.add_line(dof);
                  held.set_inhomogeneity(dof,
                                         has_last ? last_displacement[dof] :
                                                    0.);
                }
          }
      held.close();
      constraints.copy_from(held);
      n_isolated = Utilities::MPI::sum(n_isolated, context.communicator);
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
    std::size_t
    NodalSystem<dim>::count_critical_bonds(const double factor)
    {
      AssertThrow(!critical_stretch.empty() && last_displacement.size() > 0,
                  ExcInternalError());
      find_bonds_over(bond_operator,
                      critical_stretch,
                      factor,
                      last_displacement);
      const std::size_t n = bond_operator.count_exceeded_bonds();
      bond_operator.set_kinematics(false);
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
                      last_displacement);
      const std::size_t n = bond_operator.commit_broken_bonds(bond_state);
      bond_operator.set_kinematics(false);
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
