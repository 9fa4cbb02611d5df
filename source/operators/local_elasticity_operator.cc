#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/local_elasticity_operator.h>

#include <algorithm>
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


    namespace
    {
      /// The bit of the lattice neighbour at @p offset (each entry -1, 0
      /// or 1, not all 0) in the masks: its index among the 3^dim offsets
      /// with the centre left out; -1 for any other offset.
      template <int dim>
      int
      neighbor_bit(const std::array<std::int64_t, dim> &offset)
      {
        int index = 0, scale = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            if (offset[d] < -1 || offset[d] > 1)
              return -1;
            index += int(offset[d] + 1) * scale;
            scale *= 3;
          }
        const int centre = (scale - 1) / 2;
        return index == centre ? -1 : index < centre ? index : index - 1;
      }


      /// Whether a dual cube is cut in two: every bond between its corners
      /// on the two sides of one of its mid-planes broken (corner[b]: the
      /// node at vertex b; one end's mask tells, since BondState breaks
      /// both). A cube with only some of those broken keeps its stiffness:
      /// the intact bonds still hold its corners together.
      template <int dim, typename Corners>
      bool
      cube_is_cut(const Corners                    &corner,
                  const std::vector<std::uint32_t> &masks)
      {
        constexpr unsigned int n_vertices = 1u << dim;
        bool                   any        = false;
        for (unsigned int a = 0; a < n_vertices; ++a)
          any = any || masks[corner[a]] != 0;
        if (!any)
          return false;
        for (unsigned int plane = 0; plane < dim; ++plane)
          {
            bool separated = true;
            for (unsigned int a = 0; a < n_vertices && separated; ++a)
              if (((a >> plane) & 1) == 0)
                for (unsigned int b = 0; b < n_vertices && separated; ++b)
                  if ((b >> plane) & 1)
                    {
                      std::array<std::int64_t, dim> offset;
                      for (unsigned int d = 0; d < dim; ++d)
                        offset[d] = int((b >> d) & 1) - int((a >> d) & 1);
                      separated =
                        (masks[corner[a]] >> neighbor_bit<dim>(offset)) & 1u;
                    }
            if (separated)
              return true;
          }
        return false;
      }
    } // namespace


    template <int dim>
    std::vector<std::uint32_t>
    LocalElasticityOperator<dim>::broken_neighbor_masks(
      const Discretization::NodeSet<dim>      &nodes,
      const Discretization::Lattice<dim>      &lattice,
      const Discretization::NeighborList<dim> &lists,
      const Discretization::BondState<dim>    &bonds)
    {
      // The owners' masks, sent to every off-process copy through a vector
      // with one entry per node (the bonds are broken in both directions
      // after BondState::synchronize(), so either end's mask would do; the
      // owner's is the one every process has).
      LinearAlgebra::distributed::Vector<double> exchanged(
        nodes.node_partitioner());
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          if (!bonds.any_broken(i))
            continue;
          std::uint32_t mask = 0;
          const auto   &x    = lattice.coordinates(i);
          for (unsigned int k = 0; k < lists.n_bonds(i); ++k)
            if (bonds.is_broken(i, k))
              {
                auto y = lattice.coordinates(bonds.neighbor(i, k));
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] -= x[d];
                const int bit = neighbor_bit<dim>(y);
                if (bit >= 0)
                  mask |= std::uint32_t(1) << bit;
              }
          exchanged(nodes[i].dofs[0] / dim) = mask;
        }
      exchanged.update_ghost_values();
      std::vector<std::uint32_t> masks(nodes.size(), 0);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        masks[i] =
          static_cast<std::uint32_t>(exchanged(nodes[i].dofs[0] / dim));
      return masks;
    }


    template <int dim>
    void
    LocalElasticityOperator<dim>::assemble(
      const Discretization::NodeSet<dim> &nodes,
      const Discretization::Lattice<dim> &lattice,
      const Models::Model<dim>           &model,
      const AffineConstraints<double>    &constraints,
      TrilinosWrappers::SparseMatrix     &matrix,
      const std::vector<std::uint32_t>   *broken_masks,
      const CoarseLattice<dim>           *coarse)
    {
      AssertThrow(lattice.is_uniform(),
                  ExcMessage("The local elasticity preconditioner needs a "
                             "uniform grid of cubes (the cell centres must "
                             "form a lattice)."));
      constexpr unsigned int n_vertices = 1u << dim;
      // On a coarse lattice: cubes of s lattice steps, its own DoFs.
      const unsigned int s      = coarse != nullptr ? coarse->stride() : 1;
      const double       h      = s * lattice.spacing();
      const double       mu     = model.shear_modulus();
      double             lambda = model.bulk_modulus() - 2. / 3. * mu;
      if (dim == 2 && model.plane_stress())
        lambda = 2 * lambda * mu / (lambda + 2 * mu);
      const FullMatrix<double> k = element_matrix(h, lambda, mu);

      const auto is_row = [&](const unsigned int i) {
        return coarse == nullptr || coarse->is_coarse(i);
      };
      const auto dof_of = [&](const unsigned int i, const unsigned int p) {
        return coarse != nullptr ? coarse->dof(i, p) : nodes[i].dofs[p];
      };
      // Prescribed: on the full lattice the PD DoF of the same node and
      // component, as its owner has it (a held node's hold is known to its
      // owner only); on a coarse lattice as the coarse lattice decides.
      const std::vector<std::uint8_t> owner_masks =
        coarse == nullptr ? owner_constraint_masks(nodes, constraints) :
                            std::vector<std::uint8_t>();
      const auto prescribed = [&](const unsigned int i, const unsigned int p) {
        return coarse != nullptr ? coarse->is_prescribed(i, p) :
                                   bool((owner_masks[i] >> p) & 1);
      };
      IndexSet owned(nodes.relevant_dofs().size());
      if (coarse != nullptr)
        owned = coarse->owned_dofs();
      else
        {
          for (unsigned int i = 0; i < nodes.n_owned(); ++i)
            for (const auto dof : nodes[i].dofs)
              owned.add_index(dof);
          owned.compress();
        }

      // A coarse cube (s = 2) exists only where every lattice point in it
      // is a node: one whose corners exist around a missing node (a notch
      // narrower than s h) would be stiff across the notch.
      const auto is_filled = [&](const std::array<int, n_vertices> &corner) {
        if (s == 1)
          return true;
        const auto        &lower = lattice.coordinates(corner[0]);
        const unsigned int width = s + 1;
        for (unsigned int o = 0; o < Utilities::pow(width, dim); ++o)
          {
            std::array<std::int64_t, dim> y = lower;
            for (unsigned int d = 0, q = o; d < dim; ++d, q /= width)
              y[d] += q % width;
            if (lattice.node_at(y) < 0)
              return false;
          }
        return true;
      };
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
                  y[d] +=
                    std::int64_t(s) * (int((b >> d) & 1) - int((a >> d) & 1));
                corner[b] = lattice.node_at(y);
                complete  = corner[b] >= 0;
              }
            if (complete && is_filled(corner))
              f(a, corner);
          }
      };

      // A dual cube is cut when a bond between two of its corners is
      // broken: its stiffness is scaled by cut_cube_factor, so that the
      // preconditioner's elasticity has the cracks the PD bonds have.
      // A coarse cube (s = 2) is cut when one of the 2^dim cubes of side
      // h it holds is: its nodes lie within two lattice steps of the
      // coarse node whose row is assembled, all in the node set.
      const auto is_cut = [&](const auto &corner) {
        if (s == 1)
          return cube_is_cut<dim>(corner, *broken_masks);
        const auto &lower = lattice.coordinates(corner[0]);
        for (unsigned int sub = 0; sub < n_vertices; ++sub)
          {
            std::array<int, n_vertices> fine_corner;
            bool                        complete = true;
            for (unsigned int b = 0; b < n_vertices && complete; ++b)
              {
                std::array<std::int64_t, dim> y = lower;
                for (unsigned int d = 0; d < dim; ++d)
                  y[d] += int((sub >> d) & 1) + int((b >> d) & 1);
                fine_corner[b] = lattice.node_at(y);
                complete       = fine_corner[b] >= 0;
              }
            if (complete && cube_is_cut<dim>(fine_corner, *broken_masks))
              return true;
          }
        return false;
      };
      const auto cube_factor = [&](const auto &corner) {
        return broken_masks != nullptr && is_cut(corner) ? cut_cube_factor : 1.;
      };

      // Each node's dual cubes, found once per node (lattice look-ups),
      // with their stiffness factors.
      struct Cube
      {
        unsigned int                vertex; // the node's vertex in the cube
        std::array<int, n_vertices> corner;
        double                      factor;
      };
      std::vector<Cube> cubes;
      const auto        collect_cubes = [&](const unsigned int i) {
        cubes.clear();
        for_each_cube(i, [&](const unsigned int a, const auto &corner) {
          cubes.push_back({a, corner, cube_factor(corner)});
        });
      };
      // A row's entries by the corner's offset from the node (3^dim
      // places) and component: no search per entry.
      constexpr unsigned int n_places = dim == 2 ? 9 : 27;
      const auto             place =
        [](const unsigned int a, const unsigned int b, const unsigned int r) {
          unsigned int index = 0, scale = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              index += (1 + int((b >> d) & 1) - int((a >> d) & 1)) * scale;
              scale *= 3;
            }
          return index * dim + r;
        };

      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      std::vector<types::global_dof_index> columns;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          if (!is_row(i))
            continue;
          collect_cubes(i);
          for (unsigned int p = 0; p < dim; ++p)
            {
              const auto row = dof_of(i, p);
              columns.assign(1, row);
              if (!prescribed(i, p))
                for (const auto &cube : cubes)
                  for (const int j : cube.corner)
                    for (unsigned int r = 0; r < dim; ++r)
                      if (!prescribed(j, r))
                        columns.push_back(dof_of(j, r));
              std::sort(columns.begin(), columns.end());
              columns.erase(std::unique(columns.begin(), columns.end()),
                            columns.end());
              dsp.add_entries(row, columns.begin(), columns.end(), true);
            }
        }
      matrix.reinit(owned, owned, dsp, nodes.get_communicator());

      // A node in no complete dual cube (a one-cell-thin part) keeps a
      // diagonal of the scale of its neighbours': the stencil's diagonal
      // in the bulk. Each entry sums its cubes' contributions in cube
      // order and enters the matrix once.
      const double                       bulk_diagonal = n_vertices * k(0, 0);
      std::array<double, n_places * dim> values;
      std::array<types::global_dof_index, n_places * dim> cols;
      std::array<bool, n_places * dim>                    used;
      std::vector<types::global_dof_index>                row_cols;
      std::vector<double>                                 row_values;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          if (!is_row(i))
            continue;
          collect_cubes(i);
          for (unsigned int p = 0; p < dim; ++p)
            {
              const auto row      = dof_of(i, p);
              double     diagonal = 0;
              used.fill(false);
              for (const auto &cube : cubes)
                {
                  const unsigned int a = cube.vertex;
                  diagonal += cube.factor * k(a * dim + p, a * dim + p);
                  if (prescribed(i, p))
                    continue;
                  for (unsigned int b = 0; b < n_vertices; ++b)
                    for (unsigned int r = 0; r < dim; ++r)
                      {
                        const auto col = dof_of(cube.corner[b], r);
                        if (col == row || prescribed(cube.corner[b], r))
                          continue;
                        const unsigned int q = place(a, b, r);
                        if (!used[q])
                          {
                            used[q]   = true;
                            values[q] = 0;
                            cols[q]   = col;
                          }
                        values[q] += cube.factor * k(a * dim + p, b * dim + r);
                      }
                }
              row_cols.assign(1, row);
              row_values.assign(1, diagonal > 0 ? diagonal : bulk_diagonal);
              for (unsigned int q = 0; q < n_places * dim; ++q)
                if (used[q])
                  {
                    row_cols.push_back(cols[q]);
                    row_values.push_back(values[q]);
                  }
              matrix.add(row,
                         row_cols.size(),
                         row_cols.data(),
                         row_values.data(),
                         false);
            }
        }
      matrix.compress(VectorOperation::add);
    }


    template <int dim>
    std::size_t
    LocalElasticityOperator<dim>::n_cut_cubes(
      const Discretization::NodeSet<dim> &nodes,
      const Discretization::Lattice<dim> &lattice,
      const std::vector<std::uint32_t>   &broken_masks)
    {
      // Only the cubes with a corner whose mask is not empty can be cut:
      // those are the cubes x_i - a of such nodes i (a a vertex), each
      // counted where its lower corner is owned.
      constexpr unsigned int n_vertices = 1u << dim;
      std::vector<int>       lower_corners;
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (broken_masks[i] != 0)
          for (unsigned int a = 0; a < n_vertices; ++a)
            {
              std::array<int, n_vertices> corner;
              bool                        complete = true;
              for (unsigned int b = 0; b < n_vertices && complete; ++b)
                {
                  auto y = lattice.coordinates(i);
                  for (unsigned int d = 0; d < dim; ++d)
                    y[d] += int((b >> d) & 1) - int((a >> d) & 1);
                  corner[b] = lattice.node_at(y);
                  complete  = corner[b] >= 0;
                }
              if (complete && corner[0] < int(nodes.n_owned()) &&
                  cube_is_cut<dim>(corner, broken_masks))
                lower_corners.push_back(corner[0]);
            }
      std::sort(lower_corners.begin(), lower_corners.end());
      const std::size_t n_cut =
        std::unique(lower_corners.begin(), lower_corners.end()) -
        lower_corners.begin();
      return Utilities::MPI::sum(n_cut, nodes.get_communicator());
    }


    template class LocalElasticityOperator<2>;
    template class LocalElasticityOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
