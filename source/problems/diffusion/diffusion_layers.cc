// The boundary layers of the diffusion problem type: which nodes form the
// Dirichlet and flux layers, how their values are filled (a function, the
// surface value, or a reflection through the physical surface), and the
// flux and volume sources. Split from diffusion.cc.

#include <deal.II/base/mpi.h>

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>

#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    Diffusion<dim>::setup_layers(Simulator<dim> &simulator)
    {
      // Layers: Dirichlet values and flux layers, each layer must hold a
      // node.
      const auto &tria   = simulator.get_dof_handler().get_triangulation();
      const auto &set    = *nodes;
      const auto  layers = [&](const std::vector<types::boundary_id> &ids,
                              const std::string                     &ids_entry,
                              const std::string                     &ids_text,
                              const double                           thickness,
                              const std::string &thickness_entry,
                              const std::string &thickness_text) {
        std::vector<unsigned int> owned;
        if (ids.empty())
          return owned;
        Boundary::check_boundary_ids(tria,
                                     ids,
                                     section + "/" + ids_entry,
                                     ids_text);
        std::vector<unsigned int> n_in_layer;
        const auto                layer =
          Boundary::BoundaryLayers<dim>(tria, ids).layer_of_nodes(set,
                                                                  thickness *
                                                                    horizon,
                                                                  &n_in_layer);
        for (unsigned int k = 0; k < ids.size(); ++k)
          AssertThrow(n_in_layer[k] > 0,
                      ExcInvalidInput(section + "/" + thickness_entry,
                                      thickness_text,
                                      "the layer of boundary id " +
                                        std::to_string(ids[k]) +
                                        " holds no node centre; use a layer "
                                         "of at least half a cell"));
        for (unsigned int i = 0; i < set.n_owned(); ++i)
          if (layer[i] != numbers::invalid_unsigned_int)
            owned.push_back(i);
        return owned;
      };
      dirichlet_nodes = layers(dirichlet_ids,
                               "Dirichlet boundary ids",
                               dirichlet_ids_text,
                               dirichlet_thickness,
                               "Dirichlet layer thickness",
                               dirichlet_thickness_text);
      flux_nodes      = layers(flux_ids,
                          "Flux boundary ids",
                          flux_ids_text,
                          flux_thickness,
                          "Flux layer thickness",
                          flux_thickness_text);
      // Where a flux layer meets a Dirichlet layer the prescribed value
      // wins.
      std::vector<bool> is_dirichlet(set.n_owned(), false);
      for (const auto i : dirichlet_nodes)
        is_dirichlet[i] = true;
      std::vector<unsigned int> flux_only;
      for (const auto i : flux_nodes)
        if (!is_dirichlet[i])
          flux_only.push_back(i);
      flux_nodes = flux_only;

      setup_layer_values(simulator);

      prescribed_nodes = dirichlet_nodes;
      if (flux_values == FluxValues::mirror)
        prescribed_nodes.insert(prescribed_nodes.end(),
                                flux_nodes.begin(),
                                flux_nodes.end());
      is_prescribed.assign(c.locally_owned_size(), false);
      for (const auto i : prescribed_nodes)
        is_prescribed[op.vector_index(i)] = true;

      // A body whose every node is prescribed has nothing to solve for:
      // the run would only replay the boundary values.
      const MPI_Comm comm = simulator.get_communicator();
      const auto     free_after =
        [&](const std::size_t n_prescribed) -> types::global_dof_index {
        return Utilities::MPI::sum<types::global_dof_index>(set.n_owned() -
                                                              n_prescribed,
                                                            comm);
      };
      const bool dirichlet_only = free_after(dirichlet_nodes.size()) == 0;
      AssertThrow(free_after(prescribed_nodes.size()) > 0,
                  ExcInvalidInput(
                    section + (dirichlet_only ? "/Dirichlet layer thickness" :
                                                "/Flux layer thickness"),
                    dirichlet_only ? dirichlet_thickness_text :
                                     flux_thickness_text,
                    std::string("every node lies in a ") +
                      (dirichlet_only ? "Dirichlet layer" :
                                        "Dirichlet layer or mirror flux "
                                        "layer") +
                      " (" +
                      format_number((dirichlet_only ? dirichlet_thickness :
                                                      flux_thickness) *
                                    horizon) +
                      " thick), so no value is left to compute; use a "
                      "thinner layer, a smaller horizon or a larger body"));
    }


    template <int dim>
    void
    Diffusion<dim>::setup_layer_values(Simulator<dim> &simulator)
    {
      surface_points.clear();
      reflections.clear();
      reflection_passes           = 0;
      const bool dirichlet_mirror = layer_values == LayerValues::mirror;
      const bool flux_mirror      = flux_values == FluxValues::mirror;
      const bool dirichlet_points =
        layer_values != LayerValues::function && !dirichlet_ids.empty();
      if (!dirichlet_points && !(flux_mirror && !flux_ids.empty()))
        return;
      const auto    &tria    = simulator.get_dof_handler().get_triangulation();
      const MPI_Comm comm    = simulator.get_communicator();
      const auto    &lattice = simulator.get_neighbor_lists().lattice();
      const auto     n       = nodes->size();

      // Per node of the set (ghosts too: reflection chains pass through
      // them): its layer (0 none, 1 Dirichlet, 2 flux; Dirichlet wins where
      // they meet), the surface point x_b = p + l (x - p) / |x - p| from the
      // nearest point p of its layer's outer face inwards through the
      // layer, and the node at the mirror image 2 x_b - x.
      enum Kind : unsigned char
      {
        none,
        dirichlet,
        flux
      };
      std::vector<unsigned char> kind(n, none);
      std::vector<Point<dim>>    x_b(n);
      const auto mark = [&](const std::vector<types::boundary_id> &ids,
                            const double                           thickness,
                            const Kind                             k) {
        if (ids.empty())
          return;
        const double l = thickness * horizon;
        const auto   faces =
          Boundary::BoundaryLayers<dim>(tria, ids).nearest_face_points(*nodes,
                                                                       l);
        for (unsigned int i = 0; i < n; ++i)
          if (kind[i] == none && std::isfinite(faces[i][0]))
            {
              const Tensor<1, dim> inward = (*nodes)[i].location - faces[i];
              kind[i]                     = k;
              x_b[i] = faces[i] + l / inward.norm() * inward;
            }
      };
      mark(dirichlet_ids, dirichlet_thickness, dirichlet);
      if (flux_mirror)
        mark(flux_ids, flux_thickness, flux);

      const auto reflected = [&](const unsigned int i) {
        return (kind[i] == dirichlet && dirichlet_mirror) ||
               (kind[i] == flux && flux_mirror);
      };
      std::vector<int> image(n, -1);
      for (unsigned int i = 0; i < n; ++i)
        if (reflected(i))
          {
            const Point<dim> &x = (*nodes)[i].location;
            if (lattice.is_uniform())
              {
                auto y = lattice.coordinates(i);
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] +=
                    std::llround(2 * (x_b[i][d] - x[d]) / lattice.spacing());
                image[i] = lattice.node_at(y);
              }
            if (image[i] >= 0 &&
                (*nodes)[image[i]].location.distance(
                  Point<dim>(2 * x_b[i] - x)) > 1e-6 * lattice.spacing())
              image[i] = -1;
          }
      // Levels: 1 for an image whose value is known before any reflection
      // (a free node, or a layer node filled by a function or the surface
      // value), 1 + its level for an image that is itself reflected (near
      // edges and corners the image across the nearest face lies in the
      // next face's layer: reflected again). The level of a ghost image
      // whose own image lies outside this process's node set stays
      // unknown here (0); its owner knows it.
      std::vector<unsigned int> level(n, 0);
      for (unsigned int sweep = 0; sweep <= dim; ++sweep)
        for (unsigned int i = 0; i < n; ++i)
          if (reflected(i) && image[i] >= 0)
            level[i] = reflected(image[i]) ?
                         (level[image[i]] > 0 ? level[image[i]] + 1 : 0) :
                         1;

      unsigned int missing_dirichlet = 0, missing_flux = 0, passes = 0;
      const auto   add = [&](const unsigned int i) {
        if (!reflected(i))
          return;
        if (image[i] < 0 || level[i] > dim)
          ++(kind[i] == dirichlet ? missing_dirichlet : missing_flux);
        // Unknown here (a chain through another process): as many passes
        // as a chain can have.
        passes = std::max(passes, level[i] == 0 ? dim : level[i]);
        Reflection r;
        r.node     = i;
        r.image    = image[i] < 0 ? 0u : static_cast<unsigned int>(image[i]);
        r.level    = level[i];
        r.odd      = kind[i] == dirichlet;
        r.surface  = x_b[i];
        r.distance = 2 * (*nodes)[i].location.distance(x_b[i]);
        reflections.push_back(r);
      };
      for (const auto i : dirichlet_nodes)
        {
          surface_points.push_back(x_b[i]);
          add(i);
        }
      if (flux_mirror)
        for (const auto i : flux_nodes)
          add(i);
      const std::string why = " has no node at its mirror image (mirror "
                              "layers need a uniform grid whose layers end "
                              "at cell faces, and a body thicker than two "
                              "layers)";
      AssertThrow(Utilities::MPI::sum(missing_dirichlet, comm) == 0,
                  ExcInvalidInput(section + "/Dirichlet layer values",
                                  layer_values_text,
                                  "a Dirichlet layer node" + why +
                                    "; use 'surface value'"));
      AssertThrow(Utilities::MPI::sum(missing_flux, comm) == 0,
                  ExcInvalidInput(section + "/Flux layer values",
                                  flux_values_text,
                                  "a flux layer node" + why +
                                    "; use 'source'"));
      // Every process runs the same passes (each has a ghost update), also
      // one that owns no reflected node.
      reflection_passes = Utilities::MPI::max(passes, comm);
      reflection_shift.resize(reflections.size());
    }


    template <int dim>
    void
    Diffusion<dim>::apply_layer_values(const double t, VectorType &x) const
    {
      boundary_value->set_time(t);
      if (layer_values == LayerValues::function)
        for (const auto i : dirichlet_nodes)
          {
            const double g = boundary_value->value((*nodes)[i].location);
            finite_check.value(g, boundary_value_entry, (*nodes)[i].location,
                               true, t);
            x.local_element(op.vector_index(i)) = g;
          }
      else if (layer_values == LayerValues::surface_value)
        for (unsigned int k = 0; k < dirichlet_nodes.size(); ++k)
          {
            const double g = boundary_value->value(surface_points[k]);
            finite_check.value(g, boundary_value_entry, surface_points[k],
                               true, t);
            x.local_element(op.vector_index(dirichlet_nodes[k])) = g;
          }
      if (reflection_passes == 0)
        return;
      // Reflections read the free nodes (level 1) or layer nodes of a
      // lower level (edges, corners), some of them off-process. Dirichlet:
      // the odd reflection through the boundary value, C(x) = 2 g(x_b) -
      // C(x_m); flux q into the body: the even one with the gradient the
      // flux gives, C(x) = C(x_m) + |x - x_m| q(x_b) / K. Both are
      // first-order Taylor expansions about x_b, exact for a solution
      // linear along the normal and second order for a smooth one. Pass p
      // (after a ghost update) makes every node of level <= p right, so
      // all passes recompute all reflections and no process needs to know
      // the level of a chain that runs through another process.
      boundary_flux->set_time(t);
      const double inverse_diffusivity = 1. / kernel.diffusivity();
      for (unsigned int k = 0; k < reflections.size(); ++k)
        {
          const auto  &r = reflections[k];
          const double g = r.odd ? boundary_value->value(r.surface) :
                                   boundary_flux->value(r.surface);
          finite_check.value(g,
                             r.odd ? boundary_value_entry : boundary_flux_entry,
                             r.surface,
                             true,
                             t);
          reflection_shift[k] =
            r.odd ? 2 * g : r.distance * inverse_diffusivity * g;
        }
      for (unsigned int pass = 0; pass < reflection_passes; ++pass)
        {
          x.update_ghost_values();
          for (unsigned int k = 0; k < reflections.size(); ++k)
            {
              const auto  &r     = reflections[k];
              const double image = x.local_element(op.vector_index(r.image));
              x.local_element(op.vector_index(r.node)) =
                reflection_shift[k] + (r.odd ? -image : image);
            }
          x.zero_out_ghost_values();
        }
    }


    template <int dim>
    void
    Diffusion<dim>::evaluate_source(const double t, VectorType &x) const
    {
      x = 0;
      if (with_source)
        {
          source->set_time(t);
          for (unsigned int i = 0; i < nodes->n_owned(); ++i)
            {
              const double value = source->value((*nodes)[i].location);
              finite_check.value(value, source_entry, (*nodes)[i].location,
                                 true, t);
              x.local_element(op.vector_index(i)) = value;
            }
        }
      if (with_flux && flux_values == FluxValues::source)
        {
          // A flux q through the surface enters as the source q / l spread
          // over the layer of thickness l (its integral over the layer is
          // q times the area).
          boundary_flux->set_time(t);
          const double inverse = 1. / (flux_thickness * horizon);
          for (const auto i : flux_nodes)
            {
              const double q = boundary_flux->value((*nodes)[i].location);
              finite_check.value(q, boundary_flux_entry, (*nodes)[i].location,
                                 true, t);
              x.local_element(op.vector_index(i)) += inverse * q;
            }
        }
    }


#define PERIDEAL_INSTANTIATE(dim)                                              \
  template void Diffusion<dim>::setup_layers(Simulator<dim> &);                \
  template void Diffusion<dim>::setup_layer_values(Simulator<dim> &);          \
  template void Diffusion<dim>::apply_layer_values(const double, VectorType &) \
    const;                                                                     \
  template void Diffusion<dim>::evaluate_source(const double, VectorType &)    \
    const;
    PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
