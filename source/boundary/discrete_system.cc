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


    template <int dim>
    bool
    DiscreteSystem<dim>::supports_bond_breaking() const
    {
      return false;
    }


    // The problem type asks supports_bond_breaking() before it calls any
    // of the following.
    template <int dim>
    std::size_t
    DiscreteSystem<dim>::setup_failure(const SystemContext<dim> &,
                                       const std::vector<double> &,
                                       const CutBonds &)
    {
      AssertThrow(false, ExcInternalError());
      return 0;
    }


    template <int dim>
    bool
    DiscreteSystem<dim>::supports_dynamic_relaxation() const
    {
      return false;
    }


    template <int dim>
    void
    DiscreteSystem<dim>::set_dynamic_relaxation(
      const Solvers::DynamicRelaxation *)
    {
      AssertThrow(false, ExcInternalError());
    }


    template <int dim>
    bool
    DiscreteSystem<dim>::supports_finite_deformation() const
    {
      return false;
    }


    template <int dim>
    void
    DiscreteSystem<dim>::set_finite_deformation(const NewtonControl &)
    {
      AssertThrow(false, ExcInternalError());
    }


    template <int dim>
    void
    DiscreteSystem<dim>::solve_step(const SystemContext<dim> &,
                                    TrilinosWrappers::MPI::Vector &)
    {
      AssertThrow(false, ExcInternalError());
    }


    template <int dim>
    std::size_t
    DiscreteSystem<dim>::count_critical_bonds(const double)
    {
      AssertThrow(false, ExcInternalError());
      return 0;
    }


    template <int dim>
    std::size_t
    DiscreteSystem<dim>::break_critical_bonds(const double)
    {
      AssertThrow(false, ExcInternalError());
      return 0;
    }


    template <int dim>
    std::vector<double>
    DiscreteSystem<dim>::damage(const SystemContext<dim> &) const
    {
      AssertThrow(false, ExcInternalError());
      return {};
    }


    template <int dim>
    unsigned int
    DiscreteSystem<dim>::n_isolated_nodes() const
    {
      return 0;
    }


    template <int dim>
    unsigned int
    DiscreteSystem<dim>::n_held_dofs_without_stiffness() const
    {
      return 0;
    }


    template <int dim>
    Tensor<1, dim>
    DiscreteSystem<dim>::holding_force(const SystemContext<dim> &,
                                       const std::vector<bool> &) const
    {
      AssertThrow(false, ExcInternalError());
      return {};
    }


    template class DiscreteSystem<2>;
    template class DiscreteSystem<3>;
  } // namespace Boundary
} // namespace PeriDEAL
