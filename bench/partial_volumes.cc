// perideal-bench-partial-volumes: cost and accuracy of the 3D partial-volume
// algorithms on uniform grids.
//
//   perideal-bench-partial-volumes [--reference-dir DIR] [--output-dir DIR]
//                                  [--quick]
//
// For every variant (exact; quasi-analytical with Taylor order N = 2, 4, 8,
// 12, 16, 20; approximate; full) it measures
//  - the time of one call of uniform_grid_weight() on a partial cell, i.e. a
//    wedge offset 0 <= x <= y <= z, z >= 1, whose exact coefficient lies
//    strictly between 0 and 1, for m-ratios m = 1, 1.05, ..., 10: only
//    these cells cost anything, whole and empty cells are decided by two
//    comparisons in every algorithm;
//  - the largest absolute error of beta against the high-precision mpmath
//    reference tests/quadrature/reference/beta_3d.csv (rows with
//    1 <= m <= 10: every cell with beta > 0, partial and whole), and
//    against the exact kernel on every wedge cell for the same fine m grid.
// Results go to DIR/partial_volumes.csv and, as a table, to stdout.

#include <deal.II/base/parameter_handler.h>

#include <perideal/quadrature/partial_volume.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#ifndef PERIDEAL_REFERENCE_DIR
#  define PERIDEAL_REFERENCE_DIR "tests/quadrature/reference"
#endif

using namespace PeriDEAL;
using namespace PeriDEAL::Quadrature;

namespace
{
  const char *usage =
    "Usage: perideal-bench-partial-volumes [options]\n"
    "Time per partial cell and maximum error of every 3D partial-volume\n"
    "algorithm on uniform grids (m-ratio 1 to 10).\n"
    "\n"
    "Options:\n"
    "  --reference-dir DIR  where beta_3d.csv lies (default: " PERIDEAL_REFERENCE_DIR
    ")\n"
    "  --output-dir DIR     where partial_volumes.csv is written\n"
    "                       (default: results/partial_volumes)\n"
    "  --quick              coarse m grid and short timings (smoke test)\n"
    "  --help               this text\n";

  [[noreturn]] void
  fail(const std::string &message)
  {
    std::cerr << "perideal-bench-partial-volumes: error: " << message << '\n';
    std::exit(1);
  }

  struct Options
  {
    std::string reference_dir = PERIDEAL_REFERENCE_DIR;
    std::string output_dir    = "results/partial_volumes";
    bool        quick         = false;
  };

  Options
  parse_command_line(int argc, char **argv)
  {
    Options o;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg   = argv[i];
        auto              value = [&]() -> std::string {
          if (i + 1 >= argc)
            fail("option " + arg + " needs a value\n\n" + usage);
          return argv[++i];
        };
        if (arg == "--help" || arg == "-h")
          {
            std::cout << usage;
            std::exit(0);
          }
        else if (arg == "--reference-dir")
          o.reference_dir = value();
        else if (arg == "--output-dir")
          o.output_dir = value();
        else if (arg == "--quick")
          o.quick = true;
        else
          fail("unknown option '" + arg + "'\n\n" + usage);
      }
    return o;
  }

  /// One algorithm with its parameters, created through the registry.
  struct Variant
  {
    std::string                       name;
    int                               taylor_order; // 0: not applicable
    std::unique_ptr<PartialVolume<3>> algorithm;

    std::string
    label() const
    {
      return taylor_order > 0 ? name + " N=" + std::to_string(taylor_order) :
                                name;
    }
  };

  Variant
  make_variant(const std::string &name, const int taylor_order)
  {
    ParameterHandler prm;
    PartialVolumeRegistry<3>::declare_parameters(prm);
    if (taylor_order > 0)
      {
        prm.enter_subsection(name);
        prm.set("Taylor order", std::to_string(taylor_order));
        prm.leave_subsection();
      }
    return {name, taylor_order, PartialVolumeRegistry<3>::create(name, prm)};
  }

  struct Cell
  {
    double             m;
    std::array<int, 3> offset;
    double             beta; // reference or exact value
  };

  /**
   * The rows of beta_3d.csv (header m,x,y,z,beta) with 1 <= m <= 10. Values
   * may carry more digits than a double holds; strtod rounds them.
   */
  std::vector<Cell>
  read_reference(const std::string &file_name)
  {
    std::ifstream in(file_name);
    if (!in)
      fail("cannot read the reference file " + file_name +
           "\n(generate it with /usr/bin/python3 "
           "tests/quadrature/reference/generate_reference.py, or pass "
           "--reference-dir)");
    std::string line;
    std::getline(in, line);
    if (line.rfind("m,x,y,z,beta", 0) != 0)
      fail(file_name + ": expected the header 'm,x,y,z,beta', got '" + line +
           "'");
    std::vector<Cell> rows;
    unsigned int      line_number = 1;
    while (std::getline(in, line))
      {
        ++line_number;
        if (line.empty() || line[0] == '#')
          continue;
        std::array<double, 5> v;
        std::istringstream    fields(line);
        std::string           field;
        unsigned int          n = 0;
        try
          {
            for (; n < 5 && std::getline(fields, field, ','); ++n)
              {
                std::size_t end = 0;
                v[n]            = std::stod(field, &end);
                if (end != field.size() &&
                    field.find_first_not_of(" \r", end) != std::string::npos)
                  throw std::invalid_argument(field);
              }
          }
        catch (const std::exception &)
          {
            n = 0;
          }
        if (n != 5 || std::getline(fields, field, ','))
          fail(file_name + ":" + std::to_string(line_number) +
               ": expected five numbers m,x,y,z,beta, got '" + line + "'");
        Cell c{v[0], {}, v[4]};
        for (unsigned int d = 0; d < 3; ++d)
          {
            c.offset[d] = static_cast<int>(std::lround(v[1 + d]));
            if (c.offset[d] != v[1 + d])
              fail(file_name + ":" + std::to_string(line_number) +
                   ": offsets must be integers, got '" + line + "'");
          }
        if (c.m >= 1 && c.m <= 10)
          rows.push_back(c);
      }
    if (rows.empty())
      fail(file_name + " has no rows with 1 <= m <= 10");
    return rows;
  }

  /// m = 1 + k * step for k = 0, ..., rounded once, not accumulated.
  std::vector<double>
  m_grid(const int steps_per_unit, const double m_max)
  {
    std::vector<double> result;
    for (int k = 0; 1. + double(k) / steps_per_unit <= m_max + 1e-12; ++k)
      result.push_back(double(steps_per_unit + k) / steps_per_unit);
    return result;
  }

  /// Every wedge offset 0 <= x <= y <= z, 1 <= z <= ceil(m + 1/2).
  std::vector<std::array<int, 3>>
  wedge_offsets(const double m)
  {
    const int                       bound = std::ceil(m + 0.5);
    std::vector<std::array<int, 3>> result;
    for (int z = 1; z <= bound; ++z)
      for (int y = 0; y <= z; ++y)
        for (int x = 0; x <= y; ++x)
          result.push_back({{x, y, z}});
    return result;
  }

  /// The largest |a - b| with the place where it occurs; NaN wins.
  struct MaxError
  {
    double             value = 0;
    double             m     = 0;
    std::array<int, 3> offset{};

    void
    add(const double a, const double b, const Cell &c)
    {
      const double e = std::abs(a - b);
      if (e > value || (std::isnan(e) && !std::isnan(value)))
        {
          value  = e;
          m      = c.m;
          offset = c.offset;
        }
    }

    std::string
    where() const
    {
      char s[80];
      std::snprintf(s,
                    sizeof s,
                    "m=%.10g (%d,%d,%d)",
                    m,
                    offset[0],
                    offset[1],
                    offset[2]);
      return s;
    }
  };

  volatile double sink;

  /**
   * Nanoseconds per call of uniform_grid_weight() over @p cells: the whole
   * set is evaluated repeatedly in 5 blocks of at least @p min_seconds / 5
   * each, and the fastest block counts, so that a burst of other load on
   * the machine does not.
   */
  double
  time_per_call(const PartialVolume<3>  &algorithm,
                const std::vector<Cell> &cells,
                const double             min_seconds)
  {
    using clock = std::chrono::steady_clock;
    double sum  = 0;
    for (const Cell &c : cells) // warm-up
      sum += algorithm.uniform_grid_weight(c.offset, c.m);
    double best = std::numeric_limits<double>::infinity();
    for (unsigned int block = 0; block < 5; ++block)
      {
        std::size_t calls   = 0;
        double      seconds = 0;
        const auto  start   = clock::now();
        do
          {
            for (const Cell &c : cells)
              sum += algorithm.uniform_grid_weight(c.offset, c.m);
            calls += cells.size();
            seconds =
              std::chrono::duration<double>(clock::now() - start).count();
        } while (seconds < min_seconds / 5);
        best = std::min(best, seconds / calls * 1e9);
      }
    sink = sum;
    return best;
  }

  /**
   * Nanoseconds per partial cell when the whole uniform-grid table is built
   * (uniform_grid_weights() on every wedge offset, one call per m-ratio, as
   * UniformGridWeights does): the total time over all m-ratios divided by
   * the number of partial cells. Algorithms that share work between cells
   * (exact: corner measures) profit here. Fastest of 5 blocks.
   */
  double
  time_per_table_cell(
    const PartialVolume<3> &algorithm,
    const std::vector<std::pair<double, std::vector<std::array<int, 3>>>>
                     &tables,
    const std::size_t n_partial,
    const double      min_seconds)
  {
    using clock = std::chrono::steady_clock;
    double sum  = 0;
    double best = std::numeric_limits<double>::infinity();
    for (unsigned int block = 0; block < 5; ++block)
      {
        std::size_t cells   = 0;
        double      seconds = 0;
        const auto  start   = clock::now();
        do
          {
            for (const auto &[m, offsets] : tables)
              sum += algorithm.uniform_grid_weights(offsets, m).back();
            cells += n_partial;
            seconds =
              std::chrono::duration<double>(clock::now() - start).count();
        } while (seconds < min_seconds / 5);
        best = std::min(best, seconds / cells * 1e9);
      }
    sink = sum;
    return best;
  }
} // namespace

int
main(int argc, char **argv)
{
  const Options o = parse_command_line(argc, argv);
  try
    {
      const std::string       reference_file = o.reference_dir + "/beta_3d.csv";
      const std::vector<Cell> reference      = read_reference(reference_file);

      std::vector<Variant> variants;
      variants.push_back(make_variant("exact", 0));
      for (const int n : {2, 4, 8, 12, 16, 20})
        variants.push_back(make_variant("quasi-analytical", n));
      variants.push_back(make_variant("approximate", 0));
      variants.push_back(make_variant("full", 0));
      const Variant &exact = variants.front();

      // All wedge cells of the fine m grid with their exact coefficients;
      // the partial ones are the timing set.
      const std::vector<double> ms = o.quick ? m_grid(4, 3.) : m_grid(20, 10.);
      std::vector<Cell>         all_cells, partial_cells;
      std::vector<std::pair<double, std::vector<std::array<int, 3>>>> tables;
      for (const double m : ms)
        tables.emplace_back(m, wedge_offsets(m));
      for (const double m : ms)
        for (const auto &offset : wedge_offsets(m))
          {
            const Cell c{m,
                         offset,
                         exact.algorithm->uniform_grid_weight(offset, m)};
            all_cells.push_back(c);
            if (c.beta > 0 && c.beta < 1)
              partial_cells.push_back(c);
          }
      const double min_seconds = o.quick ? 0.02 : 0.5;

      std::printf("PeriDEAL partial-volume benchmark (3D, uniform grid)\n"
                  "reference: %s, %zu rows with 1 <= m <= 10\n"
                  "fine grid: m = %g to %g in %zu steps, %zu wedge cells, "
                  "%zu of them partial (timed)\n\n",
                  reference_file.c_str(),
                  reference.size(),
                  ms.front(),
                  ms.back(),
                  ms.size() - 1,
                  all_cells.size(),
                  partial_cells.size());
      std::printf("%-22s %10s %10s %13s %13s  %-28s %s\n",
                  "algorithm",
                  "ns/call",
                  "ns/table",
                  "max err (ref)",
                  "max err(fine)",
                  "worst cell (ref)",
                  "worst cell (fine)");

      std::filesystem::create_directories(o.output_dir);
      const std::string csv_name = o.output_dir + "/partial_volumes.csv";
      std::ofstream     csv(csv_name);
      if (!csv)
        fail("cannot write " + csv_name);
      csv << "algorithm,taylor_order,ns_per_partial_cell,"
             "ns_per_partial_cell_in_table,"
             "max_abs_error_vs_reference,max_abs_error_vs_exact_fine_grid,"
             "n_reference_rows\n";

      for (const Variant &v : variants)
        {
          MaxError vs_reference, vs_exact;
          for (const Cell &c : reference)
            vs_reference.add(v.algorithm->uniform_grid_weight(c.offset, c.m),
                             c.beta,
                             c);
          for (const Cell &c : all_cells)
            vs_exact.add(v.algorithm->uniform_grid_weight(c.offset, c.m),
                         c.beta,
                         c);
          const double ns =
            time_per_call(*v.algorithm, partial_cells, min_seconds);
          const double ns_table = time_per_table_cell(*v.algorithm,
                                                      tables,
                                                      partial_cells.size(),
                                                      min_seconds);

          std::printf("%-22s %10.1f %10.1f %13.3e %13.3e  %-28s %s\n",
                      v.label().c_str(),
                      ns,
                      ns_table,
                      vs_reference.value,
                      vs_exact.value,
                      vs_reference.value > 0 ? vs_reference.where().c_str() :
                                               "-",
                      vs_exact.value > 0 ? vs_exact.where().c_str() : "-");
          std::fflush(stdout);
          char line[256];
          std::snprintf(line,
                        sizeof line,
                        "%s,%s,%.4g,%.4g,%.6e,%.6e,%zu\n",
                        v.name.c_str(),
                        v.taylor_order > 0 ?
                          std::to_string(v.taylor_order).c_str() :
                          "",
                        ns,
                        ns_table,
                        vs_reference.value,
                        vs_exact.value,
                        reference.size());
          csv << line;
        }
      // Cost against size: building one table as the m-ratio grows.
      {
        const std::string name = o.output_dir + "/table_time_vs_m.csv";
        std::ofstream     out(name);
        if (!out)
          fail("cannot write " + name);
        out << "m,algorithm,taylor_order,n_wedge_cells,n_partial_cells,"
               "microseconds_per_table\n";
        const std::vector<double> sizes =
          o.quick ?
            std::vector<double>{2., 3.} :
            std::vector<double>{2., 3., 5., 7.5, 10., 15., 20., 35., 50.};
        for (const double m : sizes)
          {
            const std::vector<std::vector<std::array<int, 3>>> offsets{
              wedge_offsets(m)};
            std::size_t n_partial = 0;
            for (const double beta :
                 exact.algorithm->uniform_grid_weights(offsets[0], m))
              n_partial += (beta > 0 && beta < 1);
            for (const Variant &v : variants)
              if (v.name != "full" &&
                  (v.taylor_order == 0 || v.taylor_order == 4 ||
                   v.taylor_order == 20))
                {
                  const double ns_per_cell =
                    time_per_table_cell(*v.algorithm,
                                        {{m, offsets[0]}},
                                        n_partial,
                                        min_seconds / 4);
                  char line[256];
                  std::snprintf(line,
                                sizeof line,
                                "%g,%s,%s,%zu,%zu,%.4g\n",
                                m,
                                v.name.c_str(),
                                v.taylor_order > 0 ?
                                  std::to_string(v.taylor_order).c_str() :
                                  "",
                                offsets[0].size(),
                                n_partial,
                                ns_per_cell * n_partial * 1e-3);
                  out << line;
                }
          }
        std::printf("\nTable time against m written: %s\n", name.c_str());
      }

      std::printf("\n\"max err (fine)\" is against the exact kernel on all "
                  "wedge cells of the fine grid;\nexact's own entry there is "
                  "0 by definition. Written: %s\n",
                  csv_name.c_str());
    }
  catch (const std::exception &e)
    {
      std::cerr << "perideal-bench-partial-volumes: error: " << e.what()
                << '\n';
      return 1;
    }
  return 0;
}
