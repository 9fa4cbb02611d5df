#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/model.h>

#include <limits>
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
    ElasticConstants::parse_parameters(ParameterHandler  &prm,
                                       const std::string &path)
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
                      ExcInvalidInput(path + "Bulk modulus",
                                      str(bulk),
                                      "give a bulk modulus > 0"));
          AssertThrow(shear > 0,
                      ExcInvalidInput(path + "Shear modulus",
                                      str(shear),
                                      "give a shear modulus > 0"));
          stiffness_entry =
            bulk >= shear ?
              std::make_pair("Bulk modulus", prm.get("Bulk modulus")) :
              std::make_pair("Shear modulus", prm.get("Shear modulus"));
        }
      else
        {
          const double E  = prm.get_double("Young's modulus");
          const double nu = prm.get_double("Poisson's ratio");
          AssertThrow(E > 0,
                      ExcInvalidInput(path + "Young's modulus",
                                      str(E),
                                      "give a Young's modulus > 0"));
          AssertThrow(nu > -1 && nu < 0.5,
                      ExcInvalidInput(path + "Poisson's ratio",
                                      str(nu),
                                      "an isotropic solid needs "
                                      "-1 < nu < 0.5"));
          bulk            = E / (3 * (1 - 2 * nu));
          shear           = E / (2 * (1 + nu));
          stiffness_entry = {"Young's modulus", prm.get("Young's modulus")};
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
      prm.declare_entry("Density",
                        "1",
                        Patterns::Double(0),
                        "Mass density rho (kg/m^3, > 0); used by the "
                        "explicit dynamics problem type.");
      prm.declare_entry("Critical stretch",
                        "0",
                        Patterns::Double(0),
                        "Bond failure: a bond whose stretch |y_j - y_i| / "
                        "|x_j - x_i| - 1 exceeds this value breaks for good "
                        "(explicit dynamics). 0: no failure, unless "
                        "'Fracture energy' is given (give at most one).");
      prm.declare_entry("Fracture energy",
                        "0",
                        Patterns::Double(0),
                        "Bond failure from the critical energy release rate "
                        "G0 (J/m^2): the critical stretch that dissipates G0 "
                        "per unit crack area (bond-based PMB: Silling & "
                        "Askari 2005; LPS: the drop of the model's energy, "
                        "dilatation included, when the bonds across a plane "
                        "break; both derived for every influence function "
                        "in doc/explicit-dynamics.md). 0: not used.");
    }


    template <int dim>
    void
    IsotropicModel<dim>::parse_parameters(ParameterHandler &prm)
    {
      constants.parse_parameters(prm, this->input_path());
      given_as_moduli =
        prm.get("Elastic constants") == "bulk and shear modulus";
      omega = InfluenceFunctionRegistry::create(prm.get("Influence function"));
      mass_density           = prm.get_double("Density");
      given_critical_stretch = prm.get_double("Critical stretch");
      fracture_energy        = prm.get_double("Fracture energy");
      AssertThrow(mass_density > 0,
                  ExcInvalidInput(this->input_path() + "Density",
                                  prm.get("Density"),
                                  "give a mass density > 0"));
      AssertThrow(given_critical_stretch == 0 || fracture_energy == 0,
                  ExcInvalidInput(this->input_path() + "Fracture energy",
                                  prm.get("Fracture energy"),
                                  "give either 'Critical stretch' or "
                                  "'Fracture energy', not both (the other "
                                  "one = 0)"));
    }


    template <int dim>
    void
    Model<dim>::set_input_path(const std::string &input_path)
    {
      path = input_path;
    }


    template <int dim>
    const std::string &
    Model<dim>::input_path() const
    {
      return path;
    }


    template <int dim>
    std::vector<UnusedEntry>
    Model<dim>::unused_entries() const
    {
      return {};
    }


    template <int dim>
    std::vector<UnusedEntry>
    IsotropicModel<dim>::unused_entries() const
    {
      const std::string why =
        "'Elastic constants' selects " +
        std::string(given_as_moduli ? "the bulk and shear modulus" :
                                      "Young's modulus and Poisson's ratio") +
        "; give the material by those, or select the other pair";
      if (given_as_moduli)
        return {{"Young's modulus", why}, {"Poisson's ratio", why}};
      return {{"Bulk modulus", why}, {"Shear modulus", why}};
    }


    template <int dim>
    double
    Model<dim>::critical_stretch(const double) const
    {
      return std::numeric_limits<double>::infinity();
    }


    template <int dim>
    double
    Model<dim>::density() const
    {
      return 1;
    }


    template <int dim>
    std::pair<std::string, std::string>
    Model<dim>::stiffness_entry() const
    {
      return {};
    }


    template <int dim>
    double
    IsotropicModel<dim>::critical_stretch(const double horizon) const
    {
      if (given_critical_stretch > 0)
        return given_critical_stretch;
      if (fracture_energy > 0)
        return critical_stretch_from_fracture_energy(fracture_energy, horizon);
      return std::numeric_limits<double>::infinity();
    }


    template <int dim>
    double
    IsotropicModel<dim>::critical_stretch_from_fracture_energy(
      const double G0,
      const double) const
    {
      std::ostringstream value;
      value << G0;
      AssertThrow(false,
                  ExcInvalidInput(this->input_path() + "Fracture energy",
                                  value.str(),
                                  "this model has no relation between "
                                  "fracture energy and critical stretch; "
                                  "give 'Critical stretch' instead"));
      return 0;
    }


    template <int dim>
    double
    IsotropicModel<dim>::density() const
    {
      return mass_density;
    }


    template <int dim>
    std::pair<std::string, std::string>
    IsotropicModel<dim>::stiffness_entry() const
    {
      return constants.stiffness_entry;
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


    template class Model<1>;
    template class Model<2>;
    template class Model<3>;
    template class IsotropicModel<2>;
    template class IsotropicModel<3>;
  } // namespace Models

  template class PluginRegistry<Models::Model<1>>;
  template class PluginRegistry<Models::Model<2>>;
  template class PluginRegistry<Models::Model<3>>;
} // namespace PeriDEAL
