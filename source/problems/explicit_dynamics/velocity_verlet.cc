/**
 * @file
 * The velocity-Verlet integrator of explicit dynamics.
 */

#include <deal.II/base/parallel.h>

#include <perideal/problems/explicit_dynamics/velocity_verlet.h>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      // Entries per task of the threaded updates.
      constexpr unsigned int grain = 8192;
    } // namespace


    void
    VelocityVerlet::set_time_step(const double step)
    {
      dt = step;
    }


    double
    VelocityVerlet::time_step() const
    {
      return dt;
    }


    void
    VelocityVerlet::advance_first_half(VectorType                &u,
                                       VectorType                &v,
                                       const VectorType          &a,
                                       const std::vector<double> &free) const
    {
      const unsigned int n  = u.locally_owned_size();
      double            *pu = u.begin(), *pv = v.begin();
      const double      *pa = a.begin(), *pf = free.data();
      // Entry by entry: threads change no rounding.
      dealii::parallel::apply_to_subranges(
        0u,
        n,
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int k = begin; k < end; ++k)
            {
              const double half = pv[k] + 0.5 * dt * pa[k];
              const double next = pu[k] + dt * half;
              pv[k]             = pf[k] != 0 ? half : pv[k];
              pu[k]             = pf[k] != 0 ? next : pu[k];
            }
        },
        grain);
    }


    void
    VelocityVerlet::advance_second_half(VectorType                &v,
                                        const VectorType          &a,
                                        const std::vector<double> &free) const
    {
      const unsigned int n  = v.locally_owned_size();
      double            *pv = v.begin();
      const double      *pa = a.begin(), *pf = free.data();
      dealii::parallel::apply_to_subranges(
        0u,
        n,
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int k = begin; k < end; ++k)
            {
              const double next = pv[k] + 0.5 * dt * pa[k];
              pv[k]             = pf[k] != 0 ? next : pv[k];
            }
        },
        grain);
    }


    double
    VelocityVerlet::add_load_work(double                     work,
                                  const double               factor,
                                  const VectorType          &load,
                                  const VectorType          &v,
                                  const std::vector<double> &free) const
    {
      const unsigned int n  = v.locally_owned_size();
      const double      *pl = load.begin(), *pv = v.begin(), *pf = free.data();
      for (unsigned int k = 0; k < n; ++k)
        work += 0.5 * factor * pl[k] * dt * pv[k] * pf[k];
      return work;
    }
  } // namespace Problems
} // namespace PeriDEAL
