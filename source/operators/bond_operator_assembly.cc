// The assembled stiffness of BondOperator: the Trilinos matrix built from the
// same stencil, lists, bond state and kernel as the matrix-free apply().

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/thread_local_storage.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/base/collective_checks.h>
#include <perideal/operators/bond_operator.h>

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>

#include <algorithm>
#include <cstdint>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    template <typename Function>
    void
    BondOperator<dim>::for_each_bond_constants(
      const unsigned int                 i,
      const std::ptrdiff_t               base,
      const std::vector<std::ptrdiff_t> &box_delta,
      const Function                    &f) const
    {
      if (use_lattice)
        {
          const auto       &lattice = lists->lattice();
          const std::size_t si      = slot[i];
          double            n[dim];
          const auto        visit = [&](const unsigned int k,
                                 const double       g_scale) {
            for (unsigned int d = 0; d < dim; ++d)
              n[d] = stencil.n[d][k];
            f(static_cast<unsigned int>(
                lattice.node_at_slot(si + stencil.slot_offset[k])),
              base + box_delta[k],
              n,
              stencil.g[k] * g_scale,
              stencil.a[k],
              stencil.b[k]);
          };
          if (on_stencil(i))
            for (unsigned int k = 0; k < stencil.g.size(); ++k)
              visit(k, 1.);
          else
            for (std::size_t b = list_first[i]; b < list_first[i + 1]; ++b)
              visit(list_stencil_index[b], list_theta_scale[i]);
        }
      else
        for (std::size_t b = list_first[i]; b < list_first[i + 1]; ++b)
          {
            const ListBond &bond = list_bonds[b];
            f(static_cast<unsigned int>(bond.neighbor_slot),
              static_cast<std::ptrdiff_t>(bond.neighbor_slot),
              bond.n,
              bond.g,
              bond.a,
              bond.b);
          }
    }


    namespace
    {
      /// Per-thread scratch of the row kernel: blocks by key, marks, and the
      /// keys touched.
      template <int dim>
      struct RowScratch
      {
        std::vector<Tensor<2, dim>> block;
        std::vector<std::uint8_t>   mark;
        std::vector<std::ptrdiff_t> touched;

        void
        resize(const std::size_t n_keys)
        {
          if (block.size() != n_keys)
            {
              block.assign(n_keys, Tensor<2, dim>());
              mark.assign(n_keys, 0);
              touched.clear();
            }
        }

        void
        touch(const std::ptrdiff_t key)
        {
          if (!mark[key])
            {
              mark[key] = 1;
              touched.push_back(key);
            }
        }

        void
        clear()
        {
          for (const auto key : touched)
            {
              mark[key]  = 0;
              block[key] = Tensor<2, dim>();
            }
          touched.clear();
        }
      };
    } // namespace


    template <int dim>
    void
    BondOperator<dim>::assemble(TrilinosWrappers::SparseMatrix  &matrix,
                                const AffineConstraints<double> *constraints,
                                TrilinosWrappers::MPI::Vector   *rhs) const
    {
      const auto        &node_set = *nodes;
      const unsigned int n        = node_set.size();
      const unsigned int n_owned  = node_set.n_owned();
      const MPI_Comm     comm     = node_set.get_communicator();
      AssertThrow(constraints == nullptr || rhs != nullptr,
                  ExcMessage("BondOperator::assemble: constraints need a "
                             "right-hand side vector."));

      // Which components are prescribed, and to what: looked up once here,
      // never in the loops over nonzeros.
      std::vector<std::uint8_t> prescribed(std::size_t(n) * dim, 0);
      std::vector<double>       prescribed_value(prescribed.size(), 0.);
      std::vector<std::uint8_t> fully_prescribed(n, 0);
      bool                      only_values = true;
      if (constraints != nullptr)
        for (unsigned int k = 0; k < n; ++k)
          {
            unsigned int count = 0;
            for (unsigned int c = 0; c < dim; ++c)
              {
                const auto dof = node_set[k].dofs[c];
                if (constraints->is_constrained(dof))
                  {
                    only_values = only_values &&
                                  constraints->get_constraint_entries(dof)
                                    ->empty();
                    prescribed[std::size_t(k) * dim + c] = 1;
                    prescribed_value[std::size_t(k) * dim + c] =
                      constraints->get_inhomogeneity(dof);
                    ++count;
                  }
              }
            fully_prescribed[k] = (count == dim);
          }
      throw_on_any_rank(only_values ?
                          std::string() :
                          "The PD operator eliminates only prescribed values "
                          "u_k = g_k, not constraints that couple DoFs.",
                        comm);

      // Keys of the scratch: on the lattice the index in a box of side
      // 2R + 1 around the row's node (R = the coupling reach in cells), off
      // it the local node index.
      const auto                 &lattice = lists->lattice();
      int                         reach   = 0;
      std::vector<std::ptrdiff_t> box_delta;
      std::ptrdiff_t              width = 1, centre = 0;
      std::size_t                 n_keys = n;
      if (use_lattice)
        {
          for (const auto &o : lists->stencil())
            for (unsigned int d = 0; d < dim; ++d)
              reach = std::max(reach, std::abs(o.offset[d]));
          const int R = (state_based ? 2 : 1) * reach;
          width       = 2 * R + 1;
          n_keys      = 1;
          std::ptrdiff_t stride = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              centre += R * stride;
              stride *= width;
              n_keys *= width;
            }
          for (const auto &o : lists->stencil())
            {
              std::ptrdiff_t delta = 0, s = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  delta += o.offset[d] * s;
                  s *= width;
                }
              box_delta.push_back(delta);
            }
        }
      // The node at key @p key of row node i.
      const auto node_of_key = [&](const unsigned int   i,
                                   const std::ptrdiff_t key) -> unsigned int {
        if (!use_lattice)
          return key;
        std::array<std::int64_t, dim> y = lattice.coordinates(i);
        std::ptrdiff_t                rest = key;
        for (unsigned int d = 0; d < dim; ++d)
          {
            y[d] += rest % width - (width - 1) / 2;
            rest /= width;
          }
        return static_cast<unsigned int>(lattice.node_at(y));
      };
      // The key of node k in row i.
      const auto key_of_node = [&](const unsigned int i,
                                   const unsigned int k) -> std::ptrdiff_t {
        if (!use_lattice)
          return k;
        const auto    &x = lattice.coordinates(i), &y = lattice.coordinates(k);
        std::ptrdiff_t key = 0, s = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            key += (y[d] - x[d] + (width - 1) / 2) * s;
            s *= width;
          }
        return key;
      };

      // dF_i/du into the scratch, by key (block = dF_i/du_k):
      //   F_i = sum_j [a (s_i theta_i + s_j theta_j) + b (s_i + s_j) e_ij] n,
      //   d theta_p/du_q = g_pq n_pq (q != p), -G_p (q = p).
      const auto form_row = [&](const unsigned int  i,
                                RowScratch<dim>    &scratch,
                                const bool          values) {
        const std::ptrdiff_t key_i = use_lattice ? centre : i;
        const double         s_i   = s_slot[slot[i]];
        auto                &block = scratch.block;
        scratch.touch(key_i);
        Tensor<1, dim> A, G_i;
        for_each_bond_constants(
          i,
          key_i,
          box_delta,
          [&](const unsigned int   j,
              const std::ptrdiff_t key_j,
              const double        *n_ij,
              const double         g,
              const double         a,
              const double         b) {
            scratch.touch(key_j);
            const double s_j = s_slot[slot[j]];
            if (values)
              {
                const double kb = b * (s_i + s_j);
                for (unsigned int p = 0; p < dim; ++p)
                  for (unsigned int q = 0; q < dim; ++q)
                    {
                      const double v = kb * n_ij[p] * n_ij[q];
                      block[key_j][p][q] += v;
                      block[key_i][p][q] -= v;
                    }
              }
            if (!state_based)
              return;
            double t[dim];
            for (unsigned int p = 0; p < dim; ++p)
              {
                A[p] += a * s_i * n_ij[p];
                G_i[p] += g * n_ij[p];
                t[p] = a * s_j * n_ij[p];
              }
            Tensor<1, dim> G_j;
            for_each_bond_constants(
              j,
              key_j,
              box_delta,
              [&](const unsigned int,
                  const std::ptrdiff_t key_q,
                  const double        *n_jq,
                  const double         g_jq,
                  const double,
                  const double) {
                scratch.touch(key_q);
                if (!values)
                  return;
                Tensor<2, dim> &target = block[key_q];
                for (unsigned int q = 0; q < dim; ++q)
                  {
                    const double gn = g_jq * n_jq[q];
                    G_j[q] += gn;
                    for (unsigned int p = 0; p < dim; ++p)
                      target[p][q] += t[p] * gn;
                  }
              });
            if (values)
              for (unsigned int p = 0; p < dim; ++p)
                for (unsigned int q = 0; q < dim; ++q)
                  block[key_j][p][q] -= t[p] * G_j[q];
          });
        if (state_based && values)
          {
            for_each_bond_constants(
              i,
              key_i,
              box_delta,
              [&](const unsigned int,
                  const std::ptrdiff_t key_j,
                  const double        *n_ij,
                  const double         g,
                  const double,
                  const double) {
                for (unsigned int p = 0; p < dim; ++p)
                  for (unsigned int q = 0; q < dim; ++q)
                    block[key_j][p][q] += A[p] * g * n_ij[q];
              });
            for (unsigned int p = 0; p < dim; ++p)
              for (unsigned int q = 0; q < dim; ++q)
                block[key_i][p][q] -= A[p] * G_i[q];
          }
      };

      // The positive diagonal kept in the row of a prescribed DoF: the
      // pairwise part of K_kk (the scale of K_kk, one pass over the bonds).
      const auto prescribed_diagonal = [&](const unsigned int i,
                                           const unsigned int r) {
        double       d   = 0;
        const double s_i = s_slot[slot[i]];
        for_each_bond_constants(i,
                                0,
                                box_delta,
                                [&](const unsigned int j,
                                    const std::ptrdiff_t,
                                    const double *n_ij,
                                    const double,
                                    const double,
                                    const double b) {
                                  d += std::abs(b * (s_i + s_slot[slot[j]])) *
                                       n_ij[r] * n_ij[r];
                                });
        return d > 0 ? d : 1.;
      };

      // Bulk rows (uniform grid): the node and every neighbour on the shared
      // stencil. Their blocks are one block shifted: computed once.
      std::vector<std::uint8_t> bulk_row(n_owned, 0);
      RowScratch<dim>           bulk;
      std::vector<std::ptrdiff_t> bulk_keys;
      if (use_lattice)
        {
          int representative = -1;
          for (unsigned int i = 0; i < n_owned; ++i)
            if (on_stencil(i))
              {
                bool all = true;
                for (unsigned int k = 0; k < stencil.g.size() && all; ++k)
                  all = on_stencil(static_cast<unsigned int>(
                    lattice.node_at_slot(slot[i] + stencil.slot_offset[k])));
                bulk_row[i] = all;
                if (all && representative < 0)
                  representative = i;
              }
          if (representative >= 0)
            {
              bulk.resize(n_keys);
              form_row(representative, bulk, true);
              bulk_keys = bulk.touched;
              std::sort(bulk_keys.begin(), bulk_keys.end());
            }
        }

      Threads::ThreadLocalStorage<RowScratch<dim>> thread_scratch;
      const auto scratch_of = [&]() -> RowScratch<dim> & {
        auto &scratch = thread_scratch.get();
        scratch.resize(n_keys);
        return scratch;
      };
      // The column nodes of row node i in ascending column order (keys
      // ascending = slots ascending on the lattice; node index off it);
      // leaves the scratch marked, to be cleared by the caller.
      const auto row_keys =
        [&](const unsigned int i,
            RowScratch<dim>   &scratch,
            const bool         values) -> const std::vector<std::ptrdiff_t> & {
        if (use_lattice && bulk_row[i])
          return bulk_keys;
        form_row(i, scratch, values);
        std::sort(scratch.touched.begin(), scratch.touched.end());
        return scratch.touched;
      };

      // Columns: every node within two bonds of an owned node, ordered by
      // slot on the lattice and by local index otherwise, dim columns each.
      std::vector<int>                               column_of_node(n, -1);
      std::vector<unsigned int>                      column_nodes;
      std::vector<TrilinosWrappers::types::int_type> column_gids;
      {
        std::vector<std::uint8_t> used(n, 0);
        for (unsigned int i = 0; i < n_owned; ++i)
          {
            used[i] = 1;
            for_each_bond_constants(
              i,
              0,
              box_delta,
              [&](const unsigned int j,
                  const std::ptrdiff_t,
                  const double *,
                  const double,
                  const double,
                  const double) { used[j] |= 2; });
          }
        if (state_based)
          for (unsigned int j = 0; j < n; ++j)
            if (used[j] & 2)
              for_each_bond_constants(
                j,
                0,
                box_delta,
                [&](const unsigned int q,
                    const std::ptrdiff_t,
                    const double *,
                    const double,
                    const double,
                    const double) { used[q] |= 4; });
        std::vector<unsigned int> order;
        for (unsigned int k = 0; k < n; ++k)
          if (used[k])
            order.push_back(k);
        if (use_lattice)
          std::sort(order.begin(),
                    order.end(),
                    [&](const unsigned int p, const unsigned int q) {
                      return slot[p] < slot[q];
                    });
        std::vector<TrilinosWrappers::types::int_type> gids;
        gids.reserve(order.size() * dim);
        for (unsigned int c = 0; c < order.size(); ++c)
          {
            column_of_node[order[c]] = c;
            for (unsigned int d = 0; d < dim; ++d)
              gids.push_back(node_set[order[c]].dofs[d]);
          }
        column_gids.swap(gids);
        column_nodes.swap(order);
      }

      const IndexSet  &owned = partitioner->locally_owned_range();
      const Epetra_Map row_map = owned.make_trilinos_map(comm, false);
      Epetra_MpiComm   epetra_comm(comm);
      const Epetra_Map column_map(-1,
                                  static_cast<int>(column_gids.size()),
                                  column_gids.data(),
                                  0,
                                  epetra_comm);
      std::vector<int> row_of_node(n_owned);
      for (unsigned int i = 0; i < n_owned; ++i)
        row_of_node[i] = row_map.LID(
          static_cast<TrilinosWrappers::types::int_type>(node_set[i].dofs[0]));

      // Row lengths, then the graph, built in blocks of rows: the column
      // lists of a block are formed in parallel and inserted in order.
      std::vector<int> row_length(owned.n_elements(), 0);
      const auto       free_columns = [&](const unsigned int i,
                                    const std::vector<std::ptrdiff_t> &keys,
                                    std::vector<int> *columns) {
        int count = 0;
        for (const auto key : keys)
          {
            const unsigned int k    = node_of_key(i, key);
            const int          base = column_of_node[k] * dim;
            for (unsigned int c = 0; c < dim; ++c)
              if (!prescribed[std::size_t(k) * dim + c])
                {
                  ++count;
                  if (columns != nullptr)
                    columns->push_back(base + c);
                }
          }
        return count;
      };
      parallel::apply_to_subranges(
        0u,
        n_owned,
        [&](const unsigned int begin, const unsigned int end) {
          auto &scratch = scratch_of();
          for (unsigned int i = begin; i < end; ++i)
            {
              int count = 0;
              if (!fully_prescribed[i])
                {
                  count = free_columns(i, row_keys(i, scratch, false), nullptr);
                  scratch.clear();
                }
              for (unsigned int r = 0; r < dim; ++r)
                row_length[row_of_node[i] + r] =
                  prescribed[std::size_t(i) * dim + r] ? 1 : count;
            }
        },
        64);

      Epetra_CrsGraph graph(Copy, row_map, column_map, row_length.data(), true);
      {
        constexpr unsigned int        block_rows = 512;
        std::vector<std::vector<int>> columns(block_rows);
        for (unsigned int first = 0; first < n_owned; first += block_rows)
          {
            const unsigned int last = std::min(n_owned, first + block_rows);
            parallel::apply_to_subranges(
              first,
              last,
              [&](const unsigned int begin, const unsigned int end) {
                auto &scratch = scratch_of();
                for (unsigned int i = begin; i < end; ++i)
                  {
                    auto &list = columns[i - first];
                    list.clear();
                    if (fully_prescribed[i])
                      continue;
                    free_columns(i, row_keys(i, scratch, false), &list);
                    scratch.clear();
                  }
              },
              16);
            for (unsigned int i = first; i < last; ++i)
              for (unsigned int r = 0; r < dim; ++r)
                {
                  const int row = row_of_node[i] + r;
                  int       error;
                  if (prescribed[std::size_t(i) * dim + r])
                    {
                      int diagonal = column_of_node[i] * dim + r;
                      error        = graph.InsertMyIndices(row, 1, &diagonal);
                    }
                  else
                    error = graph.InsertMyIndices(row,
                                                  columns[i - first].size(),
                                                  columns[i - first].data());
                  AssertThrow(error == 0,
                              ExcMessage("Epetra_CrsGraph::InsertMyIndices "
                                         "failed with error " +
                                         std::to_string(error)));
                }
          }
      }
      AssertThrow(graph.FillComplete(row_map, row_map) == 0,
                  ExcMessage("Epetra_CrsGraph::FillComplete failed."));
      {
        // deal.II's matrix shares the graph (Epetra graphs are reference
        // counted); the temporary holds a second value array for a moment.
        Epetra_CrsMatrix layout(Copy, graph);
        AssertThrow(layout.FillComplete(row_map, row_map) == 0,
                    ExcMessage("Epetra_CrsMatrix::FillComplete failed."));
        matrix.reinit(layout, false);
      }
      const Epetra_CrsMatrix &epetra = matrix.trilinos_matrix();
      AssertThrow(epetra.ColMap().SameAs(column_map),
                  ExcInternalError());

      // Values, threaded over rows: each row written in place.
      std::vector<double> rhs_add(constraints != nullptr ? owned.n_elements() :
                                                           0,
                                  0.);
      parallel::apply_to_subranges(
        0u,
        n_owned,
        [&](const unsigned int begin, const unsigned int end) {
          auto &scratch = scratch_of();
          for (unsigned int i = begin; i < end; ++i)
            {
              const bool use_bulk = use_lattice && bulk_row[i];
              const std::vector<std::ptrdiff_t> *keys = nullptr;
              if (!fully_prescribed[i])
                keys = &row_keys(i, scratch, true);
              const auto &block = use_bulk ? bulk.block : scratch.block;
              for (unsigned int r = 0; r < dim; ++r)
                {
                  const int row = row_of_node[i] + r;
                  int       length;
                  double   *values;
                  int      *columns;
                  epetra.ExtractMyRowView(row, length, values, columns);
                  if (prescribed[std::size_t(i) * dim + r])
                    {
                      const double d = prescribed_diagonal(i, r);
                      values[0]      = d;
                      rhs_add[row] +=
                        d * prescribed_value[std::size_t(i) * dim + r];
                      continue;
                    }
                  for (int e = 0; e < length; ++e)
                    {
                      const unsigned int   k   = column_nodes[columns[e] / dim];
                      const std::ptrdiff_t key = key_of_node(i, k);
                      values[e] = -block[key][r][columns[e] % dim];
                    }
                  if (constraints != nullptr)
                    {
                      double moved = 0;
                      for (const auto key : *keys)
                        {
                          const unsigned int k = node_of_key(i, key);
                          for (unsigned int c = 0; c < dim; ++c)
                            if (prescribed[std::size_t(k) * dim + c])
                              moved +=
                                block[key][r][c] *
                                prescribed_value[std::size_t(k) * dim + c];
                        }
                      rhs_add[row] += moved;
                    }
                }
              if (!use_bulk && !fully_prescribed[i])
                scratch.clear();
            }
        },
        16);
      if (constraints != nullptr)
        {
          for (unsigned int l = 0; l < owned.n_elements(); ++l)
            if (rhs_add[l] != 0)
              (*rhs)[owned.nth_index_in_set(l)] += rhs_add[l];
          rhs->compress(VectorOperation::add);
        }
    }


    template void
    BondOperator<2>::assemble(TrilinosWrappers::SparseMatrix &,
                              const AffineConstraints<double> *,
                              TrilinosWrappers::MPI::Vector *) const;
    template void
    BondOperator<3>::assemble(TrilinosWrappers::SparseMatrix &,
                              const AffineConstraints<double> *,
                              TrilinosWrappers::MPI::Vector *) const;
  } // namespace Operators
} // namespace PeriDEAL
