/**
 * @file
 * The linear solves of the diffusion problem type (implicit steps and the
 * steady state): solve() on the free nodes with the prescribed values
 * lifted to the right-hand side, by CG (GMRES where the operator is not
 * symmetric) preconditioned by Jacobi or by algebraic multigrid on the
 * local Laplacian that setup_local_laplacian() assembles.
 */

#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <perideal/base/exceptions.h>
#include <perideal/problems/diffusion.h>
#include <perideal/problems/diffusion/instantiate.h>
#include <perideal/solvers/amg.h>
#include <perideal/solvers/krylov.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    namespace
    {
      /**
       * alpha x - beta L x on the free nodes, the identity on the
       * prescribed ones (whose values do not enter the free rows: they are
       * lifted to the right-hand side).
       */
      template <int dim>
      struct SystemOperator
      {
        using VectorType = LinearAlgebra::distributed::Vector<double>;
        const Operators::DiffusionOperator<dim> &op;
        const std::vector<bool>                 &is_prescribed;
        double                                   alpha, beta;
        mutable VectorType                       tmp, result;

        void
        vmult(VectorType &dst, const VectorType &src) const
        {
          const unsigned int n = src.locally_owned_size();
          for (unsigned int k = 0; k < n; ++k)
            tmp.local_element(k) = is_prescribed[k] ? 0. : src.local_element(k);
          tmp.update_ghost_values();
          op.apply(tmp, result);
          tmp.zero_out_ghost_values();
          for (unsigned int k = 0; k < n; ++k)
            dst.local_element(k) =
              is_prescribed[k] ?
                src.local_element(k) :
                alpha * src.local_element(k) - beta * result.local_element(k);
        }
      };


    } // namespace


    template <int dim>
    unsigned int
    Diffusion<dim>::solve(Simulator<dim>   &simulator,
                          const double      alpha,
                          const double      beta,
                          const VectorType &b,
                          VectorType       &x)
    {
      // Lift the prescribed values: b_free += beta (L g)_free, g the
      // prescribed values (zero elsewhere).
      VectorType lifted(b), g;
      op.initialize_vector(g);
      const unsigned int n = x.locally_owned_size();
      for (unsigned int k = 0; k < n; ++k)
        if (is_prescribed[k])
          g.local_element(k) = x.local_element(k);
      g.update_ghost_values();
      op.apply(g, lc);
      for (unsigned int k = 0; k < n; ++k)
        lifted.local_element(k) =
          is_prescribed[k] ? x.local_element(k) :
                             b.local_element(k) + beta * lc.local_element(k);

      SystemOperator<dim> system{op, is_prescribed, alpha, beta, {}, {}};
      op.initialize_vector(system.tmp);
      op.initialize_vector(system.result);
      x.zero_out_ghost_values();
      check_solve_input(simulator, b, lifted, x);
      const double  norm = lifted.l2_norm();
      SolverControl control(max_iterations, std::max(tolerance * norm, 1e-300));
      const MPI_Comm comm = simulator.get_communicator();
      try
        {
          if (norm == 0)
            x = 0;
          else
            {
              // CG where the operator is symmetric, GMRES (deal.II's
              // defaults: left-preconditioned, 30 vectors) where not.
              const Solvers::Method method = op.is_symmetric() ?
                                               Solvers::Method::cg :
                                               Solvers::Method::gmres;
              const typename SolverGMRES<VectorType>::AdditionalData gmres;
              if (local_laplacian)
                Solvers::run_krylov(method,
                                    gmres,
                                    control,
                                    system,
                                    x,
                                    lifted,
                                    *amg);
              else
                {
                  VectorType inverse_diagonal;
                  op.initialize_vector(inverse_diagonal);
                  for (unsigned int k = 0; k < n; ++k)
                    inverse_diagonal.local_element(k) =
                      is_prescribed[k] ?
                        1. :
                        1. / (alpha + beta * row_sum.local_element(k));
                  const DiagonalMatrix<VectorType> jacobi(inverse_diagonal);
                  Solvers::run_krylov(method,
                                      gmres,
                                      control,
                                      system,
                                      x,
                                      lifted,
                                      jacobi);
                }
            }
        }
      catch (const SolverControl::NoConvergence &e)
        {
          if (!std::isfinite(e.last_residual))
            check_solve_result(simulator, false, e.last_residual, x);
          AssertThrow(false,
                      ExcMessage(
                        "The linear solve of step " +
                        std::to_string(step_number + 1) + " (t = " +
                        format_number(time) + ") did not converge: residual " +
                        format_number(e.last_residual) + " after " +
                        std::to_string(e.last_step) + " iterations, " +
                        "target " + format_number(control.tolerance()) +
                        ". Raise 'diffusion/Maximum iterations', use "
                        "'Preconditioner = local laplacian', or a shorter "
                        "'Time step'. The output written before is "
                        "complete."));
        }
      (void)comm;
      if (norm == 0)
        return 0; // no iteration: last_step() would be invalid_unsigned_int
      check_solve_result(simulator,
                         control.last_check() == SolverControl::success,
                         control.last_value(),
                         x);
      return control.last_step();
    }


    template <int dim>
    void
    Diffusion<dim>::setup_local_laplacian(Simulator<dim> &simulator,
                                          const double    alpha,
                                          const double    beta)
    {
      // alpha I - beta K Delta_h on the free nodes, Delta_h the cell-centred
      // finite-volume Laplacian (2 dim + 1 points, no flux across the
      // outer boundary); identity rows and no columns for the prescribed
      // nodes, so that the matrix stays symmetric. At wavelengths above
      // the horizon L behaves like K Delta (flux matching), below it the
      // PD symbol saturates: spectrally equivalent at fixed m-ratio.
      TimerOutput::Scope scope(simulator.get_timer(), "local Laplacian");
      const auto        &lattice = simulator.get_neighbor_lists().lattice();
      const MPI_Comm     comm    = simulator.get_communicator();
      AssertThrow(lattice.is_uniform(),
                  ExcInvalidInput(section + "/Preconditioner",
                                  "local laplacian",
                                  "the local Laplacian needs a uniform grid; "
                                  "use 'jacobi' on this mesh"));
      // Whether each node of the set (ghosts too) is prescribed.
      VectorType flag;
      op.initialize_vector(flag);
      for (const auto i : prescribed_nodes)
        flag.local_element(op.vector_index(i)) = 1;
      flag.update_ghost_values();
      const auto prescribed = [&](const unsigned int i) {
        return flag.local_element(op.vector_index(i)) != 0;
      };
      const auto global = [&](const unsigned int i) {
        return (*nodes)[i].dofs[0] / dim;
      };
      const IndexSet &owned = op.get_partitioner()->locally_owned_range();
      const double    a =
        beta * kernel.diffusivity() / (lattice.spacing() * lattice.spacing());
      TrilinosWrappers::SparsityPattern pattern(owned, comm, 2 * dim + 1);
      std::vector<std::vector<std::pair<types::global_dof_index, double>>> rows(
        nodes->n_owned());
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          auto &row = rows[i];
          if (prescribed(i))
            {
              row.emplace_back(global(i), 1.);
              continue;
            }
          double diagonal = alpha;
          for (unsigned int d = 0; d < dim; ++d)
            for (const int side : {-1, 1})
              {
                auto y = lattice.coordinates(i);
                y[d] += side;
                const int j = lattice.node_at(y);
                if (j < 0)
                  continue;
                diagonal += a;
                if (!prescribed(j))
                  row.emplace_back(global(j), -a);
              }
          row.emplace_back(global(i), diagonal);
        }
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        for (const auto &entry : rows[i])
          pattern.add(global(i), entry.first);
      pattern.compress();
      laplacian = std::make_unique<TrilinosWrappers::SparseMatrix>();
      laplacian->reinit(pattern);
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        for (const auto &entry : rows[i])
          laplacian->set(global(i), entry.first, entry.second);
      laplacian->compress(VectorOperation::insert);
      amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      Solvers::initialize_amg(*amg, *laplacian, amg_settings, {});
    }


#define PERIDEAL_INSTANTIATE(dim)                                               \
  template unsigned int Diffusion<dim>::solve(Simulator<dim> &,                 \
                                              const double,                     \
                                              const double,                     \
                                              const VectorType &,               \
                                              VectorType &);                    \
  template void         Diffusion<dim>::setup_local_laplacian(Simulator<dim> &, \
                                                      const double,     \
                                                      const double);
    PERIDEAL_DIFFUSION_INSTANTIATE(PERIDEAL_INSTANTIATE)
#undef PERIDEAL_INSTANTIATE
  } // namespace Problems
} // namespace PeriDEAL
