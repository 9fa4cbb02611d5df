/**
 * @file
 * The summary CSV of include/perideal/io/run_summary.h: its columns, the
 * check of an existing file's header, and the row each run appends.
 */

#include <deal.II/base/multithread_info.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/io/run_summary.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace IO
  {
    namespace
    {
      /// The columns of the summary CSV.
      const std::string summary_header =
        "dim,model,algorithm,n_ranks,n_nodes,n_constrained_nodes,"
        "h,horizon,m_ratio,n_bonds,nnz,solver,iterations,"
        "relative_residual,equilibrium_residual,l2_error,"
        "max_error,time_mesh,time_nodes,time_neighbors,"
        "time_operator,time_assembly,time_solve,time_output,"
        "time_total,peak_memory_mb,treatment,taylor_order,"
        "n_unknowns,n_surface_nodes,n_fictitious_nodes,"
        "max_normalized_error,operator,preconditioner,"
        "time_preconditioner,n_threads,problem_type";

      const std::string summary_columns_differ =
        "the file exists with other columns (an older version or another "
        "program wrote it), and a row appended to it would be misread; name "
        "a new file, or move the old one away.";

      /// One row of the CSV, in the columns of summary_header.
      std::string
      summary_row(const RunSummary &summary)
      {
        std::ostringstream csv;
        const auto         t = [&](const std::string &phase) {
          const auto it = summary.seconds.find(phase);
          return it == summary.seconds.end() ? 0. : it->second;
        };
        csv << std::setprecision(10) << summary.dim << ",\"" << summary.model
            << "\",\"" << summary.partial_volumes << "\"," << summary.n_ranks
            << ',' << summary.n_nodes << ',' << summary.n_constrained_nodes
            << ',' << summary.h << ',' << summary.horizon << ','
            << summary.horizon / summary.h << ',' << summary.n_bonds << ','
            << summary.n_nonzeros << ",\"" << summary.solver.method << "\","
            << summary.solver.iterations << ','
            << summary.solver.relative_residual << ','
            << summary.equilibrium_residual << ','
            << (summary.has_errors ? format_number(summary.errors.l2) : "")
            << ','
            << (summary.has_errors ? format_number(summary.errors.max) : "")
            << ',' << t("mesh") << ',' << t("nodes and ghost exchange") << ','
            << t("neighbour search and weights") << ',' << t("operator setup")
            << ',' << t("assembly") << ',' << t("solve") << ',' << t("output")
            << ',' << t("total") << ',' << summary.peak_memory_mb << ",\""
            << summary.treatment << "\"," << summary.taylor_order << ','
            << summary.n_unknowns << ',' << summary.n_surface_nodes << ','
            << summary.n_fictitious_nodes << ','
            << (summary.has_errors ?
                  format_number(summary.errors.max_normalized) :
                  "")
            << ",\"" << summary.operator_type << "\",\""
            << summary.preconditioner << "\"," << t("preconditioner setup")
            << ',' << MultithreadInfo::n_threads() << ",\""
            << summary.problem_type << "\"\n";
        return csv.str();
      }
    } // namespace


    std::string
    check_run_summary_columns(const std::string &file)
    {
      std::ifstream in(file);
      std::string   first_line;
      return in && std::getline(in, first_line) &&
                 first_line != summary_header ?
               summary_columns_differ :
               std::string();
    }


    void
    append_run_summary(const std::string &file,
                       const RunSummary  &summary,
                       const MPI_Comm     communicator)
    {
      const std::string header = summary_header;
      std::string       error;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          std::string earlier;
          if (std::filesystem::exists(file))
            {
              std::ifstream     in(file);
              std::stringstream content;
              content << in.rdbuf();
              earlier = content.str();
              if (!earlier.empty() &&
                  earlier.substr(0, earlier.find('\n')) != header)
                error = "Invalid value '" + file +
                        "' for the parameter 'Output/Summary file': " +
                        summary_columns_differ;
              if (!earlier.empty() && earlier.back() != '\n')
                earlier += '\n';
            }
          const std::filesystem::path parent =
            std::filesystem::path(file).parent_path();
          std::error_code ignored;
          if (!parent.empty())
            std::filesystem::create_directories(parent, ignored);
          const std::string row = summary_row(summary);
          if (error.empty())
            {
              const std::string written =
                write_then_rename(file, [&](std::ostream &out) {
                  out << (earlier.empty() ? header + "\n" : earlier) << row;
                });
              if (!written.empty())
                error = "Invalid value '" + file +
                        "' for the parameter 'Output/Summary file': " + written;
            }
        }
      throw_on_any_rank(error, communicator);
    }
  } // namespace IO
} // namespace PeriDEAL
