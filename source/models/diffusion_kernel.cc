#include <deal.II/base/numbers.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/diffusion_kernel.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace PeriDEAL
{
  namespace Models
  {
    void
    DiffusionKernel::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Diffusivity",
                        "1",
                        Patterns::Double(),
                        "The classical diffusivity K (m^2/s) that the "
                        "micro-diffusivity matches; > 0.");
      prm.declare_entry("Flux exponent",
                        "2",
                        Patterns::Integer(),
                        "q in J = kappa omega(|xi|/delta) (C' - C) / |xi|^q: "
                        "0, 1, 2 or 3.");
      prm.declare_entry(
        "Micro-diffusivity calibration",
        "continuum",
        Patterns::Selection("continuum|lattice"),
        "continuum: kappa by flux matching on the continuous ball (the "
        "paper's Eq. 25); lattice: kappa matched on the discrete stencil of "
        "the uniform grid, so that the discrete operator maps quadratics "
        "exactly to K Lap C and converges to classical diffusion as the "
        "horizon shrinks at fixed m-ratio (uniform grids only).");
      prm.declare_entry("Influence function",
                        "constant",
                        Patterns::Selection(
                          InfluenceFunctionRegistry::pattern_string()),
                        "The influence function omega(|xi|/delta) of the "
                        "diffusion bonds.");
    }


    void
    DiffusionKernel::parse_parameters(ParameterHandler  &prm,
                                      const std::string &section)
    {
      K                = prm.get_double("Diffusivity");
      diffusivity_text = prm.get("Diffusivity");
      section_name     = section;
      AssertThrow(K > 0 && std::isfinite(K),
                  ExcInvalidInput(section + "/Diffusivity",
                                  prm.get("Diffusivity"),
                                  "give a diffusivity > 0 (m^2/s)"));
      const long exponent = prm.get_integer("Flux exponent");
      AssertThrow(exponent >= 0 && exponent <= 3,
                  ExcInvalidInput(section + "/Flux exponent",
                                  prm.get("Flux exponent"),
                                  "q must be 0, 1, 2 or 3"));
      q          = static_cast<unsigned int>(exponent);
      on_lattice = prm.get("Micro-diffusivity calibration") == "lattice";
      omega_name = prm.get("Influence function");
      omega      = InfluenceFunctionRegistry::create(omega_name);
    }


    double
    DiffusionKernel::ball_moment(const unsigned int       dim,
                                 const double             horizon,
                                 const int                p,
                                 const InfluenceFunction &omega)
    {
      // int_B omega(r/delta) r^p dV = S_{d-1} int_0^delta omega r^{p+d-1} dr
      //                            = S_{d-1} delta^{p+d} M_{p+d-1}.
      static constexpr double sphere[] = {2, 2 * numbers::PI, 4 * numbers::PI};
      AssertThrow(dim >= 1 && dim <= 3 && p + int(dim) - 1 >= 0,
                  ExcInternalError());
      return sphere[dim - 1] * std::pow(horizon, p + int(dim)) *
             omega.moment(static_cast<unsigned int>(p + int(dim) - 1));
    }


    void
    DiffusionKernel::reinit(const unsigned int dim, const double horizon_)
    {
      AssertThrow(omega != nullptr, ExcMessage("parse_parameters() first"));
      horizon = horizon_;
      kappa   = 2. * dim * K / ball_moment(dim, horizon, 2 - int(q), *omega);
      check_kappa();
    }


    void
    DiffusionKernel::check_kappa() const
    {
      if (std::isfinite(kappa) && kappa > 0)
        return;
      std::ostringstream why;
      why << "with the horizon " << horizon
          << " the micro-diffusivity kappa (the diffusivity over the horizon "
             "to the power d + 2 - q) is "
          << kappa
          << ", out of the range of double precision numbers (about 1e-308 "
             "to 1e308); give the diffusivity of a real medium, about 1e-12 "
             "to 1e-3 m^2/s (or of order 1 in nondimensional units)";
      AssertThrow(false,
                  ExcInvalidInput(section_name + "/Diffusivity",
                                  diffusivity_text,
                                  why.str()));
    }


    template <int dim>
    void
    DiffusionKernel::calibrate_on_lattice(
      const double                             h,
      const std::vector<std::array<int, dim>> &offsets,
      const std::vector<double>               &fractions)
    {
      AssertThrow(kappa > 0 && offsets.size() == fractions.size(),
                  ExcMessage("reinit() first, one fraction per offset"));
      double sum = 0;
      for (unsigned int k = 0; k < offsets.size(); ++k)
        {
          double r2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            r2 += double(offsets[k][d]) * offsets[k][d];
          const double r = std::sqrt(r2) * h;
          // conductance() / kappa times r^2.
          sum +=
            conductance(r) / kappa * r * r * fractions[k] * std::pow(h, dim);
        }
      AssertThrow(sum > 0, ExcMessage("The stencil has no bonds."));
      kappa = 2. * dim * K / sum;
      check_kappa();
    }


    template void
    DiffusionKernel::calibrate_on_lattice<1>(
      const double,
      const std::vector<std::array<int, 1>> &,
      const std::vector<double> &);
    template void
    DiffusionKernel::calibrate_on_lattice<2>(
      const double,
      const std::vector<std::array<int, 2>> &,
      const std::vector<double> &);
    template void
    DiffusionKernel::calibrate_on_lattice<3>(
      const double,
      const std::vector<std::array<int, 3>> &,
      const std::vector<double> &);


    double
    DiffusionKernel::conductance(const double r) const
    {
      // The one-point rule evaluates the kernel at the neighbour's centre,
      // which lies up to half a cell diagonal beyond the horizon for cells
      // that the horizon cuts: no cut-off there (the partial volume holds
      // the geometry), but an influence that turns negative beyond the
      // horizon (conical) is taken as 0 so that no bond conducts backwards.
      return kappa * std::max(omega->value(r / horizon), 0.) /
             std::pow(r, int(q));
    }
  } // namespace Models
} // namespace PeriDEAL
