#ifndef perideal_operators_bond_operator_templates_h
#define perideal_operators_bond_operator_templates_h

// The bond visitors of BondOperator that more than one of its source files
// use (layout, linear apply and diagonal, fracture passes, energy, assembly,
// time step bound). Each is instantiated with a lambda of the file that
// calls it, so it is compiled with that file's flags.

#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>

#include <array>
#include <cmath>
#include <cstdint>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_intact_bond(const unsigned int i,
                                            const Function    &f) const
    {
      lists->for_each_bond(
        i,
        [&](const unsigned int k, const unsigned int j, const double w) {
          if (bond_state == nullptr || !bond_state->is_broken(i, k))
            f(j, w);
        });
    }


    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_list_bond(const unsigned int i,
                                          const Function    &f) const
    {
      for (std::size_t b = layout.list_first[i]; b < layout.list_end[i]; ++b)
        {
          const ListBond &bond = list_bonds[b];
          double          xi[dim];
          for (unsigned int d = 0; d < dim; ++d)
            xi[d] = bond.n[d] * bond.r;
          f(bond, xi);
        }
    }


    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::sweep_blocks(const Pass &pass, const Function &f) const
    {
      layout.sweep_chunks_and_runs(
        pass,
        [&](const std::size_t n_blocks, const auto &block) {
          layout.for_chunk_ranges(n_blocks,
                                  [&](const std::size_t begin,
                                      const std::size_t end) {
                                    // Bonds over their critical stretch, found
                                    // in this subrange (allocates only when a
                                    // bond fails), handed over once.
                                    std::vector<ExceededBond> found;
                                    for (std::size_t c = begin; c < end; ++c)
                                      f(block(c), found);
                                    if (!found.empty())
                                      record_exceeded(found);
                                  });
        });
    }


    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_gather_node(const Pass     &pass,
                                            const Function &f) const
    {
      parallel::apply_to_subranges(
        std::size_t(0),
        pass.gather_nodes.size(),
        [&](const std::size_t begin, const std::size_t end) {
          // Bonds over their critical stretch, found in this subrange
          // (allocates only when a bond fails), handed over once.
          std::vector<ExceededBond> found;
          const GatherViews         v = gather_views();
          std::vector<double> failed(layout.use_lattice ? stencil.r.size() : 0);
          for (std::size_t q = begin; q < end; ++q)
            {
              const unsigned int i = pass.gather_nodes[q];
              f(i, std::size_t(layout.slot[i]), v, failed.data(), found);
            }
          if (!found.empty())
            record_exceeded(found);
        },
        LoopLayout<dim>::node_grain);
    }


    template <int dim>
    template <typename Function>
    PERIDEAL_BOND_KERNEL_INLINE void
    BondOperator<dim>::for_each_linear_list_bond(const unsigned int i,
                                                 const std::size_t  si,
                                                 const Function    &f) const
    {
      const auto eta = [&](const std::size_t sj) {
        return [&, sj](const unsigned int d) {
          return u_slot[d][sj] - u_slot[d][si];
        };
      };
      if (layout.use_lattice)
        for (std::size_t b = layout.list_first[i]; b < layout.list_end[i]; ++b)
          {
            const unsigned int k  = layout.list_stencil_index[b];
            const std::size_t  sj = si + layout.stencil_offset[k];
            const auto         n  = [&](const unsigned int d) {
              return stencil.n[d][k];
            };
            f(sj,
              n,
              stencil.g[k],
              stencil.a[k],
              stencil.b[k],
              BondKernel::linear_extension<dim>(n, eta(sj)));
          }
      else
        for (std::size_t b = layout.list_first[i]; b < layout.list_end[i]; ++b)
          {
            const ListBond   &bond = list_bonds[b];
            const std::size_t sj   = bond.neighbor_slot;
            const auto n = [&](const unsigned int d) { return bond.n[d]; };
            f(sj,
              n,
              bond.g,
              bond.a,
              bond.b,
              BondKernel::linear_extension<dim>(bond.n, eta(sj)));
          }
    }


    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_bond_constants(
      const unsigned int                 i,
      const std::ptrdiff_t               base,
      const std::vector<std::ptrdiff_t> &box_delta,
      const Function                    &f) const
    {
      if (layout.use_lattice)
        {
          const std::size_t si = layout.slot[i];
          double            n[dim];
          const auto visit = [&](const unsigned int k, const double g_scale) {
            for (unsigned int d = 0; d < dim; ++d)
              n[d] = stencil.n[d][k];
            f(si + layout.stencil_offset[k],
              base + box_delta[k],
              n,
              stencil.g[k] * g_scale,
              stencil.a[k],
              stencil.b[k]);
          };
          if (layout.on_stencil(i))
            for (unsigned int k = 0; k < stencil.g.size(); ++k)
              visit(k, 1.);
          else
            for (std::size_t b = layout.list_first[i]; b < layout.list_end[i];
                 ++b)
              visit(layout.list_stencil_index[b], list_theta_scale[i]);
        }
      else
        for (std::size_t b = layout.list_first[i]; b < layout.list_end[i]; ++b)
          {
            const ListBond &bond = list_bonds[b];
            f(std::size_t(bond.neighbor_slot),
              static_cast<std::ptrdiff_t>(bond.neighbor_slot),
              bond.n,
              bond.g,
              bond.a,
              bond.b);
          }
    }
  } // namespace Operators
} // namespace PeriDEAL

#endif
