#include <perideal/base/collective_checks.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace PeriDEAL
{
  void
  throw_on_any_rank(const std::string &local_error, const MPI_Comm comm)
  {
    const unsigned int n_failed =
      dealii::Utilities::MPI::sum(local_error.empty() ? 0u : 1u, comm);
    if (n_failed == 0)
      return;
    for (const auto &message :
         dealii::Utilities::MPI::all_gather(comm, local_error))
      if (!message.empty())
        AssertThrow(false, dealii::ExcMessage(message));
  }


  std::string
  check_writable_file(const std::string &path)
  {
    namespace fs = std::filesystem;
    std::error_code error;
    const fs::path  file(path);
    if (fs::is_directory(file, error))
      return "'" + path + "' is a directory";
    const fs::path directory =
      file.has_parent_path() ? file.parent_path() : fs::path(".");
    if (!fs::is_directory(directory, error))
      {
        // A directory that does not exist yet is created when the file is
        // written, if it can be.
        const std::string why = check_writable_directory(directory.string());
        return why.empty() ? "" : "its directory cannot be created: " + why;
      }
    if (access(directory.c_str(), W_OK) != 0)
      return "the directory '" + directory.string() + "' is not writable";
    if (fs::exists(file, error) && access(file.c_str(), W_OK) != 0)
      return "the file exists and is not writable";
    return "";
  }


  std::string
  check_writable_directory(const std::string &path)
  {
    namespace fs = std::filesystem;
    std::error_code error;
    fs::path        p = fs::absolute(fs::path(path), error);
    while (!p.empty() && !fs::exists(p, error))
      {
        if (p == p.parent_path())
          break;
        p = p.parent_path();
      }
    if (!fs::is_directory(p, error))
      return "'" + p.string() + "' exists and is not a directory";
    if (access(p.c_str(), W_OK) != 0)
      return "the directory '" + p.string() + "' is not writable";
    return "";
  }


  std::string
  write_then_rename(const std::string                         &path,
                    const std::function<void(std::ostream &)> &write)
  {
    namespace fs = std::filesystem;
    std::error_code code;
    const fs::path  parent = fs::path(path).parent_path();
    if (!parent.empty())
      fs::create_directories(parent, code);
    const std::string temporary = path + ".tmp";
    std::string       error;
    {
      std::ofstream out(temporary);
      if (!out)
        error = "'" + temporary + "' cannot be opened for writing";
      else
        {
          write(out);
          out.close();
          if (!out)
            error = "writing '" + temporary + "' failed (disk full?)";
        }
    }
    if (error.empty())
      {
        fs::rename(temporary, path, code);
        if (code)
          error = "renaming '" + temporary + "' failed: " + code.message();
      }
    if (!error.empty())
      fs::remove(temporary, code);
    return error;
  }
} // namespace PeriDEAL
