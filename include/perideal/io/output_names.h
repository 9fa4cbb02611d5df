#ifndef perideal_io_output_names_h
#define perideal_io_output_names_h

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace IO
  {
    /**
     * A name under which a run writes (or which it reads and must not
     * overwrite), and the input entry that chose it: the raw material of
     * check_output_names().
     */
    struct OutputName
    {
      enum class Kind
      {
        /// One file, and its temporary "<file>.tmp" (write_then_rename()).
        file,
        /**
         * The numbered records of a time series: "<path>_<n>.pvtu" and
         * "<path>_<n>.<rank>.vtu" for every n and rank, and their
         * temporaries; @p path is the stem "<directory>/<base name>".
         */
        records,
        /// A directory and everything in it (checkpoints).
        directory,
        /// A file the run reads (a mesh): nothing may be written over it.
        input
      };

      /// The entry, as 'subsection/Entry'.
      std::string entry;
      /// Its value as given.
      std::string value;
      /// Where the run writes (see Kind), relative to the working directory.
      std::string path;
      Kind        kind = Kind::file;
      /// What it is, for messages ("the energy file").
      std::string what;
    };

    /**
     * Refuse names under which two outputs of a run (or an output and an
     * input) would meet: the same file, a file among the records of a time
     * series or inside a checkpoint directory, a file that would have to be
     * the directory of another, or a temporary name of one that is the name
     * of another. One would overwrite or delete the other, in the middle of
     * a run. Paths are compared after resolving '.', '..' and symbolic
     * links of directories that exist.
     *
     * Throws ExcInvalidInput naming the later entry of @p names, its value,
     * the path and the earlier entry with its value. Reads the file system
     * (to resolve paths) but writes nothing; not collective (run it through
     * check_on_all_ranks()).
     */
    void
    check_output_names(const std::vector<OutputName> &names);
  } // namespace IO
} // namespace PeriDEAL

#endif
