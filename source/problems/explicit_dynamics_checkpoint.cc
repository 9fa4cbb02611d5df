#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

// Checkpoint and restart of the explicit dynamics problem type.
//
// Layout of <Output/Directory>/checkpoint/:
//   run.bin          (rank 0) time, step, counters, energy rows, records;
//                    the keys that define the state (input entries such as
//                    the model's constants, and properties of the
//                    discretisation such as a hash of the node positions);
//                    per process that wrote the state: its number of
//                    nodes, the size and the checksum of its state file;
//                    last, the checksum of run.bin itself
//   state.<rank>.bin (every rank) per owned node: its position (the key),
//                    u, v, a and the force, and the positions of the
//                    neighbours at the ends of its broken bonds
// Checksums are 64-bit FNV-1a over every byte of a file. The first 88 bytes
// of run.bin (magic to the number of energy rows) and the layout of the
// state files are those of the first format (PERIDYN2), so that the
// position of a field does not depend on the format.
// Nodes are identified by their position, which is the same bits on every
// process and for every partition (the mesh is rebuilt from the input), so
// a run may resume on another number of processes: each process reads every
// state file and keeps the records of its own nodes. Every key is the same
// on any partition for the same reason. The mesh of a PD run never changes,
// so the triangulation itself is not saved (with adaptive refinement this
// would become Triangulation::save/load with the node data attached to
// cells).
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
      constexpr std::uint64_t magic    = 0x5045524944594e33; // "PERIDYN3"
      constexpr std::uint64_t magic_v2 = 0x5045524944594e32; // "PERIDYN2"

      /// 64-bit FNV-1a of the bytes added so far.
      struct Checksum
      {
        std::uint64_t value = 0xcbf29ce484222325ULL;

        void
        add(const char *data, const std::size_t n)
        {
          for (std::size_t k = 0; k < n; ++k)
            {
              value ^= static_cast<unsigned char>(data[k]);
              value *= 0x100000001b3ULL;
            }
        }
      };

      std::string
      hex(const std::uint64_t x)
      {
        std::ostringstream s;
        s << "0x" << std::hex << std::setw(16) << std::setfill('0') << x;
        return s.str();
      }

      /// All the digits of a double: keys compare as text.
      std::string
      exact(const double x)
      {
        char buffer[32];
        std::snprintf(buffer, sizeof(buffer), "%.17g", x);
        return buffer;
      }

      std::string
      corrupt_message(const std::string &file, const std::string &what)
      {
        return "Corrupt checkpoint: '" + file + "' " + what +
               ". Restore the checkpoint from a copy, or start afresh "
               "without 'explicit dynamics/Resume from checkpoint' (in "
               "another 'Output/Directory', or with 'explicit "
               "dynamics/Overwrite checkpoint = true').";
      }

      /// A file written through a checksum.
      class ChecksumWriter
      {
      public:
        explicit ChecksumWriter(const std::filesystem::path &path)
          : out(path, std::ios::binary)
        {}

        void
        write(const void *data, const std::size_t n)
        {
          out.write(static_cast<const char *>(data), n);
          checksum.add(static_cast<const char *>(data), n);
          size += n;
        }

        template <typename T>
        void
        put(const T &value)
        {
          write(&value, sizeof(T));
        }

        void
        put_string(const std::string &text)
        {
          put<std::uint64_t>(text.size());
          write(text.data(), text.size());
        }

        void
        put_doubles(const std::vector<double> &values)
        {
          put<std::uint64_t>(values.size());
          write(values.data(), values.size() * sizeof(double));
        }

        std::ofstream out;
        Checksum      checksum;
        std::uint64_t size = 0;
      };

      /**
       * A checkpoint file read as if it may be corrupt: nothing is read past
       * its end, and every count is held against the bytes left (and a
       * limit from the mesh) before anything is allocated or read, so that
       * a corrupt count is an error, never a loop or an allocation of
       * petabytes. Errors throw std::runtime_error with
       * corrupt_message(). What is read goes through the checksum.
       */
      class CheckedReader
      {
      public:
        CheckedReader(const std::filesystem::path &path,
                      const std::uint64_t          size)
          : in(path, std::ios::binary)
          , file(path.string())
          , left(size)
        {
          if (!in)
            corrupt("cannot be opened");
        }

        [[noreturn]] void
        corrupt(const std::string &what) const
        {
          throw std::runtime_error(corrupt_message(file, what));
        }

        void
        read_raw(void *data, const std::size_t n)
        {
          if (n > left)
            corrupt("ends too early (" + std::to_string(left) +
                    " bytes left, " + std::to_string(n) +
                    " needed): it is truncated");
          in.read(static_cast<char *>(data), n);
          if (!in)
            corrupt("cannot be read to its end");
          left -= n;
        }

        void
        read(void *data, const std::size_t n)
        {
          read_raw(data, n);
          checksum.add(static_cast<const char *>(data), n);
        }

        template <typename T>
        T
        get()
        {
          T value{};
          read(&value, sizeof(T));
          return value;
        }

        /// A count of items of at least @p bytes_each bytes each, at most
        /// @p limit (@p limit_text says what the limit is).
        std::uint64_t
        get_count(const std::uint64_t bytes_each,
                  const std::uint64_t limit,
                  const std::string  &what,
                  const std::string  &limit_text)
        {
          const auto n = get<std::uint64_t>();
          if (n > limit)
            corrupt("gives " + std::to_string(n) + " as its " + what +
                    ", more than the " + std::to_string(limit) + " " +
                    limit_text);
          if (bytes_each > 0 && n > left / bytes_each)
            corrupt("gives " + std::to_string(n) + " as its " + what +
                    ", more than the " + std::to_string(left) +
                    " bytes left in the file can hold (a corrupt count, or a "
                    "truncated file)");
          return n;
        }

        std::string
        get_string(const std::string &what)
        {
          std::string text(get_count(1, left, what, "bytes"), '\0');
          read(text.data(), text.size());
          return text;
        }

        /// Read and drop @p n bytes (they count for the checksum).
        void
        skip(std::uint64_t n)
        {
          char buffer[4096];
          while (n > 0)
            {
              const std::size_t k = std::min<std::uint64_t>(n, sizeof(buffer));
              read(buffer, k);
              n -= k;
            }
        }

        std::uint64_t
        bytes_left() const
        {
          return left;
        }

        Checksum checksum;

      private:
        std::ifstream     in;
        const std::string file;
        std::uint64_t     left;
      };

      /// The size of @p path, or an error naming it.
      std::uint64_t
      checkpoint_file_size(const std::filesystem::path &path)
      {
        std::error_code code;
        const auto      size = std::filesystem::file_size(path, code);
        if (code)
          throw std::runtime_error(
            corrupt_message(path.string(),
                            "is missing or cannot be read (" + code.message() +
                              ")"));
        return size;
      }

      /// An entry name of ParameterHandler's tree (every character but
      /// [a-zA-Z0-9] is written as '_' and two hexadecimal digits).
      std::string
      demangle(const std::string &name)
      {
        std::string result;
        for (std::size_t k = 0; k < name.size(); ++k)
          if (name[k] == '_' && k + 2 < name.size())
            {
              result += static_cast<char>(
                std::stoi(name.substr(k + 1, 2), nullptr, 16));
              k += 2;
            }
          else
            result += name[k];
        return result;
      }

      /// Every entry of the tree as 'subsection/.../entry' = value.
      void
      collect_entries(const boost::property_tree::ptree  &section,
                      const std::string                  &prefix,
                      std::map<std::string, std::string> &entries)
      {
        for (const auto &[key, child] : section)
          {
            const std::string name = prefix + demangle(key);
            if (const auto value = child.get_optional<std::string>("value"))
              entries[name] = *value;
            else
              collect_entries(child, name + "/", entries);
          }
      }

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
    ExplicitDynamics<dim>::parse_checkpoint_parameters(ParameterHandler &prm)
    {
      overwrite_checkpoint = prm.get_bool("Overwrite checkpoint");
      AssertThrow(!(resume && overwrite_checkpoint),
                  ExcInvalidInput("explicit dynamics/Overwrite checkpoint",
                                  "true",
                                  "a run with 'Resume from checkpoint = "
                                  "true' continues its checkpoint and "
                                  "replaces no other; set it to false (it "
                                  "lets a run that starts afresh replace a "
                                  "checkpoint)"));

      // The entries live all over the file, and this is called inside the
      // subsection 'explicit dynamics': read them from the whole tree.
      std::stringstream json;
      prm.print_parameters(json, ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      std::map<std::string, std::string> entries;
      collect_entries(tree, "", entries);

      checkpoint_inputs.clear();
      const auto add = [&](const std::string &name) {
        const auto entry = entries.find(name);
        AssertThrow(entry != entries.end(), ExcInternalError());
        checkpoint_inputs.push_back({name, entry->second, true, ""});
      };
      const auto add_all_under = [&](const std::string &section) {
        for (const auto &[name, value] : entries)
          if (name.rfind(section + "/", 0) == 0)
            checkpoint_inputs.push_back({name, value, true, ""});
      };
      add("Dimension");
      add("Material model/Model");
      add_all_under("Material model/" + entries["Material model/Model"]);
      add("Horizon/Specification");
      add(entries["Horizon/Specification"] == "m-ratio" ? "Horizon/m-ratio" :
                                                          "Horizon/Length");
      add("Partial volumes/Algorithm");
      add_all_under("Partial volumes/" + entries["Partial volumes/Algorithm"]);
      // The mesh file's content is in the hash of the node positions.
      add("Geometry/Mesh");
      if (entries["Geometry/Mesh"] == "subdivided box")
        for (const char *name :
             {"Lower corner", "Upper corner", "Subdivisions"})
          add(std::string("Geometry/") + name);
      add("Geometry/Global refinements");
      std::vector<std::string> own = {"Kinematics",
                                      "Pre-cracks",
                                      "No-fail boxes",
                                      "No-fail boundary ids",
                                      "Probe points",
                                      "Crack tip origin",
                                      "Crack tip region",
                                      "Crack tip damage",
                                      "End time",
                                      "Time step"};
      if (!no_fail_ids.empty())
        own.push_back("No-fail layer thickness");
      if (given_time_step == 0)
        own.push_back("Safety factor");
      for (const auto &name : own)
        add("explicit dynamics/" + name);
    }


    template <int dim>
    const std::vector<typename ExplicitDynamics<dim>::CheckpointKey> &
    ExplicitDynamics<dim>::checkpoint_keys(Simulator<dim> &simulator)
    {
      if (!checkpoint_state_keys.empty())
        return checkpoint_state_keys;
      const auto    &nodes = simulator.get_nodes();
      const MPI_Comm comm  = simulator.get_communicator();

      // One checksum per node, of its position and volume, summed (mod
      // 2^64): the total does not depend on the partition.
      std::uint64_t           node_sum = 0;
      std::array<double, dim> lower, upper;
      lower.fill(std::numeric_limits<double>::infinity());
      upper.fill(-std::numeric_limits<double>::infinity());
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          Checksum node;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double x = nodes[i].location[d];
              node.add(reinterpret_cast<const char *>(&x), sizeof(x));
              lower[d] = std::min(lower[d], x);
              upper[d] = std::max(upper[d], x);
            }
          const double volume = nodes[i].volume();
          node.add(reinterpret_cast<const char *>(&volume), sizeof(volume));
          // A final mix (splitmix64), so that sums of similar nodes do not
          // cancel.
          std::uint64_t z = node.value;
          z               = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
          z               = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
          node_sum += z ^ (z >> 31);
        }
      node_sum        = Utilities::MPI::sum(node_sum, comm);
      std::string box = "(";
      for (unsigned int d = 0; d < dim; ++d)
        box += (d > 0 ? ", " : "") + exact(Utilities::MPI::min(lower[d], comm));
      box += ") to (";
      for (unsigned int d = 0; d < dim; ++d)
        box += (d > 0 ? ", " : "") + exact(Utilities::MPI::max(upper[d], comm));
      box += ")";
      const std::uint64_t n_nodes =
        Utilities::MPI::sum<std::uint64_t>(nodes.n_owned(), comm);
      const std::uint64_t n_bonds = Utilities::MPI::sum<std::uint64_t>(
        simulator.get_neighbor_lists().n_owned_bonds(),
        comm);

      // The columns of the energy file, as write_output() writes them.
      std::string columns = "time,step,kinetic_energy,elastic_energy,"
                            "external_work,energy_balance,broken_bonds";
      for (unsigned int k = 0; k < probe_points.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          columns += ",probe" + std::to_string(k) + "_u" + "xyz"[c];
      if (crack_tip.enabled())
        for (const auto &name : crack_tip.column_names())
          columns += "," + name;

      const std::string mesh =
        "the mesh: 'Geometry/...' or the content of 'Geometry/Mesh file'";
      checkpoint_state_keys = checkpoint_inputs;
      const auto add        = [&](const std::string &name,
                           const std::string &value,
                           const std::string &hint) {
        checkpoint_state_keys.push_back({name, value, false, hint});
      };
      add("number of nodes", std::to_string(n_nodes), mesh);
      add("bounding box of the nodes", box, mesh);
      add("hash of the node positions and volumes", hex(node_sum), mesh);
      add("horizon",
          exact(simulator.get_horizon()),
          "'Horizon/...' and the mesh");
      add("number of bonds",
          std::to_string(n_bonds),
          "the horizon, the mesh and 'Partial volumes/Algorithm'");
      add("critical stretch",
          exact(
            simulator.get_model().critical_stretch(simulator.get_horizon())),
          "the failure constants of 'Material model' and the horizon");
      add("energy file columns",
          columns,
          "'explicit dynamics/Probe points' and 'Crack tip origin'");
      add("time step",
          exact(dt),
          "'explicit dynamics/End time', 'Time step' and 'Safety factor', "
          "the mesh and the material constants");
      add("number of steps",
          std::to_string(n_steps),
          "'explicit dynamics/End time' and the time step");
      return checkpoint_state_keys;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::write_checkpoint(Simulator<dim> &simulator)
    {
      namespace fs        = std::filesystem;
      const MPI_Comm comm = simulator.get_communicator();
      const auto     rank = Utilities::MPI::this_mpi_process(comm);
      const fs::path base(simulator.get_output().directory());
      const fs::path fresh = base / "checkpoint.new",
                     good = base / "checkpoint", old = base / "checkpoint.old";
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
      simulator.get_pcout()
        << "           resumed from " << dir.string() << " at step "
        << step_number << " (t = " << time << " s), " << broken_bonds
        << " broken bonds" << std::endl;
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
      const fs::path base(simulator.get_output().directory());
      std::string    error;
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        for (const char *name : {"checkpoint", "checkpoint.old"})
          {
            const fs::path  path = base / name / "run.bin";
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


    template void
    ExplicitDynamics<2>::write_checkpoint(Simulator<2> &);
    template void
    ExplicitDynamics<3>::write_checkpoint(Simulator<3> &);
    template void
    ExplicitDynamics<2>::read_checkpoint(Simulator<2> &);
    template void
    ExplicitDynamics<3>::read_checkpoint(Simulator<3> &);
    template void
    ExplicitDynamics<2>::parse_checkpoint_parameters(ParameterHandler &);
    template void
    ExplicitDynamics<3>::parse_checkpoint_parameters(ParameterHandler &);
    template const std::vector<ExplicitDynamics<2>::CheckpointKey> &
    ExplicitDynamics<2>::checkpoint_keys(Simulator<2> &);
    template const std::vector<ExplicitDynamics<3>::CheckpointKey> &
    ExplicitDynamics<3>::checkpoint_keys(Simulator<3> &);
    template void
    ExplicitDynamics<2>::check_checkpoint_overwrite(Simulator<2> &) const;
    template void
    ExplicitDynamics<3>::check_checkpoint_overwrite(Simulator<3> &) const;
  } // namespace Problems
} // namespace PeriDEAL
