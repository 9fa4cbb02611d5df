#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <type_traits>

// The passes of BondOperator with finite kinematics and bond failure
// (explicit dynamics and fracture), compiled with the bond-loop flags and
// without floating-point contraction (-ffp-contract=off). Where a chunk or
// run starts depends on the partition, so a node's lane may be evaluated in
// a loop's vector body on one partition and in its scalar remainder on
// another; the compiler may fuse a multiply-add in one and not the other.
// The lane loops therefore spell their multiply-adds out
// (BondKernel::FusedArithmetic), which both paths round alike: a node's
// forces, and so its bond failures, are bitwise the same on every partition.

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      using Fused = BondKernel::FusedArithmetic;
    } // namespace


    template <int dim>
    template <bool finite_kinematics>
    void
    BondOperator<dim>::nonlinear_dilatation_pass() const
    {
      // One vectorised sweep over runs of consecutive slots: the chunks of
      // the shared stencil (every offset) or the runs of list nodes (the
      // offsets of their common bonds, with their own dilatation factor).
      sweep_blocks(
        theta_work(),
        [&](const Block &blk, std::vector<ExceededBond> &found) {
          alignas(64) double         theta[chunk_size];
          alignas(64) double         failed[chunk_size];
          alignas(64) double         gone_lane[chunk_size];
          const std::size_t          s0    = blk.first_slot;
          const unsigned int         len   = blk.length;
          const std::uint16_t *const index = blk.index;
          const std::size_t          n_k   = blk.n_index;
          for (unsigned int l = 0; l < len; ++l)
            theta[l] = 0;
          for (std::size_t q = 0; q < n_k; ++q)
            {
              const std::size_t    k = index != nullptr ? index[q] : q;
              const std::ptrdiff_t o = layout.stencil_offset[k];
              const double         g = stencil.g[k], r = stencil.r[k],
                           inv_r = stencil.inv_r[k];
              double        xi[dim], nk[dim];
              const double *ui[dim], *uj[dim];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  xi[d] = stencil.xi[d][k];
                  nk[d] = stencil.n[d][k];
                  ui[d] = u_slot[d].data() + s0;
                  uj[d] = ui[d] + o;
                }
              const double       *ci = s0_slot.data() + s0, *cj = ci + o;
              double              n_failed = 0;
              const std::uint64_t broken   = blk.broken_lanes(k, gone_lane);
              // Bonds broken before (masked) count neither as intact
              // nor as newly failed.
              const auto lanes = [&](auto masked_tag) {
                constexpr bool with_mask = decltype(masked_tag)::value;
#pragma omp simd reduction(+ : n_failed)
                for (unsigned int l = 0; l < len; ++l)
                  {
                    double eta[dim];
#pragma GCC unroll 3
                    for (unsigned int d = 0; d < dim; ++d)
                      eta[d] = uj[d][l] - ui[d][l];
                    const double e =
                      BondKernel::extension<finite_kinematics, dim, Fused>(xi,
                                                                           nk,
                                                                           r,
                                                                           eta);
                    const bool below =
                      BondKernel::is_intact(e, inv_r, ci[l], cj[l]);
                    bool gone = false;
                    if constexpr (with_mask)
                      gone = gone_lane[l] != 0;
                    const bool intact = below && !gone;
                    theta[l] += intact ? g * e : 0.;
                    failed[l] = (below || gone) ? 0. : 1.;
                    n_failed += (below || gone) ? 0. : 1.;
                  }
              };
              if (broken != 0)
                lanes(std::true_type());
              else
                lanes(std::false_type());
              if (n_failed > 0)
                layout.add_failed_lanes(failed, s0, len, k, found);
            }
          if (index == nullptr)
            {
              const double s = stencil.node_factor;
              for (unsigned int l = 0; l < len; ++l)
                t_slot[s0 + l] = s * theta[l];
            }
          else
            for (unsigned int l = 0; l < len; ++l)
              t_slot[s0 + l] = theta_run_factor[s0 + l] * theta[l];
        });

      for_each_gather_node(
        theta_work(),
        [&](const unsigned int         i,
            const std::size_t          si,
            const GatherViews         &v,
            double                    *failed,
            std::vector<ExceededBond> &found) {
          double     theta = 0;
          const auto visit = [&](const std::size_t sj,
                                 const double     *xi,
                                 const double     *n,
                                 const double      r,
                                 const double      g) {
            const double e = BondKernel::extension<finite_kinematics, dim>(
              xi,
              n,
              r,
              [&](const unsigned int d) {
                return u_slot[d][sj] - u_slot[d][si];
              });
            if (BondKernel::is_intact(e, 1. / r, s0_slot[si], s0_slot[sj]))
              theta += g * e;
            else
              found.emplace_back(i, layout.node_of_slot(sj));
          };
          if (layout.use_lattice)
            {
              const std::size_t first = layout.list_first[i],
                                last  = layout.list_end[i];
              const double c_i        = s0_slot[si];
              double       ui[dim];
              for (unsigned int d = 0; d < dim; ++d)
                ui[d] = u_slot[d][si];
              double n_failed = 0;
#pragma omp simd reduction(+ : theta, n_failed)
              for (std::size_t b = first; b < last; ++b)
                {
                  const unsigned int k  = v.index[b];
                  const std::size_t  sj = si + v.offset[k];
                  const double       e =
                    BondKernel::extension<finite_kinematics, dim>(
                      [&](const unsigned int d) { return v.xi[d][k]; },
                      [&](const unsigned int d) { return v.n[d][k]; },
                      v.r[k],
                      [&](const unsigned int d) { return v.u[d][sj] - ui[d]; });
                  const bool intact =
                    BondKernel::is_intact(e, v.inv_r[k], c_i, v.s0[sj]);
                  theta += intact ? v.g[k] * e : 0.;
                  failed[b - first] = intact ? 0. : 1.;
                  n_failed += intact ? 0. : 1.;
                }
              if (n_failed > 0)
                layout.add_failed_list_bonds(i, failed, found);
              theta *= list_theta_scale[i];
            }
          else
            for_each_list_bond(i, [&](const ListBond &bond, const double *xi) {
              visit(bond.neighbor_slot, xi, bond.n, bond.r, bond.g);
            });
          t_slot[si] = s_slot[si] * theta;
        });
    }


    template <int dim>
    template <bool finite_kinematics, bool with_energy>
    void
    BondOperator<dim>::nonlinear_force_pass() const
    {
      const bool sb = state_based;
      // As in the dilatation pass: the stencil chunks, then the runs.
      sweep_blocks(
        force_work(),
        [&](const Block &blk, std::vector<ExceededBond> &found) {
          alignas(64) double         force[dim][chunk_size];
          alignas(64) double         failed[chunk_size];
          alignas(64) double         energy[chunk_size];
          alignas(64) double         gone_lane[chunk_size];
          const std::size_t          s0    = blk.first_slot;
          const unsigned int         len   = blk.length;
          const std::uint16_t *const index = blk.index;
          const std::size_t          n_k   = blk.n_index;
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int l = 0; l < len; ++l)
              force[d][l] = 0;
          if constexpr (with_energy)
            for (unsigned int l = 0; l < len; ++l)
              energy[l] = 0;
          const double *ui[dim];
          for (unsigned int d = 0; d < dim; ++d)
            ui[d] = u_slot[d].data() + s0;
          const double *ti = t_slot.data() + s0;
          const double *si = s_slot.data() + s0;
          const double *ci = s0_slot.data() + s0;
          for (std::size_t q = 0; q < n_k; ++q)
            {
              const std::size_t    k = index != nullptr ? index[q] : q;
              const std::ptrdiff_t o = layout.stencil_offset[k];
              // Bond-based: s = 1 at every node, theta = 0.
              const double a = sb ? stencil.a[k] : 0.;
              const double b = stencil.b[k], r = stencil.r[k],
                           inv_r = stencil.inv_r[k];
              double        xi[dim], nk[dim];
              const double *uj[dim];
              for (unsigned int d = 0; d < dim; ++d)
                {
                  xi[d] = stencil.xi[d][k];
                  nk[d] = stencil.n[d][k];
                  uj[d] = ui[d] + o;
                }
              const double       *tj = ti + o, *sj = si + o, *cj = ci + o;
              double              n_failed = 0;
              const std::uint64_t broken   = blk.broken_lanes(k, gone_lane);
              // Bond-based models (s = 1, no dilatation) skip the loads
              // of the state-based terms; bonds broken before (masked)
              // count neither as intact nor as newly failed.
              const auto lanes = [&](auto state_based_tag, auto masked_tag) {
                constexpr bool with_state = decltype(state_based_tag)::value;
                constexpr bool with_mask  = decltype(masked_tag)::value;
#pragma omp simd reduction(+ : n_failed)
                for (unsigned int l = 0; l < len; ++l)
                  {
                    double eta[dim];
#pragma GCC unroll 3
                    for (unsigned int d = 0; d < dim; ++d)
                      eta[d] = uj[d][l] - ui[d][l];
                    const auto bond =
                      BondKernel::deform<finite_kinematics, dim, Fused>(xi,
                                                                        nk,
                                                                        r,
                                                                        eta);
                    const double e = bond.e;
                    const bool   below =
                      BondKernel::is_intact(e, inv_r, ci[l], cj[l]);
                    bool gone = false;
                    if constexpr (with_mask)
                      gone = gone_lane[l] != 0;
                    const bool intact = below && !gone;
                    double     t;
                    if constexpr (with_state)
                      t = BondKernel::pair_force<Fused>(a,
                                                        ti[l],
                                                        tj[l],
                                                        b,
                                                        si[l],
                                                        sj[l],
                                                        e);
                    else
                      t = BondKernel::bond_based_pair_force(b, e);
                    const double ty = intact ? t * bond.scale : 0.;
#pragma GCC unroll 3
                    for (unsigned int d = 0; d < dim; ++d)
                      force[d][l] = Fused::mul_add(ty, bond.y[d], force[d][l]);
                    if constexpr (with_energy)
                      energy[l] += intact ? BondKernel::energy(b, e) : 0.;
                    failed[l] = (below || gone) ? 0. : 1.;
                    n_failed += (below || gone) ? 0. : 1.;
                  }
              };
              if (sb && broken != 0)
                lanes(std::true_type(), std::true_type());
              else if (sb)
                lanes(std::true_type(), std::false_type());
              else if (broken != 0)
                lanes(std::false_type(), std::true_type());
              else
                lanes(std::false_type(), std::false_type());
              if (n_failed > 0)
                layout.add_failed_lanes(failed, s0, len, k, found);
            }
          for (unsigned int d = 0; d < dim; ++d)
            for (unsigned int l = 0; l < len; ++l)
              f_slot[d][s0 + l] = force[d][l];
          if constexpr (with_energy)
            for (unsigned int l = 0; l < len; ++l)
              e_slot[s0 + l] = energy[l];
        });

      for_each_gather_node(
        force_work(),
        [&](const unsigned int         i,
            const std::size_t          si,
            const GatherViews         &v,
            double                    *failed,
            std::vector<ExceededBond> &found) {
          double     f[dim]      = {};
          double     node_energy = 0;
          const auto visit       = [&](const std::size_t sj,
                                 const double     *xi,
                                 const double     *n,
                                 const double      r,
                                 const double      a,
                                 const double      b) {
            const auto bond = BondKernel::deform<finite_kinematics, dim>(
              xi,
              n,
              r,
              [&](const unsigned int d) {
                return u_slot[d][sj] - u_slot[d][si];
              });
            const double e = bond.e;
            if (!BondKernel::is_intact(e, 1. / r, s0_slot[si], s0_slot[sj]))
              {
                found.emplace_back(i, layout.node_of_slot(sj));
                return;
              }
            const double t = sb ? BondKernel::pair_force(a,
                                                         t_slot[si],
                                                         t_slot[sj],
                                                         b,
                                                         s_slot[si],
                                                         s_slot[sj],
                                                         e) :
                                        BondKernel::bond_based_pair_force(b, e);
            for (unsigned int d = 0; d < dim; ++d)
              f[d] += t * bond.scale * bond.y[d];
            if constexpr (with_energy)
              node_energy += BondKernel::energy(b, e);
          };
          if (layout.use_lattice)
            {
              // Vectorised over the node's bonds (gathers), with the
              // failure decisions kept for the record.
              const std::size_t first = layout.list_first[i],
                                last  = layout.list_end[i];
              const double ti = t_slot[si], s_i = s_slot[si], c_i = s0_slot[si];
              double       ui[dim];
              for (unsigned int d = 0; d < dim; ++d)
                ui[d] = u_slot[d][si];
              double *flag = failed;
              double  f0 = 0, f1 = 0, f2 = 0, en = 0;
              double  n_failed = 0;
              // Bond-based models (s = 1, no dilatation) skip the loads
              // of the state-based terms. Inlined, so that the sums and
              // invariants are not read through the closure in the loop
              // (which keeps it from vectorising).
              const auto bonds =
                [&](auto state_based_tag) PERIDEAL_BOND_KERNEL_INLINE_LAMBDA {
                  constexpr bool with_state = decltype(state_based_tag)::value;
#pragma omp simd reduction(+ : f0, f1, f2, en, n_failed)
                  for (std::size_t b = first; b < last; ++b)
                    {
                      const unsigned int k  = v.index[b];
                      const std::size_t  sj = si + v.offset[k];
                      double             xi[dim], n[dim], eta[dim];
#pragma GCC unroll 3
                      for (unsigned int d = 0; d < dim; ++d)
                        {
                          xi[d]  = v.xi[d][k];
                          n[d]   = v.n[d][k];
                          eta[d] = v.u[d][sj] - ui[d];
                        }
                      const auto bond =
                        BondKernel::deform<finite_kinematics, dim>(xi,
                                                                   n,
                                                                   v.r[k],
                                                                   eta);
                      const double e = bond.e;
                      const bool   intact =
                        BondKernel::is_intact(e, v.inv_r[k], c_i, v.s0[sj]);
                      double t;
                      if constexpr (with_state)
                        t = BondKernel::pair_force(v.a[k],
                                                   ti,
                                                   v.t[sj],
                                                   v.b[k],
                                                   s_i,
                                                   v.s[sj],
                                                   e);
                      else
                        t = BondKernel::bond_based_pair_force(v.b[k], e);
                      const double ty = intact ? t * bond.scale : 0.;
                      f0 += ty * bond.y[0];
                      f1 += ty * bond.y[1];
                      if constexpr (dim == 3)
                        f2 += ty * bond.y[dim - 1];
                      if constexpr (with_energy)
                        en += intact ? BondKernel::energy(v.b[k], e) : 0.;
                      flag[b - first] = intact ? 0. : 1.;
                      n_failed += intact ? 0. : 1.;
                    }
                };
              if (sb)
                bonds(std::true_type());
              else
                bonds(std::false_type());
              f[0] = f0;
              f[1] = f1;
              if constexpr (dim == 3)
                f[dim - 1] = f2;
              node_energy = en;
              if (n_failed > 0)
                layout.add_failed_list_bonds(i, failed, found);
            }
          else
            for_each_list_bond(i, [&](const ListBond &bond, const double *xi) {
              visit(bond.neighbor_slot, xi, bond.n, bond.r, bond.a, bond.b);
            });
          for (unsigned int d = 0; d < dim; ++d)
            f_slot[d][si] = f[d];
          if constexpr (with_energy)
            e_slot[si] = node_energy;
        });
    }


    template void
    BondOperator<2>::nonlinear_dilatation_pass<true>() const;
    template void
    BondOperator<2>::nonlinear_dilatation_pass<false>() const;
    template void
    BondOperator<3>::nonlinear_dilatation_pass<true>() const;
    template void
    BondOperator<3>::nonlinear_dilatation_pass<false>() const;
    template void
    BondOperator<2>::nonlinear_force_pass<true, false>() const;
    template void
    BondOperator<2>::nonlinear_force_pass<true, true>() const;
    template void
    BondOperator<2>::nonlinear_force_pass<false, false>() const;
    template void
    BondOperator<2>::nonlinear_force_pass<false, true>() const;
    template void
    BondOperator<3>::nonlinear_force_pass<true, false>() const;
    template void
    BondOperator<3>::nonlinear_force_pass<true, true>() const;
    template void
    BondOperator<3>::nonlinear_force_pass<false, false>() const;
    template void
    BondOperator<3>::nonlinear_force_pass<false, true>() const;
  } // namespace Operators
} // namespace PeriDEAL
