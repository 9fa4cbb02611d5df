#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/discretization/lattice.h>
#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/fictitious_layer/layer_data.h>
#include <perideal/operators/fictitious_layer_operator.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      /// The smallest and largest cell side over all processes.
      template <int dim>
      std::pair<double, double>
      cell_side_range(const Discretization::NodeSet<dim> &nodes)
      {
        double h_min = std::numeric_limits<double>::max(), h_max = 0;
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            const auto &box = nodes[i].cell;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double side = box.get_boundary_points().second[d] -
                                    box.get_boundary_points().first[d];
                h_min = std::min(h_min, side);
                h_max = std::max(h_max, side);
              }
          }
        const MPI_Comm comm = nodes.get_communicator();
        return {Utilities::MPI::min(h_min, comm),
                Utilities::MPI::max(h_max, comm)};
      }


      /**
       * The bond constants of @p data for its stencil: the bulk weighted
       * volume m0 and, per offset, the stiffnesses from the kernel (every
       * node has m0, so the same node factor) and the dilatation weight.
       */
      template <int dim>
      void
      set_bond_constants(FictitiousLayer::LayerData<dim> &data,
                         const Models::Model<dim>        &model,
                         const double                     horizon)
      {
        const double h      = data.lattice.spacing();
        const double volume = std::pow(h, dim);
        const auto   length = [h](const auto &offset) {
          double r2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            r2 += offset[d] * offset[d];
          return std::sqrt(r2) * h;
        };
        data.m0 = 0;
        for (const auto &n : data.neighbours)
          {
            const double r = length(n.offset);
            data.m0 += model.influence(r, horizon) * r * r * n.beta * volume;
          }
        const double s_0 = model.node_factor(data.m0);
        for (const auto &n : data.neighbours)
          {
            const double r = length(n.offset);
            data.a_r.push_back(data.state_based ?
                                 BondKernel::dilatation_stiffness(
                                   model.dilatation_constant(r, horizon),
                                   s_0) :
                                 0.);
            data.b2_r.push_back(BondKernel::extension_stiffness(
              model.extension_constant(r, horizon),
              s_0,
              s_0));
            data.g_r.push_back(data.state_based ?
                                 dim / data.m0 * model.influence(r, horizon) *
                                   r * n.beta * volume :
                                 0.);
          }
      }
    } // namespace


    template <int dim>
    FictitiousLayerOperator<dim>::FictitiousLayerOperator()
      : data(std::make_unique<FictitiousLayer::LayerData<dim>>())
    {}


    template <int dim>
    FictitiousLayerOperator<dim>::~FictitiousLayerOperator() = default;


    template <int dim>
    void
    FictitiousLayerOperator<dim>::reinit(
      const DoFHandler<dim>                &dof_handler,
      const Discretization::NodeSet<dim>   &nodes,
      const Models::Model<dim>             &model,
      const double                          horizon,
      const Quadrature::PartialVolume<dim> &algorithm,
      const bool                            with_surface_nodes,
      const unsigned int                    taylor_order)
    {
      data          = std::make_unique<FictitiousLayer::LayerData<dim>>();
      auto &s       = *data;
      s.comm        = nodes.get_communicator();
      s.nodes       = &nodes;
      s.order       = taylor_order;
      s.state_based = model.is_state_based();
      const MPI_Comm     comm    = s.comm;
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);

      // Uniformity is decided in one place (Discretization::Lattice,
      // collectively, with its tolerances); the sides are only for the
      // message.
      Discretization::Lattice<dim> uniform_lattice;
      uniform_lattice.reinit(nodes);
      if (!uniform_lattice.is_uniform())
        {
          const auto [h_min, h_max] = cell_side_range(nodes);
          AssertThrow(false,
                      ExcMessage(
                        "The fictitious layer and the surface nodes need a "
                        "uniform grid of equal cubes (squares in 2D) on one "
                        "lattice, but the cell sides range from " +
                        Utilities::to_string(h_min) + " to " +
                        Utilities::to_string(h_max) +
                        " (or a cell corner is off the lattice). Fix: choose "
                        "Subdivisions that give equal sides, no local "
                        "refinement, or a mesh file of equal, aligned cubes; "
                        "or set 'Boundary treatment/Treatment = none'."));
        }
      const double h = uniform_lattice.spacing();

      // The layer reaches delta + h sqrt(d)/2 from the body: every cell
      // that meets some body node's horizon.
      const double                              m_ratio = horizon / h;
      const Quadrature::UniformGridWeights<dim> table(algorithm, m_ratio);
      s.m_ratio    = m_ratio;
      s.neighbours = table.neighbours();
      s.lattice.reinit(nodes,
                       h,
                       m_ratio + 0.5 * std::sqrt(double(dim)),
                       table.max_offset() + 6);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        for (unsigned int c = 1; c < dim; ++c)
          AssertThrow(nodes[i].dofs[c] == nodes[i].dofs[0] + c,
                      ExcInternalError());
      set_bond_constants(s, model, horizon);

      if (with_surface_nodes)
        {
          s.surface = std::make_unique<Discretization::SurfaceNodes<dim>>();
          s.surface->reinit(dof_handler, s.lattice);
        }

      // Unknown numbering: owned body DoFs, then owned surface unknowns.
      const IndexSet &owned_dofs = dof_handler.locally_owned_dofs();
      AssertThrow(owned_dofs.is_contiguous(), ExcInternalError());
      const types::global_dof_index first_dof =
        owned_dofs.n_elements() > 0 ? *owned_dofs.begin() : 0;
      const types::global_dof_index n_local_sys =
        owned_dofs.n_elements() +
        (s.surface ? dim * s.surface->owned().size() : 0);
      s.dof_start            = Utilities::MPI::all_gather(comm, first_dof);
      const auto n_local_all = Utilities::MPI::all_gather(comm, n_local_sys);
      s.sys_start.assign(n_ranks + 1, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        s.sys_start[r + 1] = s.sys_start[r] + n_local_all[r];
      s.n_sys     = s.sys_start[n_ranks];
      s.owned_sys = IndexSet(s.n_sys);
      s.owned_sys.add_range(s.sys_start[rank], s.sys_start[rank + 1]);
      s.owned_sys.compress();

      // The buckets of the surface-node lookup hold a whole extrapolation
      // stencil and the nearest surface node of every fictitious node.
      if (s.surface)
        s.surface->set_unknowns(
          s.sys_start[rank] + owned_dofs.n_elements(),
          2 * static_cast<int>(std::ceil(
                std::max<double>(m_ratio + 1.5 * std::sqrt(double(dim)) + 1,
                                 taylor_order + 3))),
          comm);
    }


    template <int dim>
    const IndexSet &
    FictitiousLayerOperator<dim>::owned_unknowns() const
    {
      return data->owned_sys;
    }


    template <int dim>
    types::global_dof_index
    FictitiousLayerOperator<dim>::unknown_index(
      const Discretization::Node<dim> &node,
      const unsigned int               c) const
    {
      return data->sys_of_dof(node.dofs[c], node.owner);
    }


    template <int dim>
    const std::vector<typename FictitiousLayerOperator<dim>::SurfaceNode> &
    FictitiousLayerOperator<dim>::owned_surface_nodes() const
    {
      static const std::vector<SurfaceNode> none;
      return data->surface ? data->surface->owned() : none;
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_surface_nodes() const
    {
      return data->surface ? data->surface->n_global() : 0;
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_fictitious_nodes() const
    {
      return data->lattice.n_fictitious();
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_neighbours_per_node() const
    {
      return data->neighbours.size();
    }


    template <int dim>
    double
    FictitiousLayerOperator<dim>::bulk_weighted_volume() const
    {
      return data->m0;
    }


    template class FictitiousLayerOperator<2>;
    template class FictitiousLayerOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
