// BondOperator: the collocation quadrature of the nodes with a full
// neighbourhood (doc/collocation.md Sects. 6 and 11): the shared bulk row
// from one WLS fit on the lattice, its pass over chunks of consecutive
// slots, and its force at one node. The adaptive switch of the hybrid
// scheme is in bond_operator_switch.cc.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <deal.II/lac/full_matrix.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>
#include <perideal/quadrature/collocation.h>

#include <cmath>
#include <limits>
#include <type_traits>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    typename BondOperator<dim>::CollocationReport
    BondOperator<dim>::use_collocation(
      const Quadrature::CollocationSettings &settings,
      const std::vector<bool>               &standard)
    {
      const MPI_Comm comm = nodes->get_communicator();
      node_rows           = NodeRows();
      node_row_of.clear();
      if (!layout.use_lattice)
        return use_collocation_per_node(settings, standard);
      AssertThrow(!state_based || (!finite && !with_failure),
                  ExcMessage("The collocation rows of state-based models are "
                             "built for linear kinematics without failure "
                             "(set_kinematics(false, {}))."));
      AssertThrow(
        !state_based ||
          settings.stabilisation_mode !=
            Quadrature::CollocationSettings::Stabilisation::all_orders,
        ExcInvalidInput("Quadrature/collocation/Stabilisation",
                        "all orders",
                        "the state-based (LPS) rows are not "
                        "stabilised yet, so the entry would have "
                        "no effect; use 'automatic'"));
      // On the lattice 'none' changes a row only where 'automatic' would
      // stabilise it: the bond-based order-4 row.
      AssertThrow(
        settings.stabilisation_mode !=
            Quadrature::CollocationSettings::Stabilisation::none ||
          (!state_based && settings.order == 4),
        ExcInvalidInput(
          "Quadrature/collocation/Stabilisation",
          "none",
          state_based ?
            "the state-based (LPS) rows are not stabilised yet, so the "
            "entry has no effect; remove it" :
            "on a uniform grid 'automatic' leaves the order-2 row as the "
            "paper gives it (it stabilises only rows per node, on "
            "irregular nodes), so the entry has no effect; remove it"));

      // The family of a bulk node: the node itself and the stencil offsets
      // within the horizon (the cells that the ball only cuts are not
      // family nodes of the collocation scheme), with their stencil index.
      const double                h = lists->lattice().spacing();
      std::vector<Tensor<1, dim>> family(1);
      std::vector<int>            stencil_index(1, -1);
      for (unsigned int k = 0; k < lists->stencil().size(); ++k)
        {
          Tensor<1, dim> xi;
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = lists->stencil()[k].offset[d] * h;
          if (xi.norm() <= horizon * (1 + 1e-12))
            {
              family.push_back(xi);
              stencil_index.push_back(k);
            }
        }
      // Stabilised rows (order 4, and order 2 with 'all orders';
      // doc/collocation.md Sects. 7.1, 7.3): bond-based only so far; the
      // state-based rows are the paper's.
      constexpr auto kind  = Quadrature::CollocationSettings::RowKind::lattice;
      const double   gamma = state_based ? 0. : settings.stabilisation(kind);
      const Quadrature::CollocationFit<dim> fit(
        settings.order,
        settings.n_collocation,
        horizon,
        (state_based ? 1. : settings.weight_radius_factor(kind)) * horizon);
      const std::vector<unsigned int> selected = fit.select(family);
      std::vector<Tensor<1, dim>>     cloud;
      for (const unsigned int j : selected)
        cloud.push_back(family[j]);

      CollocationReport report;
      report.n_collocation = cloud.size();
      report.n_monomials   = fit.basis().size();
      AssertThrow(
        cloud.size() >= fit.basis().size(),
        ExcInvalidInput(
          "Quadrature/collocation/Collocation nodes",
          std::to_string(settings.n_collocation),
          "the auxiliary grid for it gives " + std::to_string(cloud.size()) +
            " collocation nodes at this m-ratio, and a fit of order " +
            std::to_string(settings.order) + " needs at least " +
            std::to_string(fit.basis().size()) +
            "; ask for more nodes (0: the default), a lower "
            "'Order' or a larger m-ratio"));
      FullMatrix<double> q;
      report.condition = fit.fit(cloud, q);
      // The linearised bond-based pair stiffness per unit volume,
      // 2 beta(r) n (x) n (s = 1 at every node). State-based (LPS,
      // doc/collocation.md Sect. 5.2): the deviatoric part 2 beta(r) / m
      // n (x) n, the dilatation row T (d omega r / m n) and the dilatation
      // force row K (alpha(r) / m n), m the continuum weighted volume of
      // the full ball.
      const double m_continuum =
        state_based ?
          Quadrature::second_radial_moment<dim>(
            [&](const double r) { return model->influence(r, horizon); },
            horizon) :
          0.;
      const double s_continuum = state_based ? 1. / m_continuum : 1.;
      const auto   moments     = Quadrature::tensor_moments<dim>(
        fit.basis(),
        [&](const double r) {
          return 2. * model->extension_constant(r, horizon) * s_continuum;
        },
        horizon);
      std::vector<Tensor<2, dim>> row = Quadrature::tensor_row(moments, q);
      if (gamma > 0)
        Quadrature::add_stabilisation<dim>(
          row,
          fit.basis(),
          cloud,
          q,
          [&](const double r) {
            return 2. * model->extension_constant(r, horizon);
          },
          horizon,
          gamma);
      std::vector<Tensor<1, dim>> theta_row, kf_row;
      if (state_based)
        {
          theta_row =
            Quadrature::vector_row(Quadrature::vector_moments<dim>(
                                     fit.basis(),
                                     [&](const double r) {
                                       return dim *
                                              model->influence(r, horizon) * r *
                                              s_continuum;
                                     },
                                     horizon),
                                   q);
          kf_row = Quadrature::vector_row(
            Quadrature::vector_moments<dim>(
              fit.basis(),
              [&](const double r) {
                return model->dilatation_constant(r, horizon) * s_continuum;
              },
              horizon),
            q);
        }
      report.symbol =
        Quadrature::largest_symbol_eigenvalue<dim>(cloud,
                                                   row,
                                                   h,
                                                   dim == 3 ? 12 : 40,
                                                   kf_row,
                                                   theta_row);

      std::size_t n_full = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        if (lists->has_full_stencil(i))
          ++n_full;
      n_full = Utilities::MPI::sum(n_full, comm);
      report.n_cut_nodes =
        Utilities::MPI::sum(std::size_t(nodes->n_owned()), comm) - n_full;

      // Every process has fitted the same row: the decision is the same
      // everywhere.
      const bool well_conditioned =
        report.condition <= Quadrature::CollocationSettings::condition_limit;
      AssertThrow(
        well_conditioned || settings.fall_back,
        ExcInvalidInput("Quadrature/collocation/Ill-conditioned clouds",
                        "error",
                        "the collocation cloud of the bulk nodes (" +
                          std::to_string(cloud.size()) + " nodes, order " +
                          std::to_string(settings.order) +
                          ") has cond(A) = " + format_number(report.condition) +
                          " > 1e12; choose another 'Collocation nodes' or "
                          "'Order', or 'fall back' to the standard scheme"));
      collocation_node.assign(nodes->size(), 0);
      with_collocation = true;
      collocation_row  = CollocationRow();
      collocation_theta.clear();
      collocation_theta_chunks.clear();
      theta_slot.resize_fast(0);
      missed_switches = 0;
      scan_margin     = 0;
      tracking        = SwitchTracking();
      if (!well_conditioned)
        {
          report.n_ill_conditioned = n_full;
          build_work_lists();
          collocation_chunks.clear();
          return report;
        }

      // The row without the node itself (sum_k W_k = 0 to round-off, so
      // that W_0 u_i = -sum_{k>0} W_k u_i exactly: a rigid translation
      // gives no force), times the node's volume h^dim.
      const double volume = std::pow(h, dim);
      collocation_row.of_stencil_index.assign(lists->stencil().size(), -1);
      for (unsigned int j = 0; j < cloud.size(); ++j)
        {
          const int k = stencil_index[selected[j]];
          if (k < 0)
            continue;
          collocation_row.of_stencil_index[k] = collocation_row.offset.size();
          collocation_row.offset.push_back(layout.stencil_offset[k]);
          collocation_row.stencil_index.push_back(k);
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int d = 0; d < dim; ++d)
              {
                collocation_row.w[c * dim + d].push_back(volume * row[j][c][d]);
                collocation_row.sum[c][d] += volume * row[j][c][d];
              }
          if (state_based)
            for (unsigned int c = 0; c < dim; ++c)
              {
                collocation_row.theta_w[c].push_back(theta_row[j][c]);
                collocation_row.kf[c].push_back(volume * kf_row[j][c]);
              }
        }
      // The dilatation part of K_ii: dF_i/du_i = sum_k V K_k (x)
      // d theta_{i+k}/du_i (the theta_i term cancels, sum_k K_k = 0), and
      // d theta_{i+k}/du_i = T_{-k} = -T_k (the cloud is symmetric, T odd).
      if (state_based)
        for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
          for (unsigned int c = 0; c < dim; ++c)
            for (unsigned int d = 0; d < dim; ++d)
              collocation_row.sum[c][d] +=
                collocation_row.kf[c][k] * collocation_row.theta_w[d][k];
      // K_ii = V sum_k W_k must be positive definite for the static
      // solvers (and is for C2). The order-4 rows with the weight of Eq. 36
      // have a positive centre weight at m >= 3 (a negative K_ii): their
      // symbol has growing modes, doc/collocation.md Sect. 7.
      bool positive_diagonal = true;
      for (unsigned int c = 0; c < dim; ++c)
        positive_diagonal = positive_diagonal && collocation_row.sum[c][c] > 0;
      AssertThrow(positive_diagonal,
                  ExcInvalidInput(
                    "Quadrature/collocation/Order",
                    std::to_string(settings.order),
                    "the bulk collocation row of this order at this m-ratio "
                    "has a non-positive diagonal (its own node weighs "
                    "against its neighbours), and its Fourier symbol has "
                    "growing modes (largest eigenvalue " +
                      format_number(report.symbol) +
                      " of the most negative; doc/collocation.md Sect. 7): "
                      "the static operator is indefinite. Use 'Order = 2'" +
                      (state_based ? std::string() :
                                     settings.stabilisation_hint())));

      std::size_t n_collocation_nodes = 0, n_fixed_standard = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        if (layout.on_stencil(i))
          {
            if (!standard.empty() && standard[i])
              ++n_fixed_standard;
            else
              {
                collocation_node[i] = 1;
                ++n_collocation_nodes;
              }
          }
      report.n_collocation_nodes =
        Utilities::MPI::sum(n_collocation_nodes, comm);
      report.n_fixed_standard = Utilities::MPI::sum(n_fixed_standard, comm);
      if (state_based)
        {
          // The dilatation of every node (owned or ghost) with a full
          // stencil outside the fixed standard region comes from its own
          // row: the same decision on every process that has the node, so
          // the same dilatation to the bit.
          collocation_theta.assign(nodes->size(), 0);
          for (unsigned int i = 0; i < nodes->size(); ++i)
            collocation_theta[i] = needs_dilatation(i) &&
                                   layout.on_stencil(i) &&
                                   !(i < standard.size() && standard[i]);
          theta_slot.resize_fast(layout.n_slots);
          std::fill(theta_slot.begin(), theta_slot.end(), 0.);
        }
      build_work_lists();
      if (state_based)
        layout.make_chunks(
          [&](const unsigned int i) { return has_collocation_theta(i); },
          collocation_theta_chunks);
      layout.make_chunks(
        [&](const unsigned int i) { return is_collocation_node(i); },
        collocation_chunks);
      setup_switch_tracking();
      return report;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::n_missed_switches() const
    {
      return Utilities::MPI::sum(missed_switches, nodes->get_communicator());
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::n_collocation_nodes() const
    {
      std::size_t count = node_rows.node.size();
      for (const Chunk &chunk : collocation_chunks)
        count += chunk.length;
      return Utilities::MPI::sum(count, nodes->get_communicator());
    }


    template <int dim>
    void
    BondOperator<dim>::collocation_pass() const
    {
      if (!node_rows.node.empty())
        {
          node_rows_pass();
          return;
        }
      const std::size_t n_offsets = collocation_row.offset.size();
      const bool        lps       = !collocation_theta_chunks.empty();
      // The lanes [first, first + width) of a chunk: force_a += w_ab (u_b at
      // the neighbour - u_b at the node), in the order of the row (fixed by
      // the bond vectors), the same for every node, process and thread.
      // With a width fixed at compile time the forces and the node's own
      // displacement stay in registers (or at least in a small block of L1)
      // over the whole row: one load of the neighbour per entry and
      // component, where the loop over the whole chunk reloaded and stored
      // the forces at every entry. The remainder of a chunk takes
      // the same operations with its width at run time. Both round alike
      // (no contraction in this file), and so does collocation_force().
      const auto lanes = [&](const std::size_t first, const auto width) {
        constexpr unsigned int n = decltype(width)::value;
        double                 force[dim][n], ui[dim][n];
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int l = 0; l < n; ++l)
            {
              force[a][l] = 0;
              ui[a][l]    = u_slot[a][first + l];
            }
        for (std::size_t k = 0; k < n_offsets; ++k)
          {
            const std::ptrdiff_t o = collocation_row.offset[k];
            for (unsigned int b = 0; b < dim; ++b)
              {
                const double *uj = u_slot[b].data() + first + o;
                double        du[n];
#pragma omp simd
                for (unsigned int l = 0; l < n; ++l)
                  du[l] = uj[l] - ui[b][l];
                for (unsigned int a = 0; a < dim; ++a)
                  {
                    const double w = collocation_row.w[a * dim + b][k];
#pragma omp simd
                    for (unsigned int l = 0; l < n; ++l)
                      force[a][l] += w * du[l];
                  }
              }
          }
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int l = 0; l < n; ++l)
            f_slot[a][first + l] = force[a][l];
      };
      constexpr unsigned int block = 16;
      parallel::apply_to_subranges(
        std::size_t(0),
        collocation_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double force[dim][chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = collocation_chunks[c].first_slot;
              const unsigned int len = collocation_chunks[c].length;
              unsigned int       l0  = 0;
              if (!lps)
                for (; l0 + block <= len; l0 += block)
                  lanes(s0 + l0, std::integral_constant<unsigned int, block>());
              if (l0 == len)
                continue;
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int l = l0; l < len; ++l)
                  force[a][l] = 0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = collocation_row.offset[k];
                  for (unsigned int b = 0; b < dim; ++b)
                    {
                      const double *ui = u_slot[b].data() + s0;
                      const double *uj = ui + o;
                      for (unsigned int a = 0; a < dim; ++a)
                        {
                          const double w = collocation_row.w[a * dim + b][k];
#pragma omp simd
                          for (unsigned int l = l0; l < len; ++l)
                            force[a][l] += w * (uj[l] - ui[l]);
                        }
                    }
                }
              // State-based: the dilatation force, sum_k V K_k (theta_{i+k}
              // - theta_i), after the deviatoric row.
              if (lps)
                for (std::size_t k = 0; k < n_offsets; ++k)
                  {
                    const double *ti = theta_slot.data() + s0;
                    const double *tj = ti + collocation_row.offset[k];
                    for (unsigned int a = 0; a < dim; ++a)
                      {
                        const double w = collocation_row.kf[a][k];
#pragma omp simd
                        for (unsigned int l = 0; l < len; ++l)
                          force[a][l] += w * (tj[l] - ti[l]);
                      }
                  }
              for (unsigned int a = 0; a < dim; ++a)
                for (unsigned int l = l0; l < len; ++l)
                  f_slot[a][s0 + l] = force[a][l];
            }
        },
        LoopLayout<dim>::chunk_grain);
    }


    template <int dim>
    Tensor<1, dim>
    BondOperator<dim>::collocation_force(const std::size_t si) const
    {
      Tensor<1, dim> f;
      if (!node_rows.node.empty())
        {
          // The operations of node_rows_pass().
          const int r = node_row_of[layout.node_of_slot(si)];
          for (std::size_t e = node_rows.first[r]; e < node_rows.first[r + 1];
               ++e)
            for (unsigned int b = 0; b < dim; ++b)
              {
                const double du =
                  u_slot[b][node_rows.neighbor_slot[e]] - u_slot[b][si];
                for (unsigned int a = 0; a < dim; ++a)
                  f[a] += node_rows.w[(e * dim + a) * dim + b] * du;
              }
          return f;
        }
      // The operations of collocation_pass(), lane by lane.
      for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
        for (unsigned int b = 0; b < dim; ++b)
          {
            const double du =
              u_slot[b][si + collocation_row.offset[k]] - u_slot[b][si];
            for (unsigned int a = 0; a < dim; ++a)
              f[a] += collocation_row.w[a * dim + b][k] * du;
          }
      if (!collocation_theta_chunks.empty())
        for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
          {
            const double dt =
              theta_slot[si + collocation_row.offset[k]] - theta_slot[si];
            for (unsigned int a = 0; a < dim; ++a)
              f[a] += collocation_row.kf[a][k] * dt;
          }
      return f;
    }


    template <int dim>
    void
    BondOperator<dim>::collocation_dilatation_pass() const
    {
      // theta_i = sum_k T_k . (u_{i+k} - u_i) in the row's order, the same
      // for every node, process and thread; t = s theta for the standard
      // neighbours' force passes.
      const std::size_t n_offsets = collocation_row.offset.size();
      parallel::apply_to_subranges(
        std::size_t(0),
        collocation_theta_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double theta[chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = collocation_theta_chunks[c].first_slot;
              const unsigned int len = collocation_theta_chunks[c].length;
              for (unsigned int l = 0; l < len; ++l)
                theta[l] = 0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = collocation_row.offset[k];
                  for (unsigned int b = 0; b < dim; ++b)
                    {
                      const double *ui = u_slot[b].data() + s0;
                      const double *uj = ui + o;
                      const double  w  = collocation_row.theta_w[b][k];
#pragma omp simd
                      for (unsigned int l = 0; l < len; ++l)
                        theta[l] += w * (uj[l] - ui[l]);
                    }
                }
              for (unsigned int l = 0; l < len; ++l)
                {
                  theta_slot[s0 + l] = theta[l];
                  t_slot[s0 + l]     = s_slot[s0 + l] * theta[l];
                }
            }
        },
        LoopLayout<dim>::chunk_grain);
    }


#define PERIDEAL_INSTANTIATE(dim)                                             \
  template BondOperator<dim>::CollocationReport                               \
  BondOperator<dim>::use_collocation(const Quadrature::CollocationSettings &, \
                                     const std::vector<bool> &);              \
  template void BondOperator<dim>::collocation_pass() const;                  \
  template void BondOperator<dim>::collocation_dilatation_pass() const;       \
  template Tensor<1, dim> BondOperator<dim>::collocation_force(               \
    const std::size_t) const;                                                 \
  template std::size_t BondOperator<dim>::n_missed_switches() const;          \
  template std::size_t BondOperator<dim>::n_collocation_nodes() const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
