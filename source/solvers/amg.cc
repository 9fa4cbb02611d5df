#include <perideal/solvers/amg.h>

namespace PeriDEAL
{
  namespace Solvers
  {
    void
    AmgSettings::declare_parameters(ParameterHandler  &prm,
                                    const std::string &default_threshold)
    {
      prm.declare_entry("AMG smoother sweeps",
                        "2",
                        Patterns::Integer(1),
                        "Chebyshev smoother sweeps per level of the algebraic "
                        "multigrid (Trilinos ML).");
      prm.declare_entry(
        "AMG aggregation threshold",
        default_threshold,
        Patterns::Double(0),
        "Entries below this fraction of the diagonal are ignored when the "
        "algebraic multigrid builds its aggregates. PD matrices are dense "
        "within two horizons; values of 1e-4 to 1e-2 work.");
    }


    void
    AmgSettings::parse_parameters(ParameterHandler &prm)
    {
      smoother_sweeps       = prm.get_integer("AMG smoother sweeps");
      aggregation_threshold = prm.get_double("AMG aggregation threshold");
    }


    void
    initialize_amg(TrilinosWrappers::PreconditionAMG    &amg,
                   const TrilinosWrappers::SparseMatrix &matrix,
                   const AmgSettings                    &settings,
                   const std::vector<std::vector<bool>> &constant_modes)
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.constant_modes        = constant_modes;
      data.smoother_sweeps       = settings.smoother_sweeps;
      data.aggregation_threshold = settings.aggregation_threshold;
      amg.initialize(matrix, data);
    }
  } // namespace Solvers
} // namespace PeriDEAL
