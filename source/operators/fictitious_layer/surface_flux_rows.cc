#include <deal.II/base/tensor.h>

#include <perideal/operators/fictitious_layer/layer_data.h>

#include <cmath>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace FictitiousLayer
    {
      template <int dim>
      void
      add_surface_flux_rows(const LayerData<dim> &data,
                            SparseEntries        &a_rows,
                            SparseEntries        &b_rows)
      {
        using Lattice        = Discretization::ExtendedLattice<dim>;
        using Cell           = typename Lattice::Cell;
        using HalfPoint      = typename Lattice::HalfPoint;
        const auto  &lattice = data.lattice;
        const double V       = std::pow(lattice.spacing(), dim);
        const int    reach =
          static_cast<int>(std::ceil(data.m_ratio + std::sqrt(double(dim)))) +
          1;
        for (const auto &node : data.surface->owned())
          {
            const HalfPoint    ps   = lattice.half_point(node.location);
            const unsigned int a    = node.axis;
            const int          side = node.side;
            const int          F    = ps[a];
            // The cell behind the face.
            Cell c0;
            for (unsigned int d = 0; d < dim; ++d)
              c0[d] = (d == a) ? (F - side - 1) / 2 : (ps[d] - 1) / 2;

            Cell       o;
            const auto visit = [&](const auto        &self,
                                   const unsigned int d) -> void {
              if (d < dim)
                {
                  for (o[d] = -reach; o[d] <= reach; ++o[d])
                    self(self, d + 1);
                  return;
                }
              Cell cj;
              for (unsigned int e = 0; e < dim; ++e)
                cj[e] = c0[e] + o[e];
              const HalfPoint pj = Lattice::half_of_cell(cj);
              if (side * (pj[a] - F) >= 0)
                return; // not on the inner side
              if (lattice.status(cj) == Lattice::Status::none)
                return;
              const int kj = lattice.key(cj);
              for (unsigned int q = 0; q < data.neighbours.size(); ++q)
                {
                  const auto &nb = data.neighbours[q];
                  if (side * nb.offset[a] <= 0)
                    continue;
                  const int pk_a = pj[a] + 2 * nb.offset[a];
                  if (side * (pk_a - F) <= 0)
                    continue; // does not cross the plane
                  // Crossing point, tangential coordinates times |D|.
                  const long long D     = 2LL * nb.offset[a];
                  const long long Dabs  = D > 0 ? D : -D;
                  double          alpha = 1;
                  bool            hit   = true;
                  for (unsigned int t = 0; t < dim && hit; ++t)
                    if (t != a)
                      {
                        long long x = static_cast<long long>(pj[t]) * D +
                                      static_cast<long long>(F - pj[a]) *
                                        (2LL * nb.offset[t]);
                        if (D < 0)
                          x = -x;
                        const long long lo = (ps[t] - 1LL) * Dabs;
                        const long long hi = (ps[t] + 1LL) * Dabs;
                        if (x < lo || x > hi)
                          hit = false;
                        else if (x == lo || x == hi)
                          alpha *= 0.5;
                      }
                  if (!hit)
                    continue;
                  Cell ck;
                  for (unsigned int e = 0; e < dim; ++e)
                    ck[e] = cj[e] + nb.offset[e];
                  if (lattice.status(ck) == Lattice::Status::none)
                    continue;
                  const int kk = lattice.key(ck);
                  double    r  = 0;
                  for (unsigned int e = 0; e < dim; ++e)
                    r += nb.offset[e] * nb.offset[e];
                  r = std::sqrt(r);
                  Tensor<1, dim> n;
                  for (unsigned int e = 0; e < dim; ++e)
                    n[e] = nb.offset[e] / r;
                  const double w = alpha * nb.beta * V * V;
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      const auto row = node.first_unknown + c;
                      for (unsigned int c2 = 0; c2 < dim; ++c2)
                        {
                          const double v = data.b2_r[q] * w * n[c] * n[c2];
                          a_rows.add(row, dim * kk + c2, v);
                          a_rows.add(row, dim * kj + c2, -v);
                        }
                      if (data.state_based)
                        {
                          b_rows.add(row, kj, data.a_r[q] * w * n[c]);
                          b_rows.add(row, kk, data.a_r[q] * w * n[c]);
                        }
                    }
                }
            };
            visit(visit, 0);
          }
      }


      template void
      add_surface_flux_rows<2>(const LayerData<2> &,
                               SparseEntries &,
                               SparseEntries &);
      template void
      add_surface_flux_rows<3>(const LayerData<3> &,
                               SparseEntries &,
                               SparseEntries &);
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL
