#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/input_checks.h>

#include <fstream>
#include <map>

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
        line = dealii::Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(dealii::Utilities::trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            const auto equal = line.find('=');
            if (equal == std::string::npos)
              continue;
            InputEntry entry{path, number};
            entry.path.push_back(
              dealii::Utilities::trim(line.substr(4, equal - 4)));
            const std::string name  = entry.name();
            const std::string value = dealii::Utilities::trim(
              line.substr(equal + 1));
            const auto seen = first_line.find(name);
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
} // namespace PeriDEAL
