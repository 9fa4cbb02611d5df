#include <deal.II/base/timer.h>

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/base/memory_guard.h>
#include <perideal/solvers/linear_solver.h>

#include <Amesos_Mumps.h>
#include <Epetra_LinearProblem.h>

#include <cmath>
#include <memory>
#include <sstream>

namespace PeriDEAL
{
  namespace Solvers
  {
    namespace
    {
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
        const double needed    = mumps.GetINFO()[14];
        const double available = capped_available_memory_mb_per_process(comm);
        const bool   fits      = fits_in_memory(needed, available);
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

      /// The registered preconditioners that support @p form, quoted, as
      /// "'a', 'b' or 'c'".
      std::string
      names_supporting(const OperatorForm form)
      {
        std::vector<std::string> names;
        for (const auto &name : PreconditionerRegistry::names())
          if (PreconditionerRegistry::create(name)->supports(form))
            names.push_back("'" + name + "'");
        std::string list;
        for (unsigned int k = 0; k < names.size(); ++k)
          list += (k == 0                ? "" :
                   k + 1 == names.size() ? " or " :
                                           ", ") +
                  names[k];
        return list;
      }


      /**
       * Stop on a Trilinos solver that threw @p exc: @p explanation (what
       * failed, its common causes and the fixes), followed by what Trilinos
       * said.
       */
      void
      throw_trilinos_failure(const dealii::ExceptionBase &exc,
                             const std::string           &explanation)
      {
        std::ostringstream original;
        exc.print_info(original);
        AssertThrow(false,
                    ExcMessage(explanation +
                               "Trilinos said: " + original.str()));
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


    Method
    method_from_name(const std::string &name)
    {
      if (name == "direct")
        return Method::direct;
      if (name == "CG")
        return Method::cg;
      if (name == "GMRES")
        return Method::gmres;
      AssertThrow(name == "BiCGStab",
                  ExcInvalidInput("Linear solver/Method",
                                  name,
                                  "choose direct, CG, GMRES or BiCGStab"));
      return Method::bicgstab;
    }


    std::string
    name_of(const Method method)
    {
      switch (method)
        {
          case Method::direct:
            return "direct";
          case Method::cg:
            return "CG";
          case Method::gmres:
            return "GMRES";
          case Method::bicgstab:
            return "BiCGStab";
        }
      return "";
    }


    LinearSolver::LinearSolver()
      : preconditioner_object(PreconditionerRegistry::create("AMG"))
    {}


    LinearSolver::~LinearSolver() = default;


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
      std::string help =
        "Preconditioner of the Krylov methods, a plugin; its parameters are "
        "in the subsection of its name. The registered ones:";
      for (const auto &name : PreconditionerRegistry::names())
        help += " '" + name + "': " + PreconditionerRegistry::description(name);
      prm.declare_entry("Preconditioner",
                        "AMG",
                        Patterns::Selection(
                          PreconditionerRegistry::pattern_string()),
                        help);
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
      AmgSettings::declare_parameters(prm, "1e-4");
      PreconditionerRegistry::declare_parameters(prm);
    }


    void
    LinearSolver::parse_parameters(ParameterHandler &prm)
    {
      method_value            = method_from_name(prm.get("Method"));
      direct_package          = prm.get("Direct solver package");
      preconditioner_selected = prm.get("Preconditioner");
      tolerance               = prm.get_double("Relative tolerance");
      max_iterations          = prm.get_integer("Maximum iterations");
      restart_length          = prm.get_integer("GMRES restart length");
      amg.parse_parameters(prm);
      matrix_free = prm.get("Operator") == "matrix-free";
      preconditioner_object =
        PreconditionerRegistry::create(preconditioner_selected, prm);
      if (matrix_free)
        {
          AssertThrow(method_value != Method::direct,
                      ExcInvalidInput(
                        "Linear solver/Method",
                        "direct",
                        "a direct solver factorises a matrix, and "
                        "'Linear solver/Operator = matrix-free' builds none: "
                        "use 'Method = CG' (or GMRES), or 'Operator = "
                        "assembled'"));
          AssertThrow(preconditioner_object->supports(
                        OperatorForm::matrix_free),
                      ExcInvalidInput(
                        "Linear solver/Preconditioner",
                        preconditioner_selected,
                        "'" + preconditioner_selected +
                          "' needs the assembled PD matrix, and 'Linear "
                          "solver/Operator = matrix-free' builds none: use " +
                          names_supporting(OperatorForm::matrix_free) +
                          ", or 'Operator = assembled'"));
        }
      else
        AssertThrow(preconditioner_object->supports(OperatorForm::assembled),
                    ExcInvalidInput(
                      "Linear solver/Preconditioner",
                      preconditioner_selected,
                      "'" + preconditioner_selected +
                        "' is a preconditioner of the matrix-free operator: "
                        "set 'Linear solver/Operator = matrix-free', or use " +
                        names_supporting(OperatorForm::assembled) +
                        " on the assembled matrix"));
      AssertThrow(tolerance > 0 && tolerance < 1,
                  ExcInvalidInput("Linear solver/Relative tolerance",
                                  prm.get("Relative tolerance"),
                                  "give a relative tolerance above 0 (round-"
                                  "off makes 0 unreachable) and below 1, for "
                                  "instance 1e-10"));
    }


    Method
    LinearSolver::method() const
    {
      return method_value;
    }


    std::string
    LinearSolver::method_name() const
    {
      return name_of(method_value);
    }


    bool
    LinearSolver::is_matrix_free() const
    {
      return matrix_free;
    }


    const Preconditioner &
    LinearSolver::preconditioner() const
    {
      return *preconditioner_object;
    }


    const std::string &
    LinearSolver::preconditioner_name() const
    {
      return preconditioner_selected;
    }


    void
    LinearSolver::check_form(const OperatorForm form,
                             const bool         symmetric,
                             const std::string &owner) const
    {
      // (The direct method needs no symmetry, and parse_parameters()
      // already refused it for the matrix-free forms.)
      AssertThrow(symmetric || method_value != Method::cg,
                  ExcInvalidInput("Linear solver/Method",
                                  method_name(),
                                  owner + " gives a non-symmetric system: " +
                                    (form == OperatorForm::assembled ?
                                       "use GMRES, BiCGStab or the direct "
                                       "solver" :
                                       "with 'Operator = matrix-free' use "
                                       "GMRES or BiCGStab")));
      AssertThrow(preconditioner_object->supports(form),
                  ExcInvalidInput("Linear solver/Preconditioner",
                                  preconditioner_selected,
                                  "with the " + name_of(form) + " of " + owner +
                                    " choose " + names_supporting(form)));
    }


    const Preconditioner &
    LinearSolver::setup_preconditioner(const OperatorForm    form,
                                       PreconditionerSetup &&setup) const
    {
      Assert(preconditioner_object->supports(form), ExcInternalError());
      setup.amg = amg;
      preconditioner_object->initialize(form, setup);
      return *preconditioner_object;
    }


    void
    LinearSolver::release_preconditioner() const
    {
      preconditioner_object->clear();
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
      internal::check_finite_rhs(rhs_norm, method_name());
      if (rhs_norm == 0)
        {
          // A = 0 right-hand side: the solution is zero, and a relative
          // residual is meaningless.
          solution      = 0;
          report.method = method_name();
          return report;
        }

      if (method_value == Method::direct)
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
                  throw_trilinos_failure(
                    exc,
                    "The direct solver (" + report.method + ") failed on " +
                      std::to_string(matrix.m()) + " unknowns with " +
                      std::to_string(matrix.n_nonzero_elements()) +
                      " nonzeros: the matrix is singular (a rigid motion "
                      "that no Dirichlet condition fixes) or the "
                      "factorisation ran out of memory. Check 'Boundary "
                      "conditions/Dirichlet boundary ids', or use 'Linear "
                      "solver/Operator = matrix-free' with 'Method = CG'. ");
                }
            }
          report.iterations = 1;
        }
      else
        {
          AssertThrow(method_value != Method::cg || symmetric,
                      ExcInvalidInput("Linear solver/Method",
                                      method_name(),
                                      "this system is not symmetric; use "
                                      "GMRES, BiCGStab or direct"));
          report.method = method_name() + " + " + preconditioner_selected;
          PreconditionerSetup setup;
          setup.matrix         = &matrix;
          setup.constant_modes = constant_modes;
          const TrilinosWrappers::PreconditionBase &precondition =
            setup_preconditioner(OperatorForm::assembled, std::move(setup))
              .trilinos_preconditioner();

          SolverControl control(max_iterations, tolerance * rhs_norm);
          try
            {
              try
                {
                  if (method_value == Method::cg)
                    {
                      TrilinosWrappers::SolverCG solver(control);
                      solver.solve(matrix, solution, rhs, precondition);
                    }
                  else if (method_value == Method::gmres)
                    {
                      TrilinosWrappers::SolverGMRES solver(
                        control,
                        TrilinosWrappers::SolverGMRES::AdditionalData(
                          false,
                          restart_length));
                      solver.solve(matrix, solution, rhs, precondition);
                    }
                  else
                    {
                      TrilinosWrappers::SolverBicgstab solver(control);
                      solver.solve(matrix, solution, rhs, precondition);
                    }
                }
              catch (const SolverControl::NoConvergence &)
                {
                  throw;
                }
              catch (const dealii::ExceptionBase &exc)
                {
                  // AztecOO reports breakdowns as error codes.
                  throw_trilinos_failure(
                    exc,
                    "The Krylov solver (" + report.method +
                      ") broke down. Common causes: a singular system (a "
                      "rigid motion that no Dirichlet condition fixes), a "
                      "preconditioner that does not suit the matrix (try "
                      "'Linear solver/Preconditioner = AMG' or ILU, or "
                      "'Method = GMRES' for non-symmetric systems), or a "
                      "'Relative tolerance' below round-off. ");
                }
            }
          catch (const SolverControl::NoConvergence &e)
            {
              AssertThrow(false,
                          ExcNoConvergence(
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
          release_preconditioner();
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
      AssertThrow(method_value != Method::direct ||
                    report.relative_residual <= 1e-6,
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
