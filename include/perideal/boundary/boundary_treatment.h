#ifndef perideal_boundary_boundary_treatment_h
#define perideal_boundary_boundary_treatment_h

#include <deal.II/base/parameter_handler.h>

#include <perideal/base/plugin_registry.h>

#include <memory>
#include <string>

namespace PeriDEAL
{
  namespace Boundary
  {
    using namespace dealii;

    template <int dim>
    class DiscreteSystem;

    /**
     * How the surface of a peridynamic body is treated (Scabbia, Zaccariotto
     * and Galvanetto 2023, "A new surface node method ...").
     *
     * - "none": the body's own nodes only. Near the surface the
     *   neighbourhoods are incomplete (surface effect) and boundary
     *   conditions act on the nodes nearest the surface, half a cell inside
     *   the body (Dirichlet layers, tractions on the boundary cells' nodes).
     * - "fictitious layer": a layer of fictitious nodes, the lattice
     *   continued a horizon (plus half a cell diagonal) beyond the surface,
     *   completes every neighbourhood. Their displacements are Taylor
     *   extrapolations of order N from the nearest body node, their
     *   dilatations extrapolations of order N-1, their weighted volume the
     *   bulk value (paper Sect. 2.4). Boundary conditions act as for "none".
     * - "surface nodes": the fictitious layer plus one node per external cell
     *   face with its own displacement unknowns. Fictitious displacements are
     *   extrapolated from the nearest surface node (with surface and body
     *   nodes in the stencil), and each surface node carries the force-flux
     *   equation of its face (paper Sect. 3, Eqs. 34-36): Dirichlet values
     *   are imposed on surface nodes, tractions are the right-hand side of
     *   their equations.
     *
     * The classes are chosen by name in the input file through
     * BoundaryTreatmentRegistry. Each builds the DiscreteSystem that the
     * problem type drives (make_system()): the problem type never branches
     * on the treatment.
     */
    class BoundaryTreatment
    {
    public:
      virtual ~BoundaryTreatment() = default;

      /// Read the parameters of the class's own subsection.
      virtual void
      parse_parameters(ParameterHandler &prm) = 0;

      /**
       * Truncation order N of the Taylor extrapolation of displacements
       * (dilatations use N-1); zero without a fictitious layer. For the
       * run summary.
       */
      virtual unsigned int
      taylor_order() const = 0;

      /**
       * Whether the body's own nodes are the only nodes of the system (no
       * fictitious or surface nodes, no unknowns added): the time-stepping
       * problem types step the body's nodes, so they accept only a
       * treatment that says so. Default: false.
       */
      virtual bool
      body_nodes_only() const
      {
        return false;
      }

      /**
       * A new discrete system of a 2D body with this treatment, not yet set
       * up: the problem type then drives it with the run's SystemContext
       * (DiscreteSystem::setup(), solve_linear()). @p treatment_name is the
       * treatment's name in the input file, for messages.
       */
      virtual std::unique_ptr<DiscreteSystem<2>>
      make_system_2d(const std::string &treatment_name) const = 0;

      /// The same for a 3D body.
      virtual std::unique_ptr<DiscreteSystem<3>>
      make_system_3d(const std::string &treatment_name) const = 0;

      /// make_system_2d() or make_system_3d(), for templates over @p dim.
      template <int dim>
      std::unique_ptr<DiscreteSystem<dim>>
      make_system(const std::string &treatment_name) const
      {
        static_assert(dim == 2 || dim == 3, "2D and 3D only");
        if constexpr (dim == 2)
          return make_system_2d(treatment_name);
        else
          return make_system_3d(treatment_name);
      }

      /// The family's name in error messages.
      static std::string
      family_name()
      {
        return "boundary treatment";
      }
    };

    /// The registry of boundary treatments.
    using BoundaryTreatmentRegistry = PluginRegistry<BoundaryTreatment>;
  } // namespace Boundary

  extern template class PluginRegistry<Boundary::BoundaryTreatment>;
} // namespace PeriDEAL

#endif
