/**
 * @file
 * The checks of the diffusion problem type's state and linear solves: a
 * concentration that is not finite after a step (check_finite()), the
 * right-hand side and initial guess of a solve traced back to the entry
 * that made them not finite (check_solve_input()), and a solve that
 * overflowed (check_solve_result()).
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    std::string
    Diffusion<dim>::solve_label() const
    {
      if (!integrator->takes_time_steps())
        return "the steady-state solve";
      return "the linear solve of step " + std::to_string(step_number) +
             " (t = " + format_number(time) + ")";
    }


    template <int dim>
    void
    Diffusion<dim>::check_solve_input(Simulator<dim>   &simulator,
                                      const VectorType &b,
                                      const VectorType &lifted,
                                      const VectorType &x) const
    {
      // The node to report: a prescribed one first (its value spreads to
      // its free neighbours through the lifting), else the lowest DoF; the
      // same on any number of processes.
      const MPI_Comm                comm  = simulator.get_communicator();
      const types::global_dof_index none  = numbers::invalid_dof_index;
      unsigned int                  kind  = 2;
      types::global_dof_index       first = none;
      unsigned int                  node  = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const unsigned int k         = op.vector_index(i);
          const bool         bad       = is_prescribed[k] ?
                                           !std::isfinite(x.local_element(k)) :
                                           !std::isfinite(lifted.local_element(k)) ||
                               !std::isfinite(x.local_element(k));
          const unsigned int this_kind = is_prescribed[k] ? 0 : 1;
          const auto         dof       = (*nodes)[i].dofs[0];
          if (bad && (this_kind < kind || (this_kind == kind && dof < first)))
            {
              kind  = this_kind;
              first = dof;
              node  = i;
            }
        }
      const unsigned int worst = Utilities::MPI::min(kind, comm);
      if (worst == 2)
        return;
      const auto chosen =
        Utilities::MPI::min(kind == worst ? first : none, comm);
      std::string message;
      if (kind == worst && first == chosen)
        {
          const unsigned int k = op.vector_index(node);
          const Point<dim>  &p = (*nodes)[node].location;
          std::ostringstream at;
          at << "(" << p << ")";
          const auto named = [&](const std::string &function,
                                 const double       value,
                                 const double       t,
                                 const std::string &role) {
            return "Invalid value '" + expressions.at(function) +
                   "' for the parameter '" + section + "/" + function +
                   "/Function expression': it is " +
                   (std::isnan(value) ? std::string("NaN") :
                                        format_number(value)) +
                   " at the node at " + at.str() +
                   " at t = " + format_number(t) + ", " + role + " of " +
                   solve_label() +
                   "; give a function that is finite at every node and "
                   "time.";
          };
          // The times at which the right-hand side evaluates the data.
          const std::vector<double> times =
            integrator->data_times(time, dt, step_number);
          const bool first_solve =
            !integrator->takes_time_steps() || step_number <= 1;
          if (is_prescribed[k])
            message = named("Boundary concentration",
                            x.local_element(k),
                            time,
                            "a prescribed value");
          else
            {
              if (with_source)
                for (const double t : times)
                  if (message.empty())
                    {
                      source->set_time(t);
                      const double v = source->value(p);
                      if (!std::isfinite(v))
                        message =
                          named("Source", v, t, "in the right-hand side");
                    }
              if (with_flux && flux_values == FluxValues::source &&
                  std::find(flux_nodes.begin(), flux_nodes.end(), node) !=
                    flux_nodes.end())
                for (const double t : times)
                  if (message.empty())
                    {
                      boundary_flux->set_time(t);
                      const double v = boundary_flux->value(p);
                      if (!std::isfinite(v))
                        message = named("Boundary flux",
                                        v,
                                        t,
                                        "in the right-hand side");
                    }
              if (message.empty() && !std::isfinite(x.local_element(k)) &&
                  first_solve)
                message = named("Initial concentration",
                                x.local_element(k),
                                0,
                                !integrator->takes_time_steps() ?
                                  "the initial guess" :
                                  "the initial state in the right-hand side");
              if (message.empty())
                {
                  std::ostringstream text;
                  text << "The right-hand side of " << solve_label() << " is "
                       << (std::isfinite(b.local_element(k)) ?
                             lifted.local_element(k) :
                             b.local_element(k))
                       << " at the node at " << at.str()
                       << " although the source, the boundary values and "
                          "the previous concentration there are finite: "
                          "the values overflow the range of double "
                          "precision numbers (about 1e308). Check the "
                          "magnitudes of 'diffusion/Diffusivity' ("
                       << kernel.diffusivity() << "), 'diffusion/Time step' ("
                       << dt
                       << ") and the data. The output written before is "
                          "complete.";
                  message = text.str();
                }
            }
        }
      throw_on_any_rank(message, comm);
    }


    template <int dim>
    void
    Diffusion<dim>::check_solve_result(Simulator<dim>   &simulator,
                                       const bool        converged,
                                       const double      residual,
                                       const VectorType &x) const
    {
      const MPI_Comm          comm  = simulator.get_communicator();
      types::global_dof_index first = numbers::invalid_dof_index;
      unsigned int            node  = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        if (!std::isfinite(x.local_element(op.vector_index(i))) &&
            (*nodes)[i].dofs[0] < first)
          {
            first = (*nodes)[i].dofs[0];
            node  = i;
          }
      const auto chosen = Utilities::MPI::min(first, comm);
      if (converged && chosen == numbers::invalid_dof_index)
        return;
      // One process reports: the owner of the node, or rank 0 when no
      // node is reported.
      const bool         reporter = chosen != numbers::invalid_dof_index ?
                                      first == chosen :
                                      Utilities::MPI::this_mpi_process(comm) == 0;
      std::ostringstream text;
      if (reporter)
        {
          text << "The right-hand side and the initial guess of "
               << solve_label() << " are finite, but ";
          if (!converged)
            text << "the solver stopped at the residual " << residual
                 << (std::isfinite(residual) ?
                       " without reaching its tolerance" :
                       ", which is not finite")
                 << (first == chosen ? ", and " : "");
          if (first == chosen)
            text << "the solution at the node at (" << (*nodes)[node].location
                 << ") is " << x.local_element(op.vector_index(node));
          text << ": the system overflows the range of double precision "
                  "numbers (about 1e308). Check the magnitudes of "
                  "'diffusion/Diffusivity' ("
               << kernel.diffusivity() << ")"
               << (integrator->takes_time_steps() ?
                     ", 'diffusion/Time step' (" + format_number(dt) + ")" :
                     std::string())
               << " and the data. The output written before is complete.";
        }
      throw_on_any_rank(text.str(), comm);
    }


    template <int dim>
    void
    Diffusion<dim>::check_finite(Simulator<dim> &simulator)
    {
      // The sources and boundary values were finite where they were
      // evaluated (else their entry would be named): the solution diverged.
      std::ostringstream advice;
      if (integrator->is_conditionally_stable())
        advice << "The run is unstable: reduce 'diffusion/Time step' "
                  "(forward Euler bound "
               << dt_bound << ") or check the constants.";
      else
        advice << "Check the constants and the solver settings.";
      finite_check.check_state(
        *nodes,
        {{c.begin(), c.locally_owned_size()}},
        [&](const unsigned int i) {
          return std::isfinite(c.local_element(op.vector_index(i)));
        },
        step_number,
        time,
        "The concentration",
        advice.str(),
        simulator.get_communicator());
    }


#define PERIDEAL_INSTANTIATE(dim)                                                   \
  template void        Diffusion<dim>::check_finite(Simulator<dim> &);              \
  template std::string Diffusion<dim>::solve_label() const;                         \
  template void        Diffusion<dim>::check_solve_input(Simulator<dim> &,          \
                                                  const VectorType &,        \
                                                  const VectorType &,        \
                                                  const VectorType &) const; \
  template void        Diffusion<dim>::check_solve_result(Simulator<dim> &,         \
                                                   const bool,               \
                                                   const double,             \
                                                   const VectorType &) const;
    PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
