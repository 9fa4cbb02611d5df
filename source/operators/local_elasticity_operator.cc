#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/local_elasticity_operator.h>

#include <cmath>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    FullMatrix<double>
    LocalElasticityOperator<dim>::element_matrix(const double h,
                                                 const double lambda,
                                                 const double mu)
    {
      constexpr unsigned int n_vertices = 1u << dim;
      FullMatrix<double>     k(n_vertices * dim, n_vertices * dim);
      // 2-point Gauss rule per direction: exact for the Q1 stiffness.
      const double gauss[2] = {0.5 - 0.5 / std::sqrt(3.),
                               0.5 + 0.5 / std::sqrt(3.)};
      const double weight   = std::pow(h, dim) / n_vertices;
      for (unsigned int q = 0; q < n_vertices; ++q)
        {
          double xq[dim];
          for (unsigned int d = 0; d < dim; ++d)
            xq[d] = gauss[(q >> d) & 1];
          // Gradients of the shape functions at the point (reference
          // coordinates in [0,1], scaled by 1/h).
          double grad[n_vertices][dim];
          for (unsigned int a = 0; a < n_vertices; ++a)
            for (unsigned int p = 0; p < dim; ++p)
              {
                double g = 1;
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    const bool   upper = (a >> d) & 1;
                    const double phi   = upper ? xq[d] : 1 - xq[d];
                    const double dphi  = upper ? 1 : -1;
                    g *= (d == p ? dphi / h : phi);
                  }
                grad[a][p] = g;
              }
          for (unsigned int a = 0; a < n_vertices; ++a)
            for (unsigned int b = 0; b < n_vertices; ++b)
              {
                double dot = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  dot += grad[a][d] * grad[b][d];
                for (unsigned int p = 0; p < dim; ++p)
                  for (unsigned int r = 0; r < dim; ++r)
                    k(a * dim + p, b * dim + r) +=
                      weight *
                      (lambda * grad[a][p] * grad[b][r] +
                       mu * (grad[a][r] * grad[b][p] + (p == r ? dot : 0.)));
              }
        }
      return k;
    }


    template <int dim>
    void
    LocalElasticityOperator<dim>::assemble(
      const Discretization::NodeSet<dim> &nodes,
      const Discretization::Lattice<dim> &lattice,
      const Models::Model<dim>           &model,
      const AffineConstraints<double>    &constraints,
      TrilinosWrappers::SparseMatrix     &matrix)
    {
      AssertThrow(lattice.is_uniform(),
                  ExcMessage("The local elasticity preconditioner needs a "
                             "uniform grid of cubes (the cell centres must "
                             "form a lattice)."));
      constexpr unsigned int n_vertices = 1u << dim;
      const double           h          = lattice.spacing();
      const double           mu         = model.shear_modulus();
      double                 lambda     = model.bulk_modulus() - 2. / 3. * mu;
      if (dim == 2 && model.plane_stress())
        lambda = 2 * lambda * mu / (lambda + 2 * mu);
      const FullMatrix<double> k = element_matrix(h, lambda, mu);

      IndexSet owned(nodes.relevant_dofs().size());
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (const auto dof : nodes[i].dofs)
          owned.add_index(dof);
      owned.compress();

      // The dual cubes that contain node i: i is vertex a of the cube with
      // lower corner x_i - a. Calls f(a, corner nodes) for each complete
      // cube.
      auto for_each_cube = [&](const unsigned int i, const auto &f) {
        const auto                 &x = lattice.coordinates(i);
        std::array<int, n_vertices> corner;
        for (unsigned int a = 0; a < n_vertices; ++a)
          {
            bool complete = true;
            for (unsigned int b = 0; b < n_vertices && complete; ++b)
              {
                std::array<std::int64_t, dim> y = x;
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] += int((b >> d) & 1) - int((a >> d) & 1);
                corner[b] = lattice.node_at(y);
                complete  = corner[b] >= 0;
              }
            if (complete)
              f(a, corner);
          }
      };

      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int p = 0; p < dim; ++p)
          {
            const auto row = nodes[i].dofs[p];
            dsp.add(row, row);
            if (constraints.is_constrained(row))
              continue;
            for_each_cube(i, [&](const unsigned int, const auto &corner) {
              for (const int j : corner)
                for (unsigned int r = 0; r < dim; ++r)
                  if (!constraints.is_constrained(nodes[j].dofs[r]))
                    dsp.add(row, nodes[j].dofs[r]);
            });
          }
      matrix.reinit(owned, owned, dsp, nodes.get_communicator());

      // A node in no complete dual cube (a one-cell-thin part) keeps a
      // diagonal of the scale of its neighbours': the stencil's diagonal
      // in the bulk.
      const double bulk_diagonal = n_vertices * k(0, 0);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        for (unsigned int p = 0; p < dim; ++p)
          {
            const auto row      = nodes[i].dofs[p];
            double     diagonal = 0;
            for_each_cube(i, [&](const unsigned int a, const auto &corner) {
              diagonal += k(a * dim + p, a * dim + p);
              if (constraints.is_constrained(row))
                return;
              for (unsigned int b = 0; b < n_vertices; ++b)
                for (unsigned int r = 0; r < dim; ++r)
                  {
                    const auto col = nodes[corner[b]].dofs[r];
                    if (col != row && !constraints.is_constrained(col))
                      matrix.add(row, col, k(a * dim + p, b * dim + r));
                  }
            });
            matrix.add(row, row, diagonal > 0 ? diagonal : bulk_diagonal);
          }
      matrix.compress(VectorOperation::add);
    }


    template class LocalElasticityOperator<2>;
    template class LocalElasticityOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
