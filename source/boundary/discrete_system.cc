#include <perideal/boundary/discrete_system.h>

namespace PeriDEAL
{
  namespace Boundary
  {
    template <int dim>
    void
    DiscreteSystem<dim>::check_input(const Solvers::LinearSolver &) const
    {}


    template <int dim>
    std::vector<IO::NodeField>
    DiscreteSystem<dim>::node_fields(
      const SystemContext<dim> &,
      const TrilinosWrappers::MPI::Vector &) const
    {
      return {};
    }


    template <int dim>
    std::vector<typename DiscreteSystem<dim>::ExtraNode>
    DiscreteSystem<dim>::extra_nodes() const
    {
      return {};
    }


    template <int dim>
    std::string
    DiscreteSystem<dim>::extra_nodes_name() const
    {
      return "";
    }


    template class DiscreteSystem<2>;
    template class DiscreteSystem<3>;
  } // namespace Boundary
} // namespace PeriDEAL
