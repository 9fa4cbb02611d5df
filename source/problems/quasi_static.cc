#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/problems/node_region.h>
#include <perideal/problems/quasi_static.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    QuasiStatic<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Time",
        "1",
        Patterns::Double(),
        "The (pseudo-)time t at which the functions of 'Boundary "
        "conditions' (Dirichlet displacement, Body force, Traction, "
        "Boundary stress) and 'Analytical solution' are evaluated: the "
        "problem is the equilibrium under the loads at this instant. As in "
        "the static steps of finite-element codes, the default 1 is the end "
        "of a unit load ramp, so a load 'p*t' acts in full; functions that "
        "do not use t are the same at any time.");
    }


    template <int dim>
    void
    QuasiStatic<dim>::parse_parameters(ParameterHandler &prm)
    {
      load_time = prm.get_double("Time");
      AssertThrow(std::isfinite(load_time),
                  ExcInvalidInput("quasi-static/Time",
                                  prm.get("Time"),
                                  "give a finite time"));
    }


    template <int dim>
    void
    QuasiStatic<dim>::check_input(const Simulator<dim> &simulator) const
    {
      AssertThrow(
        simulator.get_node_data_file().empty() ||
          simulator.get_analytical_solution() != nullptr,
        ExcInvalidInput("Output/Node data file",
                        simulator.get_node_data_file(),
                        "the node data file holds the errors against the "
                        "analytical solution: set 'Analytical solution/Compare "
                        "with analytical solution = true', or leave the entry "
                        "empty"));
      simulator.get_boundary_treatment()
        .template make_system<dim>(simulator.get_boundary_treatment_name())
        ->check_input(simulator.get_linear_solver());
      if (simulator.get_quadrature_scheme().collocation() != nullptr)
        check_collocation_input(simulator);
    }


    template <int dim>
    bool
    QuasiStatic<dim>::supports_collocation() const
    {
      return true;
    }


    template <int dim>
    bool
    QuasiStatic<dim>::supports_hybrid() const
    {
      return true;
    }


    template <int dim>
    void
    QuasiStatic<dim>::check_collocation_input(
      const Simulator<dim> &simulator) const
    {
      const std::string &scheme = simulator.get_quadrature_scheme_name();
      AssertThrow(simulator.get_boundary_treatment().body_nodes_only(),
                  ExcInvalidInput("Quadrature/Scheme",
                                  scheme,
                                  "the collocation rows are built for the "
                                  "body's own nodes, and the boundary "
                                  "treatment '" +
                                    simulator.get_boundary_treatment_name() +
                                    "' adds others; use 'Boundary "
                                    "treatment/Treatment = none' or 'Scheme "
                                    "= standard'"));
      AssertThrow(
        !simulator.get_model().is_state_based() ||
          simulator.get_node_perturbation() == 0,
        ExcInvalidInput("Geometry/Node perturbation",
                        format_number(simulator.get_node_perturbation()),
                        "the collocation rows of the state-based model are "
                        "built for nodes at the cell centres so far (perturbed "
                        "nodes take bond-based rows); set 0, use a bond-based "
                        "model, or 'Quadrature/Scheme = standard'"));
      const auto *hybrid = simulator.get_quadrature_scheme().hybrid();
      AssertThrow(hybrid == nullptr || !hybrid->adaptive,
                  ExcInvalidInput("Quadrature/hybrid/Configuration",
                                  "adaptive",
                                  "a quasi-static solve breaks no bonds, so "
                                  "no node would ever switch to the standard "
                                  "scheme; set 'Configuration = fixed' (the "
                                  "standard boxes and layers, and the nodes "
                                  "whose ball is cut, are standard)"));
      const auto &solver = simulator.get_linear_solver();
      solver.check_form(solver.is_matrix_free() ?
                          Solvers::OperatorForm::matrix_free :
                          Solvers::OperatorForm::assembled,
                        false,
                        "the quadrature scheme '" + scheme + "'");
    }


    template <int dim>
    std::vector<UnusedEntry>
    QuasiStatic<dim>::unused_entries(const Simulator<dim> &simulator) const
    {
      std::vector<UnusedEntry> unused =
        simulator.get_boundary_conditions().unused_entries();
      for (const char *entry :
           {"Critical stretch", "Fracture energy", "Density"})
        unused.push_back({std::string("Material model/*/") + entry,
                          "the quasi-static problem is linear and static: it "
                          "breaks no bonds and has no inertia (the entry "
                          "acts in 'Problem type = explicit dynamics'); "
                          "remove it"});
      if (simulator.get_analytical_solution() == nullptr)
        unused.push_back({"Analytical solution/Displacement/",
                          "'Analytical solution/Compare with analytical "
                          "solution' is false; set it to true to compare, "
                          "or remove the entry"});
      return unused;
    }


    template <int dim>
    void
    QuasiStatic<dim>::run(Simulator<dim> &simulator)
    {
      // Every function of the set-up at the one time of this problem.
      simulator.set_time(load_time);
      simulator.get_pcout()
        << "           boundary conditions evaluated at t = "
        << format_number(load_time) << " ('quasi-static/Time')"
        << (simulator.get_boundary_conditions().load_depends_on_time() ||
                simulator.get_boundary_conditions()
                  .dirichlet_depends_on_time() ?
              "; they depend on t" :
              "; they do not depend on t")
        << std::endl;
      Boundary::SystemContext<dim> context = simulator.system_context();
      // The hybrid scheme's fixed standard region (empty without it).
      const std::vector<bool> standard = hybrid_standard_region(simulator);
      context.hybrid_standard          = &standard;
      system = simulator.get_boundary_treatment().template make_system<dim>(
        simulator.get_boundary_treatment_name());
      system->setup(context);
      system->solve_linear(context, displacement);
      postprocess(simulator);
    }


    template <int dim>
    void
    QuasiStatic<dim>::postprocess(Simulator<dim> &simulator)
    {
      const auto  ctx                    = simulator.system_context();
      const auto *analytical_solution    = simulator.get_analytical_solution();
      const unsigned int         n_owned = ctx.nodes.n_owned();
      std::vector<IO::NodeField> fields  = {{"node_volume", {}},
                                            {"mpi_rank", {}},
                                            {"constrained", {}}};
      const double rank = Utilities::MPI::this_mpi_process(ctx.communicator);
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          fields[0].values.push_back(ctx.nodes[i].volume());
          fields[1].values.push_back(rank);
          fields[2].values.push_back(system->is_constrained(ctx.nodes[i]));
        }
      const auto operator_fields = system->node_fields(ctx, displacement);
      fields.insert(fields.begin(),
                    operator_fields.begin(),
                    operator_fields.end());

      if (analytical_solution != nullptr)
        {
          IO::NodeField  error{"displacement_error", {}};
          IO::NodeField  normalized{"normalized_error", {}};
          Vector<double> exact(dim);
          double         e2 = 0, u2 = 0, e_max = 0, u_max = 0;
          // Largest analytical magnitude of each component (Eq. 38).
          Tensor<1, dim> component_max;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(ctx.nodes[i].location, exact);
              for (unsigned int c = 0; c < dim; ++c)
                component_max[c] =
                  std::max(component_max[c], std::abs(exact[c]));
            }
          for (unsigned int c = 0; c < dim; ++c)
            component_max[c] =
              Utilities::MPI::max(component_max[c], ctx.communicator);
          double normalized_max = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              analytical_solution->vector_value(ctx.nodes[i].location, exact);
              double e = 0, u = 0, n2 = 0;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const double diff =
                    displacement[ctx.nodes[i].dofs[c]] - exact[c];
                  e += diff * diff;
                  u += exact[c] * exact[c];
                  if (component_max[c] > 0)
                    n2 += std::pow(diff / component_max[c], 2);
                }
              e2 += ctx.nodes[i].volume() * e;
              u2 += ctx.nodes[i].volume() * u;
              e_max          = std::max(e_max, std::sqrt(e));
              u_max          = std::max(u_max, std::sqrt(u));
              normalized_max = std::max(normalized_max, std::sqrt(n2));
              error.values.push_back(std::sqrt(e));
              normalized.values.push_back(std::sqrt(n2));
            }
          ctx.summary.errors.max_normalized =
            Utilities::MPI::max(normalized_max, ctx.communicator);
          if (!simulator.get_node_data_file().empty())
            write_node_data(simulator, component_max);
          fields.push_back(normalized);
          // Nodes of the system besides the body's (surface nodes): the
          // same measure at their locations.
          const auto extra = system->extra_nodes();
          if (!system->extra_nodes_name().empty())
            {
              double surface_max = 0;
              for (const auto &node : extra)
                {
                  analytical_solution->vector_value(node.location, exact);
                  double n2 = 0;
                  for (unsigned int c = 0; c < dim; ++c)
                    if (component_max[c] > 0)
                      n2 += std::pow((node.displacement[c] - exact[c]) /
                                       component_max[c],
                                     2);
                  surface_max = std::max(surface_max, std::sqrt(n2));
                }
              surface_max = Utilities::MPI::max(surface_max, ctx.communicator);
              ctx.pcout << "           " << system->extra_nodes_name()
                        << ": largest normalized error " << std::scientific
                        << std::setprecision(3) << surface_max
                        << std::defaultfloat << std::endl;
            }
          e2                     = Utilities::MPI::sum(e2, ctx.communicator);
          u2                     = Utilities::MPI::sum(u2, ctx.communicator);
          e_max                  = Utilities::MPI::max(e_max, ctx.communicator);
          u_max                  = Utilities::MPI::max(u_max, ctx.communicator);
          ctx.summary.has_errors = true;
          ctx.summary.errors.l2  = u2 > 0 ? std::sqrt(e2 / u2) : std::sqrt(e2);
          ctx.summary.errors.max = u_max > 0 ? e_max / u_max : e_max;
          fields.push_back(error);
          ctx.pcout << "           error against the analytical solution: "
                    << "relative L2 " << std::scientific << std::setprecision(3)
                    << ctx.summary.errors.l2 << ", relative max "
                    << ctx.summary.errors.max << ", normalized max (Eq. 38) "
                    << ctx.summary.errors.max_normalized << std::defaultfloat
                    << std::endl;
        }

      const auto        &output = simulator.get_output();
      TimerOutput::Scope scope(ctx.timer, "output");
      const std::string  record =
        output.write(ctx.dof_handler, ctx.nodes, displacement, fields);
      if (!record.empty())
        ctx.pcout << "[" << std::setw(8) << std::fixed << std::setprecision(2)
                  << simulator.elapsed() << " s] wrote " << output.directory()
                  << "/" << record << std::defaultfloat << std::endl;
    }


    template <int dim>
    void
    QuasiStatic<dim>::write_node_data(Simulator<dim>       &simulator,
                                      const Tensor<1, dim> &component_max) const
    {
      const auto  ctx                   = simulator.system_context();
      const auto *analytical_solution   = simulator.get_analytical_solution();
      const std::string &node_data_file = simulator.get_node_data_file();
      // Rows: kind (0 body, 1 surface), x, u, exact, normalized error.
      std::vector<double> rows;
      Vector<double>      exact(dim);
      const auto          add =
        [&](const int kind, const Point<dim> &x, const Tensor<1, dim> &u) {
          analytical_solution->vector_value(x, exact);
          rows.push_back(kind);
          double n2 = 0;
          for (unsigned int c = 0; c < dim; ++c)
            rows.push_back(x[c]);
          for (unsigned int c = 0; c < dim; ++c)
            rows.push_back(u[c]);
          for (unsigned int c = 0; c < dim; ++c)
            {
              rows.push_back(exact[c]);
              if (component_max[c] > 0)
                n2 += std::pow((u[c] - exact[c]) / component_max[c], 2);
            }
          rows.push_back(std::sqrt(n2));
        };
      for (unsigned int i = 0; i < ctx.nodes.n_owned(); ++i)
        {
          Tensor<1, dim> u;
          for (unsigned int c = 0; c < dim; ++c)
            u[c] = displacement[ctx.nodes[i].dofs[c]];
          add(0, ctx.nodes[i].location, u);
        }
      for (const auto &node : system->extra_nodes())
        add(1, node.location, node.displacement);
      const auto all = Utilities::MPI::gather(ctx.communicator, rows, 0);
      // Written by process 0 under a temporary name; the verdict is shared
      // so that a failure there does not leave the others waiting.
      std::string error;
      if (Utilities::MPI::this_mpi_process(ctx.communicator) == 0)
        error = write_then_rename(node_data_file, [&](std::ostream &out) {
          const char *const names[] = {"x", "y", "z"};
          out << "kind";
          for (unsigned int c = 0; c < dim; ++c)
            out << ',' << names[c];
          for (unsigned int c = 0; c < dim; ++c)
            out << ",u_" << names[c];
          for (unsigned int c = 0; c < dim; ++c)
            out << ",exact_" << names[c];
          out << ",normalized_error\n" << std::setprecision(12);
          const unsigned int width = 3 * dim + 2;
          for (const auto &part : all)
            for (std::size_t r = 0; r < part.size(); r += width)
              {
                out << (part[r] == 0 ? "body" : "surface");
                for (unsigned int k = 1; k < width; ++k)
                  out << ',' << part[r + k];
                out << '\n';
              }
        });
      throw_on_any_rank(error.empty() ?
                          error :
                          "Invalid value '" + node_data_file +
                            "' for the parameter 'Output/Node data file': " +
                            error + ".",
                        ctx.communicator);
    }


    template class QuasiStatic<2>;
    template class QuasiStatic<3>;
  } // namespace Problems
} // namespace PeriDEAL

PERIDEAL_REGISTER_PROBLEM_TYPE(
  PeriDEAL::Problems::QuasiStatic,
  "quasi-static",
  "The linear quasi-static PD problem K u = V b with volumetric Dirichlet "
  "layers, body forces and tractions; assembled or matrix-free.")
