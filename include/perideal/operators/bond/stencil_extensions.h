#ifndef perideal_operators_bond_stencil_extensions_h
#define perideal_operators_bond_stencil_extensions_h

// The bond extensions of the shared stencil at the lanes of a chunk: the
// loop that the hybrid switch's scan and the energy of the collocation
// nodes share. Include it only in files compiled with the bond loops' flags
// (-fopenmp-simd, CMakeLists.txt).

#include <deal.II/base/aligned_vector.h>

#include <perideal/operators/bond/bond_kernel.h>

#include <array>
#include <cstddef>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    /**
     * The extension of every bond of the shared stencil at the lanes of one
     * chunk (slots @p first ... @p first + @p length - 1, nodes on the
     * stencil), with the force passes' kinematics, from @p u_slot: for each
     * offset k in stencil order, <tt>lane_of_offset(k, o)</tt> (o: the slot
     * offset of k) gives the lane body, called as <tt>lane(l, e)</tt> for
     * every lane l, vectorised over the lanes. Per lane the bonds come in
     * stencil order, the same on every process and thread.
     */
    template <bool with_finite,
              int  dim,
              typename StencilData,
              typename LaneOfOffset>
    inline void
    for_each_stencil_extension(
      const StencilData                                    &stencil,
      const std::vector<std::ptrdiff_t>                    &offsets,
      const std::array<dealii::AlignedVector<double>, dim> &u_slot,
      const std::size_t                                     first,
      const unsigned int                                    length,
      const LaneOfOffset                                   &lane_of_offset)
    {
      for (std::size_t k = 0; k < offsets.size(); ++k)
        {
          const std::ptrdiff_t o = offsets[k];
          double               xi[dim], n[dim];
          for (unsigned int d = 0; d < dim; ++d)
            {
              xi[d] = stencil.xi[d][k];
              n[d]  = stencil.n[d][k];
            }
          const double  r = stencil.r[k];
          const double *ui[dim];
          for (unsigned int d = 0; d < dim; ++d)
            ui[d] = u_slot[d].data() + first;
          const auto lane = lane_of_offset(k, o);
#pragma omp simd
          for (unsigned int l = 0; l < length; ++l)
            {
              const auto eta = [&](const unsigned int d) {
                return ui[d][l + o] - ui[d][l];
              };
              lane(l, BondKernel::extension<with_finite, dim>(xi, n, r, eta));
            }
        }
    }
  } // namespace Operators
} // namespace PeriDEAL

#endif
