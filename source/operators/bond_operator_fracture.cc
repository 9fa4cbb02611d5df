#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>

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

      using LoopLayout::chunk_grain;
      using LoopLayout::node_grain;

      /// Consecutive slots and the stencil offsets to visit for them
      /// (index == nullptr: all of them); with broken bonds, the mask words
      /// of the one or two blocks of 64 slots that they span (nullptr:
      /// none broken there) and the first slot's place in its block.
      struct Block
      {
        std::size_t          first_slot;
        unsigned int         length;
        const std::uint16_t *index;
        std::size_t          n_index;
        const std::uint64_t *mask_low  = nullptr;
        const std::uint64_t *mask_high = nullptr;
        unsigned int         shift     = 0;

        /// The broken bonds of offset @p k: bit l for the slot first_slot + l.
        std::uint64_t
        broken(const std::size_t k) const
        {
          return (mask_low != nullptr ? mask_low[k] >> shift : 0) |
                 (mask_high != nullptr ? mask_high[k] << (64 - shift) : 0);
        }
      };

      /// The Block of a chunk of nodes of the full stencil, with the mask
      /// words of its blocks of 64 slots (BondOperator::block_mask_first).
      template <typename ChunkType>
      Block
      masked_block(const ChunkType                  &chunk,
                   const std::vector<std::int64_t>  &block_mask_first,
                   const std::vector<std::uint64_t> &mask_words,
                   const std::size_t                 n_offsets)
      {
        Block block{chunk.first_slot, chunk.length, nullptr, n_offsets};
        const std::size_t b0 = chunk.first_slot / 64;
        const std::size_t b1 = (chunk.first_slot + chunk.length - 1) / 64;
        block.shift          = chunk.first_slot % 64;
        if (block_mask_first[b0] >= 0)
          block.mask_low = mask_words.data() + block_mask_first[b0];
        // A chunk of at most 64 slots spans a second block only if it does
        // not start at the first slot of a block (shift > 0).
        if (b1 != b0 && block_mask_first[b1] >= 0)
          block.mask_high = mask_words.data() + block_mask_first[b1];
        return block;
      }

      /// Calls @p sweep (a pass's vectorised loop over Blocks) for the
      /// chunks of the full stencil, with their broken bonds masked, and
      /// then for the runs of surface nodes over their common offsets
      /// (list_stencil_index): the same two sweeps in the dilatation and force
      /// passes.
      template <typename ChunkType, typename RunType, typename Sweep>
      void
      sweep_chunks_and_runs(
        const std::vector<ChunkType>     &chunks,
        const std::vector<RunType>       &runs,
        const std::vector<std::uint16_t> &list_stencil_index,
        const std::vector<std::int64_t>  &block_mask_first,
        const std::vector<std::uint64_t> &mask_words,
        const std::size_t                 n_offsets,
        const Sweep                      &sweep)
      {
        sweep(chunks.size(), [&](const std::size_t c) {
          return masked_block(chunks[c],
                              block_mask_first,
                              mask_words,
                              n_offsets);
        });
        sweep(runs.size(), [&](const std::size_t c) {
          const RunType &run = runs[c];
          return Block{run.first_slot,
                       run.length,
                       list_stencil_index.data() + run.index_first,
                       run.n_index};
        });
      }
    } // namespace


    template <int dim>
    void
    BondOperator<dim>::set_kinematics(const bool finite_deformation,
                                      const std::vector<double> &stretch)
    {
      const unsigned int n    = nodes->size();
      const MPI_Comm     comm = nodes->get_communicator();
      AssertThrow(Utilities::MPI::min((stretch.empty() || stretch.size() == n) ?
                                        1 :
                                        0,
                                      comm) == 1,
                  ExcMessage("BondOperator::set_kinematics: one critical "
                             "stretch per node of the set."));
      finite           = finite_deformation;
      critical_stretch = stretch;
      with_failure     = false;
      for (const double s0 : critical_stretch)
        with_failure = with_failure || std::isfinite(s0);
      with_failure = Utilities::MPI::max(with_failure ? 1 : 0, comm) == 1;
      s0_slot.resize_fast(0);
      if (finite || with_failure)
        {
          s0_slot.resize_fast(n_slots);
          std::fill(s0_slot.begin(),
                    s0_slot.end(),
                    std::numeric_limits<double>::infinity());
          if (with_failure)
            for (unsigned int i = 0; i < n; ++i)
              s0_slot[slot[i]] = critical_stretch[i];
        }
      std::lock_guard<std::mutex> lock(exceeded_mutex);
      exceeded.clear();
    }


    template <int dim>
    void
    BondOperator<dim>::record_exceeded(
      const std::vector<ExceededBond> &found) const
    {
      std::lock_guard<std::mutex> lock(exceeded_mutex);
      exceeded.insert(exceeded.end(), found.begin(), found.end());
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::commit_broken_bonds(
      Discretization::BondState<dim> &state)
    {
      AssertThrow(&state == bond_state,
                  ExcMessage("commit_broken_bonds() needs the bond state "
                             "given to reinit()."));
      {
        std::lock_guard<std::mutex> lock(exceeded_mutex);
        std::sort(exceeded.begin(), exceeded.end());
        exceeded.erase(std::unique(exceeded.begin(), exceeded.end()),
                       exceeded.end());
        for (const auto &[i, j] : exceeded)
          if (lists->has_list(i))
            {
              const int k = state.bond_index(i, j);
              Assert(k >= 0, ExcInternalError());
              state.break_bond(i, k);
            }
        exceeded.clear();
      }
      const std::size_t n_new = state.synchronize();
      if (n_new > 0)
        update_work_lists(state.take_changed_nodes());
      return n_new;
    }


    template <int dim>
    template <bool finite_kinematics>
    void
    BondOperator<dim>::nonlinear_dilatation_pass() const
    {
      const std::size_t n_offsets = stencil.slot_offset.size();
      // One vectorised sweep over runs of consecutive slots: the chunks of
      // the shared stencil (every offset) or the runs of list nodes (the
      // offsets of their common bonds, with their own dilatation factor).
      const auto sweep = [&](const std::size_t n_blocks, const auto &block) {
        parallel::apply_to_subranges(
          std::size_t(0),
          n_blocks,
          [&](const std::size_t begin, const std::size_t end) {
            // Bonds over their critical stretch, found in this subrange
            // (allocates only when a bond fails), handed over once.
            std::vector<ExceededBond> found;
            alignas(64) double        theta[chunk_size];
            alignas(64) double        failed[chunk_size];
            alignas(64) double        gone_lane[chunk_size];
            for (std::size_t c = begin; c < end; ++c)
              {
                const Block                blk   = block(c);
                const std::size_t          s0    = blk.first_slot;
                const unsigned int         len   = blk.length;
                const std::uint16_t *const index = blk.index;
                const std::size_t          n_k   = blk.n_index;
                for (unsigned int l = 0; l < len; ++l)
                  theta[l] = 0;
                for (std::size_t q = 0; q < n_k; ++q)
                  {
                    const std::size_t    k = index != nullptr ? index[q] : q;
                    const std::ptrdiff_t o = stencil.slot_offset[k];
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
                    const double *ci = s0_slot.data() + s0, *cj = ci + o;
                    double        n_failed = 0;
                    const bool    masked =
                      blk.mask_low != nullptr || blk.mask_high != nullptr;
                    const std::uint64_t broken = masked ? blk.broken(k) : 0;
                    // The mask as one double per lane (a vectorised test
                    // in the lane loop; a bit test there is not).
                    if (broken != 0)
                      for (unsigned int l = 0; l < len; ++l)
                        gone_lane[l] = double((broken >> l) & 1);
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
                            BondKernel::extension<finite_kinematics,
                                                  dim,
                                                  Fused>(xi, nk, r, eta);
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
                      for (unsigned int l = 0; l < len; ++l)
                        if (failed[l] != 0)
                          found.emplace_back(node_of_slot(s0 + l),
                                             node_of_slot(s0 + l + o));
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
              }
            if (!found.empty())
              record_exceeded(found);
          },
          chunk_grain);
      };
      sweep_chunks_and_runs(full_theta_chunks,
                            theta_runs,
                            list_stencil_index,
                            block_mask_first,
                            mask_words,
                            n_offsets,
                            sweep);

      parallel::apply_to_subranges(
        std::size_t(0),
        theta_gather_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          // Bonds over their critical stretch, found in this subrange
          // (allocates only when a bond fails), handed over once.
          std::vector<ExceededBond> found;
          // Raw views of the stencil and the slot arrays for the gathers.
          const std::uint16_t  *index  = list_stencil_index.data();
          const std::ptrdiff_t *offset = stencil.slot_offset.data();
          const double *rs = stencil.r.data(), *inv_rs = stencil.inv_r.data(),
                       *gs = stencil.g.data(), *as = stencil.a.data(),
                       *bs = stencil.b.data(), *ts = t_slot.data(),
                       *ss = s_slot.data(), *s0s = s0_slot.data();
          const double *xs[dim], *ns[dim], *us[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              xs[d] = stencil.xi[d].data();
              ns[d] = stencil.n[d].data();
              us[d] = u_slot[d].data();
            }
          std::vector<double> failed(use_lattice ? stencil.r.size() : 0);
          (void)gs;
          (void)as;
          (void)bs;
          (void)ts;
          (void)ss;
          for (std::size_t q = begin; q < end; ++q)
            {
              const unsigned int i     = theta_gather_nodes[q];
              const std::size_t  si    = slot[i];
              double             theta = 0;
              const auto         visit = [&](const std::size_t sj,
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
                  found.emplace_back(i, node_of_slot(sj));
              };
              if (use_lattice)
                {
                  const std::size_t first = list_first[i], last = list_end[i];
                  const double      c_i = s0_slot[si];
                  double            ui[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    ui[d] = u_slot[d][si];
                  double n_failed = 0;
#pragma omp simd reduction(+ : theta, n_failed)
                  for (std::size_t b = first; b < last; ++b)
                    {
                      const unsigned int k  = index[b];
                      const std::size_t  sj = si + offset[k];
                      const double       e =
                        BondKernel::extension<finite_kinematics, dim>(
                          [&](const unsigned int d) { return xs[d][k]; },
                          [&](const unsigned int d) { return ns[d][k]; },
                          rs[k],
                          [&](const unsigned int d) {
                            return us[d][sj] - ui[d];
                          });
                      const bool intact =
                        BondKernel::is_intact(e, inv_rs[k], c_i, s0s[sj]);
                      theta += intact ? gs[k] * e : 0.;
                      failed[b - first] = intact ? 0. : 1.;
                      n_failed += intact ? 0. : 1.;
                    }
                  if (n_failed > 0)
                    for (std::size_t b = first; b < last; ++b)
                      if (failed[b - first] != 0)
                        found.emplace_back(i,
                                           node_of_slot(si + offset[index[b]]));
                  theta *= list_theta_scale[i];
                }
              else
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const ListBond &bond = list_bonds[b];
                    double          xi[dim];
                    for (unsigned int d = 0; d < dim; ++d)
                      xi[d] = bond.n[d] * bond.r;
                    visit(bond.neighbor_slot, xi, bond.n, bond.r, bond.g);
                  }
              t_slot[si] = s_slot[si] * theta;
            }
          if (!found.empty())
            record_exceeded(found);
        },
        node_grain);
    }


    template <int dim>
    template <bool finite_kinematics, bool with_energy>
    void
    BondOperator<dim>::nonlinear_force_pass() const
    {
      const std::size_t n_offsets = stencil.slot_offset.size();
      const bool        sb        = state_based;
      // As in the dilatation pass: the stencil chunks, then the runs.
      const auto sweep = [&](const std::size_t n_blocks, const auto &block) {
        parallel::apply_to_subranges(
          std::size_t(0),
          n_blocks,
          [&](const std::size_t begin, const std::size_t end) {
            // Bonds over their critical stretch, found in this subrange
            // (allocates only when a bond fails), handed over once.
            std::vector<ExceededBond> found;
            alignas(64) double        force[dim][chunk_size];
            alignas(64) double        failed[chunk_size];
            alignas(64) double        energy[chunk_size];
            alignas(64) double        gone_lane[chunk_size];
            for (std::size_t c = begin; c < end; ++c)
              {
                const Block                blk   = block(c);
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
                    const std::ptrdiff_t o = stencil.slot_offset[k];
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
                    const double *tj = ti + o, *sj = si + o, *cj = ci + o;
                    double        n_failed = 0;
                    const bool    masked =
                      blk.mask_low != nullptr || blk.mask_high != nullptr;
                    const std::uint64_t broken = masked ? blk.broken(k) : 0;
                    // The mask as one double per lane (a vectorised test
                    // in the lane loop; a bit test there is not).
                    if (broken != 0)
                      for (unsigned int l = 0; l < len; ++l)
                        gone_lane[l] = double((broken >> l) & 1);
                    // Bond-based models (s = 1, no dilatation) skip the loads
                    // of the state-based terms; bonds broken before (masked)
                    // count neither as intact nor as newly failed.
                    const auto lanes = [&](auto state_based_tag,
                                           auto masked_tag) {
                      constexpr bool with_state =
                        decltype(state_based_tag)::value;
                      constexpr bool with_mask = decltype(masked_tag)::value;
#pragma omp simd reduction(+ : n_failed)
                      for (unsigned int l = 0; l < len; ++l)
                        {
                          double eta[dim];
#pragma GCC unroll 3
                          for (unsigned int d = 0; d < dim; ++d)
                            eta[d] = uj[d][l] - ui[d][l];
                          const auto bond =
                            BondKernel::deform<finite_kinematics, dim, Fused>(
                              xi,
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
                            force[d][l] =
                              Fused::mul_add(ty, bond.y[d], force[d][l]);
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
                      for (unsigned int l = 0; l < len; ++l)
                        if (failed[l] != 0)
                          found.emplace_back(node_of_slot(s0 + l),
                                             node_of_slot(s0 + l + o));
                  }
                for (unsigned int d = 0; d < dim; ++d)
                  for (unsigned int l = 0; l < len; ++l)
                    f_slot[d][s0 + l] = force[d][l];
                if constexpr (with_energy)
                  for (unsigned int l = 0; l < len; ++l)
                    e_slot[s0 + l] = energy[l];
              }
            if (!found.empty())
              record_exceeded(found);
          },
          chunk_grain);
      };
      sweep_chunks_and_runs(full_force_chunks,
                            force_runs,
                            list_stencil_index,
                            block_mask_first,
                            mask_words,
                            n_offsets,
                            sweep);

      parallel::apply_to_subranges(
        std::size_t(0),
        force_gather_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          // Bonds over their critical stretch, found in this subrange
          // (allocates only when a bond fails), handed over once.
          std::vector<ExceededBond> found;
          // Raw views of the stencil and the slot arrays for the gathers.
          const std::uint16_t  *index  = list_stencil_index.data();
          const std::ptrdiff_t *offset = stencil.slot_offset.data();
          const double *rs = stencil.r.data(), *inv_rs = stencil.inv_r.data(),
                       *gs = stencil.g.data(), *as = stencil.a.data(),
                       *bs = stencil.b.data(), *ts = t_slot.data(),
                       *ss = s_slot.data(), *s0s = s0_slot.data();
          const double *xs[dim], *ns[dim], *us[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              xs[d] = stencil.xi[d].data();
              ns[d] = stencil.n[d].data();
              us[d] = u_slot[d].data();
            }
          std::vector<double> failed(use_lattice ? stencil.r.size() : 0);
          (void)gs;
          (void)as;
          (void)bs;
          (void)ts;
          (void)ss;
          for (std::size_t q = begin; q < end; ++q)
            {
              const unsigned int i           = force_gather_nodes[q];
              const std::size_t  si          = slot[i];
              double             f[dim]      = {};
              double             node_energy = 0;
              const auto         visit       = [&](const std::size_t sj,
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
                    found.emplace_back(i, node_of_slot(sj));
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
              if (use_lattice)
                {
                  // Vectorised over the node's bonds (gathers), with the
                  // failure decisions kept for the record.
                  const std::size_t first = list_first[i], last = list_end[i];
                  const double      ti = t_slot[si], s_i = s_slot[si],
                               c_i = s0_slot[si];
                  double ui[dim];
                  for (unsigned int d = 0; d < dim; ++d)
                    ui[d] = u_slot[d][si];
                  double *flag = failed.data();
                  double  f0 = 0, f1 = 0, f2 = 0, en = 0;
                  double  n_failed = 0;
                  // Bond-based models (s = 1, no dilatation) skip the loads
                  // of the state-based terms. Inlined, so that the sums and
                  // invariants are not read through the closure in the loop
                  // (which keeps it from vectorising).
                  const auto bonds =
                    [&](auto state_based_tag)
                      PERIDEAL_BOND_KERNEL_INLINE_LAMBDA {
                        constexpr bool with_state =
                          decltype(state_based_tag)::value;
#pragma omp simd reduction(+ : f0, f1, f2, en, n_failed)
                        for (std::size_t b = first; b < last; ++b)
                          {
                            const unsigned int k  = index[b];
                            const std::size_t  sj = si + offset[k];
                            double             xi[dim], n[dim], eta[dim];
#pragma GCC unroll 3
                            for (unsigned int d = 0; d < dim; ++d)
                              {
                                xi[d]  = xs[d][k];
                                n[d]   = ns[d][k];
                                eta[d] = us[d][sj] - ui[d];
                              }
                            const auto bond =
                              BondKernel::deform<finite_kinematics, dim>(xi,
                                                                         n,
                                                                         rs[k],
                                                                         eta);
                            const double e = bond.e;
                            const bool   intact =
                              BondKernel::is_intact(e, inv_rs[k], c_i, s0s[sj]);
                            double t;
                            if constexpr (with_state)
                              t = BondKernel::pair_force(as[k],
                                                         ti,
                                                         ts[sj],
                                                         bs[k],
                                                         s_i,
                                                         ss[sj],
                                                         e);
                            else
                              t = BondKernel::bond_based_pair_force(bs[k], e);
                            const double ty = intact ? t * bond.scale : 0.;
                            f0 += ty * bond.y[0];
                            f1 += ty * bond.y[1];
                            if constexpr (dim == 3)
                              f2 += ty * bond.y[dim - 1];
                            if constexpr (with_energy)
                              en += intact ? BondKernel::energy(bs[k], e) : 0.;
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
                    for (std::size_t b = first; b < last; ++b)
                      if (failed[b - first] != 0)
                        found.emplace_back(i,
                                           node_of_slot(si + offset[index[b]]));
                }
              else
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const ListBond &bond = list_bonds[b];
                    double          xi[dim];
                    for (unsigned int d = 0; d < dim; ++d)
                      xi[d] = bond.n[d] * bond.r;
                    visit(bond.neighbor_slot,
                          xi,
                          bond.n,
                          bond.r,
                          bond.a,
                          bond.b);
                  }
              for (unsigned int d = 0; d < dim; ++d)
                f_slot[d][si] = f[d];
              if constexpr (with_energy)
                e_slot[si] = node_energy;
            }
          if (!found.empty())
            record_exceeded(found);
        },
        node_grain);
    }


    template <int dim>
    double
    BondOperator<dim>::elastic_energy(const VectorType &displacement) const
    {
      // V_i W_i = 1/2 s_i sum_j b_ij e_ij^2 + 1/2 V_i lambda theta_i^2,
      // with b_ij = V_i w_ij beta(r_ij) (Model::dilatation_energy_modulus()).
      std::vector<double> theta;
      compute_dilatation(displacement, theta);
      if (!state_based)
        copy_in(displacement);
      const double lambda = model->dilatation_energy_modulus();
      const bool   fail   = s0_slot.size() > 0;
      const auto   term   = [&](const std::size_t si,
                            const std::size_t sj,
                            const double     *xi,
                            const double     *n,
                            const double      r,
                            const double      b) {
        const auto eta = [&](const unsigned int d) {
          return u_slot[d][sj] - u_slot[d][si];
        };
        const double e = finite ?
                               BondKernel::extension<true, dim>(xi, n, r, eta) :
                               BondKernel::extension<false, dim>(xi, n, r, eta);
        // The force passes' test, so that the energy leaves out the bonds
        // that they leave out.
        if (fail && !BondKernel::is_intact(e, 1. / r, s0_slot[si], s0_slot[sj]))
          return 0.;
        return BondKernel::energy(b, e);
      };
      const double energy = parallel::accumulate_from_subranges<double>(
        [&](const unsigned int begin, const unsigned int end) {
          double sum = 0;
          for (unsigned int i = begin; i < end; ++i)
            {
              const std::size_t si    = slot[i];
              double            bonds = 0;
              if (use_lattice)
                {
                  const auto visit = [&](const unsigned int k) {
                    double xi[dim], n[dim];
                    for (unsigned int d = 0; d < dim; ++d)
                      {
                        xi[d] = stencil.xi[d][k];
                        n[d]  = stencil.n[d][k];
                      }
                    bonds += term(si,
                                  si + stencil.slot_offset[k],
                                  xi,
                                  n,
                                  stencil.r[k],
                                  stencil.b[k]);
                  };
                  if (on_stencil(i))
                    for (unsigned int k = 0; k < stencil.r.size(); ++k)
                      visit(k);
                  else
                    for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                      visit(list_stencil_index[b]);
                }
              else
                for (std::size_t b = list_first[i]; b < list_end[i]; ++b)
                  {
                    const ListBond &bond = list_bonds[b];
                    double          xi[dim];
                    for (unsigned int d = 0; d < dim; ++d)
                      xi[d] = bond.n[d] * bond.r;
                    bonds +=
                      term(si, bond.neighbor_slot, xi, bond.n, bond.r, bond.b);
                  }
              sum += 0.5 * s_slot[si] * bonds +
                     0.5 * (*nodes)[i].volume() * lambda * theta[i] * theta[i];
            }
          return sum;
        },
        0u,
        nodes->n_owned(),
        node_grain);
      return Utilities::MPI::sum(energy, nodes->get_communicator());
    }


#define PERIDEAL_INSTANTIATE(dim)                              \
  template void BondOperator<dim>::set_kinematics(             \
    const bool,                                                \
    const std::vector<double> &);                              \
  template void BondOperator<dim>::record_exceeded(            \
    const std::vector<ExceededBond> &) const;                  \
  template std::size_t BondOperator<dim>::commit_broken_bonds( \
    Discretization::BondState<dim> &);                         \
  template double BondOperator<dim>::elastic_energy(const VectorType &) const;
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
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
