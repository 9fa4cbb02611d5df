#include <deal.II/base/mpi.h>

#include <perideal/operators/constrained_operator.h>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    ConstrainedOperator<dim>::initialize(
      const BondOperator<dim>         &bond_operator,
      const AffineConstraints<double> &constraints,
      const VectorType                *diagonal)
    {
      op                = &bond_operator;
      const auto &part  = *op->get_partitioner();
      const auto  local = part.locally_owned_size();
      prescribed_entry.assign(local, false);
      prescribed_value.assign(local, 0.);
      bool only_values = true;
      for (unsigned int k = 0; k < local; ++k)
        {
          const auto dof = part.local_to_global(k);
          if (constraints.is_constrained(dof))
            {
              only_values =
                only_values && constraints.get_constraint_entries(dof)->empty();
              prescribed_entry[k] = true;
              prescribed_value[k] = constraints.get_inhomogeneity(dof);
            }
        }
      // Reduced before throwing: a coupling constraint may exist on one
      // process only.
      AssertThrow(Utilities::MPI::min(only_values ? 1 : 0,
                                      part.get_mpi_communicator()) == 1,
                  ExcMessage("The PD operator eliminates only prescribed "
                             "values u_k = g_k, not constraints that couple "
                             "DoFs."));
      op->initialize_dof_vector(diag);
      op->initialize_dof_vector(work);
      if (diagonal != nullptr)
        diag = *diagonal;
      else
        op->compute_diagonal(diag);
      // A prescribed row keeps its diagonal, or 1 where it has none (a node
      // held because its bonds broke): the row is decoupled and its entry
      // of the lifted solution stays exactly zero (zero right-hand side),
      // so the value only has to be positive for the diagonal
      // preconditioners and dynamic relaxation. A free row without bonds
      // would make K singular: it is reported by the solvers.
      for (unsigned int k = 0; k < local; ++k)
        if (prescribed_entry[k] && !(diag.local_element(k) > 0))
          diag.local_element(k) = 1.;
      applications = 0;
    }


    template <int dim>
    void
    ConstrainedOperator<dim>::vmult(VectorType       &dst,
                                    const VectorType &src) const
    {
      const unsigned int local = prescribed_entry.size();
      for (unsigned int k = 0; k < local; ++k)
        work.local_element(k) = prescribed_entry[k] ? 0. : src.local_element(k);
      work.update_ghost_values();
      op->apply_linearised(work, dst);
      for (unsigned int k = 0; k < local; ++k)
        dst.local_element(k) = prescribed_entry[k] ?
                                 diag.local_element(k) * src.local_element(k) :
                                 -dst.local_element(k);
      ++applications;
    }


    template <int dim>
    void
    ConstrainedOperator<dim>::residual(VectorType       &r,
                                       const VectorType &x,
                                       const VectorType &b) const
    {
      if (!op->finite_kinematics())
        {
          vmult(r, x);
          r.sadd(-1., 1., b);
          return;
        }
      AssertThrow(prescribed_force.size() == x.size(),
                  ExcMessage("ConstrainedOperator::residual() with finite "
                             "kinematics needs lift() first."));
      const unsigned int local = prescribed_entry.size();
      for (unsigned int k = 0; k < local; ++k)
        work.local_element(k) =
          prescribed_entry[k] ? prescribed_value[k] : x.local_element(k);
      work.update_ghost_values();
      op->apply(work, r);
      // b_f - A(x)_f = b_f + F(x + g)_f - F(g)_f.
      for (unsigned int k = 0; k < local; ++k)
        r.local_element(k) =
          prescribed_entry[k] ?
            b.local_element(k) - diag.local_element(k) * x.local_element(k) :
            b.local_element(k) + r.local_element(k) -
              prescribed_force.local_element(k);
      ++applications;
    }


    template <int dim>
    void
    ConstrainedOperator<dim>::lift(const VectorType &load,
                                   VectorType       &rhs,
                                   VectorType       &prescribed) const
    {
      const unsigned int local = prescribed_entry.size();
      initialize_dof_vector(prescribed);
      initialize_dof_vector(rhs);
      for (unsigned int k = 0; k < local; ++k)
        prescribed.local_element(k) = prescribed_value[k];
      prescribed.update_ghost_values();
      // rhs = load - K g = load + F(g) on free DoFs.
      op->apply(prescribed, rhs);
      if (op->finite_kinematics())
        prescribed_force = rhs;
      else
        prescribed_force.reinit(0);
      for (unsigned int k = 0; k < local; ++k)
        rhs.local_element(k) = prescribed_entry[k] ?
                                 0. :
                                 load.local_element(k) + rhs.local_element(k);
      prescribed.zero_out_ghost_values();
    }


    template <int dim>
    const typename ConstrainedOperator<dim>::VectorType &
    ConstrainedOperator<dim>::diagonal() const
    {
      return diag;
    }


    template <int dim>
    types::global_dof_index
    ConstrainedOperator<dim>::m() const
    {
      return op->get_partitioner()->size();
    }


    template <int dim>
    void
    ConstrainedOperator<dim>::initialize_dof_vector(VectorType &v) const
    {
      op->initialize_dof_vector(v);
    }


    template class ConstrainedOperator<2>;
    template class ConstrainedOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
