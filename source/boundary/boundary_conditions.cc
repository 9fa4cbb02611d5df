#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>


#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/base/input_checks.h>
#include <perideal/base/read_number.h>
#include <perideal/boundary/boundary_conditions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/discretization/crack_geometry.h>

#include <algorithm>
#include <sstream>

namespace PeriDEAL
{
  namespace Boundary
  {
    namespace
    {
      const char *const component_names = "x|y|z";

      // Whether the function of the current subsection uses its time
      // variable: the last of 'Variable names' when there are dim + 1 (as
      // ParsedFunction decides).
      bool
      uses_time(ParameterHandler &prm, const unsigned int dim)
      {
        const auto names =
          Utilities::split_string_list(prm.get("Variable names"));
        return names.size() == dim + 1 &&
               expression_uses_variable(prm.get("Function expression"),
                                        names.back());
      }


      // A vector function in the subsection @p name: checks the number of
      // components before deal.II's parser does, to name the entry; sets
      // @p time_dependent to whether it uses t.
      template <int dim>
      std::unique_ptr<Functions::ParsedFunction<dim>>
      parse_vector_function(ParameterHandler  &prm,
                            const std::string &name,
                            bool              &time_dependent)
      {
        prm.enter_subsection(name);
        time_dependent               = uses_time(prm, dim);
        const std::string expression = prm.get("Function expression");
        const auto        n_given =
          Utilities::split_string_list(expression, ';').size();
        AssertThrow(n_given == dim,
                    ExcInvalidInput("Boundary conditions/" + name +
                                      "/Function expression",
                                    expression,
                                    "give " + std::to_string(dim) +
                                      " expressions separated by ';', one "
                                      "per displacement component"));
        auto function = std::make_unique<Functions::ParsedFunction<dim>>(dim);
        function->parse_parameters(prm);
        prm.leave_subsection();
        return function;
      }

      // Whether face f of cell lies on a boundary with one of the (sorted)
      // ids.
      template <class CellIterator>
      bool
      on_boundary(const CellIterator                    &cell,
                  const unsigned int                     f,
                  const std::vector<types::boundary_id> &ids)
      {
        return cell->at_boundary(f) &&
               std::binary_search(ids.begin(),
                                  ids.end(),
                                  cell->face(f)->boundary_id());
      }


      // The value of a dim-component function as a tensor.
      template <int dim>
      Tensor<1, dim>
      tensor_value(const Function<dim> &function, const Point<dim> &p)
      {
        Tensor<1, dim> result;
        for (unsigned int c = 0; c < dim; ++c)
          result[c] = function.value(p, c);
        return result;
      }
    } // namespace


    template <int dim>
    BoundaryConditions<dim>::BoundaryConditions()
      : dirichlet_components(dim, true)
    {}


    template <int dim>
    void
    BoundaryConditions<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Dirichlet boundary ids",
        "",
        Patterns::List(Patterns::Integer(0, 254)),
        "Boundary ids of the faces whose volumetric layer has a prescribed "
        "displacement. A box made by PeriDEAL has ids 0/1 on x = min/max, "
        "2/3 on y, 4/5 on z; a mesh file brings its own ids.");
      prm.declare_entry("Dirichlet components",
                        dim == 1 ? "x" : (dim == 2 ? "x,y" : "x,y,z"),
                        Patterns::MultipleSelection(
                          dim == 1 ? "x" :
                                     (dim == 2 ? "x|y" : component_names)),
                        "The displacement components prescribed in the "
                        "Dirichlet layer; the others are free there.");
      prm.declare_entry(
        "Dirichlet layer thickness",
        "1",
        Patterns::Double(0),
        "Thickness of the Dirichlet layer in horizons: nodes closer than "
        "this to a Dirichlet face are constrained. With a state-based model "
        "a thickness of 2 gives every free node's neighbours a full "
        "neighbourhood.");
      prm.declare_entry(
        "Dirichlet boxes",
        "",
        Patterns::Anything(),
        "Boxes 'xmin, ymin[, zmin], xmax, ymax[, zmax]' (several separated "
        "by ';') whose nodes have the 'Dirichlet components' prescribed like "
        "those of the Dirichlet layers: a prescribed region that is not a "
        "layer along a whole face, such as the impact zone of a "
        "Kalthoff-Winkler plate. Empty: none.");
      prm.declare_entry(
        "Dirichlet box components",
        "",
        Patterns::Anything(),
        "The displacement components prescribed in each of the 'Dirichlet "
        "boxes': one list per box, in the order of the boxes, separated by "
        "';' (e.g. 'x, y; y; y' for a load point held in x and y and two "
        "rollers). Empty: every box prescribes the 'Dirichlet components'.");
      prm.enter_subsection("Dirichlet displacement");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();

      prm.enter_subsection("Body force");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();

      prm.declare_entry("Traction boundary ids",
                        "",
                        Patterns::List(Patterns::Integer(0, 254)),
                        "Boundary ids of the faces that carry the traction "
                        "given in the subsection 'Traction'.");
      prm.enter_subsection("Traction");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
      prm.leave_subsection();
      prm.declare_entry(
        "Traction given as",
        "vector",
        Patterns::Selection("vector|stress tensor"),
        "'vector': the traction is the function in 'Traction' (force per "
        "area). 'stress tensor': the traction is tau(x) n, with tau the "
        "function in 'Boundary stress' and n the face's outward normal, so "
        "one input serves every face of a body.");
      prm.enter_subsection("Boundary stress");
      Functions::ParsedFunction<dim>::declare_parameters(prm, dim * dim);
      prm.leave_subsection();
    }


    template <int dim>
    std::vector<std::vector<bool>>
    BoundaryConditions<dim>::parse_box_components(const std::string &text,
                                                  const unsigned int n_boxes)
    {
      const std::string entry = "Boundary conditions/Dirichlet box components";
      const std::string names =
        dim == 1 ? "x" : (dim == 2 ? "x, y" : "x, y, z");
      std::vector<std::vector<bool>> masks;
      if (Utilities::trim(text).empty())
        return masks;
      AssertThrow(n_boxes > 0,
                  ExcInvalidInput(entry,
                                  text,
                                  "there are no 'Dirichlet boxes', so these "
                                  "components would prescribe nothing; give "
                                  "the boxes, or leave the entry empty"));
      const auto lists = Utilities::split_string_list(text, ';');
      AssertThrow(lists.size() == n_boxes,
                  ExcInvalidInput(entry,
                                  text,
                                  "it gives " + std::to_string(lists.size()) +
                                    " component lists for " +
                                    std::to_string(n_boxes) +
                                    " Dirichlet boxes; give one list per "
                                    "box, separated by ';'"));
      for (const auto &list : lists)
        {
          std::vector<bool> mask(dim, false);
          const auto        words = Utilities::split_string_list(list, ',');
          AssertThrow(!words.empty(),
                      ExcInvalidInput(entry,
                                      text,
                                      "a box with no component prescribes "
                                      "nothing; name its components (" +
                                        names + ")"));
          for (const auto &w : words)
            {
              AssertThrow(w.size() == 1 && w[0] >= 'x' &&
                            w[0] < static_cast<char>('x' + dim),
                          ExcInvalidInput(entry,
                                          text,
                                          "'" + w +
                                            "' is not a displacement "
                                            "component of this " +
                                            std::to_string(dim) +
                                            "D run; use " + names));
              mask[w[0] - 'x'] = true;
            }
          masks.push_back(mask);
        }
      return masks;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::parse_parameters(ParameterHandler &prm)
    {
      dirichlet_ids = parse_boundary_ids(prm.get("Dirichlet boundary ids"));
      traction_ids  = parse_boundary_ids(prm.get("Traction boundary ids"));
      for (const auto id : traction_ids)
        AssertThrow(std::find(dirichlet_ids.begin(), dirichlet_ids.end(), id) ==
                      dirichlet_ids.end(),
                    ExcInvalidInput("Boundary conditions/Traction boundary ids",
                                    prm.get("Traction boundary ids"),
                                    "boundary id " + std::to_string(id) +
                                      " is also a Dirichlet boundary id; a "
                                      "face carries either a displacement "
                                      "or a traction"));
      const auto components =
        Utilities::split_string_list(prm.get("Dirichlet components"));
      dirichlet_components.assign(dim, false);
      for (const auto &c : components)
        dirichlet_components[c[0] - 'x'] = true;

      dirichlet_boxes_text = prm.get("Dirichlet boxes");
      dirichlet_boxes =
        Discretization::parse_boxes<dim>(dirichlet_boxes_text,
                                         "Boundary conditions/Dirichlet boxes");
      dirichlet_box_components_text = prm.get("Dirichlet box components");
      dirichlet_box_components =
        parse_box_components(dirichlet_box_components_text,
                             dirichlet_boxes.size());
      AssertThrow(!components.empty() ||
                    (dirichlet_ids.empty() && dirichlet_boxes.empty()),
                  ExcInvalidInput("Boundary conditions/Dirichlet components",
                                  prm.get("Dirichlet components"),
                                  "with no component the Dirichlet layers "
                                  "and boxes would prescribe nothing; name "
                                  "the prescribed components (e.g. 'x, y'), "
                                  "or remove 'Dirichlet boundary ids' and "
                                  "'Dirichlet boxes'"));
      layer_thickness      = prm.get_double("Dirichlet layer thickness");
      layer_thickness_text = prm.get("Dirichlet layer thickness");
      AssertThrow(
        dirichlet_ids.empty() || layer_thickness > 0,
        ExcInvalidInput("Boundary conditions/Dirichlet layer thickness",
                        prm.get("Dirichlet layer thickness"),
                        "give a thickness > 0 (in horizons), for instance 1"));

      dirichlet_displacement =
        parse_vector_function<dim>(prm,
                                   "Dirichlet displacement",
                                   dirichlet_uses_time);
      prm.enter_subsection("Dirichlet displacement");
      dirichlet_expression_text = prm.get("Function expression");
      prm.leave_subsection();
      body_force =
        parse_vector_function<dim>(prm, "Body force", body_force_uses_time);
      traction =
        parse_vector_function<dim>(prm, "Traction", traction_uses_time);
      traction_from_stress = prm.get("Traction given as") == "stress tensor";
      prm.enter_subsection("Body force");
      zero_body_force = true;
      for (const auto &component :
           Utilities::split_string_list(prm.get("Function expression"), ';'))
        {
          double x = 1;
          zero_body_force =
            zero_body_force && read_number(component, x) && x == 0;
        }
      prm.leave_subsection();
      prm.enter_subsection("Boundary stress");
      {
        stress_uses_time             = uses_time(prm, dim);
        const std::string expression = prm.get("Function expression");
        const auto        n_given =
          Utilities::split_string_list(expression, ';').size();
        AssertThrow(
          n_given == dim * dim,
          ExcInvalidInput("Boundary conditions/Boundary stress/Function "
                          "expression",
                          expression,
                          "give " + std::to_string(dim * dim) +
                            " expressions separated by ';', the stress tensor "
                            "row by row (tau_11; tau_12; ...)"));
        boundary_stress =
          std::make_unique<Functions::ParsedFunction<dim>>(dim * dim);
        boundary_stress->parse_parameters(prm);
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    BoundaryConditions<dim>::check_boundary_ids(
      const Triangulation<dim> &triangulation) const
    {
      for (const auto &[ids, entry] :
           {std::make_pair(&dirichlet_ids, "Dirichlet boundary ids"),
            std::make_pair(&traction_ids, "Traction boundary ids")})
        Boundary::check_boundary_ids(triangulation,
                                     *ids,
                                     std::string("Boundary conditions/") +
                                       entry,
                                     boundary_ids_to_string(*ids));
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::is_dirichlet_boundary(
      const types::boundary_id id) const
    {
      return std::binary_search(dirichlet_ids.begin(), dirichlet_ids.end(), id);
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::is_traction_boundary(
      const types::boundary_id id) const
    {
      return std::binary_search(traction_ids.begin(), traction_ids.end(), id);
    }


    template <int dim>
    const std::vector<bool> &
    BoundaryConditions<dim>::dirichlet_component_mask() const
    {
      return dirichlet_components;
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::dirichlet_value(const Point<dim> &p) const
    {
      return tensor_value(*dirichlet_displacement, p);
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::body_force_value(const Point<dim> &p) const
    {
      return tensor_value(*body_force, p);
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::traction_value(const Point<dim>     &p,
                                            const Tensor<1, dim> &normal) const
    {
      Tensor<1, dim> result;
      if (traction_from_stress)
        {
          Vector<double> tau(dim * dim);
          boundary_stress->vector_value(p, tau);
          for (unsigned int i = 0; i < dim; ++i)
            for (unsigned int j = 0; j < dim; ++j)
              result[i] += tau[i * dim + j] * normal[j];
        }
      else
        result = tensor_value(*traction, p);
      return result;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::make_constraints(
      const DoFHandler<dim>              &dof_handler,
      const Discretization::NodeSet<dim> &nodes,
      const double                        horizon,
      AffineConstraints<double>          &constraints) const
    {
      const MPI_Comm comm = dof_handler.get_communicator();
      constraints.clear();
      constraints.reinit(nodes.relevant_dofs());

      check_boundary_ids(dof_handler.get_triangulation());

      if (dirichlet_ids.empty() && dirichlet_boxes.empty())
        {
          constraints.close();
          return;
        }

      const double              thickness = layer_thickness * horizon;
      std::vector<unsigned int> nodes_of_id;
      const auto                layer =
        BoundaryLayers<dim>(dof_handler.get_triangulation(), dirichlet_ids)
          .layer_of_nodes(nodes, thickness, &nodes_of_id);
      // Every box must hold a node (checked over all processes, naming the
      // box); then which boxes hold each node, so that each box prescribes
      // its own components.
      Discretization::nodes_in_boxes(nodes,
                                     dirichlet_boxes,
                                     "Boundary conditions/Dirichlet boxes",
                                     dirichlet_boxes_text,
                                     "prescribes nothing");
      std::vector<std::vector<bool>> in_box(dirichlet_boxes.size(),
                                            std::vector<bool>(nodes.size()));
      for (unsigned int k = 0; k < dirichlet_boxes.size(); ++k)
        for (unsigned int i = 0; i < nodes.size(); ++i)
          in_box[k][i] = dirichlet_boxes[k].point_inside(nodes[i].location);
      Vector<double>    g(dim);
      std::string       non_finite;
      std::vector<bool> prescribed(dim);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const auto &node = nodes[i];
          bool        any  = false;
          for (unsigned int c = 0; c < dim; ++c)
            {
              prescribed[c] = layer[i] != numbers::invalid_unsigned_int &&
                              dirichlet_components[c];
              for (unsigned int k = 0; k < dirichlet_boxes.size(); ++k)
                if (in_box[k][i])
                  prescribed[c] =
                    prescribed[c] || (dirichlet_box_components.empty() ?
                                        dirichlet_components[c] :
                                        dirichlet_box_components[k][c]);
              any = any || prescribed[c];
            }
          if (!any)
            continue;
          dirichlet_displacement->vector_value(node.location, g);
          for (unsigned int c = 0; c < dim; ++c)
            if (prescribed[c])
              {
                if (!std::isfinite(g[c]) && non_finite.empty())
                  {
                    std::ostringstream where;
                    where << "Invalid value '" << dirichlet_expression_text
                          << "' for the parameter 'Boundary "
                             "conditions/Dirichlet displacement/Function "
                             "expression': component "
                          << c << " is " << g[c] << " at the node ("
                          << node.location << ")";
                    if (dirichlet_uses_time)
                      where
                        << " at t = "
                        << format_number(dirichlet_displacement->get_time());
                    where << "; give an expression that is finite in every "
                             "Dirichlet layer and box.";
                    non_finite = where.str();
                  }
                constraints.add_line(node.dofs[c]);
                constraints.set_inhomogeneity(node.dofs[c], g[c]);
              }
        }
      throw_on_any_rank(non_finite, comm);
      for (unsigned int k = 0; k < dirichlet_ids.size(); ++k)
        AssertThrow(
          nodes_of_id[k] > 0,
          ExcInvalidInput("Boundary conditions/Dirichlet layer thickness",
                          layer_thickness_text,
                          "the Dirichlet layer of boundary id " +
                            std::to_string(dirichlet_ids[k]) + " (" +
                            format_number(thickness) +
                            " thick) holds no node centre, so it prescribes "
                            "nothing; use a layer of at least half a cell (a "
                            "thickness above h / (2 horizon))"));
      constraints.close();

      const unsigned int n_free =
        Utilities::MPI::sum(nodes.n_owned() -
                              n_constrained_nodes(nodes, constraints),
                            comm);
      AssertThrow(
        n_free > 0,
        ExcInvalidInput("Boundary conditions/Dirichlet layer thickness",
                        layer_thickness_text,
                        "every node lies in a Dirichlet layer (" +
                          format_number(thickness) +
                          " thick) or box; use a thinner layer, smaller "
                          "boxes, a smaller horizon or a larger body"));
    }


    template <int dim>
    unsigned int
    BoundaryConditions<dim>::n_constrained_nodes(
      const Discretization::NodeSet<dim> &nodes,
      const AffineConstraints<double>    &constraints) const
    {
      unsigned int n = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int c = 0; c < dim; ++c)
          if (constraints.is_constrained(nodes[i].dofs[c]))
            {
              ++n;
              break;
            }
      return n;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::add_load(
      const DoFHandler<dim>              &dof_handler,
      const Discretization::NodeSet<dim> &nodes,
      const AffineConstraints<double>    &constraints,
      TrilinosWrappers::MPI::Vector      &load) const
    {
      collect_load(dof_handler, nodes, constraints, load, nullptr);
    }


    template <int dim>
    std::vector<typename BoundaryConditions<dim>::LoadSite>
    BoundaryConditions<dim>::add_constant_load(
      const DoFHandler<dim>              &dof_handler,
      const Discretization::NodeSet<dim> &nodes,
      const AffineConstraints<double>    &constraints,
      TrilinosWrappers::MPI::Vector      &load) const
    {
      std::vector<LoadSite> sites;
      collect_load(dof_handler, nodes, constraints, load, &sites);
      return sites;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::collect_load(
      const DoFHandler<dim>              &dof_handler,
      const Discretization::NodeSet<dim> &nodes,
      const AffineConstraints<double>    &constraints,
      TrilinosWrappers::MPI::Vector      &load,
      std::vector<LoadSite>              *sites) const
    {
      const bool body_later = sites != nullptr && body_force_uses_time;
      const bool traction_later =
        sites != nullptr &&
        (traction_from_stress ? stress_uses_time : traction_uses_time);
      Vector<double> value(dim);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          if (body_later)
            {
              LoadSite site;
              site.point   = nodes[i].location;
              site.measure = nodes[i].volume();
              for (unsigned int c = 0; c < dim; ++c)
                site.dofs[c] = constraints.is_constrained(nodes[i].dofs[c]) ?
                                 numbers::invalid_dof_index :
                                 nodes[i].dofs[c];
              sites->push_back(site);
              continue;
            }
          body_force->vector_value(nodes[i].location, value);
          for (unsigned int c = 0; c < dim; ++c)
            if (!constraints.is_constrained(nodes[i].dofs[c]))
              load[nodes[i].dofs[c]] += nodes[i].volume() * value[c];
        }

      if (!traction_ids.empty())
        {
          const auto                          &fe = dof_handler.get_fe();
          std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const unsigned int f : cell->face_indices())
                if (on_boundary(cell, f, traction_ids))
                  {
                    cell->get_dof_indices(dofs);
                    // Outward normal of the axis-aligned face.
                    const Tensor<1, dim> out =
                      cell->face(f)->center() - cell->center();
                    unsigned int axis = 0;
                    for (unsigned int d = 1; d < dim; ++d)
                      if (std::abs(out[d]) > std::abs(out[axis]))
                        axis = d;
                    Tensor<1, dim> normal;
                    normal[axis] = out[axis] > 0 ? 1 : -1;
                    // A 1D face is a point: the traction is a force.
                    double area = 1;
                    if constexpr (dim > 1)
                      area = cell->face(f)->measure();
                    if (traction_later)
                      {
                        LoadSite site;
                        site.point   = cell->face(f)->center();
                        site.normal  = normal;
                        site.measure = area;
                        site.on_face = true;
                        for (unsigned int k = 0; k < dofs.size(); ++k)
                          site.dofs[fe.system_to_component_index(k).first] =
                            constraints.is_constrained(dofs[k]) ?
                              numbers::invalid_dof_index :
                              dofs[k];
                        sites->push_back(site);
                        continue;
                      }
                    const Tensor<1, dim> t =
                      traction_value(cell->face(f)->center(), normal);
                    for (unsigned int k = 0; k < dofs.size(); ++k)
                      if (!constraints.is_constrained(dofs[k]))
                        load[dofs[k]] +=
                          area * t[fe.system_to_component_index(k).first];
                  }
        }
      load.compress(VectorOperation::add);

      // Non-finite loads (an expression that divides by zero somewhere)
      // are named before anything is solved with them.
      std::string non_finite;
      for (const auto dof : load.locally_owned_elements())
        if (!std::isfinite(load[dof]))
          {
            non_finite =
              "The load is not finite at DoF " + std::to_string(dof) +
              ": check the expressions of 'Boundary conditions/Body force' "
              "and 'Boundary conditions/Traction' (or 'Boundary stress'); "
              "they must be finite on the whole body and its loaded faces.";
            break;
          }
      throw_on_any_rank(non_finite, dof_handler.get_communicator());
    }


    template <int dim>
    Tensor<1, dim>
    BoundaryConditions<dim>::load_at(const LoadSite &site) const
    {
      return site.measure * (site.on_face ?
                               traction_value(site.point, site.normal) :
                               body_force_value(site.point));
    }


    template <int dim>
    std::string
    BoundaryConditions<dim>::load_entry(const LoadSite &site) const
    {
      return !site.on_face        ? "Boundary conditions/Body force" :
             traction_from_stress ? "Boundary conditions/Boundary stress" :
                                    "Boundary conditions/Traction";
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::load_depends_on_time() const
    {
      return body_force_uses_time ||
             (!traction_ids.empty() &&
              (traction_from_stress ? stress_uses_time : traction_uses_time));
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::dirichlet_depends_on_time() const
    {
      return dirichlet_uses_time;
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::has_dirichlet() const
    {
      return !dirichlet_ids.empty() || !dirichlet_boxes.empty();
    }


    template <int dim>
    bool
    BoundaryConditions<dim>::has_load() const
    {
      return !zero_body_force || !traction_ids.empty();
    }


    template <int dim>
    std::vector<UnusedEntry>
    BoundaryConditions<dim>::unused_entries() const
    {
      const std::string        section = "Boundary conditions/";
      std::vector<UnusedEntry> unused;
      if (!has_dirichlet())
        for (const char *entry :
             {"Dirichlet components", "Dirichlet displacement/"})
          unused.push_back({section + entry,
                            "neither 'Dirichlet boundary ids' nor 'Dirichlet "
                            "boxes' is given, so nothing is prescribed; give "
                            "them, or remove the entry"});
      if (dirichlet_ids.empty())
        unused.push_back({section + "Dirichlet layer thickness",
                          "it is the thickness of the layers along "
                          "'Dirichlet boundary ids', and none are given; "
                          "give them, or remove the entry"});
      if (traction_ids.empty())
        for (const char *entry :
             {"Traction/", "Boundary stress/", "Traction given as"})
          unused.push_back({section + entry,
                            "no 'Traction boundary ids' are given, so no "
                            "face carries a traction; give them, or remove "
                            "the entry"});
      else if (traction_from_stress)
        unused.push_back({section + "Traction/",
                          "'Traction given as = stress tensor' takes the "
                          "traction from 'Boundary stress'; set 'Traction "
                          "given as = vector' to use this function"});
      else
        unused.push_back({section + "Boundary stress/",
                          "'Traction given as = vector' takes the traction "
                          "from 'Traction'; set 'Traction given as = stress "
                          "tensor' to use this function"});
      return unused;
    }


    template <int dim>
    void
    BoundaryConditions<dim>::set_time(const double t)
    {
      for (auto *function : {dirichlet_displacement.get(),
                             body_force.get(),
                             traction.get(),
                             boundary_stress.get()})
        if (function != nullptr)
          function->set_time(t);
    }


    template class BoundaryConditions<1>;
    template class BoundaryConditions<2>;
    template class BoundaryConditions<3>;
  } // namespace Boundary
} // namespace PeriDEAL
