// perideal-partial-volume-figures: the data of Figs. 10 and 11 of Scabbia,
// Zaccariotto, Galvanetto (2022), "Accurate computation of partial volumes in
// 3D peridynamics", Sect. 4 and 4.1, for PeriDEAL's 3D algorithms.
//
//   perideal-partial-volume-figures [--output-dir DIR] [--quick]
//
// In scaled units (grid spacing 1, node at the origin, horizon m = delta/h):
//  - fig10.csv (m = 1, 1.5, ..., 10, the paper's grid) and fig10_fine.csv
//    (m = 1, 1.05, ..., 10): the relative error of the neighbourhood volume,
//    Eq. (34), eps_V = |(1 + sum_j beta_j) / (4/3 pi m^3) - 1|, for
//    quasi-analytical with N = 2, 4, 6, 8, 12, 16, 20 and for exact;
//  - fig11.csv (m = 1, 1.05, ..., 10): the neighbourhood volume V_H of
//    Eq. (35) and its relative error, and the weighted volume with the
//    Gaussian influence function omega = exp(-|xi|^2 / m^2),
//    m_num = sum_j omega_j |xi_j|^2 beta_j, divided by its analytical value
//    (Eq. 36) m_an = (3/2 sqrt(pi) erf(1) - 5/e) pi m^5, and its relative
//    error (Eq. 37), for approximate, quasi-analytical N = 4 and N = 20, and
//    exact.
// The m values are (k0 + k) / k0, rounded once: the same doubles as the
// decimal literals 1.05, 3.05, ... of the reference data. Non-finite results
// (quasi-analytical dividing by zero at an exact tangency) are written as
// they come ("inf", "nan"): they are findings, not glitches of the plot.

#include <deal.II/base/parameter_handler.h>

#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace PeriDEAL;
using namespace PeriDEAL::Quadrature;

namespace
{
  const char *usage =
    "Usage: perideal-partial-volume-figures [options]\n"
    "Neighbourhood volume and Gaussian weighted volume on uniform grids\n"
    "(Figs. 10 and 11 of Scabbia et al. 2022) for the 3D algorithms.\n"
    "\n"
    "Options:\n"
    "  --output-dir DIR  where fig10.csv, fig10_fine.csv and fig11.csv are\n"
    "                    written (default: results/partial_volume_figures)\n"
    "  --quick           m in [1, 3] only (smoke test)\n"
    "  --help            this text\n";

  [[noreturn]] void
  fail(const std::string &message)
  {
    std::cerr << "perideal-partial-volume-figures: error: " << message << "\n\n"
              << usage;
    std::exit(1);
  }

  struct Options
  {
    std::string output_dir = "results/partial_volume_figures";
    bool        quick      = false;
  };

  Options
  parse_command_line(int argc, char **argv)
  {
    Options o;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h")
          {
            std::cout << usage;
            std::exit(0);
          }
        else if (arg == "--output-dir")
          {
            if (i + 1 >= argc)
              fail("option --output-dir needs a value");
            o.output_dir = argv[++i];
          }
        else if (arg == "--quick")
          o.quick = true;
        else
          fail("unknown option '" + arg + "'");
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
    csv_prefix() const
    {
      return name + "," +
             (taylor_order > 0 ? std::to_string(taylor_order) : "") + ",";
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

  /// m = 1, 1 + 1/steps_per_unit, ..., m_max, each rounded once.
  std::vector<double>
  m_grid(const int steps_per_unit, const double m_max)
  {
    std::vector<double> result;
    for (int k = 0; steps_per_unit + k <= m_max * steps_per_unit + 1e-9; ++k)
      result.push_back(double(steps_per_unit + k) / steps_per_unit);
    return result;
  }

  /// Eq. (34): the relative error of the neighbourhood volume.
  double
  volume_error(const double volume, const double m)
  {
    return std::abs(volume / (4. / 3. * M_PI * m * m * m) - 1);
  }

  /**
   * Eq. (36) in scaled units: the weighted volume of the ball of radius m
   * with omega = exp(-r^2/m^2), \int_0^m omega r^2 4 pi r^2 dr.
   */
  double
  analytical_weighted_volume(const double m)
  {
    return (1.5 * std::sqrt(M_PI) * std::erf(1.) - 5. / M_E) * M_PI *
           std::pow(m, 5);
  }

  /// sum_j omega_j |xi_j|^2 beta_j over all neighbours (the node's own
  /// cell has |xi| = 0).
  double
  weighted_volume(const UniformGridWeights<3> &table, const double m)
  {
    double sum = 0;
    for (const auto &n : table.neighbours())
      {
        const double r2 = double(n.offset[0]) * n.offset[0] +
                          double(n.offset[1]) * n.offset[1] +
                          double(n.offset[2]) * n.offset[2];
        sum += std::exp(-r2 / (m * m)) * r2 * n.beta;
      }
    return sum;
  }

  /// @p maximum = max(@p maximum, @p x), where a NaN, once seen, stays.
  void
  update_maximum(double &maximum, const double x)
  {
    if (!std::isnan(maximum) && !(x <= maximum))
      maximum = x;
  }

  std::ofstream
  open_csv(const std::string &file_name, const std::string &header)
  {
    std::ofstream out(file_name);
    if (!out)
      fail("cannot write " + file_name);
    out << header << '\n';
    return out;
  }

  std::string
  format(const double x)
  {
    char s[32];
    std::snprintf(s, sizeof s, "%.17g", x);
    return s;
  }

  void
  write_fig10(const std::string          &file_name,
              const std::vector<double>  &ms,
              const std::vector<Variant> &variants)
  {
    std::ofstream csv =
      open_csv(file_name, "m,algorithm,taylor_order,rel_error_volume");
    for (const Variant &v : variants)
      for (const double m : ms)
        {
          const UniformGridWeights<3> table(*v.algorithm, m);
          csv << format(m) << ',' << v.csv_prefix()
              << format(volume_error(table.neighbourhood_measure(), m)) << '\n';
        }
  }
} // namespace

int
main(int argc, char **argv)
{
  const Options o = parse_command_line(argc, argv);
  try
    {
      const double m_max = o.quick ? 3. : 10.;
      std::filesystem::create_directories(o.output_dir);

      std::vector<Variant> fig10_variants;
      for (const int n : {2, 4, 6, 8, 12, 16, 20})
        fig10_variants.push_back(make_variant("quasi-analytical", n));
      fig10_variants.push_back(make_variant("exact", 0));
      write_fig10(o.output_dir + "/fig10.csv",
                  m_grid(2, m_max),
                  fig10_variants);
      write_fig10(o.output_dir + "/fig10_fine.csv",
                  m_grid(20, m_max),
                  fig10_variants);

      std::vector<Variant> fig11_variants;
      fig11_variants.push_back(make_variant("approximate", 0));
      fig11_variants.push_back(make_variant("quasi-analytical", 4));
      fig11_variants.push_back(make_variant("quasi-analytical", 20));
      fig11_variants.push_back(make_variant("exact", 0));
      std::ofstream csv =
        open_csv(o.output_dir + "/fig11.csv",
                 "m,algorithm,taylor_order,volume,rel_error_volume,"
                 "normalised_weighted_volume,rel_error_weighted_volume");
      std::printf("Fig. 11 data (max over m = 1 to %g, step 0.05)\n"
                  "%-22s %16s %16s\n",
                  m_max,
                  "algorithm",
                  "max eps_V",
                  "max eps_m");
      for (const Variant &v : fig11_variants)
        {
          double max_volume_error = 0, max_weighted_error = 0;
          for (const double m : m_grid(20, m_max))
            {
              const UniformGridWeights<3> table(*v.algorithm, m);
              const double volume = table.neighbourhood_measure();
              const double weighted =
                weighted_volume(table, m) / analytical_weighted_volume(m);
              const double eps_V = volume_error(volume, m);
              const double eps_m = std::abs(weighted - 1);
              update_maximum(max_volume_error, eps_V);
              update_maximum(max_weighted_error, eps_m);
              csv << format(m) << ',' << v.csv_prefix() << format(volume) << ','
                  << format(eps_V) << ',' << format(weighted) << ','
                  << format(eps_m) << '\n';
            }
          const std::string label =
            v.taylor_order > 0 ?
              v.name + " N=" + std::to_string(v.taylor_order) :
              v.name;
          std::printf("%-22s %16.3e %16.3e\n",
                      label.c_str(),
                      max_volume_error,
                      max_weighted_error);
        }
      std::printf("Written: %s/{fig10,fig10_fine,fig11}.csv\n",
                  o.output_dir.c_str());
    }
  catch (const std::exception &e)
    {
      std::cerr << "perideal-partial-volume-figures: error: " << e.what()
                << '\n';
      return 1;
    }
  return 0;
}
