#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <perideal/models/influence_function.h>

#include <cmath>

namespace PeriDEAL
{
  namespace Models
  {
    double
    InfluenceFunction::moment(const unsigned int k) const
    {
      // 30 Gauss points: exact for the polynomial influence functions and
      // to round-off for the Gaussian (an entire function) up to k ~ 20.
      const QGauss<1> quadrature(30);
      double          sum = 0;
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const double s = quadrature.point(q)[0];
          sum += quadrature.weight(q) * value(s) * std::pow(s, k);
        }
      return sum;
    }


    void
    InfluenceFunction::parse_parameters(ParameterHandler &)
    {}


    std::string
    InfluenceFunction::family_name()
    {
      return "influence function";
    }


    namespace
    {
      class Gaussian : public InfluenceFunction
      {
      public:
        double
        value(const double s) const override
        {
          return std::exp(-s * s);
        }

        static void
        declare_parameters(ParameterHandler &)
        {}
      };

      class Constant : public InfluenceFunction
      {
      public:
        double
        value(const double) const override
        {
          return 1;
        }

        static void
        declare_parameters(ParameterHandler &)
        {}
      };

      class Conical : public InfluenceFunction
      {
      public:
        double
        value(const double s) const override
        {
          return 1 - s;
        }

        static void
        declare_parameters(ParameterHandler &)
        {}
      };

      /**
       * delta/|xi|: the influence function of LAMMPS's pair style peri/lps
       * (1/r there; a state-based model is invariant under a constant
       * factor in omega). Singular at s = 0, which no bond reaches; its
       * moments are exact, and the order-0 moment diverges.
       */
      class InverseDistance : public InfluenceFunction
      {
      public:
        double
        value(const double s) const override
        {
          return 1 / s;
        }

        double
        moment(const unsigned int k) const override
        {
          AssertThrow(k > 0,
                      ExcMessage(
                        "The influence function 'inverse distance' (delta/r) "
                        "has no finite moment of order 0, which this model "
                        "needs to calibrate its constants (a diffusion kernel "
                        "with q = dim, or the corrosion calibration with "
                        "q = dim). Choose another 'Influence function' or "
                        "another q."));
          return 1. / k;
        }

        static void
        declare_parameters(ParameterHandler &)
        {}
      };
    } // namespace
  }   // namespace Models

  template class PluginRegistry<Models::InfluenceFunction>;
} // namespace PeriDEAL

PERIDEAL_REGISTER_CLASS(PeriDEAL::Models::InfluenceFunction,
                        PeriDEAL::Models::Gaussian,
                        "gaussian",
                        "exp(-|xi|^2 / delta^2) (Scabbia et al. 2022, Eq. 10)")
PERIDEAL_REGISTER_CLASS(PeriDEAL::Models::InfluenceFunction,
                        PeriDEAL::Models::Constant,
                        "constant",
                        "1 within the horizon")
PERIDEAL_REGISTER_CLASS(PeriDEAL::Models::InfluenceFunction,
                        PeriDEAL::Models::Conical,
                        "conical",
                        "1 - |xi| / delta within the horizon")
PERIDEAL_REGISTER_CLASS(
  PeriDEAL::Models::InfluenceFunction,
  PeriDEAL::Models::InverseDistance,
  "inverse distance",
  "delta / |xi| within the horizon (LAMMPS's peri/lps uses 1/|xi|)")
