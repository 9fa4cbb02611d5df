#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>

// Checkpoint and restart of the explicit dynamics problem type.
//
// Layout of <Output/Directory>/checkpoint/:
//   run.bin          (rank 0) time, step, counters, energy rows, records,
//                    the number of processes that wrote the state
//   state.<rank>.bin (every rank) per owned node: its position (the key),
//                    u, v, a and the force, and the positions of the
//                    neighbours at the ends of its broken bonds
// Nodes are identified by their position, which is the same bits on every
// process and for every partition (the mesh is rebuilt from the input), so
// a run may resume on another number of processes: each process reads every
// state file and keeps the records of its own nodes. The mesh of a PD run
// never changes, so the triangulation itself is not saved (with adaptive
// refinement this would become Triangulation::save/load with the node data
// attached to cells).
// All files go to checkpoint.new/ first; when every rank has written its
// part, rank 0 renames checkpoint/ to checkpoint.old/, checkpoint.new/ to
// checkpoint/ and removes checkpoint.old/. A run killed at any moment leaves
// a complete checkpoint in checkpoint/ or, between the two renames, in
// checkpoint.old/; read_checkpoint() looks in that order.

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      constexpr std::uint64_t magic = 0x5045524944594e32; // "PERIDYN2"

      template <typename T>
      void
      put(std::ostream &out, const T &value)
      {
        out.write(reinterpret_cast<const char *>(&value), sizeof(T));
      }

      template <typename T>
      T
      get(std::istream &in)
      {
        T value{};
        in.read(reinterpret_cast<char *>(&value), sizeof(T));
        return value;
      }

      void
      put_doubles(std::ostream &out, const std::vector<double> &values)
      {
        put<std::uint64_t>(out, values.size());
        out.write(reinterpret_cast<const char *>(values.data()),
                  values.size() * sizeof(double));
      }

      std::vector<double>
      get_doubles(std::istream &in)
      {
        std::vector<double> values(get<std::uint64_t>(in));
        in.read(reinterpret_cast<char *>(values.data()),
                values.size() * sizeof(double));
        return values;
      }
    } // namespace


    template <int dim>
    void
    ExplicitDynamics<dim>::write_checkpoint(Simulator<dim> &simulator)
    {
      namespace fs         = std::filesystem;
      const MPI_Comm comm  = simulator.get_communicator();
      const auto     rank  = Utilities::MPI::this_mpi_process(comm);
      const auto     ranks = Utilities::MPI::n_mpi_processes(comm);
      const fs::path base(simulator.get_output().directory());
      const fs::path fresh = base / "checkpoint.new",
                     good = base / "checkpoint", old = base / "checkpoint.old";
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
      const auto  write_file = [&](const fs::path &path, const auto &write) {
        std::ofstream out(path, std::ios::binary);
        write(out);
        out.flush();
        if (!out)
          error = "Cannot write the checkpoint file '" + path.string() + "'.";
      };
      const auto &nodes = simulator.get_nodes();
      write_file(fresh / ("state." + std::to_string(rank) + ".bin"),
                 [&](std::ostream &out) {
                   put(out, magic);
                   put<std::uint64_t>(out, nodes.n_owned());
                   for (unsigned int i = 0; i < nodes.n_owned(); ++i)
                     {
                       for (unsigned int d = 0; d < dim; ++d)
                         put(out, nodes[i].location[d]);
                       for (const auto *vector : {&u, &v, &a, &force})
                         for (unsigned int c = 0; c < dim; ++c)
                           put(out, (*vector)[nodes[i].dofs[c]]);
                       put<std::uint64_t>(out, bond_state.n_broken(i));
                       const unsigned int n_bonds =
                         simulator.get_neighbor_lists().n_bonds(i);
                       for (unsigned int k = 0; k < n_bonds; ++k)
                         if (bond_state.is_broken(i, k))
                           for (unsigned int d = 0; d < dim; ++d)
                             put(out,
                                 nodes[bond_state.neighbor(i, k)].location[d]);
                     }
                 });
      if (rank == 0)
        write_file(fresh / "run.bin", [&](std::ostream &out) {
          put(out, magic);
          put<std::uint64_t>(out, ranks);
          put(out, time);
          put(out, dt);
          put<std::uint64_t>(out, step_number);
          put<std::uint64_t>(out, n_steps);
          put(out, external_work);
          put(out, load_factor);
          put<std::uint64_t>(out, broken_bonds);
          put(out, next_output_time);
          put<std::uint64_t>(out, energy_rows.size());
          for (const auto &row : energy_rows)
            put_doubles(out, row);
          put<std::uint64_t>(out, records.size());
          for (const auto &[t, name] : records)
            {
              put(out, t);
              put<std::uint64_t>(out, name.size());
              out.write(name.data(), name.size());
            }
        });
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
    ExplicitDynamics<dim>::read_checkpoint(Simulator<dim> &simulator)
    {
      namespace fs        = std::filesystem;
      const MPI_Comm comm = simulator.get_communicator();
      const auto     rank = Utilities::MPI::this_mpi_process(comm);
      const fs::path base(simulator.get_output().directory());
      // The complete checkpoint: checkpoint/, or checkpoint.old/ if the run
      // was killed between the two renames. Rank 0 decides for everyone.
      int where = 0;
      if (rank == 0)
        where = fs::exists(base / "checkpoint" / "run.bin")     ? 1 :
                fs::exists(base / "checkpoint.old" / "run.bin") ? 2 :
                                                                  0;
      where = Utilities::MPI::broadcast(comm, where, 0);
      AssertThrow(where > 0,
                  ExcInvalidInput("explicit dynamics/Resume from checkpoint",
                                  "true",
                                  "there is no checkpoint in '" +
                                    (base / "checkpoint").string() +
                                    "'; run without resuming first, with "
                                    "'Checkpoint every steps' or 'Steps per "
                                    "run'"));
      const fs::path dir =
        base / (where == 1 ? "checkpoint" : "checkpoint.old");

      std::string   error;
      std::ifstream run(dir / "run.bin", std::ios::binary);
      if (get<std::uint64_t>(run) != magic)
        error = "'" + (dir / "run.bin").string() +
                "' is not a PeriDEAL dynamics checkpoint.";
      throw_on_any_rank(error, comm);
      const auto writers           = get<std::uint64_t>(run);
      time                         = get<double>(run);
      const double checkpoint_step = get<double>(run);
      step_number                  = get<std::uint64_t>(run);
      const auto saved_n_steps     = get<std::uint64_t>(run);
      AssertThrow(checkpoint_step == dt && saved_n_steps == n_steps,
                  ExcInvalidInput("explicit dynamics/Resume from checkpoint",
                                  "true",
                                  "the checkpoint's time step or number of "
                                  "steps differs from this input's (did "
                                  "'End time', 'Time step' or the mesh "
                                  "change?); resume with the input that "
                                  "wrote it"));
      external_work    = get<double>(run);
      load_factor      = get<double>(run);
      broken_bonds     = get<std::uint64_t>(run);
      next_output_time = get<double>(run);
      energy_rows.resize(get<std::uint64_t>(run));
      for (auto &row : energy_rows)
        row = get_doubles(run);
      records.resize(get<std::uint64_t>(run));
      for (auto &[t, name] : records)
        {
          t = get<double>(run);
          name.resize(get<std::uint64_t>(run));
          run.read(name.data(), name.size());
        }
      if (!run)
        error = "The checkpoint file '" + (dir / "run.bin").string() +
                "' is truncated.";
      throw_on_any_rank(error, comm);

      // Every process reads every state file and keeps its own nodes: the
      // writers' partition does not matter.
      const auto &nodes = simulator.get_nodes();
      using Key         = std::array<double, dim>;
      std::map<Key, unsigned int> index_of;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          Key key;
          for (unsigned int d = 0; d < dim; ++d)
            key[d] = nodes[i].location[d];
          index_of.emplace(key, i);
        }
      unsigned int restored = 0, unknown_neighbors = 0;
      check_on_all_ranks(
        [&]() {
          for (std::uint64_t r = 0; r < writers; ++r)
            {
              const fs::path path =
                dir / ("state." + std::to_string(r) + ".bin");
              std::ifstream in(path, std::ios::binary);
              AssertThrow(get<std::uint64_t>(in) == magic,
                          ExcMessage("The checkpoint file '" + path.string() +
                                     "' is missing or not a PeriDEAL "
                                     "dynamics checkpoint."));
              const auto n_records = get<std::uint64_t>(in);
              const auto read_key  = [&]() {
                Key key;
                for (unsigned int d = 0; d < dim; ++d)
                  key[d] = get<double>(in);
                return key;
              };
              for (std::uint64_t record = 0; record < n_records && in; ++record)
                {
                  const auto it = index_of.find(read_key());
                  const bool mine =
                    it != index_of.end() && it->second < nodes.n_owned();
                  double values[4][dim];
                  for (auto &vector : values)
                    for (unsigned int c = 0; c < dim; ++c)
                      vector[c] = get<double>(in);
                  const auto n_broken = get<std::uint64_t>(in);
                  if (mine)
                    {
                      const unsigned int i = it->second;
                      ++restored;
                      for (unsigned int c = 0; c < dim; ++c)
                        {
                          const auto dof = nodes[i].dofs[c];
                          u[dof]         = values[0][c];
                          v[dof]         = values[1][c];
                          a[dof]         = values[2][c];
                          force[dof]     = values[3][c];
                        }
                      for (std::uint64_t b = 0; b < n_broken; ++b)
                        {
                          const auto neighbor = index_of.find(read_key());
                          const int  k =
                            neighbor == index_of.end() ?
                               -1 :
                               bond_state.bond_index(i, neighbor->second);
                          if (k < 0)
                            ++unknown_neighbors;
                          else if (!bond_state.is_broken(i, k))
                            bond_state.break_bond(i, k);
                        }
                    }
                  else
                    in.seekg(n_broken * dim * sizeof(double), std::ios::cur);
                }
              AssertThrow(in,
                          ExcMessage("The checkpoint file '" + path.string() +
                                     "' is truncated."));
            }
        },
        comm);
      AssertThrow(Utilities::MPI::min(restored == nodes.n_owned() &&
                                          unknown_neighbors == 0 ?
                                        1 :
                                        0,
                                      comm) == 1,
                  ExcInvalidInput("explicit dynamics/Resume from checkpoint",
                                  "true",
                                  "the checkpoint in '" + dir.string() +
                                    "' does not fit this mesh (nodes or "
                                    "bonds not found: another mesh or "
                                    "horizon?); resume with the input that "
                                    "wrote it"));
      bond_state.synchronize();
      u.update_ghost_values();
      bond_operator.update_bond_state();
      simulator.get_pcout()
        << "           resumed from " << dir.string() << " at step "
        << step_number << " (t = " << time << " s), " << broken_bonds
        << " broken bonds" << std::endl;
    }


    template void
    ExplicitDynamics<2>::write_checkpoint(Simulator<2> &);
    template void
    ExplicitDynamics<3>::write_checkpoint(Simulator<3> &);
    template void
    ExplicitDynamics<2>::read_checkpoint(Simulator<2> &);
    template void
    ExplicitDynamics<3>::read_checkpoint(Simulator<3> &);
  } // namespace Problems
} // namespace PeriDEAL
