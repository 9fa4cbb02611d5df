#ifndef perideal_problems_explicit_dynamics_checkpoint_format_h
#define perideal_problems_explicit_dynamics_checkpoint_format_h

/**
 * @file
 * The file format of the checkpoints of the explicit dynamics problem type
 * (Problems::ExplicitDynamics): the marks of the formats, the checksum, a
 * writer that checksums what it writes and a reader that holds every count
 * against the bytes left. Shared by the source files that write, read and
 * key a checkpoint; not part of the library's interface.
 */

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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
//                    neighbours at the ends of its broken bonds; with the
//                    hybrid quadrature scheme (a key), then the number and
//                    the positions of the owned nodes that are still
//                    collocation nodes
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
    namespace internal
    {
      namespace ExplicitDynamicsCheckpoint
      {
        constexpr std::uint64_t magic    = 0x5045524944594e33; // "PERIDYN3"
        constexpr std::uint64_t magic_v2 = 0x5045524944594e32; // "PERIDYN2"

        /**
         * The checkpoint directories under 'Output/Directory': the last
         * complete checkpoint, the one being written (renamed into place
         * when complete) and the previous one (kept until the rename has
         * succeeded, so that a run killed in between still has one).
         */
        struct Directories
        {
          explicit Directories(const std::string &output_directory)
            : base(output_directory)
            , good(base / "checkpoint")
            , fresh(base / "checkpoint.new")
            , old(base / "checkpoint.old")
          {}

          std::filesystem::path base, good, fresh, old;
        };

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

        /// @p x as 16 hexadecimal digits after "0x".
        inline std::string
        hex(const std::uint64_t x)
        {
          std::ostringstream s;
          s << "0x" << std::hex << std::setw(16) << std::setfill('0') << x;
          return s.str();
        }

        /// The message of a corrupt checkpoint file @p file: @p what is
        /// wrong, and what to do.
        inline std::string
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
                const std::size_t k =
                  std::min<std::uint64_t>(n, sizeof(buffer));
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
        inline std::uint64_t
        checkpoint_file_size(const std::filesystem::path &path)
        {
          std::error_code code;
          const auto      size = std::filesystem::file_size(path, code);
          if (code)
            throw std::runtime_error(
              corrupt_message(path.string(),
                              "is missing or cannot be read (" +
                                code.message() + ")"));
          return size;
        }
      } // namespace ExplicitDynamicsCheckpoint
    }   // namespace internal
  }     // namespace Problems
} // namespace PeriDEAL

#endif
