#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/model.h>

#include <sstream>

namespace PeriDEAL
{
  namespace Models
  {
    template <int dim>
    std::string
    Model<dim>::family_name()
    {
      return "material model";
    }


    double
    ElasticConstants::youngs_modulus() const
    {
      return 9 * bulk * shear / (3 * bulk + shear);
    }


    double
    ElasticConstants::poissons_ratio() const
    {
      return (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear));
    }


    double
    ElasticConstants::planar_bulk_modulus() const
    {
      return plane_stress ? 9 * bulk * shear / (3 * bulk + 4 * shear) :
                            bulk + shear / 3;
    }


    void
    ElasticConstants::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Elastic constants",
                        "Young's modulus and Poisson's ratio",
                        Patterns::Selection(
                          "Young's modulus and Poisson's ratio|"
                          "bulk and shear modulus"),
                        "Which pair of constants defines the material.");
      prm.declare_entry("Young's modulus",
                        "1e9",
                        Patterns::Double(),
                        "Young's modulus E (Pa), > 0.");
      prm.declare_entry("Poisson's ratio",
                        "0.25",
                        Patterns::Double(),
                        "Poisson's ratio nu, -1 < nu < 0.5 (nu <= 0.5 for "
                        "plane stress).");
      prm.declare_entry("Bulk modulus",
                        "6.6666666666666667e8",
                        Patterns::Double(),
                        "Bulk modulus K (Pa), > 0.");
      prm.declare_entry("Shear modulus",
                        "4e8",
                        Patterns::Double(),
                        "Shear modulus mu (Pa), > 0.");
      prm.declare_entry("Plane model",
                        "plane strain",
                        Patterns::Selection("plane strain|plane stress"),
                        "Two-dimensional problems only: plane strain or "
                        "plane stress (per unit thickness).");
    }


    void
    ElasticConstants::parse_parameters(ParameterHandler &prm)
    {
      auto str = [](const double x) {
        std::ostringstream s;
        s << x;
        return s.str();
      };
      plane_stress = prm.get("Plane model") == "plane stress";
      if (prm.get("Elastic constants") == "bulk and shear modulus")
        {
          bulk  = prm.get_double("Bulk modulus");
          shear = prm.get_double("Shear modulus");
          AssertThrow(bulk > 0,
                      ExcInvalidInput("Bulk modulus",
                                      str(bulk),
                                      "give a bulk modulus > 0"));
          AssertThrow(shear > 0,
                      ExcInvalidInput("Shear modulus",
                                      str(shear),
                                      "give a shear modulus > 0"));
        }
      else
        {
          const double E  = prm.get_double("Young's modulus");
          const double nu = prm.get_double("Poisson's ratio");
          AssertThrow(E > 0,
                      ExcInvalidInput("Young's modulus",
                                      str(E),
                                      "give a Young's modulus > 0"));
          AssertThrow(nu > -1 && nu < 0.5,
                      ExcInvalidInput("Poisson's ratio",
                                      str(nu),
                                      "an isotropic solid needs "
                                      "-1 < nu < 0.5"));
          bulk  = E / (3 * (1 - 2 * nu));
          shear = E / (2 * (1 + nu));
        }
    }


    template <int dim>
    void
    IsotropicModel<dim>::declare_parameters(
      ParameterHandler  &prm,
      const std::string &default_influence)
    {
      ElasticConstants::declare_parameters(prm);
      prm.declare_entry("Influence function",
                        default_influence,
                        Patterns::Selection(
                          InfluenceFunctionRegistry::pattern_string()),
                        "The influence function omega(|xi|/delta).");
    }


    template <int dim>
    void
    IsotropicModel<dim>::parse_parameters(ParameterHandler &prm)
    {
      constants.parse_parameters(prm);
      omega = InfluenceFunctionRegistry::create(prm.get("Influence function"));
    }


    template <int dim>
    double
    IsotropicModel<dim>::influence(const double r, const double horizon) const
    {
      return omega->value(r / horizon);
    }


    template <int dim>
    double
    IsotropicModel<dim>::bulk_modulus() const
    {
      return constants.bulk;
    }


    template <int dim>
    double
    IsotropicModel<dim>::shear_modulus() const
    {
      return constants.shear;
    }


    template <int dim>
    bool
    IsotropicModel<dim>::plane_stress() const
    {
      return dim == 2 && constants.plane_stress;
    }


    template class Model<2>;
    template class Model<3>;
    template class IsotropicModel<2>;
    template class IsotropicModel<3>;
  } // namespace Models

  template class PluginRegistry<Models::Model<2>>;
  template class PluginRegistry<Models::Model<3>>;
} // namespace PeriDEAL
