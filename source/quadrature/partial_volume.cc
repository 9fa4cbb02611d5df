#include <deal.II/base/parameter_handler.h>

#include <perideal/quadrature/partial_volume.h>

namespace PeriDEAL
{
  namespace Quadrature
  {
    template <int dim>
    double
    PartialVolume<dim>::uniform_grid_weight(const std::array<int, dim> &offset,
                                            const double m_ratio) const
    {
      return weight(Point<dim>(), m_ratio, unit_cell<dim>(offset));
    }


    template <int dim>
    std::vector<double>
    PartialVolume<dim>::uniform_grid_weights(
      const std::vector<std::array<int, dim>> &offsets,
      const double                             m_ratio) const
    {
      std::vector<double> betas;
      betas.reserve(offsets.size());
      for (const auto &offset : offsets)
        betas.push_back(uniform_grid_weight(offset, m_ratio));
      return betas;
    }


    template <int dim>
    void
    PartialVolume<dim>::parse_parameters(ParameterHandler &)
    {}


    template <int dim>
    std::string
    PartialVolume<dim>::family_name()
    {
      return "partial-volume algorithm (" + std::to_string(dim) + "D)";
    }


    template <int dim>
    BoundingBox<dim>
    unit_cell(const std::array<int, dim> &offset)
    {
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = offset[d] - 0.5;
          upper[d] = offset[d] + 0.5;
        }
      return BoundingBox<dim>(std::make_pair(lower, upper));
    }


    template class PartialVolume<1>;
    template class PartialVolume<2>;
    template class PartialVolume<3>;
    template BoundingBox<1>
    unit_cell<1>(const std::array<int, 1> &);
    template BoundingBox<2>
    unit_cell<2>(const std::array<int, 2> &);
    template BoundingBox<3>
    unit_cell<3>(const std::array<int, 3> &);
  } // namespace Quadrature

  template class PluginRegistry<Quadrature::PartialVolume<1>>;
  template class PluginRegistry<Quadrature::PartialVolume<2>>;
  template class PluginRegistry<Quadrature::PartialVolume<3>>;
} // namespace PeriDEAL
