// BondOperator's linear passes (small-strain kinematics, no failure): the
// dilatations and forces of apply(), the energy of a force evaluation and
// the exact diagonal of the stiffness, compiled with the bond-loop flags.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <algorithm>
#include <array>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    BondOperator<dim>::copy_in(const VectorType &displacement) const
    {
      const double *values = displacement.begin();
      layout.for_each_node(nodes->size(), [&](const unsigned int i) {
        for (unsigned int c = 0; c < dim; ++c)
          u_slot[c][layout.slot[i]] = values[layout.vector_index[i] + c];
      });
    }


    template <int dim>
    void
    BondOperator<dim>::dilatation_pass() const
    {
      const std::size_t n_offsets = layout.stencil_offset.size();
      // The plain dilatations too, for the collocation rows of LPS.
      const bool store_theta = !collocation_theta_chunks.empty();
      // The uniform bulk: theta_i = sum_k g_k n_k . (u_{i+k} - u_i),
      // vectorised over a run of consecutive slots.
      parallel::apply_to_subranges(
        std::size_t(0),
        theta_work().chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double theta[chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = theta_work().chunks[c].first_slot;
              const unsigned int len = theta_work().chunks[c].length;
              for (unsigned int l = 0; l < len; ++l)
                theta[l] = 0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = layout.stencil_offset[k];
                  double               gn[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    gn[d] = stencil.g[k] * stencil.n[d][k];
                  const double *ui[dim], *uj[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      ui[d] = u_slot[d].data() + s0;
                      uj[d] = ui[d] + o;
                    }
#pragma omp simd
                  for (unsigned int l = 0; l < len; ++l)
                    {
                      // g e with g folded into the direction.
                      theta[l] += BondKernel::linear_extension_of_lane<dim>(gn,
                                                                            uj,
                                                                            ui,
                                                                            l);
                    }
                }
              const double s = stencil.node_factor;
              for (unsigned int l = 0; l < len; ++l)
                t_slot[s0 + l] = s * theta[l];
              if (store_theta)
                for (unsigned int l = 0; l < len; ++l)
                  theta_slot[s0 + l] = theta[l];
            }
        },
        LoopLayout<dim>::chunk_grain);

      layout.for_each_node_of(theta_work().list_nodes,
                              [&](const unsigned int i, const std::size_t si) {
                                double theta = 0;
                                for_each_linear_list_bond(
                                  i,
                                  si,
                                  [&](const std::size_t,
                                      const auto &,
                                      const double g,
                                      const double,
                                      const double,
                                      const double e)
                                    PERIDEAL_BOND_KERNEL_INLINE_LAMBDA {
                                      theta += g * e;
                                    });
                                if (layout.use_lattice)
                                  theta *= list_theta_scale[i];
                                t_slot[si] = s_slot[si] * theta;
                                if (store_theta)
                                  theta_slot[si] = theta;
                              });
      if (store_theta)
        collocation_dilatation_pass();
    }


    template <int dim>
    void
    BondOperator<dim>::force_pass() const
    {
      const std::size_t n_offsets = layout.stencil_offset.size();
      const bool        sb        = state_based;
      parallel::apply_to_subranges(
        std::size_t(0),
        force_work().chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double force[dim][chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  s0  = force_work().chunks[c].first_slot;
              const unsigned int len = force_work().chunks[c].length;
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int l = 0; l < len; ++l)
                  force[d][l] = 0;
              const double *ui[dim];
              for (unsigned int d = 0; d < dim; ++d)
                ui[d] = u_slot[d].data() + s0;
              const double *ti = t_slot.data() + s0;
              const double *si = s_slot.data() + s0;
              for (std::size_t k = 0; k < n_offsets; ++k)
                {
                  const std::ptrdiff_t o = layout.stencil_offset[k];
                  const double         a = stencil.a[k], b = stencil.b[k];
                  double               nk[dim];
                  const double        *uj[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      nk[d] = stencil.n[d][k];
                      uj[d] = ui[d] + o;
                    }
                  if (sb)
                    {
                      const double *tj = ti + o, *sj = si + o;
#pragma omp simd
                      for (unsigned int l = 0; l < len; ++l)
                        {
                          const double e =
                            BondKernel::linear_extension_of_lane<dim>(nk,
                                                                      uj,
                                                                      ui,
                                                                      l);
                          const double t = BondKernel::pair_force(a,
                                                                  ti[l],
                                                                  tj[l],
                                                                  b,
                                                                  si[l],
                                                                  sj[l],
                                                                  e);
                          for (unsigned int d = 0; d < dim; ++d)
                            force[d][l] += t * nk[d];
                        }
                    }
                  else
                    {
                    // Bond-based: s = 1 at every node.
#pragma omp simd
                      for (unsigned int l = 0; l < len; ++l)
                        {
                          const double e =
                            BondKernel::linear_extension_of_lane<dim>(nk,
                                                                      uj,
                                                                      ui,
                                                                      l);
                          const double t =
                            BondKernel::bond_based_pair_force(b, e);
                          for (unsigned int d = 0; d < dim; ++d)
                            force[d][l] += t * nk[d];
                        }
                    }
                }
              for (unsigned int d = 0; d < dim; ++d)
                for (unsigned int l = 0; l < len; ++l)
                  f_slot[d][s0 + l] = force[d][l];
            }
        },
        LoopLayout<dim>::chunk_grain);

      layout.for_each_node_of(force_work().list_nodes,
                              [&](const unsigned int i, const std::size_t si) {
                                double f[dim] = {};
                                for_each_linear_list_bond(
                                  i,
                                  si,
                                  [&](const std::size_t sj,
                                      const auto       &n,
                                      const double,
                                      const double a,
                                      const double b,
                                      const double e)
                                    PERIDEAL_BOND_KERNEL_INLINE_LAMBDA {
                                      const double t =
                                        BondKernel::pair_force(a,
                                                               t_slot[si],
                                                               t_slot[sj],
                                                               b,
                                                               s_slot[si],
                                                               s_slot[sj],
                                                               e);
                                      for (unsigned int d = 0; d < dim; ++d)
                                        f[d] += t * n(d);
                                    });
                                for (unsigned int d = 0; d < dim; ++d)
                                  f_slot[d][si] = f[d];
                              });
    }


    template <int dim>
    void
    BondOperator<dim>::apply(const VectorType &displacement,
                             VectorType       &force) const
    {
      apply_passes<false>(displacement, force);
    }


    template <int dim>
    void
    BondOperator<dim>::apply_linearised(const VectorType &displacement,
                                        VectorType       &force) const
    {
      apply_passes<false>(displacement, force, true);
    }


    template <int dim>
    double
    BondOperator<dim>::apply_with_energy(const VectorType &displacement,
                                         VectorType       &force) const
    {
      if (!finite && !with_failure)
        {
          apply_passes<false>(displacement, force);
          return elastic_energy(displacement);
        }
      e_slot.resize_fast(layout.n_slots);
      apply_passes<true>(displacement, force);
      // V_i W_i = 1/2 s_i sum_j b_ij e_ij^2 + 1/2 V_i lambda theta_i^2 as
      // in elastic_energy(), summed in node order (the same on every run).
      const double lambda = model->dilatation_energy_modulus();
      // The pair energies of the collocation nodes' bonds
      // (set_collocation_energy()), node by node on the threads; summed
      // below in node order.
      std::vector<double> bond_energy;
      if (bond_energy_at_collocation_nodes && has_collocation_rows())
        {
          bond_energy.assign(nodes->n_owned(), 0.);
          collocation_bond_energies(bond_energy);
        }
      double energy = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          const std::size_t si = layout.slot[i];
          if (is_collocation_node(i))
            {
              if (bond_energy_at_collocation_nodes)
                // The pair energy of its bonds (set_collocation_energy()).
                energy += 0.5 * s_slot[si] * bond_energy[i];
              else
                // The linear collocation row: -1/2 u_i . F_i.
                for (unsigned int d = 0; d < dim; ++d)
                  energy -= 0.5 * u_slot[d][si] * f_slot[d][si];
              continue;
            }
          const double theta =
            state_based && s_slot[si] != 0 ? t_slot[si] / s_slot[si] : 0.;
          energy += 0.5 * s_slot[si] * e_slot[si] +
                    0.5 * (*nodes)[i].volume() * lambda * theta * theta;
        }
      return Utilities::MPI::sum(energy, nodes->get_communicator());
    }


    template <int dim>
    template <bool with_energy>
    void
    BondOperator<dim>::apply_passes(const VectorType &displacement,
                                    VectorType       &force,
                                    const bool        linearised) const
    {
      copy_in(displacement);
      if (finite && !linearised)
        {
          if (state_based)
            nonlinear_dilatation_pass<true>();
          nonlinear_force_pass<true, with_energy>();
          if (has_collocation_rows())
            collocation_pass();
        }
      else if (with_failure && !linearised)
        {
          if (state_based)
            nonlinear_dilatation_pass<false>();
          nonlinear_force_pass<false, with_energy>();
          if (has_collocation_rows())
            collocation_pass();
        }
      else
        {
          if (state_based)
            dilatation_pass();
          force_pass();
          if (has_collocation_rows())
            collocation_pass();
        }
      double *values = force.begin();
      layout.for_each_node(nodes->n_owned(), [&](const unsigned int i) {
        for (unsigned int c = 0; c < dim; ++c)
          values[layout.vector_index[i] + c] = f_slot[c][layout.slot[i]];
      });
    }


    template <int dim>
    void
    BondOperator<dim>::compute_dilatation(const VectorType    &displacement,
                                          std::vector<double> &dilatation) const
    {
      dilatation.assign(nodes->size(), 0.);
      if (!state_based)
        return;
      copy_in(displacement);
      if (finite)
        nonlinear_dilatation_pass<true>();
      else if (with_failure)
        nonlinear_dilatation_pass<false>();
      else
        dilatation_pass();
      for (unsigned int i = 0; i < nodes->size(); ++i)
        if (lists->has_list(i))
          dilatation[i] = t_slot[layout.slot[i]] / s_slot[layout.slot[i]];
    }


    template <int dim>
    void
    BondOperator<dim>::compute_diagonal(VectorType &diagonal) const
    {
      // K_ii = V_i sum_j w [beta (s_i + s_j) n (x) n + alpha s_i n (x) G_i
      //        - alpha s_j n (x) g_ji], G_i = sum_j g_ij, with
      // g_ij = (d / m_i) omega r w_ij n_ij (see the class documentation).
      if (layout.use_lattice)
        {
          // On the lattice every bond's constants are the stencil's:
          // g_ij = g_k m_0 / m_i, and g_ji = g_k m_0 / m_j (w_ji = w_ij).
          const double m0 = stencil_weighted_volume;
          parallel::apply_to_subranges(
            0u,
            nodes->n_owned(),
            [&](const unsigned int begin, const unsigned int end) {
              for (unsigned int i = begin; i < end; ++i)
                {
                  if (is_collocation_node(i) && collocation_theta.empty())
                    {
                      // K_ii = V_i sum_k W_k (use_collocation()).
                      for (unsigned int c = 0; c < dim; ++c)
                        diagonal.local_element(layout.vector_index[i] + c) =
                          collocation_row.sum[c][c];
                      continue;
                    }
                  if (is_collocation_node(i))
                    {
                      // LPS rows: K_ii = V sum_k W_k - V sum_k K_k (x)
                      // d theta_{i+k}/du_i - V (sum_k K_k) (x) sum_k T_k,
                      // with d theta_j/du_i = -T_k from j's row T, or
                      // -g_k m_0/m_j n_k from its standard one.
                      const std::size_t si = layout.slot[i];
                      for (unsigned int c = 0; c < dim; ++c)
                        {
                          double w_sum = 0, k_sum = 0, t_sum = 0, coupled = 0;
                          for (std::size_t k = 0;
                               k < collocation_row.offset.size();
                               ++k)
                            {
                              w_sum += collocation_row.w[c * dim + c][k];
                              k_sum += collocation_row.kf[c][k];
                              t_sum += collocation_row.theta_w[c][k];
                              const unsigned int j = layout.node_of_slot(
                                si + collocation_row.offset[k]);
                              const unsigned int sk =
                                collocation_row.stencil_index[k];
                              const double d_theta =
                                has_collocation_theta(j) ?
                                  -collocation_row.theta_w[c][k] :
                                  -stencil.g[sk] * m0 / m[j] * stencil.n[c][sk];
                              coupled += collocation_row.kf[c][k] * d_theta;
                            }
                          diagonal.local_element(layout.vector_index[i] + c) =
                            w_sum - coupled - k_sum * t_sum;
                        }
                      continue;
                    }
                  const std::size_t si  = layout.slot[i];
                  const double      s_i = s_slot[si];
                  Tensor<1, dim>    G, a_sum, diag;
                  auto              add = [&](const unsigned int k) {
                    // The neighbour's slot from the stencil's slot offset
                    // (no lattice look-up per bond).
                    const std::size_t  sj = si + layout.stencil_offset[k];
                    const unsigned int j = layout.node_of_slot(sj);
                    const double       s_j = s_slot[sj];
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        const double n_c = stencil.n[c][k];
                        diag[c] += BondKernel::extension_stiffness(stencil.b[k],
                                                                   s_i,
                                                                   s_j) *
                                   n_c * n_c;
                        if (state_based)
                          {
                            G[c] += stencil.g[k] * m0 / m[i] * n_c;
                            a_sum[c] +=
                              BondKernel::dilatation_stiffness(stencil.a[k],
                                                               s_i) *
                              n_c;
                            // d theta_j / du_i: the standard row of j, or
                            // (LPS collocation) its row T at the offset
                            // -k, -T_k (the row is odd), if i is in j's
                            // cloud.
                            if (!has_collocation_theta(j))
                              diag[c] +=
                                BondKernel::dilatation_stiffness(stencil.a[k],
                                                                 s_j) *
                                n_c * n_c * stencil.g[k] * m0 / m[j];
                            else if (const int kc =
                                       collocation_row.of_stencil_index[k];
                                     kc >= 0)
                              diag[c] +=
                                BondKernel::dilatation_stiffness(stencil.a[k],
                                                                 s_j) *
                                n_c * collocation_row.theta_w[c][kc];
                          }
                      }
                  };
                  layout.for_each_stencil_index(i, add);
                  for (unsigned int c = 0; c < dim; ++c)
                    diagonal.local_element(layout.vector_index[i] + c) =
                      diag[c] + a_sum[c] * G[c];
                }
            },
            LoopLayout<dim>::node_grain);
          return;
        }
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          if (is_collocation_node(i))
            {
              // A row of its own (irregular nodes): K_ii = sum_k V W_k.
              const int r = node_row_of[i];
              for (unsigned int c = 0; c < dim; ++c)
                {
                  double sum = 0;
                  for (std::size_t e = node_rows.first[r];
                       e < node_rows.first[r + 1];
                       ++e)
                    sum += node_rows.w[(e * dim + c) * dim + c];
                  diagonal.local_element(layout.vector_index[i] + c) = sum;
                }
              continue;
            }
          const Point<dim> &x      = (*nodes)[i].location;
          const double      volume = (*nodes)[i].volume();
          const double      s_i    = s_slot[layout.slot[i]];
          Tensor<1, dim>    G, a_sum, diag;
          for_each_intact_bond(i, [&](const unsigned int j, const double w) {
            const Tensor<1, dim> xi    = (*nodes)[j].location - x;
            const double         r     = xi.norm();
            const Tensor<1, dim> n     = xi / r;
            const double         s_j   = s_slot[layout.slot[j]];
            const double         alpha = model->dilatation_constant(r, horizon);
            const double         beta  = model->extension_constant(r, horizon);
            for (unsigned int c = 0; c < dim; ++c)
              diag[c] +=
                BondKernel::extension_stiffness(volume * w * beta, s_i, s_j) *
                n[c] * n[c];
            if (!state_based)
              return;
            G += dim / m[i] * model->influence(r, horizon) * r * w * n;
            a_sum +=
              BondKernel::dilatation_stiffness(volume * w * alpha, s_i) * n;
            // g_ji: node j's bond back to i (weight w_ji), if it has one.
            double w_ji = 0;
            if (lists->has_full_stencil(j))
              w_ji = w * (*nodes)[i].volume() / (*nodes)[j].volume();
            else
              for (const auto &bond : lists->bonds(j))
                if (bond.neighbor == i)
                  {
                    w_ji = bond.weight;
                    break;
                  }
            const double g_ji =
              dim / m[j] * model->influence(r, horizon) * r * w_ji;
            for (unsigned int c = 0; c < dim; ++c)
              diag[c] +=
                BondKernel::dilatation_stiffness(volume * w * alpha, s_j) *
                n[c] * g_ji * n[c];
          });
          for (unsigned int c = 0; c < dim; ++c)
            diagonal.local_element(layout.vector_index[i] + c) =
              diag[c] + a_sum[c] * G[c];
        }
    }


#define PERIDEAL_INSTANTIATE(dim)                                              \
  template void BondOperator<dim>::copy_in(const VectorType &) const;          \
  template void BondOperator<dim>::dilatation_pass() const;                    \
  template void BondOperator<dim>::force_pass() const;                         \
  template void BondOperator<dim>::apply(const VectorType &, VectorType &)     \
    const;                                                                     \
  template void   BondOperator<dim>::apply_linearised(const VectorType &,      \
                                                    VectorType &) const;     \
  template double BondOperator<dim>::apply_with_energy(const VectorType &,     \
                                                       VectorType &) const;    \
  template void   BondOperator<dim>::compute_dilatation(const VectorType &,    \
                                                      std::vector<double> &) \
    const;                                                                     \
  template void BondOperator<dim>::compute_diagonal(VectorType &) const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
