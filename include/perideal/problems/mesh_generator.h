#ifndef perideal_problems_mesh_generator_h
#define perideal_problems_mesh_generator_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/tria.h>

#include <perideal/base/plugin_registry.h>
#include <perideal/io/output_names.h>

#include <optional>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    using namespace dealii;

    /**
     * How the simulator's coarse mesh is made, chosen with 'Geometry/Mesh'
     * (`subdivided box`, `file`). Each kind registers itself with
     * PERIDEAL_REGISTER_MESH_GENERATOR, so that adding one touches no
     * central switch. The entries of every kind live directly in the
     * subsection 'Geometry' (not in a subsection of their own, which would
     * change the input format); the simulator declares them, refines the
     * coarse mesh globally and checks its cells.
     */
    template <int dim>
    class MeshGenerator
    {
    public:
      /**
       * The size of the coarse mesh when it is known before the mesh is
       * built, for the memory guard (Simulator::check_memory_estimate()).
       */
      struct CoarseSize
      {
        /// Number of coarse cells (a double: a careless input can
        /// overflow any integer).
        double n_cells = 0;
        /// The cell side in x, for a horizon given as a length.
        double spacing = 0;
        /// The entry that sets the size ('subsection/Entry') and its
        /// value, which a refusal names.
        std::string entry, value;
      };

      virtual ~MeshGenerator() = default;

      /// Read and check the entries of 'Geometry' this kind uses; @p prm
      /// is inside 'Geometry'. Errors name the entry and the value.
      virtual void
      parse_parameters(ParameterHandler &prm) = 0;

      /// Build the coarse mesh into @p triangulation (collective: every
      /// process builds, or fails, alike).
      virtual void
      create_coarse_mesh(Triangulation<dim> &triangulation) const = 0;

      /**
       * Build the coarse mesh into @p triangulation and refine it globally
       * @p global_refinements times ('Mesh/Global refinements'). The
       * default calls create_coarse_mesh() and
       * Triangulation::refine_global(); a kind may build the same fine mesh
       * faster (SubdividedBox: fewer coarse cells, refined more often).
       * Collective.
       */
      virtual void
      create_mesh(Triangulation<dim> &triangulation,
                  const unsigned int  global_refinements) const;

      /// The size of the coarse mesh, if known before create_coarse_mesh().
      /// Default: unknown (no memory guard before the mesh exists).
      virtual std::optional<CoarseSize>
      coarse_size() const;

      /// The files the mesh is read from, for the check that no output
      /// overwrites them. Default: none.
      virtual std::vector<IO::OutputName>
      input_names() const;

      /// The entries are declared by the simulator in 'Geometry'.
      static void
      declare_parameters(ParameterHandler &prm);

      static std::string
      family_name();
    };

    template <int dim>
    using MeshGeneratorRegistry = PluginRegistry<MeshGenerator<dim>>;

    /**
     * The pattern of 'Geometry/Mesh': the registered names with
     * @p default_name first (so that the declared pattern reads as before:
     * "subdivided box|file").
     */
    template <int dim>
    std::string
    mesh_generator_pattern(const std::string &default_name);
  } // namespace Problems

  extern template class PluginRegistry<Problems::MeshGenerator<1>>;
  extern template class PluginRegistry<Problems::MeshGenerator<2>>;
  extern template class PluginRegistry<Problems::MeshGenerator<3>>;
} // namespace PeriDEAL

/// Register the mesh generator @p Class (a template over dim) under
/// @p name, in 1D, 2D and 3D.
#define PERIDEAL_REGISTER_MESH_GENERATOR(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::MeshGenerator<1>,  \
                          Class<1>,                                \
                          name,                                    \
                          description)                             \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::MeshGenerator<2>,  \
                          Class<2>,                                \
                          name,                                    \
                          description)                             \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Problems::MeshGenerator<3>,  \
                          Class<3>,                                \
                          name,                                    \
                          description)

#endif
