#ifndef perideal_io_run_summary_h
#define perideal_io_run_summary_h

/**
 * @file
 * The run summary: what one run measured (RunSummary) and the CSV file to
 * which each run appends one row of it ('Output/Summary file').
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <perideal/solvers/solver_report.h>

#include <map>
#include <string>

namespace PeriDEAL
{
  namespace IO
  {
    using namespace dealii;

    /**
     * Errors of a computed displacement against an analytical one, over the
     * owned nodes of all processes:
     * \f[
     *   e_{L^2} = \Big(\frac{\sum_i V_i |u_i - u(x_i)|^2}
     *                      {\sum_i V_i |u(x_i)|^2}\Big)^{1/2},\qquad
     *   e_{\max} = \frac{\max_i |u_i - u(x_i)|}{\max_i |u(x_i)|}.
     * \f]
     */
    struct ErrorNorms
    {
      double l2  = 0;
      double max = 0;
      /**
       * Scabbia et al. 2023, Eq. 38: the largest over the nodes of
       * \f$\big(\sum_c ((u_{i,c} - \bar u_c(x_i)) / \max_j |\bar u_c(x_j)|)^2
       * \big)^{1/2}\f$, each component scaled by its own largest analytical
       * magnitude (components that vanish everywhere are left out).
       */
      double max_normalized = 0;
    };

    /**
     * What a run measured: sizes, solver report, errors, the wall time of
     * each phase and the peak memory; and what it ran (dimension, problem
     * type, model, partial volumes, operator and preconditioner, by name).
     * Written to the summary CSV by append_run_summary().
     */
    struct RunSummary
    {
      unsigned int dim = 0;
      std::string  problem_type;
      std::string  model;
      std::string  partial_volumes;
      /// 'matrix-free' or 'assembled'.
      std::string                   operator_type;
      std::string                   preconditioner;
      unsigned int                  n_ranks             = 1;
      types::global_dof_index       n_nodes             = 0;
      types::global_dof_index       n_constrained_nodes = 0;
      double                        h = 0, horizon = 0;
      std::size_t                   n_bonds    = 0;
      std::size_t                   n_nonzeros = 0;
      Solvers::SolverReport         solver;
      double                        equilibrium_residual = 0;
      std::string                   treatment            = "none";
      unsigned int                  taylor_order         = 0;
      types::global_dof_index       n_unknowns           = 0;
      unsigned int                  n_surface_nodes      = 0;
      unsigned int                  n_fictitious_nodes   = 0;
      bool                          has_errors           = false;
      ErrorNorms                    errors;
      std::map<std::string, double> seconds;
      double                        peak_memory_mb = 0;
    };

    /**
     * Why no row can be appended to the summary CSV @p file: an empty
     * string where the file is new, empty or has the columns of this
     * version; otherwise the reason (it exists with other columns, and a
     * row appended to it would be misread), for a message naming the entry.
     */
    std::string
    check_run_summary_columns(const std::string &file);

    /**
     * Append one row of @p summary to the CSV @p file (with the header when
     * the file is new or empty). The file is rewritten under a temporary
     * name and renamed, so that a run killed while writing never truncates
     * the rows of earlier runs. Process 0 of @p communicator writes; its
     * verdict is shared (collective): an error names 'Output/Summary file'.
     */
    void
    append_run_summary(const std::string &file,
                       const RunSummary  &summary,
                       const MPI_Comm     communicator);
  } // namespace IO
} // namespace PeriDEAL

#endif
