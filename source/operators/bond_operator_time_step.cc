// BondOperator's stable time step: the largest eigenvalue of M^-1 K, bounded
// by Gershgorin's theorem and estimated by the power method.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <algorithm>
#include <cmath>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    double
    BondOperator<dim>::gershgorin_eigenvalue_bound(const double density) const
    {
      // Gershgorin's theorem for M^{-1} K, with |K_rc| bounded term by term:
      // F_i = sum_j n_ij [a_ij (t_i + t_j) + b_ij (s_i + s_j) e_ij], t_i =
      // s_i theta_i = s_i sum_k g_ik n_ik . (u_k - u_i). The coefficients
      // of t_i sum in absolute value to A_i = 2 s_i sum_k |g_ik| |n_ik|_1;
      // row (i, c) of K sums to at most
      //   sum_j [2 |b_ij| (s_i + s_j) |n_c| |n|_1 + |a_ij| |n_c| A_j]
      //   + |sum_j a_ij n_c| A_i.
      const unsigned int  n = nodes->size();
      std::vector<double> A(n, 0.);
      // (for_each_bond_constants() reads a box offset per stencil offset.)
      std::vector<std::ptrdiff_t> no_delta(layout.use_lattice ?
                                             stencil.g.size() :
                                             0,
                                           0);
      if (state_based)
        for (const unsigned int list : {0u, 1u})
          {
            // Theta work list: stencil chunks and list nodes.
            const auto add = [&](const unsigned int i) {
              double sum = 0;
              for_each_bond_constants(i,
                                      0,
                                      no_delta,
                                      [&](const std::size_t,
                                          const std::ptrdiff_t,
                                          const double *nv,
                                          const double  g,
                                          const double,
                                          const double) {
                                        double norm1 = 0;
                                        for (unsigned int d = 0; d < dim; ++d)
                                          norm1 += std::abs(nv[d]);
                                        sum += std::abs(g) * norm1;
                                      });
              A[i] = 2 * std::abs(s_slot[layout.slot[i]]) * sum;
            };
            // Threaded: each node writes its own A_i.
            if (list == 0)
              parallel::apply_to_subranges(
                std::size_t(0),
                theta_work().chunks.size(),
                [&](const std::size_t begin, const std::size_t end) {
                  for (std::size_t c = begin; c < end; ++c)
                    {
                      const auto &chunk = theta_work().chunks[c];
                      for (unsigned int l = 0; l < chunk.length; ++l)
                        add(layout.node_of_slot(chunk.first_slot + l));
                    }
                },
                16);
            else
              parallel::apply_to_subranges(
                std::size_t(0),
                theta_work().list_nodes.size(),
                [&](const std::size_t begin, const std::size_t end) {
                  for (std::size_t b = begin; b < end; ++b)
                    add(theta_work().list_nodes[b]);
                },
                256);
          }
      // Threaded over the owned nodes: each writes the largest of its own
      // rows (a maximum: the same whatever the split).
      std::vector<double> node_largest(nodes->n_owned(), 0.);
      const auto          row_bound = [&](const unsigned int i) {
        double largest = 0;
        {
          const double s_i      = s_slot[layout.slot[i]];
          double       row[dim] = {}, C[dim] = {};
          for_each_bond_constants(
            i,
            0,
            no_delta,
            [&](const std::size_t slot_j,
                const std::ptrdiff_t,
                const double *nv,
                const double,
                const double a,
                const double b) {
              const unsigned int j     = layout.node_of_slot(slot_j);
              double             norm1 = 0;
              for (unsigned int d = 0; d < dim; ++d)
                norm1 += std::abs(nv[d]);
              const double s_j = s_slot[slot_j];
              for (unsigned int c = 0; c < dim; ++c)
                {
                  // |b (s_i + s_j)| = |b| |s_i + s_j|
                  // to the bit.
                  row[c] +=
                    2 * std::abs(BondKernel::extension_stiffness(b, s_i, s_j)) *
                    std::abs(nv[c]) * norm1;
                  if (state_based)
                    {
                      row[c] += std::abs(a) * std::abs(nv[c]) * A[j];
                      C[c] += a * nv[c];
                    }
                }
            });
          for (unsigned int c = 0; c < dim; ++c)
            largest = std::max(largest,
                               (row[c] + std::abs(C[c]) * A[i]) /
                                 (density * (*nodes)[i].volume()));
          // A collocation row: K_ii = sum_k W_k, K_ij = -W_k (times V).
          if (is_collocation_node(i))
            for (unsigned int c = 0; c < dim; ++c)
              {
                double sum = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    sum += std::abs(collocation_row.sum[c][d]);
                    for (const double w : collocation_row.w[c * dim + d])
                      sum += std::abs(w);
                  }
                largest =
                  std::max(largest, sum / (density * (*nodes)[i].volume()));
              }
        }
        node_largest[i] = largest;
      };
      parallel::apply_to_subranges(
        0u,
        nodes->n_owned(),
        [&](const unsigned int begin, const unsigned int end) {
          for (unsigned int i = begin; i < end; ++i)
            row_bound(i);
        },
        1024);
      double largest = 0;
      for (const double value : node_largest)
        largest = std::max(largest, value);
      return Utilities::MPI::max(largest, nodes->get_communicator());
    }


    template <int dim>
    double
    BondOperator<dim>::estimate_largest_eigenvalue(
      const double       density,
      const unsigned int n_iterations) const
    {
      // Power method on M^{-1} K (K x = -F(x) of the linearised kernel of
      // the intact bonds, whatever the kinematics of apply(), and of the
      // collocation rows), with the
      // Rayleigh quotient x.Kx / x.Mx in the M inner product.
      VectorType x, y;
      initialize_dof_vector(x);
      initialize_dof_vector(y);
      const unsigned int n_owned = nodes->n_owned();
      for (unsigned int i = 0; i < n_owned; ++i)
        for (unsigned int c = 0; c < dim; ++c)
          x.local_element(layout.vector_index[i] + c) =
            std::sin(1.3 * (*nodes)[i].dofs[c] + 0.2) +
            0.5 * std::cos(0.37 * (*nodes)[i].dofs[c]);
      const MPI_Comm comm   = nodes->get_communicator();
      double         lambda = 0;
      for (unsigned int it = 0; it < n_iterations; ++it)
        {
          x.update_ghost_values();
          copy_in(x);
          if (state_based)
            dilatation_pass();
          force_pass();
          // The collocation rows (the force pass skips their nodes).
          if (has_collocation_rows())
            collocation_pass();
          double xkx = 0, xmx = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            {
              const double mass = density * (*nodes)[i].volume();
              for (unsigned int c = 0; c < dim; ++c)
                {
                  const double xi = x.local_element(layout.vector_index[i] + c);
                  const double ky = -f_slot[c][layout.slot[i]];
                  xkx += xi * ky;
                  xmx += xi * mass * xi;
                  y.local_element(layout.vector_index[i] + c) = ky / mass;
                }
            }
          xkx    = Utilities::MPI::sum(xkx, comm);
          xmx    = Utilities::MPI::sum(xmx, comm);
          lambda = xmx > 0 ? xkx / xmx : 0;
          // Normalise in the M norm.
          double ymy = 0;
          for (unsigned int i = 0; i < n_owned; ++i)
            for (unsigned int c = 0; c < dim; ++c)
              ymy += density * (*nodes)[i].volume() *
                     std::pow(y.local_element(layout.vector_index[i] + c), 2);
          ymy = Utilities::MPI::sum(ymy, comm);
          if (!(ymy > 0))
            break;
          const double scale = 1. / std::sqrt(ymy);
          for (unsigned int i = 0; i < n_owned; ++i)
            for (unsigned int c = 0; c < dim; ++c)
              x.local_element(layout.vector_index[i] + c) =
                y.local_element(layout.vector_index[i] + c) * scale;
        }
      return lambda;
    }
    template double
    BondOperator<2>::gershgorin_eigenvalue_bound(const double) const;
    template double
    BondOperator<3>::gershgorin_eigenvalue_bound(const double) const;
    template double
    BondOperator<2>::estimate_largest_eigenvalue(const double,
                                                 const unsigned int) const;
    template double
    BondOperator<3>::estimate_largest_eigenvalue(const double,
                                                 const unsigned int) const;
  } // namespace Operators
} // namespace PeriDEAL
