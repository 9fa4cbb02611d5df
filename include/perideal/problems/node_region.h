#ifndef perideal_problems_node_region_h
#define perideal_problems_node_region_h

/**
 * @file
 * Regions of nodes given in the input as boxes and as layers along
 * boundary ids: the no-fail region of explicit dynamics and the fixed
 * standard region of the hybrid quadrature scheme (every problem type that
 * supports it).
 */

#include <deal.II/base/bounding_box.h>

#include <perideal/problems/simulator.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * A region of nodes given in the input as boxes and as layers along
     * boundary ids, with the entries that give it, for messages.
     */
    template <int dim>
    struct NodeRegion
    {
      const std::vector<BoundingBox<dim>> &boxes;
      std::string boxes_entry, boxes_text, boxes_purpose;
      const std::vector<types::boundary_id> &ids;
      std::string                            ids_entry, ids_text;
      /// The layer thickness in horizons.
      double      thickness;
      std::string thickness_entry, thickness_text, layer_purpose;
    };

    /**
     * Which nodes (owned and ghost) of the simulator lie in @p region.
     * Every box and every layer must hold a node centre, and every id
     * must occur in the mesh; otherwise all processes throw an error
     * naming the entry. Collective.
     */
    template <int dim>
    std::vector<bool>
    nodes_in_region(const Simulator<dim>  &simulator,
                    const NodeRegion<dim> &region);

    /**
     * The fixed standard region of the hybrid quadrature scheme
     * ('Quadrature/hybrid': 'Standard boxes', 'Standard boundary ids',
     * 'Standard layer thickness'), owned and ghost nodes; empty when the
     * scheme is not hybrid. The nodes whose ball is cut are standard too,
     * but the operator finds those itself (BondOperator::use_collocation()).
     * Collective.
     */
    template <int dim>
    std::vector<bool>
    hybrid_standard_region(const Simulator<dim> &simulator);
  } // namespace Problems
} // namespace PeriDEAL

#endif
