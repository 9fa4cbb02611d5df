// Reading the independent reference data of tests/quadrature/reference
// (shared by the tests of this folder).
#ifndef perideal_tests_quadrature_reference_data_h
#define perideal_tests_quadrature_reference_data_h

#include <deal.II/base/exceptions.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

// Rows of a CSV file with a header line, as numbers.
inline std::vector<std::vector<double>>
read_csv(const std::string &name, const unsigned int n_columns)
{
  const std::string file =
    std::string(PERIDEAL_TEST_DATA_DIR) + "/quadrature/reference/" + name;
  std::ifstream in(file);
  AssertThrow(in, dealii::ExcMessage("Cannot open the reference file " + file));
  std::string line;
  std::getline(in, line);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line))
    {
      if (line.empty())
        continue;
      std::vector<double> row;
      std::stringstream   s(line);
      std::string         field;
      while (std::getline(s, field, ','))
        row.push_back(std::stod(field));
      AssertThrow(row.size() == n_columns,
                  dealii::ExcMessage("Bad row in " + file + ": " + line));
      rows.push_back(row);
    }
  return rows;
}

#endif
