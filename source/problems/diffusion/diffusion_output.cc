/**
 * @file
 * What the diffusion problem type reports: a row of the history per
 * recorded step (total amount, extrema, iterations, errors against the
 * analytical solution, the model's columns), the progress line on rank 0,
 * the PVTU records with their PVD time series and the history CSV, and
 * the names of these outputs (output_names()).
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <string>
#include <system_error>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    Diffusion<dim>::record_history(Simulator<dim> &simulator)
    {
      const MPI_Comm comm    = simulator.get_communicator();
      double         total   = 0;
      double         lowest  = std::numeric_limits<double>::max();
      double         highest = std::numeric_limits<double>::lowest();
      double         error2 = 0, exact2 = 0, max_error = 0;
      if (compare)
        analytical->set_time(time);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const unsigned int k     = op.vector_index(i);
          const double       value = c.local_element(k);
          total += (*nodes)[i].volume() * value;
          lowest  = std::min(lowest, value);
          highest = std::max(highest, value);
          if (compare && !is_prescribed[k])
            {
              const double exact = analytical->value((*nodes)[i].location);
              error2 += (value - exact) * (value - exact);
              exact2 += exact * exact;
              max_error = std::max(max_error, std::abs(value - exact));
            }
        }
      total                   = Utilities::MPI::sum(total, comm);
      lowest                  = Utilities::MPI::min(lowest, comm);
      highest                 = Utilities::MPI::max(highest, comm);
      std::vector<double> row = {time,
                                 double(step_number),
                                 total,
                                 lowest,
                                 highest,
                                 double(last_iterations)};
      if (compare)
        {
          error2    = Utilities::MPI::sum(error2, comm);
          exact2    = Utilities::MPI::sum(exact2, comm);
          max_error = Utilities::MPI::max(max_error, comm);
          row.push_back(exact2 > 0 ? std::sqrt(error2 / exact2) :
                                     std::sqrt(error2));
          row.push_back(max_error);
        }
      if (hybrid)
        row.push_back(double(Utilities::MPI::sum(
          std::uint64_t(nodes->n_owned() - op.n_collocation_nodes_now()),
          comm)));
      const auto values = model->history_values(model_setup(), c);
      row.insert(row.end(), values.begin(), values.end());
      history.push_back(row);
    }


    template <int dim>
    void
    Diffusion<dim>::print_progress_line(Simulator<dim> &simulator)
    {
      const double now = simulator.elapsed();
      last_progress    = now;
      const auto &row  = history.back();
      auto       &out  = simulator.get_pcout();
      out << "[" << std::setw(8) << std::fixed << std::setprecision(2) << now
          << " s] ";
      if (!integrator->takes_time_steps())
        out << "steady state";
      else
        out << "step " << step_number << "/" << n_steps
            << ", t = " << std::scientific << std::setprecision(4) << time;
      out << std::scientific << std::setprecision(4) << ", total " << row[2]
          << ", min " << row[3] << ", max " << row[4];
      if (integrator->solves_linear_systems())
        out << ", " << last_iterations << " iterations";
      if (compare)
        out << ", relative l2 error " << row[6] << ", max error " << row[7];
      if (hybrid)
        out << ", standard nodes " << std::uint64_t(row[compare ? 8 : 6]);
      if (!model_columns.empty())
        out << ", "
            << model->progress_text(
                 std::vector<double>(row.end() - model_columns.size(),
                                     row.end()));
      if (integrator->takes_time_steps())
        {
          const double rate = step_number / std::max(now - loop_start, 1e-9);
          out << ", " << std::fixed << std::setprecision(1) << rate
              << " steps/s, " << std::setprecision(0)
              << (n_steps - step_number) / std::max(rate, 1e-9) << " s left";
        }
      out << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    Diffusion<dim>::write_output(Simulator<dim> &simulator)
    {
      const MPI_Comm comm = simulator.get_communicator();
      time_loop.advance_output_time(next_output_time,
                                    time,
                                    std::max(dt, 1e-300));
      const auto &output = simulator.get_output();
      if (output.enabled())
        {
          IO::NodeField concentration{"concentration", {}}, error{"error", {}},
            rank{"mpi_rank", {}}, scheme{"scheme", {}};
          if (compare)
            analytical->set_time(time);
          const double this_rank = Utilities::MPI::this_mpi_process(comm);
          for (unsigned int i = 0; i < nodes->n_owned(); ++i)
            {
              const double value = c.local_element(op.vector_index(i));
              concentration.values.push_back(value);
              if (compare)
                error.values.push_back(value -
                                       analytical->value((*nodes)[i].location));
              rank.values.push_back(this_rank);
              // As in explicit dynamics: 0 standard, 1 collocation.
              if (hybrid)
                scheme.values.push_back(op.is_collocation_node(i) ? 1. : 0.);
            }
          std::vector<IO::NodeField> fields = {concentration, rank};
          if (compare)
            fields.push_back(error);
          if (hybrid)
            fields.push_back(scheme);
          for (auto &field : model->node_fields(model_setup(), c))
            fields.push_back(std::move(field));
          const std::string record = output.write(simulator.get_dof_handler(),
                                                  *nodes,
                                                  fields,
                                                  records.size());
          records.emplace_back(time, record);
          output.write_time_series(records, comm);
        }
      if (!history_file.empty())
        {
          std::string error;
          if (Utilities::MPI::this_mpi_process(comm) == 0)
            {
              const std::string path = output.directory() + "/" + history_file;
              std::error_code   code;
              std::filesystem::create_directories(output.directory(), code);
              error = write_then_rename(path, [&](std::ostream &out) {
                out << "time,step,total,minimum,maximum,iterations";
                if (compare)
                  out << ",relative_l2_error,max_error";
                if (hybrid)
                  out << ",standard_nodes";
                for (const auto &name : model_columns)
                  out << ',' << name;
                out << '\n' << std::setprecision(12);
                for (const auto &row : history)
                  {
                    for (unsigned int k = 0; k < row.size(); ++k)
                      out << (k > 0 ? "," : "") << row[k];
                    out << '\n';
                  }
              });
              if (!error.empty())
                error =
                  "Invalid value '" + path +
                  "' for the parameter 'diffusion/History file': " + error +
                  ".";
            }
          throw_on_any_rank(error, comm);
        }
    }


    template <int dim>
    std::vector<IO::OutputName>
    Diffusion<dim>::output_names(const Simulator<dim> &simulator) const
    {
      const auto &output = simulator.get_output();
      auto        names  = output.output_names(true);
      if (!history_file.empty())
        names.push_back({section + "/History file",
                         history_file,
                         output.directory() + "/" + history_file,
                         IO::OutputName::Kind::file,
                         "the history file"});
      return names;
    }


#define PERIDEAL_INSTANTIATE(dim)                                      \
  template void Diffusion<dim>::record_history(Simulator<dim> &);      \
  template void Diffusion<dim>::print_progress_line(Simulator<dim> &); \
  template void Diffusion<dim>::write_output(Simulator<dim> &);        \
  template std::vector<IO::OutputName> Diffusion<dim>::output_names(   \
    const Simulator<dim> &) const;
    PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
