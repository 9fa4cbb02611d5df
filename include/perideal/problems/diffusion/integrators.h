#ifndef perideal_problems_diffusion_integrators_h
#define perideal_problems_diffusion_integrators_h

#include <perideal/base/input_checks.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    class Simulator;
    template <int dim>
    class Diffusion;

    /**
     * The time integrators of the diffusion problem type, one class per
     * value of 'diffusion/Time stepping', chosen once by create(). The
     * problem type asks an integrator what it needs (whether it marches
     * in time, solves linear systems, has a stability bound) instead of
     * comparing the selection, and lets it take the steps.
     */
    namespace DiffusionIntegrators
    {
      /**
       * A scheme for \f$\dot C = LC + S(t)\f$ on the free nodes with the
       * prescribed values of the layers. step() works on the state of the
       * Diffusion problem it is given (concentration, time, step count,
       * iteration counts), through the operator, the sources, the layers
       * and the linear solve of that problem.
       */
      template <int dim>
      class Integrator
      {
      public:
        virtual ~Integrator() = default;

        /// The value of 'diffusion/Time stepping' that selects it.
        virtual std::string
        name() const = 0;

        /// Whether it marches in time; false: the steady state, one solve
        /// with the data at t = 0 and no time step.
        virtual bool
        takes_time_steps() const
        {
          return true;
        }

        /// Whether a step (or the steady state) is a linear solve; the
        /// values of mirror layers depend on the solution and cannot be
        /// part of one.
        virtual bool
        solves_linear_systems() const
        {
          return true;
        }

        /// Whether a step above the stability bound (\f$2/\lambda_G\f$, or
        /// the model's limit) diverges, so that a given step is checked
        /// against it and 'Time step = 0' takes a fraction of it.
        virtual bool
        is_conditionally_stable() const
        {
          return false;
        }

        /// Whether 'Time step' must be given (> 0): there is no bound to
        /// take it from.
        virtual bool
        needs_given_time_step() const
        {
          return false;
        }

        /**
         * The entries of the subsection 'diffusion' (paths relative to it)
         * that this scheme does not read, with the reason; @p step_given:
         * 'Time step' > 0.
         */
        virtual std::vector<UnusedEntry>
        unused_entries(const bool step_given) const = 0;

        /// Once the time step is known, before the first step (the
        /// preconditioner of a fixed system matrix, say).
        virtual void
        initialize(Diffusion<dim> &problem, Simulator<dim> &simulator);

        /**
         * Advance the problem's concentration, step count and time by one
         * step, with the prescribed values at the new time; the steady
         * state: solve for it.
         */
        virtual void
        step(Diffusion<dim> &problem, Simulator<dim> &simulator) = 0;

        /**
         * The times at which the right-hand side of the solve of step
         * @p step_number (ending at @p time, of length @p dt) evaluates the
         * source and the fluxes, for messages about non-finite data.
         */
        virtual std::vector<double>
        data_times(const double        time,
                   const double        dt,
                   const std::uint64_t step_number) const;
      };


      /// 'explicit': forward Euler (paper Eq. 31), stable up to
      /// \f$2/\lambda_G\f$.
      template <int dim>
      class ForwardEuler : public Integrator<dim>
      {
      public:
        std::string
        name() const override
        {
          return "explicit";
        }

        bool
        solves_linear_systems() const override
        {
          return false;
        }

        bool
        is_conditionally_stable() const override
        {
          return true;
        }

        std::vector<UnusedEntry>
        unused_entries(const bool step_given) const override;

        /// \f$C^{n+1} = C^n + \Delta t\,(LC^n + S^n)\f$ on the free nodes.
        void
        step(Diffusion<dim> &problem, Simulator<dim> &simulator) override;
      };


      /**
       * 'implicit': the θ-scheme, backward Euler (θ = 1) or Crank-Nicolson
       * (θ = 1/2) ('Implicit scheme'), each step a solve with
       * \f$I - \theta\Delta t L\f$.
       */
      template <int dim>
      class ThetaScheme : public Integrator<dim>
      {
      public:
        explicit ThetaScheme(const double theta)
          : theta(theta)
        {}

        std::string
        name() const override
        {
          return "implicit";
        }

        bool
        needs_given_time_step() const override
        {
          return true;
        }

        std::vector<UnusedEntry>
        unused_entries(const bool step_given) const override;

        /// The local Laplacian of \f$I - \theta\Delta t L\f$, if chosen.
        void
        initialize(Diffusion<dim> &problem, Simulator<dim> &simulator) override;

        /// \f$(I - \theta\Delta t L)C^{n+1} = C^n + (1 - \theta)\Delta t
        /// (LC^n + S^n) + \theta\Delta t S^{n+1}\f$.
        void
        step(Diffusion<dim> &problem, Simulator<dim> &simulator) override;

        /// The new time, and the previous one for θ < 1.
        std::vector<double>
        data_times(const double        time,
                   const double        dt,
                   const std::uint64_t step_number) const override;

      private:
        const double theta;
      };


      /// 'steady state': \f$-LC = S\f$ (data at t = 0), one solve.
      template <int dim>
      class SteadyState : public Integrator<dim>
      {
      public:
        std::string
        name() const override
        {
          return "steady state";
        }

        bool
        takes_time_steps() const override
        {
          return false;
        }

        std::vector<UnusedEntry>
        unused_entries(const bool step_given) const override;

        void
        step(Diffusion<dim> &problem, Simulator<dim> &simulator) override;
      };


      /**
       * The integrator for 'Time stepping' = @p name ('explicit',
       * 'implicit', 'steady state'; the pattern admits no other), with
       * @p theta for the θ-scheme.
       */
      template <int dim>
      std::unique_ptr<Integrator<dim>>
      create(const std::string &name, const double theta);
    } // namespace DiffusionIntegrators
  }   // namespace Problems
} // namespace PeriDEAL

#endif
