#include <deal.II/base/mpi.h>

#include <deal.II/numerics/data_out.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/io/solution_output.h>

#include <filesystem>
#include <fstream>

namespace PeriDEAL
{
  namespace IO
  {
    template <int dim>
    void
    SolutionOutput<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Write VTU",
                        "true",
                        Patterns::Bool(),
                        "Whether to write the solution as VTU/PVTU files for "
                        "ParaView.");
      prm.declare_entry("Directory",
                        "output",
                        Patterns::DirectoryName(),
                        "Directory of the output files, created if missing; "
                        "relative to the working directory.");
      prm.declare_entry("Base name",
                        "solution",
                        Patterns::FileName(),
                        "Base name of the output files: <base name>_0.pvtu "
                        "and one <base name>_0.<rank>.vtu per process.");
    }


    template <int dim>
    void
    SolutionOutput<dim>::parse_parameters(ParameterHandler &prm)
    {
      write_vtu        = prm.get_bool("Write VTU");
      output_directory = prm.get("Directory");
      base_name        = prm.get("Base name");
      AssertThrow(!base_name.empty() &&
                    base_name.find('/') == std::string::npos,
                  ExcInvalidInput("Output/Base name",
                                  base_name,
                                  "give a plain file name without '/'; the "
                                  "directory goes in 'Directory'"));
    }


    template <int dim>
    const std::string &
    SolutionOutput<dim>::directory() const
    {
      return output_directory;
    }


    template <int dim>
    std::vector<OutputName>
    SolutionOutput<dim>::output_names(const bool time_series) const
    {
      if (!write_vtu)
        return {};
      const std::string stem = output_directory + "/" + base_name;
      std::vector<OutputName> names = {{"Output/Base name",
                                        base_name,
                                        stem,
                                        OutputName::Kind::records,
                                        "the solution records ('" + base_name +
                                          "_<n>.pvtu' and their pieces)"}};
      if (time_series)
        names.push_back({"Output/Base name",
                         base_name,
                         stem + ".pvd",
                         OutputName::Kind::file,
                         "the time series"});
      return names;
    }


    template <int dim>
    std::string
    SolutionOutput<dim>::write(
      const DoFHandler<dim>               &dof_handler,
      const Discretization::NodeSet<dim>  &nodes,
      const TrilinosWrappers::MPI::Vector &displacement,
      const std::vector<NodeField>        &fields,
      const unsigned int                   index,
      const std::vector<NodeVector>       &vectors) const
    {
      return write_record(dof_handler,
                          nodes,
                          &displacement,
                          fields,
                          index,
                          vectors);
    }


    template <int dim>
    std::string
    SolutionOutput<dim>::write(const DoFHandler<dim>              &dof_handler,
                               const Discretization::NodeSet<dim> &nodes,
                               const std::vector<NodeField>       &fields,
                               const unsigned int                  index) const
    {
      return write_record(dof_handler, nodes, nullptr, fields, index, {});
    }


    template <int dim>
    std::string
    SolutionOutput<dim>::write_record(
      const DoFHandler<dim>               &dof_handler,
      const Discretization::NodeSet<dim>  &nodes,
      const TrilinosWrappers::MPI::Vector *displacement,
      const std::vector<NodeField>        &fields,
      const unsigned int                   index,
      const std::vector<NodeVector>       &vectors) const
    {
      if (!write_vtu)
        return "";
      const MPI_Comm     comm    = dof_handler.get_communicator();
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      {
        std::string error;
        if (rank == 0)
          {
            std::error_code code;
            std::filesystem::create_directories(output_directory, code);
            if (code || !std::filesystem::is_directory(output_directory))
              error = "Invalid value '" + output_directory +
                      "' for the parameter 'Output/Directory': it cannot be "
                      "created (" +
                      code.message() + ").";
          }
        throw_on_any_rank(error, comm);
      }
      const auto                &tria = dof_handler.get_triangulation();
      std::vector<Vector<float>> cell_data(fields.size(),
                                           Vector<float>(
                                             tria.n_active_cells()));
      unsigned int               node = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            for (unsigned int f = 0; f < fields.size(); ++f)
              cell_data[f][cell->active_cell_index()] = fields[f].values[node];
            ++node;
          }
      AssertThrow(node == nodes.n_owned(), ExcInternalError());

      DataOut<dim> data_out;
      data_out.attach_dof_handler(dof_handler);
      const std::vector<std::string> names(dim, "displacement");
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        interpretation(
          dim,
          DataComponentInterpretation::component_is_part_of_vector);
      if (displacement != nullptr)
        data_out.add_data_vector(*displacement,
                                 names,
                                 DataOut<dim>::type_dof_data,
                                 interpretation);
      for (const auto &vector : vectors)
        data_out.add_data_vector(*vector.values,
                                 std::vector<std::string>(dim, vector.name),
                                 DataOut<dim>::type_dof_data,
                                 interpretation);
      for (unsigned int f = 0; f < fields.size(); ++f)
        data_out.add_data_vector(cell_data[f],
                                 fields[f].name,
                                 DataOut<dim>::type_cell_data);
      data_out.build_patches();
      // Fast compression: output of time series must not dominate a run
      // (the best compression took 1.3 s per 64,000-cell record).
      DataOutBase::VtkFlags flags;
      flags.compression_level = DataOutBase::VtkFlags::best_speed;
      data_out.set_flags(flags);

      // Every file is written under a temporary name and renamed when
      // complete: a run killed while writing leaves the previous good
      // output, never a truncated one. Pieces first, then the record that
      // names them.
      const auto piece = [&](const unsigned int r) {
        return base_name + "_" + std::to_string(index) + "." +
               std::to_string(r) + ".vtu";
      };
      const auto write_and_rename = [&](const std::string &name,
                                        const auto        &write) {
        return write_then_rename(output_directory + "/" + name, write);
      };
      throw_on_any_rank(write_and_rename(piece(rank),
                                         [&](std::ostream &out) {
                                           data_out.write_vtu(out);
                                         }),
                        comm);
      const std::string record =
        base_name + "_" + std::to_string(index) + ".pvtu";
      std::string error;
      if (rank == 0)
        {
          // Pieces of an earlier run on more processes are stale now.
          std::error_code code;
          for (unsigned int r = n_ranks;; ++r)
            if (!std::filesystem::remove(output_directory + "/" + piece(r),
                                         code))
              break;
          std::vector<std::string> pieces;
          for (unsigned int r = 0; r < n_ranks; ++r)
            pieces.push_back(piece(r));
          error = write_and_rename(record, [&](std::ostream &out) {
            data_out.write_pvtu_record(out, pieces);
          });
        }
      throw_on_any_rank(error, comm);
      return record;
    }


    template <int dim>
    std::string
    SolutionOutput<dim>::write_time_series(
      const std::vector<std::pair<double, std::string>> &records,
      const MPI_Comm                                     comm) const
    {
      if (!write_vtu)
        return "";
      const std::string name = base_name + ".pvd";
      std::string       error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        error = write_then_rename(output_directory + "/" + name,
                                  [&](std::ostream &out) {
                                    DataOutBase::write_pvd_record(out, records);
                                  });
      throw_on_any_rank(error, comm);
      return name;
    }


    template class SolutionOutput<1>;
    template class SolutionOutput<2>;
    template class SolutionOutput<3>;
  } // namespace IO
} // namespace PeriDEAL
