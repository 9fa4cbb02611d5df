// perideal-weights: quadrature coefficients of PD nodes on a uniform grid.
//
//   perideal-weights --dim 3 --m-ratio 3 --algorithm exact [--wedge]
//   perideal-weights --summary [--dim 3] [--m-ratio 3]
//
// prints CSV "x,y,z,beta" (or "x,y,beta"), one row per neighbour with
// beta > 0, or with --summary a table of neighbourhood-volume errors and
// times for every registered algorithm.

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/read_number.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

using namespace PeriDEAL;
using namespace PeriDEAL::Quadrature;

namespace
{
  // The text given after --m-ratio, for messages (as typed).
  std::string
  argv_m_ratio(const int argc, char **argv)
  {
    for (int i = 1; i + 1 < argc; ++i)
      if (std::string(argv[i]) == "--m-ratio")
        return argv[i + 1];
    return "3";
  }

  struct Options
  {
    int         dim          = 3;
    double      m_ratio      = 3.0;
    std::string algorithm    = "exact";
    int         taylor_order = -1; // not given
    bool        wedge        = false;
    bool        summary      = false;
  };

  const char *usage =
    "Usage: perideal-weights [options]\n"
    "Prints the quadrature coefficients beta of all neighbours of a node on a\n"
    "uniform grid (spacing 1, node at the origin) as CSV: header x,y,z,beta\n"
    "(x,y,beta in 2D), one row per offset with beta > 0, origin excluded.\n"
    "\n"
    "Options:\n"
    "  --dim 2|3               space dimension (default 3)\n"
    "  --m-ratio M             horizon / grid spacing, M > 0 (default 3)\n"
    "  --algorithm NAME        exact | quasi-analytical (3D) | approximate |\n"
    "                          full (default exact)\n"
    "  --taylor-order N        Taylor order of quasi-analytical (default 4)\n"
    "  --wedge                 only offsets with 0 <= x <= y <= z\n"
    "  --summary               instead of CSV: neighbourhood-volume error and\n"
    "                          time of every algorithm for this m-ratio\n"
    "  --help                  this text\n";

  [[noreturn]] void
  fail(const std::string &message)
  {
    std::cerr << "perideal-weights: error: " << message << "\n\n" << usage;
    std::exit(1);
  }

  double
  parse_number(const std::string &option, const std::string &value)
  {
    double x = 0;
    if (!read_number(value, x))
      fail("option " + option + " expects a number, got '" + value + "'");
    return x;
  }

  Options
  parse_command_line(int argc, char **argv)
  {
    Options o;
    bool    dim_given = false;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg   = argv[i];
        auto              value = [&]() -> std::string {
          if (i + 1 >= argc)
            fail("option " + arg + " needs a value");
          return argv[++i];
        };
        if (arg == "--help" || arg == "-h")
          {
            std::cout << usage;
            std::exit(0);
          }
        else if (arg == "--dim")
          {
            const double d = parse_number(arg, value());
            if (d != 2 && d != 3)
              fail("--dim must be 2 or 3, got " + std::string(argv[i]));
            o.dim     = static_cast<int>(d);
            dim_given = true;
          }
        else if (arg == "--m-ratio")
          {
            o.m_ratio = parse_number(arg, value());
            if (!(std::isfinite(o.m_ratio) && o.m_ratio > 0))
              fail("--m-ratio must be a finite number > 0 (the horizon in "
                   "grid spacings), got " +
                   std::string(argv[i]));
          }
        else if (arg == "--algorithm")
          o.algorithm = value();
        else if (arg == "--taylor-order")
          {
            const double n = parse_number(arg, value());
            if (n != std::floor(n) || n < 1 || n > 40)
              fail("--taylor-order must be an integer in [1, 40], got " +
                   std::string(argv[i]));
            o.taylor_order = static_cast<int>(n);
          }
        else if (arg == "--wedge")
          o.wedge = true;
        else if (arg == "--summary")
          o.summary = true;
        else
          fail("unknown option '" + arg + "'");
      }
    (void)dim_given;
    // Size guard: the coefficient table and the list of neighbours grow
    // like m^dim; refuse before allocating what the machine cannot hold.
    {
      const double side  = o.m_ratio + 1.5;
      const double table = 8. * std::pow(side, o.dim);
      const double list  = (8. + 4. * o.dim) * std::pow(2 * side, o.dim);
      const double gb    = (table + list) / 1073741824.;
      if (gb > 4)
        {
          std::ostringstream message;
          message << "--m-ratio " << argv_m_ratio(argc, argv)
                  << " needs an estimated " << std::setprecision(3) << gb
                  << " GB for the " << o.dim
                  << "D weight table and its neighbour list; give an m-ratio "
                     "below "
                  << std::setprecision(3)
                  << std::pow(4. * 1073741824. /
                                (8. + (8. + 4. * o.dim) * std::pow(2., o.dim)),
                              1. / o.dim) -
                       1.5;
          fail(message.str());
        }
    }
    return o;
  }

  template <int dim>
  std::unique_ptr<PartialVolume<dim>>
  create_algorithm(const std::string &name, const int taylor_order)
  {
    if (!PartialVolumeRegistry<dim>::is_registered(name))
      fail("unknown algorithm '" + name + "' in " + std::to_string(dim) +
           "D; registered: " + PartialVolumeRegistry<dim>::pattern_string());
    ParameterHandler prm;
    PartialVolumeRegistry<dim>::declare_parameters(prm);
    if (taylor_order > 0)
      {
        if (name != "quasi-analytical")
          fail("--taylor-order applies to --algorithm quasi-analytical "
               "only, not to '" +
               name + "'");
        prm.enter_subsection(name);
        prm.set("Taylor order", std::to_string(taylor_order));
        prm.leave_subsection();
      }
    return PartialVolumeRegistry<dim>::create(name, prm);
  }

  template <int dim>
  void
  print_csv(const Options &o)
  {
    const auto algorithm = create_algorithm<dim>(o.algorithm, o.taylor_order);
    const UniformGridWeights<dim> table(*algorithm, o.m_ratio);
    std::printf(dim == 2 ? "x,y,beta\n" : "x,y,z,beta\n");
    for (const auto &entry : (o.wedge ? table.wedge() : table.neighbours()))
      {
        for (unsigned int d = 0; d < dim; ++d)
          std::printf("%d,", entry.offset[d]);
        std::printf("%.17g\n", entry.beta);
      }
  }

  template <int dim>
  void
  print_summary(const Options &o)
  {
    const double exact_measure =
      (dim == 2 ? M_PI * o.m_ratio * o.m_ratio :
                  4. / 3. * M_PI * std::pow(o.m_ratio, 3));
    std::printf("PeriDEAL quadrature weights, %dD, m-ratio %g\n",
                dim,
                o.m_ratio);
    std::printf("neighbourhood %s 1 + sum(beta) against %s = %.15g\n",
                dim == 2 ? "area" : "volume",
                dim == 2 ? "pi m^2" : "4/3 pi m^3",
                exact_measure);
    if (o.m_ratio < 0.5 * std::sqrt(double(dim)))
      std::printf("(m < sqrt(%d)/2: the ball does not contain the node's own "
                  "cell, which counts by its exact part inside the ball)\n",
                  dim);
    std::printf("\n");
    std::printf("%-24s %10s %14s %14s\n",
                "algorithm",
                "neighbours",
                "rel. error",
                "time [ms]");
    std::vector<std::pair<std::string, int>> runs;
    for (const auto &name : PartialVolumeRegistry<dim>::names())
      if (name == "quasi-analytical")
        for (const int n : {4, 20})
          runs.emplace_back(name, n);
      else
        runs.emplace_back(name, -1);
    for (const auto &[name, order] : runs)
      {
        const auto algorithm = create_algorithm<dim>(name, order);
        const auto start     = std::chrono::steady_clock::now();
        const UniformGridWeights<dim> table(*algorithm, o.m_ratio);
        const double                  seconds = std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
        const std::string label =
          order > 0 ? name + " (N=" + std::to_string(order) + ")" : name;
        std::printf("%-24s %10zu %14.3e %14.3f\n",
                    label.c_str(),
                    table.neighbours().size(),
                    std::abs(table.neighbourhood_measure() / exact_measure - 1),
                    seconds * 1e3);
      }
  }
} // namespace

int
main(int argc, char **argv)
{
  const Options o = parse_command_line(argc, argv);
  try
    {
      if (o.summary)
        (o.dim == 2 ? print_summary<2>(o) : print_summary<3>(o));
      else
        (o.dim == 2 ? print_csv<2>(o) : print_csv<3>(o));
    }
  catch (const std::exception &e)
    {
      std::cerr << "perideal-weights: error: " << e.what() << '\n';
      return 1;
    }
  return 0;
}
