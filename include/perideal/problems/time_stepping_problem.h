#ifndef perideal_problems_time_stepping_problem_h
#define perideal_problems_time_stepping_problem_h

#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>
#include <perideal/problems/time_loop.h>

#include <string>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * What the time-stepping problem types (explicit dynamics, diffusion)
     * share as problem types: they step with their own integrator, so they
     * solve nothing with the simulator's 'Linear solver', and they support
     * only a boundary treatment that adds no nodes (`none`) and write no
     * node data file
     * (check_time_stepping_setup()). The rest of their loop is shared
     * through time_loop.h.
     */
    template <int dim>
    class TimeSteppingProblem : public ProblemType<dim>
    {
    public:
      /// Refuse a boundary treatment other than `none` and a node data
      /// file, naming the problem type by label().
      void
      check_input(const Simulator<dim> &simulator) const override
      {
        check_time_stepping_setup(label(),
                                  simulator.get_boundary_treatment(),
                                  simulator.get_boundary_treatment_name(),
                                  simulator.get_node_data_file());
      }

      /// Time stepping needs no linear solve of the simulator's.
      bool
      uses_linear_solver() const override
      {
        return false;
      }

    protected:
      /// The problem type as messages name it ("explicit dynamics").
      virtual std::string
      label() const = 0;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
