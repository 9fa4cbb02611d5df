/**
 * @file
 * The input of a Simulator: every entry of the parameter file declared
 * with its pattern and help text (declare_parameters()), and read and
 * checked value by value (parse_parameters()).
 */

#include <deal.II/base/utilities.h>

#include <perideal/base/exceptions.h>
#include <perideal/base/shared_libraries.h>
#include <perideal/problems/simulator.h>

#include <cmath>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      std::string
      default_list(const int dim, const std::string &value)
      {
        std::string s = value;
        for (int d = 1; d < dim; ++d)
          s += "," + value;
        return s;
      }
    } // namespace


    template <int dim>
    void
    Simulator<dim>::declare_parameters(ParameterHandler &prm)
    {
      // The driver reads it and loads the libraries in a first pass
      // (load_shared_libraries()); declared here so that the full parse
      // accepts it.
      declare_shared_library_parameters(prm);
      prm.declare_entry("Dimension",
                        "3",
                        Patterns::Integer(1, 3),
                        "Space dimension of the problem: 1, 2 or 3. 1D runs "
                        "(a serial line, shared by the processes) have only "
                        "the problem type 'diffusion'.");
      prm.declare_entry(
        "Problem type",
        ProblemTypeRegistry<dim>::is_registered("quasi-static") ?
          "quasi-static" :
          ProblemTypeRegistry<dim>::names().front(),
        Patterns::Selection(ProblemTypeRegistry<dim>::pattern_string()),
        "What to solve on the PD nodes; the entries of each problem type "
        "are in the top-level subsection of the same name.");
      ProblemTypeRegistry<dim>::declare_parameters(prm);

      prm.enter_subsection("Geometry");
      {
        prm.declare_entry(
          "Mesh",
          "subdivided box",
          Patterns::Selection(mesh_generator_pattern<dim>("subdivided box")),
          "'subdivided box': the box between 'Lower corner' and 'Upper "
          "corner' with 'Subdivisions' cells per direction (boundary ids 0/1 "
          "on x = min/max, 2/3 on y, 4/5 on z). 'file': the mesh in 'Mesh "
          "file', read with deal.II's GridIn; every cell must be an "
          "axis-aligned box.");
        prm.declare_entry("Lower corner",
                          default_list(dim, "0"),
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Lower corner of the box, one coordinate per "
                          "dimension.");
        prm.declare_entry("Upper corner",
                          default_list(dim, "1"),
                          Patterns::List(Patterns::Double(), dim, dim),
                          "Upper corner of the box.");
        prm.declare_entry("Subdivisions",
                          default_list(dim, "10"),
                          Patterns::List(Patterns::Integer(1), dim, dim),
                          "Number of cells of the box in each direction, "
                          "before global refinement. (The box is built from "
                          "these divided by the largest common power of 2, "
                          "refined back: the same cells and nodes in a "
                          "fraction of the time; a multiple of a large power "
                          "of 2 builds fastest.)");
        prm.declare_entry("Global refinements",
                          "0",
                          Patterns::Integer(0, 12),
                          "Number of times every cell is split into 2^dim.");
        prm.declare_entry(
          "Node perturbation",
          "0",
          Patterns::Double(),
          "Irregular nodes: each node moves from its cell's centre by a "
          "random offset whose component along each axis is uniform in "
          "[-f h, f h], f this fraction of the cell's side h, in [0, 0.5) "
          "so that the node stays in its cell (the hybrid-collocation paper "
          "uses 0.35). The standard scheme keeps the cells as its volumes; "
          "the collocation scheme fits a row per node. 0: nodes at the "
          "centres.");
        prm.declare_entry("Random seed",
                          "1",
                          Patterns::Integer(0),
                          "The seed of 'Node perturbation': the offsets are a "
                          "hash of it and of each cell's centre, the same on "
                          "every number of processes.");
        prm.declare_entry("Mesh file",
                          "",
                          Patterns::FileName(),
                          "Mesh read when 'Mesh = file'; the format follows "
                          "the extension (.msh, .vtk, .inp/.ucd, ...).");
      }
      prm.leave_subsection();

      prm.enter_subsection("Horizon");
      {
        prm.declare_entry(
          "Specification",
          "m-ratio",
          Patterns::Selection("m-ratio|length"),
          "How the horizon is given: as the m-ratio (horizon over the "
          "smallest cell side h) or as a length.");
        prm.declare_entry("m-ratio",
                          "3",
                          Patterns::Double(),
                          "Horizon over the smallest cell side, > 0.");
        prm.declare_entry("Length",
                          "0.3",
                          Patterns::Double(),
                          "Horizon length, > 0 and smaller than the body.");
      }
      prm.leave_subsection();

      prm.enter_subsection("Boundary treatment");
      {
        prm.declare_entry(
          "Treatment",
          "none",
          Patterns::Selection(
            Boundary::BoundaryTreatmentRegistry::pattern_string()),
          "How the body's surface is treated: 'none' (incomplete "
          "neighbourhoods, conditions on the outermost nodes), 'fictitious "
          "layer' (completed neighbourhoods by Taylor extrapolation) or "
          "'surface nodes' (fictitious layer plus nodes on the external "
          "faces carrying the boundary conditions through the force flux; "
          "Scabbia et al. 2023). The last two need a uniform grid of cubes "
          "and give a non-symmetric matrix: use the direct solver or GMRES.");
        Boundary::BoundaryTreatmentRegistry::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Partial volumes");
      {
        prm.declare_entry(
          "Algorithm",
          "exact",
          Patterns::Selection(
            Quadrature::PartialVolumeRegistry<dim>::pattern_string()),
          "How a neighbour cell's quadrature weight (the fraction of it "
          "inside the horizon) is computed. 'exact' is the closed-form "
          "volume of cell and ball.");
        Quadrature::PartialVolumeRegistry<dim>::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Quadrature");
      {
        prm.declare_entry(
          "Scheme",
          "standard",
          Patterns::Selection(
            Quadrature::QuadratureSchemeRegistry<dim>::pattern_string()),
          "The quadrature of the nonlocal operator at each node: 'standard' "
          "(the partial-volume weights of 'Partial volumes/Algorithm' at "
          "every node), 'collocation' (the WLS collocation of the "
          "hybrid-collocation paper, with the entries of the subsection "
          "'collocation', at every node whose neighbourhood is a full ball "
          "inside the body and its layers; the others standard; quasi-static "
          "and diffusion) or 'hybrid' (collocation outside a standard region "
          "that is fixed or grows where bonds near failure, subsection "
          "'hybrid'; explicit dynamics, quasi-static with 'Configuration = "
          "fixed', and diffusion in 2D and 3D, where the nodes at a phase "
          "interface (corrosion) are standard). "
          "Collocation gives a non-symmetric operator: use GMRES or "
          "BiCGStab.");
        Quadrature::QuadratureSchemeRegistry<dim>::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Material model");
      {
        // 1D has no material model (its runs are diffusion runs).
        const bool has_models = !Models::ModelRegistry<dim>::names().empty();
        prm.declare_entry("Model",
                          has_models ? "linear peridynamic solid" : "none",
                          Patterns::Selection(
                            has_models ?
                              Models::ModelRegistry<dim>::pattern_string() :
                              std::string("none")),
                          has_models ?
                            "The PD material model; its constants are in the "
                            "subsection of the same name." :
                            "1D runs have no material model: the only "
                            "problem type in 1D is 'diffusion'.");
        Models::ModelRegistry<dim>::declare_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Boundary conditions");
      Boundary::BoundaryConditions<dim>::declare_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Analytical solution");
      {
        prm.declare_entry("Compare with analytical solution",
                          "false",
                          Patterns::Bool(),
                          "Whether to report the errors of the computed "
                          "displacement against the function in the "
                          "subsection 'Displacement'.");
        prm.enter_subsection("Displacement");
        Functions::ParsedFunction<dim>::declare_parameters(prm, dim);
        prm.leave_subsection();
      }
      prm.leave_subsection();

      prm.enter_subsection("Linear solver");
      Solvers::LinearSolver::declare_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Output");
      {
        IO::SolutionOutput<dim>::declare_parameters(prm);
        prm.declare_entry(
          "Summary file",
          "",
          Patterns::FileName(),
          "CSV file to which one line per run is appended (sizes, solver, "
          "errors, phase timings, peak memory); the header is written when "
          "the file is new. Empty: no summary file.");
        prm.declare_entry(
          "Node data file",
          "",
          Patterns::FileName(),
          "CSV file with one line per node (body nodes, and surface nodes "
          "with the 'surface nodes' treatment): kind, position, computed "
          "and analytical displacement, normalized error (Scabbia et al. "
          "2023, Eq. 38). Written by process 0 for plots such as mid-plane "
          "error maps. Empty: not written.");
      }
      prm.leave_subsection();
    }


    template <int dim>
    void
    Simulator<dim>::parse_parameters(ParameterHandler &prm)
    {
      AssertThrow(prm.get_integer("Dimension") == dim,
                  ExcInvalidInput("Dimension",
                                  prm.get("Dimension"),
                                  "this simulation is " + std::to_string(dim) +
                                    "D"));
      problem_name = prm.get("Problem type");
      problem      = ProblemTypeRegistry<dim>::create(problem_name, prm);

      prm.enter_subsection("Geometry");
      {
        global_refinements = prm.get_integer("Global refinements");
        node_perturbation  = prm.get_double("Node perturbation");
        AssertThrow(node_perturbation >= 0 && node_perturbation < 0.5,
                    ExcInvalidInput("Geometry/Node perturbation",
                                    prm.get("Node perturbation"),
                                    "the offset of a node from its cell's "
                                    "centre, as a fraction of the cell's "
                                    "side, lies in [0, 0.5) (the node stays "
                                    "in its cell); 0 keeps the centres, the "
                                    "hybrid-collocation paper uses 0.35"));
        random_seed =
          static_cast<std::uint64_t>(prm.get_integer("Random seed"));
        mesh_generator = MeshGeneratorRegistry<dim>::create(prm.get("Mesh"));
        mesh_generator->parse_parameters(prm);
      }
      prm.leave_subsection();

      prm.enter_subsection("Horizon");
      {
        horizon_specification = prm.get("Specification") == "m-ratio" ?
                                  HorizonSpecification::m_ratio :
                                  HorizonSpecification::length;
        m_ratio               = prm.get_double("m-ratio");
        horizon_length        = prm.get_double("Length");
        if (horizon_specification == HorizonSpecification::m_ratio)
          {
            AssertThrow(m_ratio > 0 && std::isfinite(m_ratio),
                        ExcInvalidInput("Horizon/m-ratio",
                                        prm.get("m-ratio"),
                                        "give a horizon-to-spacing ratio > "
                                        "0, typically between 2 and 5"));
          }
        else
          AssertThrow(horizon_length > 0 && std::isfinite(horizon_length),
                      ExcInvalidInput("Horizon/Length",
                                      prm.get("Length"),
                                      "give a horizon length > 0"));
      }
      prm.leave_subsection();

      prm.enter_subsection("Partial volumes");
      algorithm_name = prm.get("Algorithm");
      algorithm =
        Quadrature::PartialVolumeRegistry<dim>::create(algorithm_name, prm);
      prm.leave_subsection();

      prm.enter_subsection("Quadrature");
      quadrature_scheme_name = prm.get("Scheme");
      quadrature_scheme = Quadrature::QuadratureSchemeRegistry<dim>::create(
        quadrature_scheme_name,
        prm);
      prm.leave_subsection();

      prm.enter_subsection("Material model");
      model_name = prm.get("Model");
      if (model_name != "none")
        {
          // As ModelRegistry::create(name, prm), with the model told where
          // its entries are, so that its messages give their full paths.
          model = Models::ModelRegistry<dim>::create(model_name);
          model->set_input_path("Material model/" + model_name + "/");
          prm.enter_subsection(model_name);
          model->parse_parameters(prm);
          prm.leave_subsection();
        }
      prm.leave_subsection();
      AssertThrow(model != nullptr || !problem->uses_material_model(),
                  ExcInvalidInput("Material model/Model",
                                  model_name,
                                  "the problem type '" + problem_name +
                                    "' needs a material model"));

      prm.enter_subsection("Boundary conditions");
      boundary_conditions.parse_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Boundary treatment");
      treatment_name = prm.get("Treatment");
      treatment =
        Boundary::BoundaryTreatmentRegistry::create(treatment_name, prm);
      prm.leave_subsection();
      summary.treatment    = treatment_name;
      summary.taylor_order = treatment->taylor_order();

      prm.enter_subsection("Analytical solution");
      {
        compare_with_analytical =
          prm.get_bool("Compare with analytical solution");
        prm.enter_subsection("Displacement");
        const std::string expression = prm.get("Function expression");
        AssertThrow(Utilities::split_string_list(expression, ';').size() == dim,
                    ExcInvalidInput(
                      "Analytical solution/Displacement/Function expression",
                      expression,
                      "give " + std::to_string(dim) +
                        " expressions separated by ';'"));
        analytical_solution =
          std::make_unique<Functions::ParsedFunction<dim>>(dim);
        analytical_solution->parse_parameters(prm);
        prm.leave_subsection();
      }
      prm.leave_subsection();

      prm.enter_subsection("Linear solver");
      linear_solver.parse_parameters(prm);
      prm.leave_subsection();

      prm.enter_subsection("Output");
      output.parse_parameters(prm);
      summary_file   = prm.get("Summary file");
      node_data_file = prm.get("Node data file");
      prm.leave_subsection();
      summary.dim             = dim;
      summary.problem_type    = problem_name;
      summary.model           = model_name;
      summary.partial_volumes = algorithm_name;
      summary.operator_type =
        linear_solver.is_matrix_free() ? "matrix-free" : "assembled";
      summary.preconditioner = linear_solver.preconditioner_name();
      if (const unsigned int c =
            linear_solver.preconditioner().local_matrix_coarsening();
          c > 1)
        summary.preconditioner += " (coarsening " + std::to_string(c) + ")";

      const bool scheme_supported =
        quadrature_scheme->hybrid() != nullptr ?
          problem->supports_hybrid() :
          quadrature_scheme->collocation() == nullptr ||
            problem->supports_collocation();
      AssertThrow(scheme_supported,
                  ExcInvalidInput(
                    "Quadrature/Scheme",
                    quadrature_scheme_name,
                    "the problem type '" + problem_name +
                      "' does not support this quadrature scheme yet "
                      "('collocation': quasi-static and diffusion; 'hybrid': "
                      "explicit dynamics, diffusion, and quasi-static with "
                      "a fixed standard region); use 'Scheme = standard'" +
                      std::string(problem->supports_hybrid() ?
                                    ", or 'hybrid' (collocation nodes that "
                                    "switch to standard where bonds near "
                                    "failure)" :
                                    "")));
      problem->check_input(*this);
      check_unused_entries(prm);
    }


#define PERIDEAL_INSTANTIATE(dim)                                          \
  template void Simulator<dim>::declare_parameters(ParameterHandler &prm); \
  template void Simulator<dim>::parse_parameters(ParameterHandler &prm);
    PERIDEAL_INSTANTIATE(1)
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
  } // namespace Problems
} // namespace PeriDEAL
