#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/exceptions.h>
#include <perideal/base/input_checks.h>
#include <perideal/base/read_number.h>

#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  std::string
  InputEntry::name() const
  {
    std::string s;
    for (const auto &p : path)
      s += (s.empty() ? "" : "/") + p;
    return s;
  }


  namespace
  {
    /**
     * Follow one trimmed line of a parameter file in PRM syntax:
     * "subsection X" enters X in @p path, "end" leaves it.
     * @return true for a "set Name = value" line, with @p name (without
     * its path) and @p value trimmed; false for every other line.
     */
    bool
    read_prm_line(const std::string        &line,
                  std::vector<std::string> &path,
                  std::string              &name,
                  std::string              &value)
    {
      if (line.rfind("subsection ", 0) == 0)
        path.push_back(dealii::Utilities::trim(line.substr(11)));
      else if (line == "end" && !path.empty())
        path.pop_back();
      else if (line.rfind("set ", 0) == 0)
        {
          // Names hold no '='; values may (muparser's "==").
          const auto equal = line.find('=');
          if (equal == std::string::npos)
            return false;
          name  = dealii::Utilities::trim(line.substr(4, equal - 4));
          value = dealii::Utilities::trim(line.substr(equal + 1));
          return true;
        }
      return false;
    }
  } // namespace


  std::vector<InputEntry>
  scan_input_file(const std::string &file)
  {
    std::ifstream                       in(file);
    std::string                         line;
    std::vector<std::string>            path;
    std::map<std::string, unsigned int> first_line;
    std::map<std::string, std::string>  first_value;
    std::vector<InputEntry>             entries;
    unsigned int                        number = 0;
    while (std::getline(in, line))
      {
        ++number;
        const auto comment = line.find('#');
        if (comment != std::string::npos)
          line.erase(comment);
        std::string entry_name, value;
        if (read_prm_line(dealii::Utilities::trim(line),
                          path,
                          entry_name,
                          value))
          {
            InputEntry entry{path, number};
            entry.path.push_back(entry_name);
            const std::string name = entry.name();
            const auto        seen = first_line.find(name);
            AssertThrow(seen == first_line.end(),
                        dealii::ExcMessage(
                          "The entry '" + name + "' is set twice in '" + file +
                          "' (line " +
                          std::to_string(
                            seen == first_line.end() ? 0 : seen->second) +
                          ": '" + first_value[name] + "', line " +
                          std::to_string(number) + ": '" + value +
                          "'); only the last value would count. Remove "
                          "one."));
            first_line[name]  = number;
            first_value[name] = value;
            entries.push_back(entry);
          }
      }
    AssertThrow(!entries.empty(),
                dealii::ExcMessage(
                  "The parameter file '" + file +
                  "' sets no entry, so it would run the default problem. "
                  "Set the entries that describe your problem; 'perideal "
                  "--print-parameters' lists them."));
    return entries;
  }


  namespace
  {
    // Every entry of @p prm with its value, by path: read back from the
    // short PRM listing, the one public way to visit all entries.
    std::map<std::string, std::string>
    all_entries(const dealii::ParameterHandler &prm)
    {
      std::ostringstream listing;
      prm.print_parameters(listing, dealii::ParameterHandler::ShortPRM);
      std::istringstream                 in(listing.str());
      std::map<std::string, std::string> values;
      std::vector<std::string>           path;
      std::string                        line;
      while (std::getline(in, line))
        {
          std::string entry_name, value;
          if (read_prm_line(dealii::Utilities::trim(line),
                            path,
                            entry_name,
                            value))
            {
              std::string name;
              for (const auto &p : path)
                name += p + "/";
              values[name + entry_name] = value;
            }
        }
      return values;
    }


    bool
    same_value(const std::string &a, const std::string &b)
    {
      std::string x, y;
      for (const char c : a)
        if (!std::isspace(static_cast<unsigned char>(c)))
          x += c;
      for (const char c : b)
        if (!std::isspace(static_cast<unsigned char>(c)))
          y += c;
      if (x == y)
        return true;
      double u = 0, v = 0;
      return read_number(x, u) && read_number(y, v) && u == v;
    }


    // Whether the entry path @p name matches @p pattern (see UnusedEntry).
    bool
    matches(const std::string &pattern, const std::string &name)
    {
      const auto p = dealii::Utilities::split_string_list(pattern, '/');
      const auto n = dealii::Utilities::split_string_list(name, '/');
      const bool subsection = !pattern.empty() && pattern.back() == '/';
      // split_string_list drops the empty item after a trailing '/'.
      if (n.size() < p.size() || (!subsection && n.size() != p.size()))
        return false;
      for (std::size_t k = 0; k < p.size(); ++k)
        if (p[k] != "*" && p[k] != n[k])
          return false;
      return true;
    }
  } // namespace


  std::vector<std::pair<std::string, std::string>>
  changed_entries(const dealii::ParameterHandler &prm,
                  const dealii::ParameterHandler &defaults)
  {
    const auto given    = all_entries(prm);
    const auto original = all_entries(defaults);
    std::vector<std::pair<std::string, std::string>> changed;
    for (const auto &[name, value] : given)
      {
        const auto other = original.find(name);
        if (other == original.end() || !same_value(value, other->second))
          changed.emplace_back(name, value);
      }
    return changed;
  }


  void
  check_unused_entries(
    const std::vector<std::pair<std::string, std::string>> &changed,
    const std::vector<UnusedEntry>                         &unused)
  {
    for (const auto &[name, value] : changed)
      for (const auto &rule : unused)
        AssertThrow(!matches(rule.pattern, name),
                    ExcInvalidInput(name,
                                    value,
                                    "this entry has no effect here: " +
                                      rule.why));
  }


  bool
  expression_uses_variable(const std::string &expression,
                           const std::string &name)
  {
    const auto word = [](const char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
    };
    std::size_t k = 0;
    while (k < expression.size())
      {
        const char c = expression[k];
        if (std::isdigit(static_cast<unsigned char>(c)) || c == '.')
          {
            // A number, with its exponent ("2e-3" holds no variable e).
            while (k < expression.size() &&
                   (std::isdigit(static_cast<unsigned char>(expression[k])) ||
                    expression[k] == '.'))
              ++k;
            if (k < expression.size() &&
                (expression[k] == 'e' || expression[k] == 'E'))
              {
                ++k;
                if (k < expression.size() &&
                    (expression[k] == '+' || expression[k] == '-'))
                  ++k;
                while (k < expression.size() &&
                       std::isdigit(static_cast<unsigned char>(expression[k])))
                  ++k;
              }
          }
        else if (word(c))
          {
            const std::size_t begin = k;
            while (k < expression.size() && word(expression[k]))
              ++k;
            if (expression.compare(begin, k - begin, name) == 0 &&
                k - begin == name.size())
              return true;
          }
        else
          ++k;
      }
    return false;
  }
} // namespace PeriDEAL
