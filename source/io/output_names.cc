#include <perideal/base/exceptions.h>
#include <perideal/io/output_names.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace PeriDEAL
{
  namespace IO
  {
    namespace
    {
      namespace fs = std::filesystem;

      /// @p path absolute, with '.', '..' and the symbolic links of the
      /// existing directories resolved, without a trailing '/'.
      fs::path
      resolve(const std::string &path)
      {
        std::error_code code;
        fs::path        absolute = fs::absolute(fs::path(path), code);
        if (code)
          absolute = fs::path(path);
        fs::path result = fs::weakly_canonical(absolute, code);
        if (code)
          result = absolute.lexically_normal();
        while (!result.has_filename() && result.has_relative_path())
          result = result.parent_path();
        return result;
      }

      /// Whether @p inner lies strictly below the directory @p outer.
      bool
      is_below(const fs::path &inner, const fs::path &outer)
      {
        auto i = inner.begin();
        for (auto o = outer.begin(); o != outer.end(); ++o, ++i)
          if (i == inner.end() || *i != *o)
            return false;
        return i != inner.end();
      }

      bool
      all_digits(const std::string &s)
      {
        return !s.empty() &&
               std::all_of(s.begin(), s.end(), [](const unsigned char c) {
                 return std::isdigit(c) != 0;
               });
      }

      /// Whether @p name is "<stem>_<n>.pvtu" or "<stem>_<n>.<rank>.vtu",
      /// or one of them with ".tmp" appended.
      bool
      is_record(std::string name, const std::string &stem)
      {
        if (name.rfind(stem + "_", 0) != 0)
          return false;
        name = name.substr(stem.size() + 1);
        const auto strip = [&](const std::string &suffix) {
          if (name.size() < suffix.size() ||
              name.compare(name.size() - suffix.size(),
                           suffix.size(),
                           suffix) != 0)
            return false;
          name.resize(name.size() - suffix.size());
          return true;
        };
        strip(".tmp");
        if (strip(".pvtu"))
          return all_digits(name);
        if (!strip(".vtu"))
          return false;
        const auto dot = name.find('.');
        return dot != std::string::npos && all_digits(name.substr(0, dot)) &&
               all_digits(name.substr(dot + 1));
      }

      /// One OutputName with its paths resolved.
      struct Claim
      {
        const OutputName *name;
        fs::path          path;

        /// The concrete paths it takes (none for records).
        std::vector<fs::path>
        names() const
        {
          switch (name->kind)
            {
              case OutputName::Kind::file:
                return {path, fs::path(path.string() + ".tmp")};
              case OutputName::Kind::records:
                return {};
              default:
                return {path};
            }
        }

        /// Whether writing it may create, overwrite or delete @p p.
        bool
        takes(const fs::path &p) const
        {
          switch (name->kind)
            {
              case OutputName::Kind::file:
                return p == path || p == fs::path(path.string() + ".tmp");
              case OutputName::Kind::records:
                return p.parent_path() == path.parent_path() &&
                       is_record(p.filename().string(),
                                 path.filename().string());
              case OutputName::Kind::directory:
                return p == path || is_below(p, path);
              default:
                return p == path;
            }
        }

        /// The paths that must be directories for it to be written.
        std::vector<fs::path>
        directories() const
        {
          switch (name->kind)
            {
              case OutputName::Kind::records:
                return {path.parent_path()};
              case OutputName::Kind::directory:
                return {path};
              default:
                return {};
            }
        }

        bool
        is_output() const
        {
          return name->kind != OutputName::Kind::input;
        }

        /// "the energy file ('explicit dynamics/Energy file' = 'e.csv')"
        std::string
        described() const
        {
          return name->what + " ('" + name->entry + "' = '" + name->value +
                 "')";
        }
      };

      std::string
      shown(const fs::path &p)
      {
        std::error_code code;
        const fs::path  here = fs::current_path(code);
        return code ? p.string() : p.lexically_proximate(here).string();
      }

      /// Why @p a and @p b cannot both be written (empty: they can); @p b is
      /// the one to blame.
      std::string
      conflict(const Claim &a, const Claim &b)
      {
        const auto same = [&](const fs::path &p) {
          return "it puts " + b.name->what + " at '" + shown(p) +
                 "', where the run also " +
                 (a.is_output() ? "writes " : "reads ") + a.described();
        };
        for (const auto &p : b.names())
          if (a.takes(p))
            return same(p);
        for (const auto &p : a.names())
          if (b.takes(p))
            return same(p);
        if (a.name->kind == OutputName::Kind::records &&
            b.name->kind == OutputName::Kind::records && a.path == b.path)
          return same(fs::path(a.path.string() + "_0.pvtu"));
        // A file where the other needs a directory, or the other way round.
        const auto file_as_directory = [&](const Claim &file,
                                           const Claim &other) {
          if (file.name->kind != OutputName::Kind::file)
            return std::string();
          for (const auto &p : file.names())
            {
              bool below = false;
              for (const auto &d : other.directories())
                below = below || d == p || is_below(d, p);
              for (const auto &q : other.names())
                below = below || is_below(q, p);
              if (below)
                return "'" + shown(p) + "' would be " + file.name->what +
                       " (" + "'" + file.name->entry + "') and a directory "
                       "of " + other.described();
            }
          return std::string();
        };
        if (a.is_output() && b.is_output())
          for (const auto &why : {file_as_directory(b, a),
                                  file_as_directory(a, b)})
            if (!why.empty())
              return why;
        return "";
      }
    } // namespace


    void
    check_output_names(const std::vector<OutputName> &names)
    {
      std::vector<Claim> claims;
      for (const auto &name : names)
        claims.push_back({&name, resolve(name.path)});
      for (unsigned int j = 0; j < claims.size(); ++j)
        for (unsigned int i = 0; i < j; ++i)
          {
            if (!claims[i].is_output() && !claims[j].is_output())
              continue;
            // Blame the later entry, or the output where one is read.
            const bool later = claims[j].is_output();
            const Claim &blamed = later ? claims[j] : claims[i];
            const Claim &other  = later ? claims[i] : claims[j];
            const std::string why = conflict(other, blamed);
            AssertThrow(why.empty(),
                        ExcInvalidInput(blamed.name->entry,
                                        blamed.name->value,
                                        why +
                                          (other.is_output() ?
                                             "; one would overwrite or "
                                             "delete the other: give each "
                                             "output a name of its own" :
                                             "; the run would overwrite or "
                                             "delete its input: give the "
                                             "output another name")));
          }
    }
  } // namespace IO
} // namespace PeriDEAL
