// A plugin library whose influence function takes a built-in name: loading
// it must stop perideal with a message naming the library and the name
// (shared_libraries.sh), not terminate it inside dlopen().

#include <deal.II/base/parameter_handler.h>

#include <perideal/models/influence_function.h>

namespace
{
  class AnotherGaussian : public PeriDEAL::Models::InfluenceFunction
  {
  public:
    double
    value(const double) const override
    {
      return 1;
    }

    static void
    declare_parameters(dealii::ParameterHandler &)
    {}
  };
} // namespace

PERIDEAL_REGISTER_INFLUENCE_FUNCTION(AnotherGaussian,
                                     "gaussian",
                                     "a second 'gaussian'")
