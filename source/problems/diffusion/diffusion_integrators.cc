/**
 * @file
 * The time integrators of the diffusion problem type: forward Euler, the
 * θ-scheme and the steady state (problems/diffusion/integrators.h), the
 * entries each leaves unused, and the choice by 'Time stepping'.
 */

#include <perideal/base/exceptions.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>
#include <perideal/problems/diffusion/integrators.h>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace DiffusionIntegrators
    {
      namespace
      {
        /// 'Implicit scheme', unused by every scheme but the θ-scheme.
        UnusedEntry
        no_implicit_scheme(const std::string &name)
        {
          return {"Implicit scheme",
                  "'Time stepping = " + name +
                    "' uses no implicit scheme; set 'Time stepping = "
                    "implicit' to use it, or remove the entry"};
        }

        /// The entries of the stability bound, unused by the schemes that
        /// have none.
        std::vector<UnusedEntry>
        no_stability_bound(const std::string &name)
        {
          return {{"Safety factor",
                   "the time step of 'Time stepping = " + name +
                     "' is 'Time step' itself; remove the entry"},
                  {"Allow unstable time step",
                   "'Time stepping = " + name +
                     "' has no stability bound to exceed; remove the "
                     "entry"}};
        }
      } // namespace


      template <int dim>
      void
      Integrator<dim>::initialize(Diffusion<dim> &, Simulator<dim> &)
      {}


      template <int dim>
      std::vector<double>
      Integrator<dim>::data_times(const double time,
                                  const double,
                                  const std::uint64_t) const
      {
        return {time};
      }


      template <int dim>
      std::vector<UnusedEntry>
      ForwardEuler<dim>::unused_entries(const bool step_given) const
      {
        std::vector<UnusedEntry> unused = {no_implicit_scheme(name())};
        for (const char *entry :
             {"Preconditioner", "Solver tolerance", "Maximum iterations"})
          unused.push_back({entry,
                            "'Time stepping = explicit' solves no linear "
                            "system; remove the entry, or choose 'implicit' "
                            "or 'steady state'"});
        if (step_given)
          unused.push_back({"Safety factor",
                            "'Time step' is given, so no fraction of the "
                            "stability bound is taken; set 'Time step = 0' "
                            "to use it, or remove the entry"});
        else
          unused.push_back({"Allow unstable time step",
                            "with 'Time step = 0' the step is 'Safety "
                            "factor' (at most 1) times the stability bound, "
                            "never above it; remove the entry"});
        return unused;
      }


      template <int dim>
      void
      ForwardEuler<dim>::step(Diffusion<dim> &p, Simulator<dim> &)
      {
        // C^{n+1} = C^n + dt (L C^n + S^n) (paper Eq. 31); prescribed
        // values at t^{n+1}.
        // A diffusion model may have left the ghost values of this state
        // up to date (corrosion exchanges them after each step): not twice.
        if (!p.c.has_ghost_elements())
          p.c.update_ghost_values();
        p.op.apply(p.c, p.lc);
        p.evaluate_source(p.time, p.s);
        p.c.zero_out_ghost_values();
        const unsigned int n = p.c.locally_owned_size();
        for (unsigned int k = 0; k < n; ++k)
          if (!p.is_prescribed[k])
            p.c.local_element(k) +=
              p.dt * (p.lc.local_element(k) + p.s.local_element(k));
        p.advance_time();
        p.apply_layer_values(p.time, p.c);
      }


      template <int dim>
      std::vector<UnusedEntry>
      ThetaScheme<dim>::unused_entries(const bool) const
      {
        return no_stability_bound(name());
      }


      template <int dim>
      void
      ThetaScheme<dim>::initialize(Diffusion<dim> &p, Simulator<dim> &simulator)
      {
        if (p.local_laplacian)
          p.setup_local_laplacian(simulator, 1, theta * p.dt);
      }


      template <int dim>
      void
      ThetaScheme<dim>::step(Diffusion<dim> &p, Simulator<dim> &simulator)
      {
        const unsigned int n = p.c.locally_owned_size();
        p.rhs                = p.c;
        if (theta < 1)
          {
            p.c.update_ghost_values();
            p.op.apply(p.c, p.lc);
            p.c.zero_out_ghost_values();
            p.evaluate_source(p.time, p.s);
            for (unsigned int k = 0; k < n; ++k)
              p.rhs.local_element(k) +=
                (1 - theta) * p.dt *
                (p.lc.local_element(k) + p.s.local_element(k));
          }
        p.advance_time();
        p.evaluate_source(p.time, p.s);
        p.rhs.add(theta * p.dt, p.s);
        p.apply_layer_values(p.time, p.c);
        p.last_iterations = p.solve(simulator, 1, theta * p.dt, p.rhs, p.c);
        p.total_iterations += p.last_iterations;
      }


      template <int dim>
      std::vector<double>
      ThetaScheme<dim>::data_times(const double        time,
                                   const double        dt,
                                   const std::uint64_t step_number) const
      {
        if (theta < 1)
          return {time, (step_number - 1) * dt};
        return {time};
      }


      template <int dim>
      std::vector<UnusedEntry>
      SteadyState<dim>::unused_entries(const bool) const
      {
        std::vector<UnusedEntry> unused = {no_implicit_scheme(name())};
        for (const char *entry : {"Time step",
                                  "End time",
                                  "Output every steps",
                                  "Output interval",
                                  "History every steps"})
          unused.push_back({entry,
                            "'Time stepping = steady state' takes no time "
                            "steps (one solve, one output, sources and "
                            "boundary values at t = 0); remove the entry, or "
                            "choose 'explicit' or 'implicit'"});
        for (auto &entry : no_stability_bound(name()))
          unused.push_back(std::move(entry));
        return unused;
      }


      template <int dim>
      void
      SteadyState<dim>::step(Diffusion<dim> &p, Simulator<dim> &simulator)
      {
        p.evaluate_source(0, p.rhs);
        if (p.local_laplacian)
          p.setup_local_laplacian(simulator, 0, 1);
        p.last_iterations = p.solve(simulator, 0, 1, p.rhs, p.c);
        p.total_iterations += p.last_iterations;
      }


      template <int dim>
      std::unique_ptr<Integrator<dim>>
      create(const std::string &name, const double theta)
      {
        if (name == "explicit")
          return std::make_unique<ForwardEuler<dim>>();
        if (name == "implicit")
          return std::make_unique<ThetaScheme<dim>>(theta);
        AssertThrow(name == "steady state", ExcInternalError());
        return std::make_unique<SteadyState<dim>>();
      }


#define PERIDEAL_INSTANTIATE(dim)                                            \
  template class Integrator<dim>;                                            \
  template class ForwardEuler<dim>;                                          \
  template class ThetaScheme<dim>;                                           \
  template class SteadyState<dim>;                                           \
  template std::unique_ptr<Integrator<dim>> create<dim>(const std::string &, \
                                                        const double);
      PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
    } // namespace DiffusionIntegrators
  }   // namespace Problems
} // namespace PeriDEAL
