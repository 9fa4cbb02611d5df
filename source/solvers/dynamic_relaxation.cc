#include <deal.II/base/timer.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/base/exceptions.h>
#include <perideal/base/reproducible_sum.h>
#include <perideal/operators/constrained_operator.h>
#include <perideal/solvers/dynamic_relaxation.h>

#include <cmath>
#include <sstream>
#include <vector>

namespace PeriDEAL
{
  namespace Solvers
  {
    void
    DynamicRelaxation::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Relative tolerance",
                        "1e-8",
                        Patterns::Double(0),
                        "Dynamic relaxation stops when the residual |b - A "
                        "x| is at most this times |b| (the test of the "
                        "Krylov solvers, on the same lifted system).");
      prm.declare_entry("Maximum iterations",
                        "1000000",
                        Patterns::Integer(1),
                        "More iterations than this stop the solve as not "
                        "converged (a load step is then cut).");
    }


    void
    DynamicRelaxation::parse_parameters(ParameterHandler  &prm,
                                        const std::string &path)
    {
      tolerance      = prm.get_double("Relative tolerance");
      max_iterations = prm.get_integer("Maximum iterations");
      AssertThrow(tolerance > 0 && tolerance < 1,
                  ExcInvalidInput(path + "Relative tolerance",
                                  prm.get("Relative tolerance"),
                                  "give a tolerance in (0, 1), for "
                                  "instance 1e-8"));
    }


    namespace
    {
      template <typename VectorType>
      double
      norm(const VectorType &v, std::vector<double> &terms, MPI_Comm comm)
      {
        for (unsigned int k = 0; k < v.locally_owned_size(); ++k)
          terms[k] = v.local_element(k) * v.local_element(k);
        return std::sqrt(reproducible_sum(terms.data(), terms.size(), comm));
      }
    } // namespace


    template <typename OperatorType, typename VectorType>
    SolverReport
    DynamicRelaxation::solve(const OperatorType &op,
                             VectorType         &x,
                             const VectorType   &b,
                             MPI_Comm            comm) const
    {
      Timer               timer;
      const unsigned int  n        = x.locally_owned_size();
      const VectorType   &diagonal = op.diagonal();
      std::vector<double> terms(n), terms2(n);
      for (unsigned int k = 0; k < n; ++k)
        AssertThrow(diagonal.local_element(k) > 0,
                    ExcMessage("Dynamic relaxation needs a positive "
                               "diagonal of the operator (a free node "
                               "without bonds?)."));

      // The largest eigenvalue of diag(A)^-1 A by power iterations, with
      // the Rayleigh quotient in the diag(A) product.
      VectorType z(x), y(x);
      for (unsigned int k = 0; k < n; ++k)
        z.local_element(k) = 1;
      double mu = 0;
      for (unsigned int it = 0; it < 50; ++it)
        {
          op.vmult(y, z);
          for (unsigned int k = 0; k < n; ++k)
            {
              terms[k]  = z.local_element(k) * y.local_element(k);
              terms2[k] = z.local_element(k) * z.local_element(k) *
                          diagonal.local_element(k);
            }
          mu = reproducible_sum(terms.data(), n, comm) /
               reproducible_sum(terms2.data(), n, comm);
          for (unsigned int k = 0; k < n; ++k)
            terms[k] = y.local_element(k) / diagonal.local_element(k);
          double scale = 0;
          for (unsigned int k = 0; k < n; ++k)
            scale = std::max(scale, std::abs(terms[k]));
          scale = Utilities::MPI::max(scale, comm);
          AssertThrow(std::isfinite(mu) && scale > 0,
                      ExcNoConvergence("dynamic relaxation: the estimate of "
                                       "the largest eigenvalue failed"));
          for (unsigned int k = 0; k < n; ++k)
            z.local_element(k) = terms[k] / scale;
        }
      std::vector<double> density(n);
      for (unsigned int k = 0; k < n; ++k)
        density[k] = 1.25 * mu / 4 * diagonal.local_element(k);

      const double b_norm = norm(b, terms, comm);
      VectorType   r(x), r_old(x), v(x);
      // The residual of the operator's own kinematics (nonlinear with
      // finite deformation); the eigenvalue estimate above is of the
      // linearised operator.
      const auto residual = [&]() {
        op.residual(r, x, b);
        return norm(r, terms, comm);
      };
      SolverReport report;
      report.method       = "dynamic relaxation";
      double       r_norm = residual();
      const double goal   = tolerance * b_norm;
      // A mode the eigenvalue estimate missed grows: back to the best
      // iterate with twice the density (a decision from reproducible sums,
      // the same on every process).
      VectorType   best_x(x);
      double       best_norm  = r_norm;
      unsigned int restarts   = 0;
      bool         restarting = true;
      unsigned int it         = 0;
      for (; r_norm > goal && it < max_iterations; ++it)
        {
          if (!std::isfinite(r_norm) || r_norm > 1e3 * best_norm)
            {
              AssertThrow(restarts < 20,
                          ExcNoConvergence(
                            "dynamic relaxation: unstable after 20 "
                            "doublings of the fictitious density"));
              ++restarts;
              for (auto &d : density)
                d *= 2;
              x          = best_x;
              r_norm     = residual();
              restarting = true;
            }
          double c = 0;
          if (restarting)
            {
              for (unsigned int k = 0; k < n; ++k)
                v.local_element(k) = r.local_element(k) / density[k] / 2;
              restarting = false;
            }
          else
            {
              // The local stiffness of each unknown from the change of its
              // force over the last step, in the Rayleigh quotient of x.
              for (unsigned int k = 0; k < n; ++k)
                {
                  const double dv = v.local_element(k);
                  const double stiffness =
                    dv != 0 ? -(r.local_element(k) - r_old.local_element(k)) /
                                (density[k] * dv) :
                              0.;
                  const double xk = x.local_element(k);
                  terms[k]        = xk * xk * stiffness;
                  terms2[k]       = xk * xk;
                }
              const double num = reproducible_sum(terms.data(), n, comm);
              const double den = reproducible_sum(terms2.data(), n, comm);
              if (num > 0 && den > 0)
                c = std::min(2 * std::sqrt(num / den), 2.);
              for (unsigned int k = 0; k < n; ++k)
                v.local_element(k) = ((2 - c) * v.local_element(k) +
                                      2 * r.local_element(k) / density[k]) /
                                     (2 + c);
            }
          x += v;
          r_old  = r;
          r_norm = residual();
          if (r_norm < best_norm)
            {
              best_norm = r_norm;
              best_x    = x;
            }
        }
      report.iterations        = it;
      report.relative_residual = b_norm > 0 ? r_norm / b_norm : r_norm;
      report.seconds           = timer.wall_time();
      if (r_norm > goal)
        {
          std::ostringstream message;
          message << "dynamic relaxation did not converge in " << it
                  << " iterations: relative residual "
                  << report.relative_residual << " against the tolerance "
                  << tolerance
                  << " ('quasi-static/dynamic relaxation/Relative "
                     "tolerance', 'Maximum iterations')";
          AssertThrow(false, ExcNoConvergence(message.str()));
        }
      return report;
    }


    template SolverReport
    DynamicRelaxation::solve(const Operators::ConstrainedOperator<2> &,
                             LinearAlgebra::distributed::Vector<double> &,
                             const LinearAlgebra::distributed::Vector<double> &,
                             MPI_Comm) const;
    template SolverReport
    DynamicRelaxation::solve(const Operators::ConstrainedOperator<3> &,
                             LinearAlgebra::distributed::Vector<double> &,
                             const LinearAlgebra::distributed::Vector<double> &,
                             MPI_Comm) const;
  } // namespace Solvers
} // namespace PeriDEAL
