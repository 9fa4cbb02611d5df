/**
 * @file
 * Regions of nodes given as boxes and boundary layers (node_region.h).
 */

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/discretization/crack_geometry.h>
#include <perideal/problems/node_region.h>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    std::vector<bool>
    nodes_in_region(const Simulator<dim>  &simulator,
                    const NodeRegion<dim> &region)
    {
      const auto       &nodes = simulator.get_nodes();
      std::vector<bool> in =
        Discretization::nodes_in_boxes(nodes,
                                       region.boxes,
                                       region.boxes_entry,
                                       region.boxes_text,
                                       region.boxes_purpose);
      if (region.ids.empty())
        return in;
      const auto &triangulation =
        simulator.get_dof_handler().get_triangulation();
      Boundary::check_boundary_ids(triangulation,
                                   region.ids,
                                   region.ids_entry,
                                   region.ids_text);
      // The counts are sums over the processes: every process throws
      // alike.
      std::vector<unsigned int> n_in_layer;
      const auto                layer =
        Boundary::BoundaryLayers<dim>(triangulation, region.ids)
          .layer_of_nodes(nodes,
                          region.thickness * simulator.get_horizon(),
                          &n_in_layer);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (layer[i] != numbers::invalid_unsigned_int)
          in[i] = true;
      for (unsigned int k = 0; k < region.ids.size(); ++k)
        AssertThrow(n_in_layer[k] > 0,
                    ExcInvalidInput(region.thickness_entry,
                                    region.thickness_text,
                                    "the " + region.layer_purpose +
                                      " of boundary id " +
                                      std::to_string(region.ids[k]) +
                                      " holds no node centre; use a "
                                      "layer of at least half a cell"));
      return in;
    }


    template <int dim>
    std::vector<bool>
    hybrid_standard_region(const Simulator<dim> &simulator)
    {
      const auto *hybrid = simulator.get_quadrature_scheme().hybrid();
      if (hybrid == nullptr)
        return {};
      const std::string path = "Quadrature/hybrid/";
      return nodes_in_region(simulator,
                             NodeRegion<dim>{hybrid->boxes,
                                             path + "Standard boxes",
                                             hybrid->boxes_text,
                                             "makes no node standard",
                                             hybrid->boundary_ids,
                                             path + "Standard boundary ids",
                                             hybrid->boundary_ids_text,
                                             hybrid->layer_thickness,
                                             path + "Standard layer thickness",
                                             hybrid->layer_thickness_text,
                                             "standard layer"});
    }


    template std::vector<bool>
    nodes_in_region(const Simulator<2> &, const NodeRegion<2> &);
    template std::vector<bool>
    nodes_in_region(const Simulator<3> &, const NodeRegion<3> &);
    template std::vector<bool>
    hybrid_standard_region(const Simulator<2> &);
    template std::vector<bool>
    hybrid_standard_region(const Simulator<3> &);
  } // namespace Problems
} // namespace PeriDEAL
