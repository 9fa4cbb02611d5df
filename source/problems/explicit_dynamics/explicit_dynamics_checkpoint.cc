/**
 * @file
 * Writing the checkpoint of an explicit dynamics run
 * (ExplicitDynamics::write_checkpoint(): into checkpoint.new, then renamed
 * into place), and the check that a run which does not resume replaces no
 * checkpoint further in time. The format is in
 * explicit_dynamics_checkpoint_format.h.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_checkpoint_format.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_internal.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsCheckpoint::ChecksumWriter;
    using internal::ExplicitDynamicsCheckpoint::magic;
    using internal::ExplicitDynamicsCheckpoint::magic_v2;


    template <int dim>
    void
    ExplicitDynamics<dim>::write_checkpoint(Simulator<dim> &simulator)
    {
      const internal::ExplicitDynamicsCheckpoint::Directories dirs(
        simulator.get_output().directory());
      namespace fs         = std::filesystem;
      const fs::path &base = dirs.base, &fresh = dirs.fresh, &good = dirs.good,
                     &old = dirs.old;
      const MPI_Comm comm = simulator.get_communicator();
      const auto     rank = Utilities::MPI::this_mpi_process(comm);
      finite_check.finish_state_check();
      sum_step_counters(comm);
      const auto &keys = checkpoint_keys(simulator);
      {
        std::string error;
        if (rank == 0)
          {
            std::error_code code;
            fs::remove_all(fresh, code);
            fs::create_directories(fresh, code);
            if (code)
              error = "Cannot create the checkpoint directory '" +
                      fresh.string() + "': " + code.message() +
                      " (check 'Output/Directory').";
          }
        throw_on_any_rank(error, comm);
      }

      std::string error;
      const auto  finish = [&](ChecksumWriter &out, const fs::path &path) {
        out.out.flush();
        if (!out.out)
          error = "Cannot write the checkpoint file '" + path.string() + "'.";
      };
      const auto &nodes = simulator.get_nodes();
      // This process's state file: number of records, size, checksum.
      std::vector<std::uint64_t> piece;
      {
        const fs::path path =
          fresh / ("state." + std::to_string(rank) + ".bin");
        ChecksumWriter out(path);
        out.put(magic);
        out.put<std::uint64_t>(nodes.n_owned());
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            for (unsigned int d = 0; d < dim; ++d)
              out.put(nodes[i].location[d]);
            for (const auto *vector : {&u, &v, &a, &force})
              for (unsigned int c = 0; c < dim; ++c)
                out.put((*vector)[nodes[i].dofs[c]]);
            out.put<std::uint64_t>(bond_state.n_broken(i));
            const unsigned int n_bonds =
              simulator.get_neighbor_lists().n_bonds(i);
            for (unsigned int k = 0; k < n_bonds; ++k)
              if (bond_state.is_broken(i, k))
                for (unsigned int d = 0; d < dim; ++d)
                  out.put(nodes[bond_state.neighbor(i, k)].location[d]);
          }
        // The hybrid scheme: after the node records, the positions of the
        // owned nodes that are still collocation nodes (every other node
        // is standard; read_checkpoint() switches them).
        if (hybrid != nullptr)
          {
            std::vector<unsigned int> collocation;
            for (unsigned int i = 0; i < nodes.n_owned(); ++i)
              if (bond_operator.is_collocation_node(i))
                collocation.push_back(i);
            out.put<std::uint64_t>(collocation.size());
            for (const unsigned int i : collocation)
              for (unsigned int d = 0; d < dim; ++d)
                out.put(nodes[i].location[d]);
          }
        finish(out, path);
        piece = {nodes.n_owned(), out.size, out.checksum.value};
      }
      const auto pieces = Utilities::MPI::gather(comm, piece, 0);
      if (rank == 0)
        {
          const fs::path path = fresh / "run.bin";
          ChecksumWriter out(path);
          out.put(magic);
          out.put<std::uint64_t>(pieces.size());
          out.put(time);
          out.put(dt);
          out.put<std::uint64_t>(step_number);
          out.put<std::uint64_t>(n_steps);
          out.put(external_work);
          out.put(load_factor);
          out.put<std::uint64_t>(broken_bonds);
          out.put(next_output_time);
          out.put<std::uint64_t>(energy_rows.size());
          for (const auto &row : energy_rows)
            out.put_doubles(row);
          out.put<std::uint64_t>(records.size());
          for (const auto &[t, name] : records)
            {
              out.put(t);
              out.put_string(name);
            }
          out.put<std::uint64_t>(keys.size());
          for (const auto &key : keys)
            {
              out.put_string(key.name);
              out.put_string(key.value);
            }
          out.put<std::uint64_t>(pieces.size());
          for (const auto &p : pieces)
            for (const auto value : p)
              out.put(value);
          // The checksum of everything before it.
          const std::uint64_t checksum = out.checksum.value;
          out.out.write(reinterpret_cast<const char *>(&checksum),
                        sizeof(checksum));
          finish(out, path);
        }
      throw_on_any_rank(error, comm);

      if (rank == 0)
        {
          std::error_code code;
          fs::remove_all(old, code);
          if (fs::exists(good))
            fs::rename(good, old, code);
          if (!code)
            fs::rename(fresh, good, code);
          if (!code)
            fs::remove_all(old, code);
          if (code)
            error = "Cannot move the checkpoint into place in '" +
                    base.string() + "': " + code.message() + ".";
        }
      throw_on_any_rank(error, comm);
      simulator.get_pcout() << "           checkpoint at step " << step_number
                            << " written to " << good.string() << std::endl;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::check_checkpoint_overwrite(
      Simulator<dim> &simulator) const
    {
      namespace fs = std::filesystem;
      if (overwrite_checkpoint)
        return;
      // The first step at which this run writes a checkpoint (none at the
      // last step); wall-time checkpoints are decided at energy rows.
      std::uint64_t first = n_steps;
      if (checkpoint_every_steps > 0)
        first = std::min<std::uint64_t>(first, checkpoint_every_steps);
      if (steps_per_run > 0)
        first = std::min<std::uint64_t>(first, steps_per_run);
      if (checkpoint_minutes > 0)
        first = std::min<std::uint64_t>(first, energy_every_steps);
      if (first >= static_cast<std::uint64_t>(n_steps))
        return;
      const double   first_time = first * dt;
      const MPI_Comm comm       = simulator.get_communicator();
      const internal::ExplicitDynamicsCheckpoint::Directories dirs(
        simulator.get_output().directory());
      std::string error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        for (const fs::path &dir : {dirs.good, dirs.old})
          {
            const fs::path  path = dir / "run.bin";
            std::error_code code;
            if (!fs::exists(path, code))
              continue;
            // The first fields are the same in every format.
            std::ifstream in(path, std::ios::binary);
            std::uint64_t mark = 0, writers = 0, step = 0;
            double        t = 0, h = 0;
            in.read(reinterpret_cast<char *>(&mark), sizeof(mark));
            in.read(reinterpret_cast<char *>(&writers), sizeof(writers));
            in.read(reinterpret_cast<char *>(&t), sizeof(t));
            in.read(reinterpret_cast<char *>(&h), sizeof(h));
            in.read(reinterpret_cast<char *>(&step), sizeof(step));
            const bool readable =
              in && (mark == magic || mark == magic_v2) && std::isfinite(t);
            const std::string fix =
              "; set 'explicit dynamics/Resume from checkpoint = true' to "
              "continue from it, or 'explicit dynamics/Overwrite checkpoint "
              "= true' to start afresh and replace it (or choose another "
              "'Output/Directory')";
            const std::string mine = "the first checkpoint of this run (step " +
                                     std::to_string(first) +
                                     ", t = " + format_number(first_time) +
                                     " s)";
            if (!readable)
              error = "Invalid value 'false' for the parameter 'explicit "
                      "dynamics/Resume from checkpoint': '" +
                      path.parent_path().string() +
                      "' holds a checkpoint that cannot be read, which " +
                      mine + " would replace" + fix + ".";
            else if (t > first_time * (1 + 1e-9))
              error = "Invalid value 'false' for the parameter 'explicit "
                      "dynamics/Resume from checkpoint': '" +
                      path.parent_path().string() +
                      "' holds a checkpoint at step " + std::to_string(step) +
                      " (t = " + format_number(t) + " s), further than " +
                      mine + ", which would replace it" + fix + ".";
            break;
          }
      throw_on_any_rank(error, comm);
    }


    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, write_checkpoint, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void,
                                           check_checkpoint_overwrite,
                                           const)
  } // namespace Problems
} // namespace PeriDEAL
