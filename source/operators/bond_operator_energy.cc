// BondOperator::elastic_energy(): the stored energy of the intact bonds with
// the kinematics and failure test of the force passes, compiled like the
// fracture passes (no floating-point contraction, see
// bond_operator_fracture.cc), so that it leaves out the bonds they leave out.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond/stencil_extensions.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <type_traits>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    double
    BondOperator<dim>::node_bond_energy(const unsigned int i) const
    {
      // sum_j b_ij e_ij^2 (times 1/2 in BondKernel::energy()) over the
      // intact bonds of node i, from u_slot.
      const bool        fail  = s0_slot.size() > 0;
      const std::size_t si    = layout.slot[i];
      double            bonds = 0;
      const auto        term  = [&](const std::size_t sj,
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
      if (layout.use_lattice)
        {
          const auto visit = [&](const unsigned int k) {
            double xi[dim], n[dim];
            for (unsigned int d = 0; d < dim; ++d)
              {
                xi[d] = stencil.xi[d][k];
                n[d]  = stencil.n[d][k];
              }
            bonds += term(si + layout.stencil_offset[k],
                          xi,
                          n,
                          stencil.r[k],
                          stencil.b[k]);
          };
          layout.for_each_stencil_index(i, visit);
        }
      else
        for_each_list_bond(i, [&](const ListBond &bond, const double *xi) {
          bonds += term(bond.neighbor_slot, xi, bond.n, bond.r, bond.b);
        });
      return bonds;
    }


    template <int dim>
    void
    BondOperator<dim>::collocation_bond_energies(
      std::vector<double> &energy) const
    {
      if (!node_rows.node.empty() || !layout.use_lattice)
        {
          parallel::apply_to_subranges(
            0u,
            nodes->n_owned(),
            [&](const unsigned int begin, const unsigned int end) {
              for (unsigned int i = begin; i < end; ++i)
                if (is_collocation_node(i))
                  energy[i] = node_bond_energy(i);
            },
            256);
          return;
        }
      // A collocation node on the lattice has every stencil bond intact
      // (one that lost a bond is standard): node_bond_energy() visits the
      // offsets in stencil order, and so do the lanes here.
      const bool fail = s0_slot.size() > 0;
      parallel::apply_to_subranges(
        std::size_t(0),
        collocation_chunks.size(),
        [&](const std::size_t begin, const std::size_t end) {
          alignas(64) double sum[chunk_size];
          for (std::size_t c = begin; c < end; ++c)
            {
              const std::size_t  first = collocation_chunks[c].first_slot;
              const unsigned int len   = collocation_chunks[c].length;
              for (unsigned int l = 0; l < len; ++l)
                sum[l] = 0;
              const double *s0i = fail ? s0_slot.data() + first : nullptr;
              // The failure test of node_bond_energy() (1 / r, not the
              // stencil's inv_r, as there). One loop per kinematics and
              // test, so that the lane body has no branch.
              const auto lanes = [&](auto finite_kinematics,
                                     auto with_failure_test) {
                constexpr bool with_finite = decltype(finite_kinematics)::value;
                constexpr bool with_test   = decltype(with_failure_test)::value;
                for_each_stencil_extension<with_finite, dim>(
                  stencil,
                  layout.stencil_offset,
                  u_slot,
                  first,
                  len,
                  [&](const std::size_t k, const std::ptrdiff_t o) {
                    const double inv_r = 1. / stencil.r[k];
                    const double b     = stencil.b[k];
                    return [&sum, s0i, o, inv_r, b](const unsigned int l,
                                                    const double       e) {
                      const bool intact =
                        !with_test ||
                        BondKernel::is_intact(e, inv_r, s0i[l], s0i[l + o]);
                      sum[l] += intact ? BondKernel::energy(b, e) : 0.;
                    };
                  });
              };
              if (finite && fail)
                lanes(std::true_type(), std::true_type());
              else if (finite)
                lanes(std::true_type(), std::false_type());
              else if (fail)
                lanes(std::false_type(), std::true_type());
              else
                lanes(std::false_type(), std::false_type());
              for (unsigned int l = 0; l < len; ++l)
                {
                  const unsigned int i = layout.node_of_slot(first + l);
                  AssertIndexRange(i, energy.size());
                  Assert(layout.on_stencil(i), ExcInternalError());
                  energy[i] = sum[l];
                }
            }
        },
        LoopLayout<dim>::chunk_grain);
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
      const double energy = parallel::accumulate_from_subranges<double>(
        [&](const unsigned int begin, const unsigned int end) {
          double sum = 0;
          for (unsigned int i = begin; i < end; ++i)
            {
              const std::size_t si = layout.slot[i];
              if (is_collocation_node(i) && !bond_energy_at_collocation_nodes)
                {
                  // The collocation row is linear: its node's share of
                  // 1/2 u.K u is -1/2 u_i . F_i.
                  const Tensor<1, dim> f = collocation_force(si);
                  for (unsigned int d = 0; d < dim; ++d)
                    sum -= 0.5 * u_slot[d][si] * f[d];
                  continue;
                }
              sum += 0.5 * s_slot[si] * node_bond_energy(i) +
                     0.5 * (*nodes)[i].volume() * lambda * theta[i] * theta[i];
            }
          return sum;
        },
        0u,
        nodes->n_owned(),
        LoopLayout<dim>::node_grain);
      return Utilities::MPI::sum(energy, nodes->get_communicator());
    }


    template double
    BondOperator<2>::elastic_energy(const VectorType &) const;
    template double
    BondOperator<3>::elastic_energy(const VectorType &) const;
    template void
    BondOperator<2>::collocation_bond_energies(std::vector<double> &) const;
    template void
    BondOperator<3>::collocation_bond_energies(std::vector<double> &) const;
    template double
    BondOperator<2>::node_bond_energy(const unsigned int) const;
    template double
    BondOperator<3>::node_bond_energy(const unsigned int) const;
  } // namespace Operators
} // namespace PeriDEAL
