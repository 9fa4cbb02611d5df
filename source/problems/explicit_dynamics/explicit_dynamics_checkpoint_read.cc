/**
 * @file
 * Resuming an explicit dynamics run (ExplicitDynamics::read_checkpoint()):
 * the checkpoint is read as possibly corrupt (sizes, counts and checksums
 * checked before use), held against this input key by key, and restored
 * node by node on any number of processes.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_checkpoint_format.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_internal.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsCheckpoint::CheckedReader;
    using internal::ExplicitDynamicsCheckpoint::checkpoint_file_size;
    using internal::ExplicitDynamicsCheckpoint::Checksum;
    using internal::ExplicitDynamicsCheckpoint::corrupt_message;
    using internal::ExplicitDynamicsCheckpoint::hex;
    using internal::ExplicitDynamicsCheckpoint::magic;
    using internal::ExplicitDynamicsCheckpoint::magic_v2;


    namespace
    {
      /// Whether two values of an entry are the same: the same text, or
      /// the same numbers ("7.2e10" and "72e9") in the same places.
      bool
      same_value(const std::string &a, const std::string &b)
      {
        if (a == b)
          return true;
        const auto tokens = [](const std::string &text) {
          std::vector<std::string> result;
          std::string              token;
          for (const char c : text + ' ')
            if (c == ',' || c == ';' || c == ' ' || c == '\t')
              {
                if (!token.empty())
                  result.push_back(token);
                token.clear();
                if (c == ';')
                  result.push_back(";");
              }
            else
              token += c;
          return result;
        };
        const auto ta = tokens(a), tb = tokens(b);
        if (ta.size() != tb.size())
          return false;
        for (unsigned int k = 0; k < ta.size(); ++k)
          if (ta[k] != tb[k])
            {
              char        *end_a = nullptr, *end_b = nullptr;
              const double x = std::strtod(ta[k].c_str(), &end_a);
              const double y = std::strtod(tb[k].c_str(), &end_b);
              if (*end_a != '\0' || *end_b != '\0' || end_a == ta[k].c_str() ||
                  end_b == tb[k].c_str() || x != y)
                return false;
            }
        return true;
      }
    } // namespace


    template <int dim>
    void
    ExplicitDynamics<dim>::read_checkpoint(Simulator<dim> &simulator)
    {
      const MPI_Comm comm = simulator.get_communicator();
      const auto     rank = Utilities::MPI::this_mpi_process(comm);
      const internal::ExplicitDynamicsCheckpoint::Directories dirs(
        simulator.get_output().directory());
      namespace fs = std::filesystem;
      // The complete checkpoint: checkpoint/, or checkpoint.old/ if the run
      // was killed between the two renames. Rank 0 decides for everyone.
      int where = 0;
      if (rank == 0)
        where = fs::exists(dirs.good / "run.bin") ? 1 :
                fs::exists(dirs.old / "run.bin")  ? 2 :
                                                    0;
      where = Utilities::MPI::broadcast(comm, where, 0);
      AssertThrow(where > 0,
                  ExcInvalidInput("explicit dynamics/Resume from checkpoint",
                                  "true",
                                  "there is no checkpoint in '" +
                                    dirs.good.string() +
                                    "'; run without resuming first, with "
                                    "'Checkpoint every steps' or 'Steps per "
                                    "run'"));
      const fs::path dir = where == 1 ? dirs.good : dirs.old;

      // What the checkpoint is checked against: the same on every process.
      const auto         &keys  = checkpoint_keys(simulator);
      const auto         &nodes = simulator.get_nodes();
      const auto         &lists = simulator.get_neighbor_lists();
      const std::uint64_t n_nodes =
        Utilities::MPI::sum<std::uint64_t>(nodes.n_owned(), comm);
      std::uint64_t max_bonds = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        max_bonds = std::max<std::uint64_t>(max_bonds, lists.n_bonds(i));
      max_bonds = Utilities::MPI::max(max_bonds, comm);

      // run.bin, read in full and checked (sizes, counts, checksum) before
      // anything of it is used. Every process reads it.
      struct Piece
      {
        std::uint64_t records, bytes, checksum;
      };
      std::uint64_t                                    writers      = 0;
      double                                           saved_time   = 0;
      std::uint64_t                                    saved_step   = 0;
      double                                           saved_work   = 0;
      double                                           saved_load   = 0;
      std::uint64_t                                    saved_broken = 0;
      double                                           saved_next   = 0;
      std::vector<std::vector<double>>                 saved_rows;
      std::vector<std::pair<double, std::string>>      saved_records;
      std::vector<std::pair<std::string, std::string>> saved_keys;
      std::vector<Piece>                               pieces;
      const fs::path run_path = dir / "run.bin";
      check_on_all_ranks(
        [&]() {
          CheckedReader in(run_path, checkpoint_file_size(run_path));
          const auto    mark = in.get<std::uint64_t>();
          if (mark == magic_v2)
            throw std::runtime_error(
              "The checkpoint '" + run_path.string() +
              "' was written by an earlier version of PeriDEAL, which "
              "recorded neither the input that defines its state nor a "
              "checksum, so it cannot be checked against this input. Start "
              "afresh without 'explicit dynamics/Resume from checkpoint' "
              "(in another 'Output/Directory', or with 'explicit "
              "dynamics/Overwrite checkpoint = true').");
          if (mark != magic)
            in.corrupt("is not a PeriDEAL dynamics checkpoint (its first "
                       "bytes are not 'PERIDYN3')");
          // Each writer has an entry of 24 bytes in the table at the end.
          writers    = in.get_count(24,
                                 std::numeric_limits<std::uint32_t>::max(),
                                 "number of processes that wrote it",
                                 "processes an MPI run can have");
          saved_time = in.get<double>();
          in.get<double>(); // dt: compared as a key
          saved_step = in.get<std::uint64_t>();
          in.get<std::uint64_t>(); // n_steps: compared as a key
          saved_work   = in.get<double>();
          saved_load   = in.get<double>();
          saved_broken = in.get<std::uint64_t>();
          saved_next   = in.get<double>();
          saved_rows.resize(
            in.get_count(8,
                         std::numeric_limits<std::uint64_t>::max(),
                         "number of energy rows",
                         ""));
          for (unsigned int k = 0; k < saved_rows.size(); ++k)
            {
              saved_rows[k].resize(
                in.get_count(8,
                             std::numeric_limits<std::uint64_t>::max(),
                             "number of values in energy row " +
                               std::to_string(k),
                             ""));
              in.read(saved_rows[k].data(),
                      saved_rows[k].size() * sizeof(double));
            }
          saved_records.resize(
            in.get_count(16,
                         std::numeric_limits<std::uint64_t>::max(),
                         "number of output records",
                         ""));
          for (auto &[t, name] : saved_records)
            {
              t    = in.get<double>();
              name = in.get_string("length of an output record's name");
            }
          saved_keys.resize(
            in.get_count(16,
                         std::numeric_limits<std::uint64_t>::max(),
                         "number of recorded input entries",
                         ""));
          for (auto &[name, value] : saved_keys)
            {
              name  = in.get_string("length of an entry's name");
              value = in.get_string("length of an entry's value");
            }
          if (in.get_count(24,
                           writers,
                           "number of state files",
                           "processes "
                           "that wrote it (its header)") != writers)
            in.corrupt("lists fewer state files than processes wrote it");
          pieces.resize(writers);
          for (auto &p : pieces)
            {
              p.records  = in.get_count(0,
                                       n_nodes,
                                       "number of nodes of a state file",
                                       "nodes of the mesh");
              p.bytes    = in.get<std::uint64_t>();
              p.checksum = in.get<std::uint64_t>();
            }
          const Checksum computed = in.checksum;
          std::uint64_t  recorded = 0;
          in.read_raw(&recorded, sizeof(recorded));
          if (in.bytes_left() != 0)
            in.corrupt("has " + std::to_string(in.bytes_left()) +
                       " bytes after its end");
          if (computed.value != recorded)
            in.corrupt("does not match its checksum (" + hex(computed.value) +
                       ", recorded " + hex(recorded) +
                       "): a byte of it has changed");
        },
        comm);

      // The input that wrote the checkpoint against this one, entry by
      // entry, then the properties of the discretisation. (The same data on
      // every process: every process throws alike.)
      std::map<std::string, std::string> saved(saved_keys.begin(),
                                               saved_keys.end());
      std::vector<std::string>           differ;
      const CheckpointKey               *first = nullptr;
      for (const auto &key : keys)
        {
          const auto it   = saved.find(key.name);
          const bool same = it != saved.end() &&
                            (key.is_entry ? same_value(it->second, key.value) :
                                            it->second == key.value);
          if (!same)
            {
              if (first == nullptr)
                first = &key;
              else if (key.is_entry && it != saved.end())
                differ.push_back("'" + key.name + "'");
            }
        }
      // Entries of the checkpoint that this input does not have (another
      // model's constants): named when nothing else differs.
      if (first == nullptr)
        for (const auto &[name, value] : saved_keys)
          if (std::none_of(keys.begin(), keys.end(), [&](const auto &key) {
                return key.name == name;
              }))
            AssertThrow(
              false,
              ExcInvalidInput("explicit dynamics/Resume from checkpoint",
                              "true",
                              "the checkpoint in '" + dir.string() +
                                "' was written by an input with the entry '" +
                                name + " = " + value +
                                "', which this input does not use; resume with "
                                "the input that wrote it, or start afresh "
                                "without 'Resume from checkpoint'"));
      if (first != nullptr)
        {
          const auto        it = saved.find(first->name);
          const std::string old_value =
            it == saved.end() ? std::string() : it->second;
          std::string others;
          for (const auto &name : differ)
            others +=
              (others.empty() ? " (other entries that differ: " : ", ") + name;
          if (!others.empty())
            others += ")";
          if (first->is_entry)
            AssertThrow(
              false,
              ExcInvalidInput(first->name,
                              first->value,
                              (it == saved.end() ?
                                 "the checkpoint in '" + dir.string() +
                                   "' was written by an input without this "
                                   "entry; remove it to resume" :
                                 "the checkpoint in '" + dir.string() +
                                   "' was written with '" + old_value +
                                   "'; set '" + first->name + "' back to '" +
                                   old_value + "' to resume from it") +
                                ", or start afresh without 'explicit "
                                "dynamics/Resume from checkpoint'" +
                                others));
          AssertThrow(
            false,
            ExcInvalidInput(
              "explicit dynamics/Resume from checkpoint",
              "true",
              "the checkpoint in '" + dir.string() +
                "' does not fit this input: its " + first->name + " is " +
                (it == saved.end() ? "not recorded" : "'" + old_value + "'") +
                ", this input's '" + first->value + "' (it follows from " +
                first->hint +
                "); resume with the input that wrote it, or "
                "start afresh without 'Resume from checkpoint'" +
                others));
        }

      // The counts of the table against the mesh: the keys match, so only
      // a corrupt checkpoint can fail here.
      std::uint64_t n_records = 0;
      for (const auto &p : pieces)
        n_records += p.records;
      std::size_t width = 0;
      for (const auto &key : keys)
        if (key.name == "energy file columns")
          width = 1 + std::count(key.value.begin(), key.value.end(), ',');
      AssertThrow(
        n_records == n_nodes &&
          std::all_of(saved_rows.begin(),
                      saved_rows.end(),
                      [&](const auto &row) { return row.size() == width; }),
        ExcMessage(
          corrupt_message(run_path.string(),
                          n_records != n_nodes ?
                            "lists " + std::to_string(n_records) +
                              " node records for a mesh of " +
                              std::to_string(n_nodes) + " nodes" :
                            "has energy rows of another width than its " +
                              std::to_string(width) + " columns")));
      time             = saved_time;
      step_number      = saved_step;
      external_work    = saved_work;
      load_factor      = saved_load;
      broken_bonds     = saved_broken;
      next_output_time = saved_next;
      energy_rows      = std::move(saved_rows);
      records          = std::move(saved_records);

      // Every process reads every state file and keeps its own nodes: the
      // writers' partition does not matter.
      using Key = std::array<double, dim>;
      std::map<Key, unsigned int> index_of;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          Key key;
          for (unsigned int d = 0; d < dim; ++d)
            key[d] = nodes[i].location[d];
          index_of.emplace(key, i);
        }
      std::vector<bool> seen(nodes.n_owned(), false);
      // The hybrid scheme: the owned nodes that were collocation nodes.
      std::vector<bool> collocation(nodes.n_owned(), false);
      unsigned int      restored = 0, unknown_neighbors = 0;
      check_on_all_ranks(
        [&]() {
          for (std::uint64_t r = 0; r < writers; ++r)
            {
              const fs::path path =
                dir / ("state." + std::to_string(r) + ".bin");
              const auto size = checkpoint_file_size(path);
              if (size != pieces[r].bytes)
                throw std::runtime_error(corrupt_message(
                  path.string(),
                  "has " + std::to_string(size) + " bytes, and " +
                    run_path.filename().string() + " recorded " +
                    std::to_string(pieces[r].bytes) +
                    " (truncated or changed)"));
              CheckedReader in(path, size);
              if (in.get<std::uint64_t>() != magic)
                in.corrupt("is not a PeriDEAL dynamics state file (its "
                           "first bytes are not 'PERIDYN3')");
              const auto record_bytes = (1 + 4 * dim) * sizeof(double) + 8;
              const auto n            = in.get_count(record_bytes,
                                          pieces[r].records,
                                          "number of node records",
                                          "recorded in run.bin for it");
              if (n != pieces[r].records)
                in.corrupt("holds " + std::to_string(n) +
                           " node records, and run.bin recorded " +
                           std::to_string(pieces[r].records));
              const auto read_key = [&]() {
                Key key;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    key[d] = in.get<double>();
                    if (!std::isfinite(key[d]))
                      in.corrupt("holds a node position that is not finite");
                  }
                return key;
              };
              for (std::uint64_t record = 0; record < n; ++record)
                {
                  const auto it = index_of.find(read_key());
                  const bool mine =
                    it != index_of.end() && it->second < nodes.n_owned();
                  double values[4][dim];
                  for (auto &vector : values)
                    for (unsigned int c = 0; c < dim; ++c)
                      vector[c] = in.get<double>();
                  const auto n_broken =
                    mine ?
                      in.get_count(dim * sizeof(double),
                                   lists.n_bonds(it->second),
                                   "number of broken bonds of node record " +
                                     std::to_string(record),
                                   "bonds of that node") :
                      in.get_count(dim * sizeof(double),
                                   max_bonds,
                                   "number of broken bonds of node record " +
                                     std::to_string(record),
                                   "bonds that any node of this mesh has");
                  if (mine)
                    {
                      const unsigned int i = it->second;
                      if (!seen[i])
                        ++restored;
                      seen[i] = true;
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
                    in.skip(n_broken * dim * sizeof(double));
                }
              // The hybrid scheme (the keys say the writer used it too):
              // the positions of the writer's collocation nodes.
              if (hybrid != nullptr)
                {
                  const auto n_collocation =
                    in.get_count(dim * sizeof(double),
                                 n,
                                 "number of collocation nodes",
                                 "node records of the file");
                  for (std::uint64_t q = 0; q < n_collocation; ++q)
                    {
                      // (Nodes of other processes are not found here.)
                      const auto it = index_of.find(read_key());
                      if (it != index_of.end() && it->second < nodes.n_owned())
                        collocation[it->second] = true;
                    }
                }
              if (in.bytes_left() != 0)
                in.corrupt("has " + std::to_string(in.bytes_left()) +
                           " bytes after its last node record");
              if (in.checksum.value != pieces[r].checksum)
                in.corrupt("does not match the checksum that run.bin "
                           "recorded for it (" +
                           hex(in.checksum.value) + ", recorded " +
                           hex(pieces[r].checksum) +
                           "): a byte of it has changed");
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
      if (hybrid != nullptr)
        {
          // The nodes that had switched when the checkpoint was written
          // switch again (the same input starts the same nodes as
          // collocation nodes, and a node never switches back).
          std::vector<unsigned int> switched;
          bool                      fits = true;
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            if (bond_operator.is_collocation_node(i) && !collocation[i])
              switched.push_back(i);
            else if (!bond_operator.is_collocation_node(i) && collocation[i])
              fits = false;
          AssertThrow(Utilities::MPI::min(fits ? 1 : 0, comm) == 1,
                      ExcInvalidInput(
                        "explicit dynamics/Resume from checkpoint",
                        "true",
                        "the checkpoint in '" + dir.string() +
                          "' holds collocation nodes that are standard "
                          "from the start in this run (another 'Quadrature' "
                          "input?); resume with the input that wrote it"));
          bond_operator.make_standard(switched);
          n_standard_nodes =
            n_total_nodes - bond_operator.n_collocation_nodes();
          // The scan's margins from the restored state (no node can switch
          // here: the run that wrote the checkpoint scanned this state at
          // the end of its last step).
          bond_operator.switch_critical_nodes(u,
                                              hybrid->adaptive ? hybrid->alpha :
                                                                 1.,
                                              hybrid->adaptive);
        }
      simulator.get_pcout()
        << "           resumed from " << dir.string() << " at step "
        << step_number << " (t = " << time << " s), " << broken_bonds
        << " broken bonds" << std::endl;
    }


    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, read_checkpoint, )
  } // namespace Problems
} // namespace PeriDEAL
