#include <perideal/base/exceptions.h>
#include <perideal/models/model.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    ProblemType<dim>::check_input(const Simulator<dim> &) const
    {}


    template <int dim>
    std::vector<IO::OutputName>
    ProblemType<dim>::output_names(const Simulator<dim> &simulator) const
    {
      return simulator.get_output().output_names(false);
    }


    template <int dim>
    std::vector<UnusedEntry>
    ProblemType<dim>::unused_entries(const Simulator<dim> &) const
    {
      return {};
    }


    template <int dim>
    std::vector<PluginSelection>
    ProblemType<dim>::plugin_selections() const
    {
      return {};
    }


    template <int dim>
    std::string
    ProblemType<dim>::family_name()
    {
      return "problem type";
    }


    template <int dim>
    double
    ProblemType<dim>::estimated_bytes_per_node(const double) const
    {
      return -1;
    }


    template <int dim>
    bool
    ProblemType<dim>::uses_linear_solver() const
    {
      return true;
    }


    template <int dim>
    void
    ProblemType<dim>::check_collocation_model(const Simulator<dim> &simulator)
    {
      if (simulator.get_quadrature_scheme().collocation() == nullptr)
        return;
      AssertThrow(!simulator.get_model().is_state_based(),
                  ExcInvalidInput("Quadrature/Scheme",
                                  simulator.get_quadrature_scheme_name(),
                                  "the collocation rows of state-based "
                                  "models (LPS, doc/collocation.md Sect. 5) "
                                  "run in quasi-static problems only so far "
                                  "(linear, without failure); use a "
                                  "bond-based model or 'Scheme = "
                                  "standard'"));
    }


    template <int dim>
    bool
    ProblemType<dim>::supports_hybrid() const
    {
      return false;
    }


    template <int dim>
    bool
    ProblemType<dim>::supports_collocation() const
    {
      return false;
    }


    template <int dim>
    bool
    ProblemType<dim>::uses_material_model() const
    {
      return true;
    }


    template <int dim>
    bool
    ProblemType<dim>::couples_two_horizons(
      const Models::Model<dim> *model) const
    {
      return model != nullptr && model->is_state_based();
    }


    template class ProblemType<1>;
    template class ProblemType<2>;
    template class ProblemType<3>;
  } // namespace Problems

  template class PluginRegistry<Problems::ProblemType<1>>;
  template class PluginRegistry<Problems::ProblemType<2>>;
  template class PluginRegistry<Problems::ProblemType<3>>;
} // namespace PeriDEAL
