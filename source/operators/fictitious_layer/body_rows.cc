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
      add_body_rows(const LayerData<dim> &data,
                    SparseEntries        &d_rows,
                    SparseEntries        &a_rows,
                    SparseEntries        &b_rows)
      {
        using Cell = typename Discretization::ExtendedLattice<dim>::Cell;
        const auto  &lattice = data.lattice;
        const auto  &nodes   = *data.nodes;
        const double V       = std::pow(lattice.spacing(), dim);
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            const Cell ci = lattice.cell_of_node(i);
            const int  ki = lattice.key(ci);
            std::array<types::global_dof_index, dim> row;
            for (unsigned int c = 0; c < dim; ++c)
              row[c] = data.sys_of_dof(nodes[i].dofs[c], nodes[i].owner);
            // The node's own columns collect a term from every bond: summed
            // here and added once.
            Tensor<2, dim> self_a;
            Tensor<1, dim> self_b, self_d;
            for (unsigned int q = 0; q < data.neighbours.size(); ++q)
              {
                const auto &nb = data.neighbours[q];
                Cell        cj;
                double      r = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    cj[d] = ci[d] + nb.offset[d];
                    r += nb.offset[d] * nb.offset[d];
                  }
                r = std::sqrt(r);
                Tensor<1, dim> n;
                for (unsigned int d = 0; d < dim; ++d)
                  n[d] = nb.offset[d] / r;
                const int kj = lattice.key(cj);
                // -F_i = -V_i sum_j [a (theta_i + theta_j) + b2 e_ij] w_ij n
                const double w = nb.beta * V * V;
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    for (unsigned int c2 = 0; c2 < dim; ++c2)
                      {
                        const double v = data.b2_r[q] * w * n[c] * n[c2];
                        a_rows.add(row[c], dim * kj + c2, -v);
                        self_a[c][c2] += v;
                      }
                    if (data.state_based)
                      {
                        b_rows.add(row[c], kj, -data.a_r[q] * w * n[c]);
                        self_b[c] -= data.a_r[q] * w * n[c];
                      }
                  }
                if (data.state_based)
                  for (unsigned int c = 0; c < dim; ++c)
                    {
                      d_rows.add(ki, dim * kj + c, data.g_r[q] * n[c]);
                      self_d[c] -= data.g_r[q] * n[c];
                    }
              }
            for (unsigned int c = 0; c < dim; ++c)
              {
                for (unsigned int c2 = 0; c2 < dim; ++c2)
                  a_rows.add(row[c], dim * ki + c2, self_a[c][c2]);
                if (data.state_based)
                  {
                    b_rows.add(row[c], ki, self_b[c]);
                    d_rows.add(ki, dim * ki + c, self_d[c]);
                  }
              }
          }
      }


      template void
      add_body_rows<2>(const LayerData<2> &,
                       SparseEntries &,
                       SparseEntries &,
                       SparseEntries &);
      template void
      add_body_rows<3>(const LayerData<3> &,
                       SparseEntries &,
                       SparseEntries &,
                       SparseEntries &);
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL
