#include <perideal/boundary/boundary_treatment.h>
#include <perideal/boundary/layer_system.h>
#include <perideal/boundary/nodal_system.h>
#include <perideal/boundary/system_context.h>

namespace PeriDEAL
{
  namespace Boundary
  {
    namespace
    {
      /// Today's behaviour: the body's own nodes only.
      class NoTreatment : public BoundaryTreatment
      {
      public:
        static void
        declare_parameters(ParameterHandler &)
        {}

        void
        parse_parameters(ParameterHandler &) override
        {}

        unsigned int
        taylor_order() const override
        {
          return 0;
        }

        bool
        body_nodes_only() const override
        {
          return true;
        }

        std::unique_ptr<DiscreteSystem<2>>
        make_system_2d(const std::string &) const override
        {
          return std::make_unique<NodalSystem<2>>();
        }

        std::unique_ptr<DiscreteSystem<3>>
        make_system_3d(const std::string &) const override
        {
          return std::make_unique<NodalSystem<3>>();
        }
      };


      /// Fictitious layer with Taylor extrapolation from the body's nodes.
      class FictitiousLayer : public BoundaryTreatment
      {
      public:
        static void
        declare_parameters(ParameterHandler &prm)
        {
          prm.declare_entry(
            "Taylor order",
            "1",
            Patterns::Integer(1, 3),
            "Truncation order N of the Taylor extrapolation of the "
            "fictitious nodes' displacements (1, 2 or 3); their dilatations "
            "use N-1. N reproduces displacement fields that are polynomials "
            "of degree N exactly in the layer.");
        }

        void
        parse_parameters(ParameterHandler &prm) override
        {
          order = prm.get_integer("Taylor order");
        }

        unsigned int
        taylor_order() const override
        {
          return order;
        }

        std::unique_ptr<DiscreteSystem<2>>
        make_system_2d(const std::string &treatment_name) const override
        {
          return std::make_unique<LayerSystem<2>>(treatment_name,
                                                  with_surface_nodes(),
                                                  order);
        }

        std::unique_ptr<DiscreteSystem<3>>
        make_system_3d(const std::string &treatment_name) const override
        {
          return std::make_unique<LayerSystem<3>>(treatment_name,
                                                  with_surface_nodes(),
                                                  order);
        }

      protected:
        /// Whether surface nodes carry the boundary conditions.
        virtual bool
        with_surface_nodes() const
        {
          return false;
        }

      private:
        unsigned int order = 1;
      };


      /// Fictitious layer plus surface nodes with force-flux equations.
      class SurfaceNodes : public FictitiousLayer
      {
      protected:
        bool
        with_surface_nodes() const override
        {
          return true;
        }
      };
    } // namespace
  }   // namespace Boundary

  template class PluginRegistry<Boundary::BoundaryTreatment>;
} // namespace PeriDEAL

PERIDEAL_REGISTER_CLASS(PeriDEAL::Boundary::BoundaryTreatment,
                        PeriDEAL::Boundary::NoTreatment,
                        "none",
                        "No correction: incomplete neighbourhoods at the "
                        "surface, boundary conditions on the body's "
                        "outermost nodes.")
PERIDEAL_REGISTER_CLASS(PeriDEAL::Boundary::BoundaryTreatment,
                        PeriDEAL::Boundary::FictitiousLayer,
                        "fictitious layer",
                        "Fictitious nodes completing the neighbourhoods, "
                        "Taylor-extrapolated from the nearest body node; "
                        "boundary conditions as for 'none'.")
PERIDEAL_REGISTER_CLASS(PeriDEAL::Boundary::BoundaryTreatment,
                        PeriDEAL::Boundary::SurfaceNodes,
                        "surface nodes",
                        "Surface node method: fictitious layer extrapolated "
                        "from surface nodes on every external cell face, "
                        "force-flux equations on the surface nodes, boundary "
                        "conditions imposed on them.")
