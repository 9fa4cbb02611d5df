/**
 * @file
 * The checks of a Simulator's input that go beyond one entry: entries set
 * for a plugin that is not selected, entries without effect on this run,
 * the memory estimate of a box mesh against the machines (base/
 * memory_guard.h), the material's stiffness at this horizon, and output
 * names that meet.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/base/input_checks.h>
#include <perideal/base/memory_guard.h>
#include <perideal/problems/simulator.h>

#include <algorithm>
#include <cmath>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    Simulator<dim>::check_input_file(const std::string &file,
                                     ParameterHandler  &prm)
    {
      const std::vector<InputEntry> entries = scan_input_file(file);

      std::vector<PluginSelection> selections = {
        {"Material model", "Model", Models::ModelRegistry<dim>::names()},
        {"Partial volumes",
         "Algorithm",
         Quadrature::PartialVolumeRegistry<dim>::names()},
        {"Quadrature",
         "Scheme",
         Quadrature::QuadratureSchemeRegistry<dim>::names(),
         {{"collocation", "hybrid"}}},
        {"Boundary treatment",
         "Treatment",
         Boundary::BoundaryTreatmentRegistry::names()},
        {"", "Problem type", ProblemTypeRegistry<dim>::names()},
        {"Linear solver",
         "Preconditioner",
         Solvers::PreconditionerRegistry::names()}};
      // Those of the selected problem type come last: an entry of another
      // problem type's plugin is refused by 'Problem type' first.
      const std::string problem_name = prm.get("Problem type");
      if (ProblemTypeRegistry<dim>::is_registered(problem_name))
        {
          const auto selected = ProblemTypeRegistry<dim>::create(problem_name);
          for (auto &selection : selected->plugin_selections())
            selections.push_back(std::move(selection));
        }
      for (const auto &entry : entries)
        {
          AssertThrow(dim == 2 || entry.path.back() != "Plane model",
                      ExcMessage("The entry '" + entry.name() + "' (line " +
                                 std::to_string(entry.line) +
                                 ") applies to 2D only, and this run is " +
                                 std::to_string(dim) +
                                 "D. Remove it, or set 'Dimension = 2'."));
          for (const auto &selection : selections)
            {
              const unsigned int depth = selection.section.empty() ? 0 : 1;
              if (entry.path.size() < depth + 2 ||
                  (depth == 1 && entry.path[0] != selection.section))
                continue;
              const std::string &plugin = entry.path[depth];
              if (std::find(selection.names.begin(),
                            selection.names.end(),
                            plugin) == selection.names.end())
                continue;
              if (depth == 1)
                prm.enter_subsection(selection.section);
              const std::string selected = prm.get(selection.selector);
              if (depth == 1)
                prm.leave_subsection();
              const std::string selector =
                (depth == 1 ? selection.section + "/" : std::string()) +
                selection.selector;
              const bool shared = std::find(selection.shared.begin(),
                                            selection.shared.end(),
                                            std::make_pair(plugin, selected)) !=
                                  selection.shared.end();
              AssertThrow(plugin == selected || shared,
                          ExcMessage(
                            "The entry '" + entry.name() + "' (line " +
                            std::to_string(entry.line) + ") belongs to '" +
                            plugin + "', but '" + selector + "' selects '" +
                            selected + "', so it would be ignored. Set '" +
                            selector + " = " + plugin +
                            "', or move the entry to the subsection '" +
                            selected + "'."));
            }
        }
    }


    template <int dim>
    void
    Simulator<dim>::check_unused_entries(const ParameterHandler &prm) const
    {
      std::vector<UnusedEntry> unused = problem->unused_entries(*this);
      if (!problem->uses_material_model())
        unused.push_back({"Material model/",
                          "the problem type '" + problem_name +
                            "' uses no elastic material model; remove the "
                            "subsection 'Material model'"});
      else if (model != nullptr)
        for (const auto &rule : model->unused_entries())
          unused.push_back(
            {"Material model/" + model_name + "/" + rule.pattern, rule.why});
      for (const auto &[entry, why] : quadrature_scheme->unused_entries())
        unused.push_back({entry, why});
      if (!problem->uses_linear_solver())
        unused.push_back({"Linear solver/",
                          "the problem type '" + problem_name +
                            "' solves no linear system with it; remove the "
                            "subsection 'Linear solver'"});
      if (node_perturbation == 0)
        unused.push_back({"Geometry/Random seed",
                          "it seeds 'Geometry/Node perturbation', which is "
                          "0 (nodes at the cell centres); set a perturbation "
                          "or remove the entry"});
      ParameterHandler defaults;
      declare_parameters(defaults);
      PeriDEAL::check_unused_entries(changed_entries(prm, defaults), unused);
    }


    template <int dim>
    void
    Simulator<dim>::check_memory_estimate(
      const typename MeshGenerator<dim>::CoarseSize &coarse) const
    {
      // Nodes of the mesh before anything is allocated, as a double (a
      // careless input can overflow any integer).
      const double n_nodes =
        std::pow(2., dim * double(global_refinements)) * coarse.n_cells;
      // Bytes per node, measured (doc/matrix-free-operator.md): about 2 KB
      // for mesh, DoF handler, node set, constraints and vectors with the
      // matrix-free operator, plus 6 KB for the AMG hierarchy of the local
      // elasticity preconditioner; an assembled matrix stores dim rows of
      // dim times the nodes within the coupling range, 12 bytes an entry,
      // and a direct solver's factors several times that.
      const double m = horizon_specification == HorizonSpecification::m_ratio ?
                         m_ratio :
                         horizon_length / std::max(1e-300, coarse.spacing);
      // Calibrated on the 28^3 LPS case (110 KB per node assembled, m = 3).
      const double reach   = couples_two_horizons() ? 2 * m : m;
      const double coupled = dim == 3 ? 4. / 3. * M_PI * reach * reach * reach :
                             dim == 2 ? M_PI * reach * reach :
                                        2 * reach;
      // (2D: 1 KB and 1.5 KB; the 2000^2 run took 9.5 GB with local
      // elasticity.)
      double       per_node = dim == 3 ? 2048 : 1024;
      const double own      = problem->estimated_bytes_per_node(
        dim == 3 ? 4. / 3. * M_PI * m * m * m :
        dim == 2 ? M_PI * m * m :
                   2 * m);
      if (own >= 0)
        per_node = own;
      else if (linear_solver.is_matrix_free())
        per_node += linear_solver.preconditioner().bytes_per_node(dim);
      else
        per_node += dim * dim * coupled * 12 *
                    (linear_solver.method() == Solvers::Method::direct ? 2 : 1);
      const double needed = n_nodes * per_node;

      // Memory available to this job: MemAvailable of each host, shared
      // among the processes on it.
      const double available =
        Utilities::MPI::sum(available_memory_per_process(communicator),
                            communicator);
      if (available <= 0) // no /proc/meminfo: no guard
        return;
      AssertThrow(
        fits_in_memory(needed, available),
        ExcInvalidInput(
          coarse.entry,
          coarse.value,
          "with 'Global refinements = " + std::to_string(global_refinements) +
            "' this is " + format_number(n_nodes) +
            " nodes, which need an estimated " +
            format_number(needed / 1073741824.) + " GB, but only " +
            format_number(available / 1073741824.) +
            " GB are available; use fewer cells" +
            (linear_solver.is_matrix_free() || !problem->uses_linear_solver() ?
               std::string(", or more machines") :
               std::string(", 'Linear solver/Operator = matrix-free' (about "
                           "2 KB per node), or more machines"))));
    }


    template <int dim>
    void
    Simulator<dim>::check_material_scale() const
    {
      if (model == nullptr || !problem->uses_material_model() ||
          model->stiffness_entry().first.empty())
        return;
      // The weighted volume m of a full ball, S_{d-1} int_0^delta omega r^{d+1}
      // dr (midpoint rule), the coefficients of the shortest and the longest
      // bond, and a row sum of the stiffness: the same on every process.
      const double       sphere = dim == 1 ? 2. :
                                  dim == 2 ? 2 * numbers::PI :
                                             4 * numbers::PI;
      const unsigned int n_r    = 256;
      double             m      = 0;
      for (unsigned int k = 0; k < n_r; ++k)
        {
          const double r = (k + 0.5) / n_r * horizon;
          m += sphere * model->influence(r, horizon) * std::pow(r, dim + 1) *
               horizon / n_r;
        }
      const double volume = sphere / dim * std::pow(horizon, dim);
      bool         finite = std::isfinite(model->bulk_modulus()) &&
                    std::isfinite(model->shear_modulus()) && std::isfinite(m) &&
                    m > 0;
      for (const double r : {h, horizon})
        {
          const double a = model->dilatation_coefficient(m, r, horizon);
          const double b = model->extension_coefficient(m, r, horizon);
          const double row =
            (std::abs(a) * dim * horizon / m * volume + std::abs(b)) * volume;
          finite = finite && std::isfinite(a) && std::isfinite(b) &&
                   std::isfinite(row);
        }
      const auto [entry, value] = get_stiffness_entry();
      AssertThrow(finite,
                  ExcInvalidInput(
                    entry,
                    value,
                    "with the horizon " + format_number(horizon) +
                      " the bond stiffness of the model (the modulus over a "
                      "power of the horizon) overflows the range of double "
                      "precision numbers (about 1e308); give the modulus of "
                      "a real material, about 1e3 to 1e12 Pa (or of order 1 "
                      "in nondimensional units)"));
    }


    template <int dim>
    void
    Simulator<dim>::check_output_names() const
    {
      using Kind = IO::OutputName::Kind;
      std::vector<IO::OutputName> names;
      for (auto &name : mesh_generator->input_names())
        names.push_back(std::move(name));
      for (auto &name : problem->output_names(*this))
        names.push_back(std::move(name));
      if (!summary_file.empty())
        names.push_back({"Output/Summary file",
                         summary_file,
                         summary_file,
                         Kind::file,
                         "the summary file"});
      if (!node_data_file.empty())
        names.push_back({"Output/Node data file",
                         node_data_file,
                         node_data_file,
                         Kind::file,
                         "the node data file"});
      check_on_all_ranks([&]() { IO::check_output_names(names); },
                         communicator);
    }


#define PERIDEAL_INSTANTIATE(dim)                                              \
  template void Simulator<dim>::check_input_file(const std::string &,          \
                                                 ParameterHandler &);          \
  template void Simulator<dim>::check_unused_entries(const ParameterHandler &) \
    const;                                                                     \
  template void Simulator<dim>::check_memory_estimate(                         \
    const MeshGenerator<dim>::CoarseSize &) const;                             \
  template void Simulator<dim>::check_material_scale() const;                  \
  template void Simulator<dim>::check_output_names() const;
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
  } // namespace Problems
} // namespace PeriDEAL
