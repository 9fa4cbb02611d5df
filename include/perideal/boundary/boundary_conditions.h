#ifndef perideal_boundary_boundary_conditions_h
#define perideal_boundary_boundary_conditions_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/parsed_function.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/base/input_checks.h>
#include <perideal/discretization/node_set.h>

#include <array>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace PeriDEAL
{
  /**
   * Boundary conditions and their treatment near the surface of a PD body.
   */
  namespace Boundary
  {
    using namespace dealii;

    /**
     * The loads and constraints of a quasi-static PD problem, as a user
     * describes them in the subsection "Boundary conditions":
     *
     * - **Prescribed displacement in a volumetric layer.** Every node whose
     *   distance to a boundary face with one of the "Dirichlet boundary
     *   ids" is less than "Dirichlet layer thickness" (in horizons) has the
     *   selected components of its displacement prescribed by the function
     *   "Dirichlet displacement", evaluated at the node. The constraints
     *   are inhomogeneous identity constraints u_k = g(x_i) in an
     *   AffineConstraints object over the locally relevant DoFs, so that a
     *   node's status is the same on every process that sees it. Nodes in
     *   one of the "Dirichlet boxes" are prescribed in the same way, each
     *   box with its own components if "Dirichlet box components" says so
     *   (rollers and pins).
     * - **Body force** b(x), applied as the nodal force V_i b(x_i).
     * - **Traction** t(x) on the boundary faces with one of the "Traction
     *   boundary ids": the force t(x_f) |f| of face f goes to the node of
     *   the cell that owns the face, i.e. the traction is spread over a
     *   boundary layer one cell thick.
     *
     * Boundary ids are those of the triangulation: for a box built by
     * PeriDEAL they are 0/1 for the faces x = min/max, 2/3 for y and 4/5
     * for z. Loads on constrained DoFs are dropped (the reaction there is
     * whatever the constraint needs).
     *
     * Every function may depend on the time t (its last variable, e.g.
     * 'x,y,t'); the functions are evaluated at the time given to
     * set_time(). Whether an expression uses t is known from its text
     * (load_depends_on_time(), dirichlet_depends_on_time()), so that time
     * stepping re-evaluates only what changes.
     */
    template <int dim>
    class BoundaryConditions
    {
    public:
      /**
       * Where a time-dependent load acts, so that time stepping can
       * re-evaluate it without a pass over the mesh: a node, with the body
       * force \f$V_i b(x_i, t)\f$, or a loaded boundary face f, with the
       * traction \f$t(x_f, t)\,|f|\f$ (load_at()).
       */
      struct LoadSite
      {
        /// The node's location, or the face's centre.
        Point<dim> point;
        /// The outward unit normal of a face; zero for a node.
        Tensor<1, dim> normal;
        /// V_i of a node, |f| of a face (1 for a 1D face, a point).
        double measure = 0;
        /// Whether the site is a face (traction) or a node (body force).
        bool on_face = false;
        /// The DoFs the force goes to, per component; invalid where the
        /// component is constrained (the load there is dropped).
        std::array<types::global_dof_index, dim> dofs;
      };

      BoundaryConditions();

      /**
       * Declare the entries of the current subsection.
       */
      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm);

      /**
       * Find the nodes of the Dirichlet layers among the owned and ghost
       * nodes of @p nodes and fill @p constraints (reinitialised over
       * nodes.relevant_dofs()). Checks that the boundary ids exist in the
       * mesh and that some nodes stay free.
       */
      void
      make_constraints(const DoFHandler<dim>              &dof_handler,
                       const Discretization::NodeSet<dim> &nodes,
                       const double                        horizon,
                       AffineConstraints<double>          &constraints) const;

      /**
       * The external nodal forces (body force and traction) on the owned
       * DoFs that are not constrained, added into @p load.
       */
      void
      add_load(const DoFHandler<dim>              &dof_handler,
               const Discretization::NodeSet<dim> &nodes,
               const AffineConstraints<double>    &constraints,
               TrilinosWrappers::MPI::Vector      &load) const;

      /**
       * As add_load(), but only the loads whose functions do not depend on
       * time go into @p load; the sites of those that do (every owned node
       * for a time-dependent body force, every loaded owned face for a
       * time-dependent traction) are returned, to be evaluated at each time
       * with load_at().
       */
      std::vector<LoadSite>
      add_constant_load(const DoFHandler<dim>              &dof_handler,
                        const Discretization::NodeSet<dim> &nodes,
                        const AffineConstraints<double>    &constraints,
                        TrilinosWrappers::MPI::Vector      &load) const;

      /// The force at @p site at the time of set_time().
      Tensor<1, dim>
      load_at(const LoadSite &site) const;

      /// The entry whose function gives the load at @p site, for messages.
      std::string
      load_entry(const LoadSite &site) const;

      /// Whether the body force or the traction in use depends on t.
      bool
      load_depends_on_time() const;

      /// Whether the prescribed 'Dirichlet displacement' depends on t.
      bool
      dirichlet_depends_on_time() const;

      /// Whether any node may be prescribed (Dirichlet ids or boxes given).
      bool
      has_dirichlet() const;

      /// Whether there is any load: a body force that is not '0' in every
      /// component, or traction boundary ids.
      bool
      has_load() const;

      /**
       * Entries of 'Boundary conditions' (full paths) that have no effect
       * with the others as given: e.g. the traction function without
       * traction boundary ids (Problems::ProblemType::unused_entries()).
       */
      std::vector<UnusedEntry>
      unused_entries() const;

      /**
       * The number of owned nodes with at least one constrained component.
       */
      unsigned int
      n_constrained_nodes(const Discretization::NodeSet<dim> &nodes,
                          const AffineConstraints<double> &constraints) const;

      /**
       * Check that every boundary id named in the input occurs in the mesh;
       * throws an error naming the entry otherwise.
       */
      void
      check_boundary_ids(const Triangulation<dim> &triangulation) const;

      /// Evaluate the functions (Dirichlet displacement, body force,
      /// traction) at time @p t from now on.
      void
      set_time(const double t);

      /// Whether faces with boundary id @p id carry a Dirichlet condition.
      bool
      is_dirichlet_boundary(const types::boundary_id id) const;

      /// 'Dirichlet layer thickness', in horizons.
      double
      dirichlet_layer_thickness() const
      {
        return layer_thickness;
      }

      /// Whether faces with boundary id @p id carry a traction.
      bool
      is_traction_boundary(const types::boundary_id id) const;

      /// Which displacement components the Dirichlet condition prescribes.
      const std::vector<bool> &
      dirichlet_component_mask() const;

      /// The prescribed displacement at @p p.
      Tensor<1, dim>
      dirichlet_value(const Point<dim> &p) const;

      /// The body force density at @p p.
      Tensor<1, dim>
      body_force_value(const Point<dim> &p) const;

      /**
       * The traction (force per area) at @p p on a face with outward unit
       * normal @p normal: the 'Traction' function, or the 'Boundary stress'
       * tensor times the normal.
       */
      Tensor<1, dim>
      traction_value(const Point<dim> &p, const Tensor<1, dim> &normal) const;

      /// The Dirichlet boundary ids as given, comma-separated.
      std::string
      dirichlet_ids_string() const
      {
        std::string s;
        for (const auto id : dirichlet_ids)
          s += (s.empty() ? "" : ", ") + std::to_string(id);
        return s;
      }

    private:
      /// The masks of 'Dirichlet box components' (empty if the entry is),
      /// one per box; throws on a malformed entry.
      static std::vector<std::vector<bool>>
      parse_box_components(const std::string &text, const unsigned int n_boxes);

      /// add_load() and add_constant_load(): with @p sites, the loads that
      /// depend on time go there instead of into @p load.
      void
      collect_load(const DoFHandler<dim>              &dof_handler,
                   const Discretization::NodeSet<dim> &nodes,
                   const AffineConstraints<double>    &constraints,
                   TrilinosWrappers::MPI::Vector      &load,
                   std::vector<LoadSite>              *sites) const;

      std::vector<types::boundary_id> dirichlet_ids;
      std::vector<bool>               dirichlet_components;
      std::vector<BoundingBox<dim>>   dirichlet_boxes;
      std::string                     dirichlet_boxes_text;
      /// 'Dirichlet box components': the components each box prescribes.
      std::vector<std::vector<bool>> dirichlet_box_components;
      std::string                    dirichlet_box_components_text;
      /// 'Dirichlet displacement/Function expression', for messages.
      std::string                     dirichlet_expression_text;
      double                          layer_thickness      = 1;
      std::string                     layer_thickness_text = "1";
      std::vector<types::boundary_id> traction_ids;

      std::unique_ptr<Functions::ParsedFunction<dim>> dirichlet_displacement;
      std::unique_ptr<Functions::ParsedFunction<dim>> body_force;
      std::unique_ptr<Functions::ParsedFunction<dim>> traction;
      std::unique_ptr<Functions::ParsedFunction<dim>> boundary_stress;
      bool traction_from_stress = false;
      /// Whether each function uses t, and whether the body force is
      /// given as zero in every component.
      bool dirichlet_uses_time = false, body_force_uses_time = false,
           traction_uses_time = false, stress_uses_time = false,
           zero_body_force = true;
    };
  } // namespace Boundary
} // namespace PeriDEAL

#endif
