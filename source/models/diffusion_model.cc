#include <perideal/models/diffusion_model.h>

namespace PeriDEAL
{
  namespace Models
  {
    template <int dim>
    void
    DiffusionModel<dim>::parse_parameters(ParameterHandler &)
    {}


    template <int dim>
    std::vector<UnusedEntry>
    DiffusionModel<dim>::unused_entries() const
    {
      return {};
    }


    template <int dim>
    bool
    DiffusionModel<dim>::supports_implicit() const
    {
      return true;
    }


    template <int dim>
    bool
    DiffusionModel<dim>::supports_collocation() const
    {
      return false;
    }


    template <int dim>
    bool
    DiffusionModel<dim>::changes_phases() const
    {
      return false;
    }


    template <int dim>
    void
    DiffusionModel<dim>::initialize(const DiffusionSetup<dim> &, VectorType &)
    {}


    template <int dim>
    double
    DiffusionModel<dim>::largest_time_step(const DiffusionSetup<dim> &) const
    {
      return std::numeric_limits<double>::infinity();
    }


    template <int dim>
    typename DiffusionModel<dim>::TimeStepLimit
    DiffusionModel<dim>::time_step_limit() const
    {
      return {};
    }


    template <int dim>
    void
    DiffusionModel<dim>::after_step(const DiffusionSetup<dim> &,
                                    const double,
                                    VectorType &,
                                    const bool)
    {}


    template <int dim>
    std::vector<std::string>
    DiffusionModel<dim>::history_columns() const
    {
      return {};
    }


    template <int dim>
    std::vector<double>
    DiffusionModel<dim>::history_values(const DiffusionSetup<dim> &,
                                        const VectorType &) const
    {
      return {};
    }


    template <int dim>
    std::vector<NodeField>
    DiffusionModel<dim>::node_fields(const DiffusionSetup<dim> &,
                                     const VectorType &) const
    {
      return {};
    }


    template <int dim>
    std::string
    DiffusionModel<dim>::progress_text(const std::vector<double> &) const
    {
      return "";
    }


    template <int dim>
    std::string
    DiffusionModel<dim>::family_name()
    {
      return "diffusion model";
    }


    namespace
    {
      /// Plain diffusion: the kernel alone.
      template <int dim>
      class PlainDiffusion : public DiffusionModel<dim>
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        /// The kernel alone: no phases.
        bool
        supports_collocation() const override
        {
          return true;
        }
      };
    } // namespace


    template class DiffusionModel<1>;
    template class DiffusionModel<2>;
    template class DiffusionModel<3>;
  } // namespace Models

  template class PluginRegistry<Models::DiffusionModel<1>>;
  template class PluginRegistry<Models::DiffusionModel<2>>;
  template class PluginRegistry<Models::DiffusionModel<3>>;
} // namespace PeriDEAL

PERIDEAL_REGISTER_DIFFUSION_MODEL(PeriDEAL::Models::PlainDiffusion,
                                  "none",
                                  "Plain diffusion with the kernel of "
                                  "'diffusion' (no phases).")
