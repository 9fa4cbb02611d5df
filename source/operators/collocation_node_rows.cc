// The collocation rows of single nodes (irregular nodes,
// 'Geometry/Node perturbation'; doc/collocation.md Sects. 6 and 11.1): the
// node-by-node fit that the elasticity (BondOperator) and the diffusion
// (DiffusionOperator) operators share.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/collocation_node_rows.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      // Whether the diagonal of a row (minus the sum of its neighbours'
      // weights) is positive: every diagonal entry of the sum of the
      // blocks, or the sum of the numbers.
      bool
      positive_diagonal(const double sum)
      {
        return sum > 0;
      }

      template <int dim>
      bool
      positive_diagonal(const Tensor<2, dim> &sum)
      {
        for (unsigned int c = 0; c < dim; ++c)
          if (!(sum[c][c] > 0))
            return false;
        return true;
      }
    } // namespace


    template <int dim, typename Entry>
    CollocationReport
    fit_node_rows(const Discretization::NodeSet<dim>      &nodes,
                  const Discretization::NeighborList<dim> &lists,
                  const double                             horizon,
                  const Quadrature::CollocationSettings   &settings,
                  const Quadrature::CollocationFit<dim>   &fit,
                  const std::vector<bool>                 &standard,
                  const RowOfFit<dim, Entry>              &row_of_fit,
                  NodeRowFits<dim, Entry>                 &rows)
    {
      const MPI_Comm                            comm = nodes.get_communicator();
      const unsigned int                        n_owned = nodes.n_owned();
      const Quadrature::ExactPartialVolume<dim> exact;
      const double ball = Quadrature::ball_volume<dim>(horizon);

      // Per owned node: 0 collocation, 1 fixed standard, 2 ball cut,
      // 3 ill-conditioned cloud, 4 non-positive diagonal; its cond(A) and
      // cloud size.
      std::vector<unsigned char> status(n_owned, 1);
      std::vector<double>        condition(n_owned, 0.);
      std::vector<unsigned int>  cloud_size(n_owned, 0);
      rows.neighbors.assign(n_owned, {});
      rows.weights.assign(n_owned, {});
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
              const Point<dim> &x = nodes[i].location;
              // The ball lies in the body and its layers when the exact
              // partial volumes of the cells fill it.
              double covered =
                exact.weight(x, horizon, nodes[i].cell) * nodes[i].volume();
              family.assign(1, Tensor<1, dim>());
              family_node.assign(1, i);
              for (const auto &bond : lists.bonds(i))
                {
                  const auto &neighbor = nodes[bond.neighbor];
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
              const std::vector<Entry> row = row_of_fit(i, cloud, q);
              Entry                    sum = Entry();
              for (unsigned int k = 0; k < cloud.size(); ++k)
                {
                  const unsigned int j = family_node[selected[k]];
                  if (j == i)
                    continue;
                  rows.neighbors[i].push_back(j);
                  rows.weights[i].push_back(row[k]);
                  sum += row[k];
                }
              status[i] = positive_diagonal(sum) ? 0 : 4;
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
      // An order-2 or a stabilised row with a non-positive diagonal comes
      // from a badly shaped cloud (a heavily perturbed one; 6 of 102400
      // stabilised C4 rows at 0.35 h, 320^2, m = 3): it falls back, or
      // stops the run, like an ill-conditioned one. The paper's order-4
      // rows with such rows are the order's fault (doc/collocation.md
      // Sect. 7) and stop the run.
      const bool cloud_fault =
        settings.order == 2 ||
        settings.stabilised(Quadrature::CollocationSettings::RowKind::per_node);
      int failed_node = -1;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          if (cloud_fault && status[i] == 4)
            status[i] = 3;
          if (status[i] == 3 && failed_node < 0)
            failed_node = i;
        }
      if (cloud_fault)
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
        where << "(" << nodes[failed_node].location << "), cond(A) "
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
                          "doc/collocation.md Sect. 7): the operator is "
                          "indefinite. Use 'Order = 2'" +
                          settings.stabilisation_hint()));

      rows.has_row.assign(n_owned, false);
      for (unsigned int i = 0; i < n_owned; ++i)
        if (status[i] == 0)
          rows.has_row[i] = true;
        else
          {
            rows.neighbors[i].clear();
            rows.weights[i].clear();
          }
      return report;
    }


    template <int dim, typename Entry>
    CollocationReport
    fit_node_rows_with_fallback(
      const Discretization::NodeSet<dim>          &nodes,
      const Discretization::NeighborList<dim>     &lists,
      const double                                 horizon,
      const Quadrature::CollocationSettings       &settings,
      const std::vector<bool>                     &standard,
      const std::function<RowOfFit<dim, Entry>(
        const Quadrature::CollocationSettings &,
        const Quadrature::CollocationFit<dim> &)> &row_maker,
      NodeRowFits<dim, Entry>                     &rows)
    {
      constexpr auto kind = Quadrature::CollocationSettings::RowKind::per_node;
      const auto     fit_of = [&](const Quadrature::CollocationSettings &s) {
        return Quadrature::CollocationFit<dim>(s.order,
                                               s.n_collocation,
                                               horizon,
                                               s.weight_radius_factor(kind) *
                                                 horizon);
      };
      const Quadrature::CollocationFit<dim> fit = fit_of(settings);
      CollocationReport                     report =
        fit_node_rows<dim, Entry>(nodes,
                                  lists,
                                  horizon,
                                  settings,
                                  fit,
                                  standard,
                                  row_maker(settings, fit),
                                  rows);
      // Bad clouds are left only with 'fall back' (fit_node_rows() stops
      // the run otherwise); the count is the same on every process.
      if (settings.order <= 2 || report.n_ill_conditioned == 0)
        return report;
      Quadrature::CollocationSettings lower           = settings;
      lower.order                                     = 2;
      lower.n_collocation                             = 0;
      const Quadrature::CollocationFit<dim> lower_fit = fit_of(lower);
      // Every node with a row or kept standard by the caller is done; the
      // second pass sees the bad clouds (and finds the cut balls again).
      std::vector<bool> done(nodes.n_owned(), false);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        done[i] = (i < standard.size() && standard[i]) || rows.has_row[i];
      NodeRowFits<dim, Entry> lower_rows;
      const CollocationReport lower_report =
        fit_node_rows<dim, Entry>(nodes,
                                  lists,
                                  horizon,
                                  lower,
                                  lower_fit,
                                  done,
                                  row_maker(lower, lower_fit),
                                  lower_rows);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        if (lower_rows.has_row[i])
          {
            rows.has_row[i]   = true;
            rows.neighbors[i] = std::move(lower_rows.neighbors[i]);
            rows.weights[i]   = std::move(lower_rows.weights[i]);
          }
      report.n_lower_order = lower_report.n_collocation_nodes;
      report.n_collocation_nodes += lower_report.n_collocation_nodes;
      report.n_ill_conditioned = lower_report.n_ill_conditioned;
      if (lower_report.n_collocation_nodes > 0)
        report.n_collocation_min =
          std::min(report.n_collocation_min, lower_report.n_collocation_min);
      return report;
    }


#define PERIDEAL_INSTANTIATE(dim, Entry)                                \
  template CollocationReport fit_node_rows<dim, Entry>(                 \
    const Discretization::NodeSet<dim> &,                               \
    const Discretization::NeighborList<dim> &,                          \
    const double,                                                       \
    const Quadrature::CollocationSettings &,                            \
    const Quadrature::CollocationFit<dim> &,                            \
    const std::vector<bool> &,                                          \
    const RowOfFit<dim, Entry> &,                                       \
    NodeRowFits<dim, Entry> &);                                         \
  template CollocationReport fit_node_rows_with_fallback<dim, Entry>(   \
    const Discretization::NodeSet<dim> &,                               \
    const Discretization::NeighborList<dim> &,                          \
    const double,                                                       \
    const Quadrature::CollocationSettings &,                            \
    const std::vector<bool> &,                                          \
    const std::function<                                                \
      RowOfFit<dim, Entry>(const Quadrature::CollocationSettings &,     \
                           const Quadrature::CollocationFit<dim> &)> &, \
    NodeRowFits<dim, Entry> &);
    template <int dim>
    using Block = Tensor<2, dim>;
    PERIDEAL_INSTANTIATE(2, double)
    PERIDEAL_INSTANTIATE(3, double)
    PERIDEAL_INSTANTIATE(2, Block<2>)
    PERIDEAL_INSTANTIATE(3, Block<3>)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
