#ifndef perideal_operators_bond_operator_templates_h
#define perideal_operators_bond_operator_templates_h

// The bond visitors of BondOperator that more than one of its source files
// use (layout, linear apply and diagonal, assembly, time step bound).

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
      if (lists->has_full_stencil(i))
        {
          const auto  &lattice = lists->lattice();
          const double volume  = std::pow(lattice.spacing(), dim);
          const auto  &x       = lattice.coordinates(i);
          const auto  &offsets = lists->stencil();
          for (unsigned int k = 0; k < offsets.size(); ++k)
            if (bond_state == nullptr || !bond_state->is_broken(i, k))
              {
                std::array<std::int64_t, dim> y = x;
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] += offsets[k].offset[d];
                f(static_cast<unsigned int>(lattice.node_at(y)),
                  offsets[k].beta * volume);
              }
        }
      else
        {
          const auto bonds = lists->bonds(i);
          for (unsigned int k = 0; k < bonds.size(); ++k)
            if (bond_state == nullptr || !bond_state->is_broken(i, k))
              f(bonds[k].neighbor, bonds[k].weight);
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
