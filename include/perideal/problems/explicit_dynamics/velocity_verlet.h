#ifndef perideal_problems_explicit_dynamics_velocity_verlet_h
#define perideal_problems_explicit_dynamics_velocity_verlet_h

#include <deal.II/lac/la_parallel_vector.h>

#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    using namespace dealii;

    /**
     * The time integrator of explicit dynamics: velocity Verlet
     * (hybrid-collocation paper, Eq. 29),
     * \f[
     *   \dot u^{n+1/2} = \dot u^n + \tfrac{\Delta t}{2}\ddot u^n,\quad
     *   u^{n+1} = u^n + \Delta t\,\dot u^{n+1/2},\quad
     *   \dot u^{n+1} = \dot u^{n+1/2} + \tfrac{\Delta t}{2}\ddot u^{n+1},
     * \f]
     * on the free DoFs of the owned nodes (a mask of 1 where free, 0 where
     * prescribed: prescribed values are set by the problem, not
     * integrated). There is no damping. ExplicitDynamics::step() calls
     * advance_first_half(), sets the prescribed values and computes the new
     * acceleration, then calls advance_second_half(); the external work of
     * the loads over the step is the trapezoidal rule in time on the
     * half-step velocity (add_load_work()).
     *
     * Only local work, no communication; each update is per DoF, so the
     * results do not depend on the partition.
     */
    class VelocityVerlet
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /// Set the time step \f$\Delta t\f$ in s.
      void
      set_time_step(const double dt);

      /// The time step \f$\Delta t\f$ in s.
      double
      time_step() const;

      /**
       * The half step of the velocity and the full step of the
       * displacement: @p v becomes \f$\dot u^{n+1/2}\f$ and @p u becomes
       * \f$u^{n+1}\f$ where @p free is not 0; both are left unchanged
       * elsewhere.
       *
       * @param[in,out] u The displacement, owned entries.
       * @param[in,out] v The velocity, owned entries.
       * @param[in] a The acceleration \f$\ddot u^n\f$.
       * @param[in] free Per owned entry: 1 free, 0 prescribed.
       */
      void
      advance_first_half(VectorType                &u,
                         VectorType                &v,
                         const VectorType          &a,
                         const std::vector<double> &free) const;

      /**
       * The second half step of the velocity with the new acceleration
       * \f$\ddot u^{n+1}\f$ @p a, where @p free is not 0.
       */
      void
      advance_second_half(VectorType                &v,
                          const VectorType          &a,
                          const std::vector<double> &free) const;

      /**
       * Add to @p work (local to this process) one half of the trapezoidal
       * rule for the work of the load @p factor times @p load on the free
       * DoFs over the step, \f$\tfrac12 g\,\sum_k f_k\,\Delta t\,\dot
       * u^{n+1/2}_k\f$, and return it. The sum runs over the owned entries
       * in order, continuing from @p work (the order of the sum is part of
       * the answer).
       */
      double
      add_load_work(double                     work,
                    const double               factor,
                    const VectorType          &load,
                    const VectorType          &v,
                    const std::vector<double> &free) const;

    private:
      double dt = 0;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
