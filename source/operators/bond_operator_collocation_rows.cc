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
      const MPI_Comm     comm    = nodes->get_communicator();
      const unsigned int n_owned = nodes->n_owned();
      AssertThrow(!state_based,
                  ExcMessage("The collocation rows of state-based models "
                             "need a uniform grid of cubes (nodes at the "
                             "cell centres) so far; irregular nodes take "
                             "bond-based models."));
      const Quadrature::CollocationFit<dim> fit(settings.order,
                                                settings.n_collocation,
                                                horizon);
      const auto moments = Quadrature::tensor_moments<dim>(
        fit.basis(),
        [&](const double r) {
          return 2. * model->extension_constant(r, horizon);
        },
        horizon);
      const Quadrature::ExactPartialVolume<dim> exact;
      const double                              ball =
        (dim == 2 ? M_PI : 4. / 3. * M_PI) * std::pow(horizon, dim);

      // Per owned node: 0 collocation, 1 fixed standard, 2 ball cut,
      // 3 ill-conditioned cloud, 4 non-positive diagonal; the row, its
      // cond(A) and cloud size.
      std::vector<unsigned char>               status(n_owned, 1);
      std::vector<std::vector<unsigned int>>   row_nodes(n_owned);
      std::vector<std::vector<Tensor<2, dim>>> row_blocks(n_owned);
      std::vector<double>                      condition(n_owned, 0.);
      std::vector<unsigned int>                cloud_size(n_owned, 0);
      parallel::apply_to_subranges(
        0u,
        n_owned,
        [&](const unsigned int begin, const unsigned int end) {
          std::vector<Tensor<1, dim>> family, cloud;
          std::vector<unsigned int>   family_node;
          FullMatrix<double>          q;
          for (unsigned int i = begin; i < end; ++i)
            {
              if (i < standard.size() && standard[i])
                continue;
              const Point<dim> &x = (*nodes)[i].location;
              // The ball lies in the body and its layers when the exact
              // partial volumes of the cells fill it.
              double covered = exact.weight(x, horizon, (*nodes)[i].cell) *
                               (*nodes)[i].volume();
              family.assign(1, Tensor<1, dim>());
              family_node.assign(1, i);
              for (const auto &bond : lists->bonds(i))
                {
                  const auto &neighbor = (*nodes)[bond.neighbor];
                  covered +=
                    exact.weight(x, horizon, neighbor.cell) * neighbor.volume();
                  const Tensor<1, dim> xi = neighbor.location - x;
                  if (xi.norm() <= horizon * (1 + 1e-12))
                    {
                      family.push_back(xi);
                      family_node.push_back(bond.neighbor);
                    }
                }
              if (covered < ball * (1 - 1e-10))
                {
                  status[i] = 2;
                  continue;
                }
              const std::vector<unsigned int> selected = fit.select(family);
              cloud.clear();
              for (const unsigned int j : selected)
                cloud.push_back(family[j]);
              cloud_size[i] = cloud.size();
              condition[i]  = cloud.size() < fit.basis().size() ?
                                std::numeric_limits<double>::infinity() :
                                fit.fit(cloud, q);
              if (!(condition[i] <=
                    Quadrature::CollocationSettings::condition_limit))
                {
                  status[i] = 3;
                  continue;
                }
              const std::vector<Tensor<2, dim>> row =
                Quadrature::tensor_row(moments, q);
              const double   volume = (*nodes)[i].volume();
              Tensor<2, dim> sum;
              for (unsigned int k = 0; k < cloud.size(); ++k)
                {
                  const unsigned int j = family_node[selected[k]];
                  if (j == i)
                    continue;
                  row_nodes[i].push_back(j);
                  row_blocks[i].push_back(volume * row[k]);
                  sum += volume * row[k];
                }
              bool positive = true;
              for (unsigned int c = 0; c < dim; ++c)
                positive = positive && sum[c][c] > 0;
              status[i] = positive ? 0 : 4;
            }
        },
        16);

      CollocationReport report;
      report.n_monomials     = fit.basis().size();
      std::size_t  counts[5] = {};
      double       worst     = 0;
      unsigned int smallest  = std::numeric_limits<unsigned int>::max(),
                   largest   = 0;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          ++counts[status[i]];
          if (status[i] == 0 || status[i] == 3 || status[i] == 4)
            {
              smallest = std::min(smallest, cloud_size[i]);
              largest  = std::max(largest, cloud_size[i]);
            }
          if ((status[i] == 0 || status[i] == 3) && !(condition[i] <= worst))
            worst = condition[i];
        }
      // An order-2 row with a non-positive diagonal comes from a badly
      // shaped cloud (a heavily perturbed one): it falls back, or stops the
      // run, like an ill-conditioned one. Higher orders with such rows are
      // the order's fault (doc/collocation.md Sect. 7) and stop the run.
      int failed_node = -1;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          if (settings.order == 2 && status[i] == 4)
            status[i] = 3;
          if (status[i] == 3 && failed_node < 0)
            failed_node = i;
        }
      if (settings.order == 2)
        {
          counts[3] += counts[4];
          counts[4] = 0;
        }
      for (auto &count : counts)
        count = Utilities::MPI::sum(count, comm);
      report.n_collocation_nodes = counts[0];
      report.n_fixed_standard    = counts[1];
      report.n_cut_nodes         = counts[2];
      report.n_ill_conditioned   = counts[3];
      report.condition           = Utilities::MPI::max(worst, comm);
      report.n_collocation       = Utilities::MPI::max(largest, comm);
      report.n_collocation_min   = Utilities::MPI::min(smallest, comm);
      report.per_node            = true;
      // A node that failed (the first of the lowest process that has
      // one), for the error below.
      std::ostringstream where;
      if (failed_node >= 0)
        where << "(" << (*nodes)[failed_node].location << "), cond(A) "
              << format_number(condition[failed_node]);
      std::string position;
      for (const auto &w : Utilities::MPI::all_gather(comm, where.str()))
        if (position.empty())
          position = w;
      AssertThrow(
        counts[3] == 0 || settings.fall_back,
        ExcInvalidInput("Quadrature/collocation/Ill-conditioned clouds",
                        "error",
                        std::to_string(counts[3]) +
                          " nodes have a collocation cloud with cond(A) > 1e12 "
                          "or a row with a non-positive diagonal (one at " +
                          position +
                          "); choose another 'Collocation nodes', a smaller "
                          "'Geometry/Node perturbation', or 'fall back' to the "
                          "standard scheme at those nodes"));
      AssertThrow(
        counts[4] == 0,
        ExcInvalidInput("Quadrature/collocation/Order",
                        std::to_string(settings.order),
                        std::to_string(counts[4]) +
                          " nodes have a collocation row of this order with "
                          "a non-positive diagonal (the node weighs against "
                          "its neighbours, "
                          "doc/collocation.md Sect. 7): the static operator is "
                          "indefinite. Use 'Order = 2'"));

      collocation_node.assign(nodes->size(), 0);
      node_row_of.assign(nodes->size(), -1);
      node_rows = NodeRows();
      for (unsigned int i = 0; i < n_owned; ++i)
        if (status[i] == 0)
          {
            collocation_node[i] = 1;
            node_row_of[i]      = node_rows.node.size();
            node_rows.node.push_back(i);
            for (unsigned int k = 0; k < row_nodes[i].size(); ++k)
              {
                node_rows.neighbor_slot.push_back(layout.slot[row_nodes[i][k]]);
                for (unsigned int c = 0; c < dim; ++c)
                  for (unsigned int d = 0; d < dim; ++d)
                    node_rows.w.push_back(row_blocks[i][k][c][d]);
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
