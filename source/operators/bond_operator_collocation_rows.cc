// BondOperator: the collocation quadrature off the lattice (irregular nodes,
// 'Geometry/Node perturbation'; doc/collocation.md Sects. 6 and 11): a row
// per node, fitted to the node's own cloud, and its pass. On a uniform
// lattice the bulk shares one row instead (bond_operator_collocation.cc).

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <deal.II/lac/full_matrix.h>

#include <perideal/base/collective_checks.h>
#include <perideal/base/exceptions.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>
#include <perideal/quadrature/collocation.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <cmath>
#include <limits>
#include <sstream>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    typename BondOperator<dim>::CollocationReport
    BondOperator<dim>::use_collocation_per_node(
      const Quadrature::CollocationSettings &settings,
      const std::vector<bool>               &standard)
    {
      const unsigned int n_owned = nodes->n_owned();
      AssertThrow(!state_based,
                  ExcMessage("The collocation rows of state-based models "
                             "need a uniform grid of cubes (nodes at the "
                             "cell centres) so far; irregular nodes take "
                             "bond-based models."));
      // Rows per node take the stabilised form for order 2 as well: on
      // perturbed clouds the paper's C2 rows have node-local growing modes
      // (doc/collocation.md Sect. 7.2). A bad order-4 cloud takes an
      // order-2 row ('fall back').
      constexpr auto kind = Quadrature::CollocationSettings::RowKind::per_node;
      // The pair stiffness 2 beta(r) n (x) n; its trace over d weighs the
      // stabilisation term (doc/collocation.md Sect. 7.1).
      const auto stiffness = [&](const double r) {
        return 2. * model->extension_constant(r, horizon);
      };
      NodeRowFits<dim, Tensor<2, dim>> fits;
      const CollocationReport          report =
        fit_node_rows_with_fallback<dim, Tensor<2, dim>>(
          *nodes,
          *lists,
          horizon,
          settings,
          standard,
          [&](const Quadrature::CollocationSettings &pass,
              const Quadrature::CollocationFit<dim> &fit)
            -> RowOfFit<dim, Tensor<2, dim>> {
            const auto moments =
              Quadrature::tensor_moments<dim>(fit.basis(), stiffness, horizon);
            const double gamma = pass.stabilisation(kind);
            return [&, moments, gamma, basis = fit.basis()](
                     const unsigned int                 i,
                     const std::vector<Tensor<1, dim>> &cloud,
                     const FullMatrix<double>          &q) {
              std::vector<Tensor<2, dim>> row =
                Quadrature::tensor_row(moments, q);
              if (gamma > 0)
                Quadrature::add_stabilisation<dim>(row,
                                                   basis,
                                                   cloud,
                                                   q,
                                                   stiffness,
                                                   horizon,
                                                   gamma);
              for (auto &block : row)
                block *= (*nodes)[i].volume();
              return row;
            };
          },
          fits);

      collocation_node.assign(nodes->size(), 0);
      with_collocation = true;
      node_row_of.assign(nodes->size(), -1);
      node_rows = NodeRows();
      for (unsigned int i = 0; i < n_owned; ++i)
        if (fits.has_row[i])
          {
            collocation_node[i] = 1;
            node_row_of[i]      = node_rows.node.size();
            node_rows.node.push_back(i);
            for (unsigned int k = 0; k < fits.neighbors[i].size(); ++k)
              {
                node_rows.neighbor_slot.push_back(
                  layout.slot[fits.neighbors[i][k]]);
                for (unsigned int c = 0; c < dim; ++c)
                  for (unsigned int d = 0; d < dim; ++d)
                    node_rows.w.push_back(fits.weights[i][k][c][d]);
              }
            node_rows.first.push_back(node_rows.neighbor_slot.size());
          }
      build_work_lists();
      return report;
    }


    template <int dim>
    void
    BondOperator<dim>::node_rows_pass() const
    {
      // Each node in the order of its row (fixed by its cloud), the same on
      // every process and thread.
      parallel::apply_to_subranges(
        std::size_t(0),
        node_rows.node.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t r = begin; r < end; ++r)
            {
              const std::size_t si     = layout.slot[node_rows.node[r]];
              double            f[dim] = {};
              for (std::size_t e = node_rows.first[r];
                   e < node_rows.first[r + 1];
                   ++e)
                {
                  const std::size_t sj = node_rows.neighbor_slot[e];
                  const double     *w  = &node_rows.w[e * dim * dim];
                  for (unsigned int b = 0; b < dim; ++b)
                    {
                      const double du = u_slot[b][sj] - u_slot[b][si];
                      for (unsigned int a = 0; a < dim; ++a)
                        f[a] += w[a * dim + b] * du;
                    }
                }
              for (unsigned int a = 0; a < dim; ++a)
                f_slot[a][si] = f[a];
            }
        },
        64);
    }


#define PERIDEAL_INSTANTIATE(dim)                                           \
  template BondOperator<dim>::CollocationReport BondOperator<               \
    dim>::use_collocation_per_node(const Quadrature::CollocationSettings &, \
                                   const std::vector<bool> &);              \
  template void BondOperator<dim>::node_rows_pass() const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
