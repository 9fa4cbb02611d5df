#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/solvers/linear_solver.h>

#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>

namespace PeriDEAL
{
  namespace Solvers
  {
    namespace
    {
      /// MemAvailable of this host divided among the processes on it, in MB
      /// (0 where /proc/meminfo is missing), or the environment variable
      /// PERIDEAL_MEMORY_LIMIT_MB (per process) where it is set and smaller:
      /// a cap for shared machines.
      double
      available_mb_per_process(const MPI_Comm comm)
      {
        double        available = 0, kb = 0;
        std::string   key, unit;
        std::ifstream meminfo("/proc/meminfo");
        while (meminfo >> key >> kb >> unit)
          if (key == "MemAvailable:")
            {
              available = kb / 1024;
              break;
            }
        MPI_Comm host;
        MPI_Comm_split_type(comm,
                            MPI_COMM_TYPE_SHARED,
                            0,
                            MPI_INFO_NULL,
                            &host);
        const unsigned int on_host =
          dealii::Utilities::MPI::n_mpi_processes(host);
        MPI_Comm_free(&host);
        available /= on_host;
        if (const char *limit = std::getenv("PERIDEAL_MEMORY_LIMIT_MB"))
          {
            const double cap = std::atof(limit);
            if (cap > 0 && (available <= 0 || cap < available))
              available = cap;
          }
        return available;
      }

      /**
       * Solve with MUMPS through Amesos, in its three phases, so that the
       * analysis's memory estimate (INFO(15), MB per process) is checked
       * against the memory available before the factorisation allocates
       * it, and MUMPS's error codes (INFOG(1)) are translated. Every check
       * is shared by all processes before anyone throws.
       */
      void
      solve_with_mumps(const TrilinosWrappers::SparseMatrix &matrix,
                       TrilinosWrappers::MPI::Vector        &solution,
                       const TrilinosWrappers::MPI::Vector  &rhs)
      {
        const MPI_Comm       comm = matrix.get_mpi_communicator();
        Epetra_LinearProblem problem(
          const_cast<Epetra_CrsMatrix *>(&matrix.trilinos_matrix()),
          &solution.trilinos_vector(),
          const_cast<Epetra_MultiVector *>(
            static_cast<const Epetra_MultiVector *>(&rhs.trilinos_vector())));
        Amesos_Mumps      mumps(problem);
        const std::string size = std::to_string(matrix.m()) + " unknowns and " +
                                 std::to_string(matrix.n_nonzero_elements()) +
                                 " nonzeros";
        const std::string fix =
          "use 'Linear solver/Operator = matrix-free' with 'Method = CG' "
          "(GMRES for the layer treatments) and a preconditioner, which "
          "needs no factors";
        const auto error_of = [&](const int code) {
          // MUMPS's INFO(1) where Amesos reported a failure (-1 if MUMPS
          // itself did not), the most negative over the processes.
          const int local  = code == 0 ? 0 : std::min(mumps.GetINFO()[0], -1);
          const int infog1 = dealii::Utilities::MPI::min(local, comm);
          if (infog1 == 0)
            return std::string();
          if (infog1 == -10)
            return "The direct solver (MUMPS) found the matrix singular (" +
                   size +
                   "): a rigid motion is not fixed, or nodes have no bonds. "
                   "Check 'Boundary conditions/Dirichlet boundary ids' and "
                   "'Dirichlet components'.";
          if (infog1 == -8 || infog1 == -9 || infog1 == -13 || infog1 == -14 ||
              infog1 == -19 || infog1 == -20)
            return "The direct solver (MUMPS) ran out of memory (" + size +
                   "; MUMPS error " + std::to_string(infog1) +
                   "): the factors of PD matrices are nearly dense; " + fix +
                   ".";
          return "The direct solver (MUMPS) failed with error INFOG(1) = " +
                 std::to_string(infog1) + " (" + size + "); " + fix +
                 ", or see the MUMPS manual for the code.";
        };

        throw_on_any_rank(error_of(mumps.SymbolicFactorization()), comm);
        // INFO(15): MB this process needs for the numerical phases.
        const double needed       = mumps.GetINFO()[14];
        const double available    = available_mb_per_process(comm);
        const bool   fits         = available <= 0 || needed <= 0.9 * available;
        const double total_needed = dealii::Utilities::MPI::sum(needed, comm);
        throw_on_any_rank(
          fits ?
            std::string() :
            "Invalid value 'direct' for the parameter 'Linear "
            "solver/Method': the direct solver (MUMPS) would need an "
            "estimated " +
              format_number(total_needed) + " MB for its factors (" + size +
              "), " + format_number(needed) + " MB on a process that has " +
              format_number(available) + " MB available; " + fix + ".",
          comm);
        throw_on_any_rank(error_of(mumps.NumericFactorization()), comm);
        throw_on_any_rank(error_of(mumps.Solve()), comm);
      }
    } // namespace


    namespace internal
    {
      void
      check_finite_rhs(const double rhs_norm, const std::string &method)
      {
        AssertThrow(std::isfinite(rhs_norm),
                    ExcMessage(
                      "The right-hand side of the linear system (" + method +
                      ") holds non-finite values (NaN or Inf), although the "
                      "loads and prescribed displacements are finite where "
                      "they are evaluated: the Dirichlet values lifted "
                      "through the stiffness overflow the range of double "
                      "precision numbers (about 1e308). Check the elastic "
                      "constants of 'Material model' and the magnitudes of "
                      "'Boundary conditions/Dirichlet displacement', 'Body "
                      "force' and 'Traction'."));
      }


      void
      check_solve_result(const bool         converged,
                         const double       last_residual,
                         const double       relative_residual,
                         const std::string &method)
      {
        AssertThrow(converged,
                    ExcMessage("The linear solver (" + method +
                               ") stopped at the residual " +
                               format_number(last_residual) +
                               " without converging, from a finite "
                               "right-hand side: the system overflows the "
                               "range of double precision numbers or is "
                               "singular. Check the elastic constants of "
                               "'Material model' and that the Dirichlet "
                               "conditions fix every rigid motion."));
        AssertThrow(std::isfinite(relative_residual),
                    ExcMessage("The linear solve (" + method +
                               ") produced non-finite values (NaN or Inf) "
                               "from a finite right-hand side: the system is "
                               "singular or overflows the range of double "
                               "precision numbers. Check that the Dirichlet "
                               "conditions fix every rigid motion (every "
                               "displacement component, and rotations), and "
                               "the elastic constants of 'Material model'."));
      }
    } // namespace internal


    void
    LinearSolver::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Operator",
        "assembled",
        Patterns::Selection("assembled|matrix-free"),
        "How the PD operator enters the solve. 'assembled': a Trilinos "
        "matrix (needed by the direct method, AMG on the PD matrix, SSOR and "
        "ILU; its memory grows like the number of nodes times the nodes "
        "within two horizons). 'matrix-free': the threaded bond loop applied "
        "in every iteration, no matrix (Krylov methods with 'Jacobi', "
        "'Chebyshev', 'local elasticity' or 'none').");
      prm.declare_entry(
        "Method",
        "direct",
        Patterns::Selection("direct|CG|GMRES|BiCGStab"),
        "How to solve the linear system. 'direct': a sparse LU/LDL^T "
        "factorisation through Trilinos Amesos (see 'Direct solver "
        "package'); robust, but its memory grows quickly with the number of "
        "nodes and with the m-ratio. 'CG': conjugate gradients, for "
        "symmetric positive definite systems (LPS and bond-based models with "
        "volumetric Dirichlet layers). 'GMRES' and 'BiCGStab': for "
        "non-symmetric systems.");
      prm.declare_entry("Direct solver package",
                        "MUMPS",
                        Patterns::Selection("MUMPS|KLU"),
                        "The Amesos package used by the direct method: "
                        "MUMPS (parallel multifrontal) or KLU (serial).");
      prm.declare_entry(
        "Preconditioner",
        "AMG",
        Patterns::Selection(
          "AMG|Jacobi|SSOR|ILU|Chebyshev|local elasticity|none"),
        "Preconditioner of the Krylov methods. With 'Operator = assembled': "
        "Trilinos ML algebraic multigrid on the PD matrix (with the rigid "
        "translations as near-null space), point Jacobi, SSOR, incomplete LU "
        "(Ifpack ILU(k) on each process, k = 'ILU fill level'), or none. "
        "With 'Operator = matrix-free': 'Jacobi' or 'Chebyshev' (degree "
        "'Chebyshev degree') on the exact diagonal, 'local elasticity' "
        "(ML multigrid on classical elasticity discretised on the same "
        "nodes, whose iteration counts stay bounded as h shrinks; uniform "
        "grids), or none.");
      prm.declare_entry("Chebyshev degree",
                        "4",
                        Patterns::Integer(1, 30),
                        "Degree of the Chebyshev polynomial preconditioner "
                        "(matrix-free operator).");
      prm.declare_entry("ILU fill level",
                        "1",
                        Patterns::Integer(0, 10),
                        "Level of fill k of the ILU(k) preconditioner.");
      prm.declare_entry("Relative tolerance",
                        "1e-10",
                        Patterns::Double(0),
                        "Krylov methods stop when |b - Ax| <= tolerance |b|. "
                        "A method that does not reach it is an error.");
      prm.declare_entry("Maximum iterations",
                        "10000",
                        Patterns::Integer(1),
                        "Iteration limit of the Krylov methods.");
      prm.declare_entry("GMRES restart length",
                        "200",
                        Patterns::Integer(1),
                        "Size of the Krylov space before GMRES restarts.");
      prm.declare_entry("AMG smoother sweeps",
                        "2",
                        Patterns::Integer(1),
                        "Chebyshev smoother sweeps per AMG level.");
      prm.declare_entry("AMG aggregation threshold",
                        "1e-4",
                        Patterns::Double(0),
                        "Entries below this fraction of the diagonal are "
                        "ignored when ML builds its aggregates. PD matrices "
                        "are dense within two horizons; values of 1e-4 to "
                        "1e-2 work.");
    }


    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      method_name      = prm.get("Method");
      direct_package   = prm.get("Direct solver package");
      preconditioner   = prm.get("Preconditioner");
      ilu_fill         = prm.get_integer("ILU fill level");
      tolerance        = prm.get_double("Relative tolerance");
      max_iterations   = prm.get_integer("Maximum iterations");
      restart_length   = prm.get_integer("GMRES restart length");
      smoother_sweeps  = prm.get_integer("AMG smoother sweeps");
      aggregation      = prm.get_double("AMG aggregation threshold");
      matrix_free      = prm.get("Operator") == "matrix-free";
      chebyshev_degree = prm.get_integer("Chebyshev degree");
      if (matrix_free)
        {
          AssertThrow(method_name != "direct",
                      ExcInvalidInput(
                        "Linear solver/Method",
                        method_name,
                        "a direct solver factorises a matrix, and "
                        "'Linear solver/Operator = matrix-free' builds none: "
                        "use 'Method = CG' (or GMRES), or 'Operator = "
                        "assembled'"));
          AssertThrow(
            preconditioner == "Jacobi" || preconditioner == "Chebyshev" ||
              preconditioner == "local elasticity" || preconditioner == "none",
            ExcInvalidInput("Linear solver/Preconditioner",
                            preconditioner,
                            "'" + preconditioner +
                              "' needs the assembled PD matrix, and 'Linear "
                              "solver/Operator = matrix-free' builds none: use "
                              "'local elasticity', 'Chebyshev' or 'Jacobi', or "
                              "'Operator = assembled'"));
        }
      else
        AssertThrow(preconditioner != "Chebyshev" &&
                      preconditioner != "local elasticity",
                    ExcInvalidInput(
                      "Linear solver/Preconditioner",
                      preconditioner,
                      "'" + preconditioner +
                        "' is a preconditioner of the matrix-free operator: "
                        "set 'Linear solver/Operator = matrix-free', or use "
                        "AMG, Jacobi, SSOR or ILU on the assembled matrix"));
      AssertThrow(tolerance > 0 && tolerance < 1,
                  ExcInvalidInput("Linear solver/Relative tolerance",
                                  prm.get("Relative tolerance"),
                                  "give a relative tolerance above 0 (round-"
                                  "off makes 0 unreachable) and below 1, for "
                                  "instance 1e-10"));
    }


    const std::string &
    LinearSolver::method() const
    {
      return method_name;
    }


    bool
    LinearSolver::is_matrix_free() const
    {
      return matrix_free;
    }


    const std::string &
    LinearSolver::preconditioner_name() const
    {
      return preconditioner;
    }


    SolverReport
    LinearSolver::solve(const TrilinosWrappers::SparseMatrix &matrix,
                        TrilinosWrappers::MPI::Vector        &solution,
                        const TrilinosWrappers::MPI::Vector  &rhs,
                        const std::vector<std::vector<bool>> &constant_modes,
                        const bool                            symmetric) const
    {
      Timer        timer;
      SolverReport report;
      const double rhs_norm = rhs.l2_norm();
      internal::check_finite_rhs(rhs_norm, method_name);
      if (rhs_norm == 0)
        {
          // A = 0 right-hand side: the solution is zero, and a relative
          // residual is meaningless.
          solution      = 0;
          report.method = method_name;
          return report;
        }

      if (method_name == "direct")
        {
          report.method = "direct (Amesos " + direct_package + ")";
          if (direct_package == "MUMPS")
            solve_with_mumps(matrix, solution, rhs);
          else
            {
              SolverControl                                  control(1, 0);
              TrilinosWrappers::SolverDirect::AdditionalData data(false,
                                                                  "Amesos_Klu");
              TrilinosWrappers::SolverDirect solver(control, data);
              try
                {
                  solver.solve(matrix, solution, rhs);
                }
              catch (const dealii::ExceptionBase &exc)
                {
                  std::ostringstream original;
                  exc.print_info(original);
                  AssertThrow(
                    false,
                    ExcMessage(
                      "The direct solver (" + report.method + ") failed on " +
                      std::to_string(matrix.m()) + " unknowns with " +
                      std::to_string(matrix.n_nonzero_elements()) +
                      " nonzeros: the matrix is singular (a rigid motion "
                      "that no Dirichlet condition fixes) or the "
                      "factorisation ran out of memory. Check 'Boundary "
                      "conditions/Dirichlet boundary ids', or use 'Linear "
                      "solver/Operator = matrix-free' with 'Method = CG'. "
                      "Trilinos said: " +
                      original.str()));
                }
            }
          report.iterations = 1;
        }
      else
        {
          AssertThrow(method_name != "CG" || symmetric,
                      ExcInvalidInput("Linear solver/Method",
                                      method_name,
                                      "this system is not symmetric; use "
                                      "GMRES, BiCGStab or direct"));
          report.method = method_name + " + " + preconditioner;

          std::unique_ptr<TrilinosWrappers::PreconditionBase> precondition;
          if (preconditioner == "AMG")
            {
              TrilinosWrappers::PreconditionAMG::AdditionalData data;
              data.elliptic              = true;
              data.constant_modes        = constant_modes;
              data.smoother_sweeps       = smoother_sweeps;
              data.aggregation_threshold = aggregation;
              auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
              amg->initialize(matrix, data);
              precondition = std::move(amg);
            }
          else if (preconditioner == "Jacobi")
            {
              auto jacobi =
                std::make_unique<TrilinosWrappers::PreconditionJacobi>();
              jacobi->initialize(matrix);
              precondition = std::move(jacobi);
            }
          else if (preconditioner == "ILU")
            {
              auto ilu = std::make_unique<TrilinosWrappers::PreconditionILU>();
              TrilinosWrappers::PreconditionILU::AdditionalData data;
              data.ilu_fill = ilu_fill;
              ilu->initialize(matrix, data);
              precondition = std::move(ilu);
            }
          else if (preconditioner == "SSOR")
            {
              auto ssor =
                std::make_unique<TrilinosWrappers::PreconditionSSOR>();
              ssor->initialize(matrix);
              precondition = std::move(ssor);
            }
          else
            precondition =
              std::make_unique<TrilinosWrappers::PreconditionIdentity>();

          SolverControl control(max_iterations, tolerance * rhs_norm);
          try
            {
              try
                {
                  if (method_name == "CG")
                    {
                      TrilinosWrappers::SolverCG solver(control);
                      solver.solve(matrix, solution, rhs, *precondition);
                    }
                  else if (method_name == "GMRES")
                    {
                      TrilinosWrappers::SolverGMRES solver(
                        control,
                        TrilinosWrappers::SolverGMRES::AdditionalData(
                          false,
                          restart_length));
                      solver.solve(matrix, solution, rhs, *precondition);
                    }
                  else
                    {
                      TrilinosWrappers::SolverBicgstab solver(control);
                      solver.solve(matrix, solution, rhs, *precondition);
                    }
                }
              catch (const SolverControl::NoConvergence &)
                {
                  throw;
                }
              catch (const dealii::ExceptionBase &exc)
                {
                  // AztecOO reports breakdowns as error codes.
                  std::ostringstream original;
                  exc.print_info(original);
                  AssertThrow(
                    false,
                    ExcMessage(
                      "The Krylov solver (" + report.method +
                      ") broke down. Common causes: a singular system (a rigid "
                      "motion that no Dirichlet condition fixes), a "
                      "preconditioner that does not suit the matrix (try "
                      "'Linear solver/Preconditioner = AMG' or ILU, or 'Method = "
                      "GMRES' for non-symmetric systems), or a 'Relative "
                      "tolerance' below round-off. Trilinos said: " +
                      original.str()));
                }
            }
          catch (const SolverControl::NoConvergence &e)
            {
              AssertThrow(false,
                          ExcMessage(
                            "The linear solver (" + report.method +
                            ") did not converge: after " +
                            std::to_string(e.last_step) +
                            " iterations the residual is " +
                            format_number(e.last_residual / rhs_norm) +
                            " of |b|, above the 'Relative tolerance' " +
                            format_number(tolerance) +
                            ". Raise 'Maximum iterations', change the "
                            "preconditioner, or use 'Method = direct'."));
            }
          report.iterations = control.last_step();
        }

      TrilinosWrappers::MPI::Vector residual(rhs);
      report.relative_residual =
        matrix.residual(residual, solution, rhs) / rhs_norm;
      // A direct solver "solves" a singular system too: its residual tells.
      internal::check_solve_result(true,
                                   0,
                                   report.relative_residual,
                                   report.method);
      AssertThrow(method_name != "direct" || report.relative_residual <= 1e-6,
                  ExcMessage("The direct solver (" + report.method +
                             ") returned a solution with relative residual " +
                             format_number(report.relative_residual) +
                             ": the system is singular or nearly so. Most "
                             "often a rigid motion is not fixed: list "
                             "'Boundary conditions/Dirichlet boundary ids' "
                             "whose layers fix every displacement component "
                             "('Dirichlet components') and the rotations."));
      report.seconds = timer.wall_time();
      return report;
    }
  } // namespace Solvers
} // namespace PeriDEAL
