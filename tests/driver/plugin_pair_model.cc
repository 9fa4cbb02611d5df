// A material model in a shared library of its own, as a user writes one
// (doc/plugins.md), for shared_libraries.sh: a bond-based pair potential
// with a constant influence function and the micromodulus given directly,
// in its own parameter subsection.

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/model.h>

namespace
{
  template <int dim>
  class PairModel : public PeriDEAL::Models::Model<dim>
  {
  public:
    static void
    declare_parameters(dealii::ParameterHandler &prm)
    {
      prm.declare_entry("Micromodulus",
                        "1e12",
                        dealii::Patterns::Double(),
                        "c of the pair force c e/|xi| (Pa/m^(dim+1)), > 0.");
    }

    void
    parse_parameters(dealii::ParameterHandler &prm) override
    {
      c = prm.get_double("Micromodulus");
      AssertThrow(c > 0,
                  PeriDEAL::ExcInvalidInput("Material model/test pair model/"
                                            "Micromodulus",
                                            prm.get("Micromodulus"),
                                            "give a micromodulus > 0"));
    }

    bool
    is_state_based() const override
    {
      return false;
    }

    double
    influence(const double, const double) const override
    {
      return 1;
    }

    double
    dilatation_constant(const double, const double) const override
    {
      return 0;
    }

    double
    extension_constant(const double r, const double) const override
    {
      return 0.5 * c / r;
    }

    double
    node_factor(const double) const override
    {
      return 1;
    }

    double
    bulk_modulus() const override
    {
      return 1;
    }

    double
    shear_modulus() const override
    {
      return 1;
    }

    double
    dilatation_energy_modulus() const override
    {
      return 0;
    }

  private:
    double c = 0;
  };
} // namespace

PERIDEAL_REGISTER_MODEL(PairModel,
                        "test pair model",
                        "A bond-based pair model with a given micromodulus "
                        "(tests/driver/plugin_pair_model.cc).")
