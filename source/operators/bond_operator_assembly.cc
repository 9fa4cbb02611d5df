// The assembled stiffness of BondOperator: the Trilinos matrix built from the
// same stencil, lists, bond state and kernel as the matrix-free apply().

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/thread_local_storage.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <perideal/base/collective_checks.h>
#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/bond_operator.templates.h>

#include <Epetra_CrsGraph.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_MpiComm.h>

#include <algorithm>
#include <cstdint>
#include <limits>

namespace PeriDEAL
{
  namespace Operators
  {
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
                    only_values =
                      only_values &&
                      constraints->get_constraint_entries(dof)->empty();
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
      // 2R + 1 around the row's node (R = the coupling reach in cells), x
      // fastest like the slots, so that ascending keys are ascending slots;
      // off the lattice the local node index.
      const auto                 &lattice = lists->lattice();
      std::vector<std::ptrdiff_t> box_delta;
      std::vector<double>         stencil_gn; // g_k n_k, dim per offset
      std::ptrdiff_t              width = 1, centre = 0;
      std::size_t                 n_keys = n;
      if (layout.use_lattice)
        {
          int reach = 0;
          for (const auto &o : lists->stencil())
            for (unsigned int d = 0; d < dim; ++d)
              reach = std::max(reach, std::abs(o.offset[d]));
          const int R = (state_based ? 2 : 1) * reach;
          width       = 2 * R + 1;
          n_keys      = 1;
          for (unsigned int d = 0; d < dim; ++d)
            {
              centre += R * static_cast<std::ptrdiff_t>(n_keys);
              n_keys *= width;
            }
          for (unsigned int k = 0; k < lists->stencil().size(); ++k)
            {
              std::ptrdiff_t delta = 0, stride = 1;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  delta += lists->stencil()[k].offset[d] * stride;
                  stride *= width;
                  stencil_gn.push_back(stencil.g[k] * stencil.n[d][k]);
                }
              box_delta.push_back(delta);
            }
        }
      throw_on_any_rank(n_keys < std::numeric_limits<std::uint32_t>::max() ?
                          std::string() :
                          "Too many nodes on one process for the assembly's "
                          "32-bit row keys: use more processes.",
                        comm);
      const auto node_of_key = [&](const unsigned int   i,
                                   const std::ptrdiff_t key) -> unsigned int {
        if (!layout.use_lattice)
          return key;
        std::array<std::int64_t, dim> y    = lattice.coordinates(i);
        std::ptrdiff_t                rest = key;
        for (unsigned int d = 0; d < dim; ++d)
          {
            y[d] += rest % width - (width - 1) / 2;
            rest /= width;
          }
        return static_cast<unsigned int>(lattice.node_at(y));
      };
      const auto key_of_node = [&](const unsigned int i,
                                   const unsigned int k) -> std::ptrdiff_t {
        if (!layout.use_lattice)
          return k;
        const auto    &x = lattice.coordinates(i), &y = lattice.coordinates(k);
        std::ptrdiff_t key = 0, stride = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            key += (y[d] - x[d] + (width - 1) / 2) * stride;
            stride *= width;
          }
        return key;
      };
      const auto on_full_stencil = [&](const unsigned int j) {
        return layout.use_lattice && layout.on_stencil(j);
      };

      // The dilatation row of node j (key key_j), d theta_j / du_q:
      // f(key_q, gn) for every q != j with gn[c] = d theta_j / du_q[c]
      // (d theta_j / du_j = -sum_q gn). The standard row (g_jq n_jq), or the
      // collocation row T of a node whose dilatation comes from it (LPS
      // collocation, use_collocation()).
      const bool lps_rows = !collocation_theta.empty();
      const auto theta_entries =
        [&](const unsigned int j, const std::ptrdiff_t key_j, const auto &f) {
          if (has_collocation_theta(j))
            for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
              {
                double gn[dim];
                for (unsigned int q = 0; q < dim; ++q)
                  gn[q] = collocation_row.theta_w[q][k];
                f(key_j + box_delta[collocation_row.stencil_index[k]], gn);
              }
          else if (on_full_stencil(j))
            for (std::size_t k = 0; k < box_delta.size(); ++k)
              f(key_j + box_delta[k], &stencil_gn[k * dim]);
          else
            for_each_bond_constants(j,
                                    key_j,
                                    box_delta,
                                    [&](const std::size_t,
                                        const std::ptrdiff_t key_q,
                                        const double        *n_jq,
                                        const double         g_jq,
                                        const double,
                                        const double) {
                                      double gn[dim];
                                      for (unsigned int q = 0; q < dim; ++q)
                                        gn[q] = g_jq * n_jq[q];
                                      f(key_q, gn);
                                    });
        };

      // The structure of row i: the keys of i, its neighbours and (state-
      // based) theirs, ascending.
      const auto row_structure = [&](const unsigned int          i,
                                     std::vector<std::uint8_t>  &mark,
                                     std::vector<std::uint32_t> &keys) {
        keys.clear();
        const std::ptrdiff_t key_i = layout.use_lattice ? centre : i;
        const auto           touch = [&](const std::ptrdiff_t key) {
          if (!mark[key])
            {
              mark[key] = 1;
              keys.push_back(key);
            }
        };
        touch(key_i);
        const auto touch_theta = [&](const std::ptrdiff_t key_q,
                                     const double *) { touch(key_q); };
        if (!node_rows.node.empty() && is_collocation_node(i))
          {
            // A row of its own (irregular nodes; keys are node indices).
            const int r = node_row_of[i];
            for (std::size_t e = node_rows.first[r]; e < node_rows.first[r + 1];
                 ++e)
              touch(layout.node_of_slot(node_rows.neighbor_slot[e]));
          }
        else if (lps_rows && is_collocation_node(i))
          // A collocation row of LPS: its cloud and their dilatation rows.
          for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
            {
              const std::ptrdiff_t key_j =
                key_i + box_delta[collocation_row.stencil_index[k]];
              touch(key_j);
              theta_entries(layout.node_of_slot(layout.slot[i] +
                                                collocation_row.offset[k]),
                            key_j,
                            touch_theta);
            }
        else
          for_each_bond_constants(i,
                                  key_i,
                                  box_delta,
                                  [&](const std::size_t    slot_j,
                                      const std::ptrdiff_t key_j,
                                      const double *,
                                      const double,
                                      const double,
                                      const double) {
                                    touch(key_j);
                                    if (state_based)
                                      theta_entries(layout.node_of_slot(slot_j),
                                                    key_j,
                                                    touch_theta);
                                  });
        std::sort(keys.begin(), keys.end());
        for (const auto key : keys)
          mark[key] = 0;
      };

      // dF_i/du_k into block[key(k)], which must be zero on entry:
      //   F_i = sum_j [a (s_i theta_i + s_j theta_j) + b (s_i + s_j) e_ij] n,
      //   d theta_p/du_q = g_pq n_pq (q != p), -G_p (q = p).
      // block += factor (x) d theta_j / du (j's dilatation row, key key_j),
      // the column of j itself included: the dilatation terms of a force
      // row, standard and collocation alike.
      const auto add_theta_row = [&](const unsigned int           j,
                                     const std::ptrdiff_t         key_j,
                                     const double                *factor,
                                     std::vector<Tensor<2, dim>> &block) {
        double G_j[dim] = {};
        theta_entries(j,
                      key_j,
                      [&](const std::ptrdiff_t key_q, const double *gn) {
                        Tensor<2, dim> &target = block[key_q];
                        for (unsigned int q = 0; q < dim; ++q)
                          {
                            G_j[q] += gn[q];
                            for (unsigned int p = 0; p < dim; ++p)
                              target[p][q] += factor[p] * gn[q];
                          }
                      });
        for (unsigned int p = 0; p < dim; ++p)
          for (unsigned int q = 0; q < dim; ++q)
            block[key_j][p][q] -= factor[p] * G_j[q];
      };

      const auto row_values = [&](const unsigned int           i,
                                  std::vector<Tensor<2, dim>> &block) {
        const std::ptrdiff_t key_i = layout.use_lattice ? centre : i;
        const double         s_i   = s_slot[layout.slot[i]];
        Tensor<1, dim>       A, G_i;
        for_each_bond_constants(
          i,
          key_i,
          box_delta,
          [&](const std::size_t    slot_j,
              const std::ptrdiff_t key_j,
              const double        *n_ij,
              const double         g,
              const double         a,
              const double         b) {
            const double s_j = s_slot[slot_j];
            const double kb  = BondKernel::extension_stiffness(b, s_i, s_j);
            for (unsigned int p = 0; p < dim; ++p)
              for (unsigned int q = 0; q < dim; ++q)
                {
                  const double v = kb * n_ij[p] * n_ij[q];
                  block[key_j][p][q] += v;
                  block[key_i][p][q] -= v;
                }
            if (!state_based)
              return;
            double       t[dim];
            const double a_i = BondKernel::dilatation_stiffness(a, s_i);
            const double a_j = BondKernel::dilatation_stiffness(a, s_j);
            for (unsigned int p = 0; p < dim; ++p)
              {
                A[p] += a_i * n_ij[p];
                G_i[p] += g * n_ij[p];
                t[p] = a_j * n_ij[p];
              }
            add_theta_row(layout.node_of_slot(slot_j), key_j, t, block);
          });
        if (!state_based)
          return;
        for_each_bond_constants(i,
                                key_i,
                                box_delta,
                                [&](const std::size_t,
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
      };

      // dF_i/du of a collocation row of LPS (use_collocation()):
      //   F_i = sum_k [V W_k (u_{i+k} - u_i) + V K_k (theta_{i+k} - theta_i)].
      const auto collocation_lps_values =
        [&](const unsigned int i, std::vector<Tensor<2, dim>> &block) {
          const std::ptrdiff_t key_i = centre;
          const std::size_t    n_row = collocation_row.offset.size();
          Tensor<1, dim>       k_sum;
          for (std::size_t k = 0; k < n_row; ++k)
            {
              const std::ptrdiff_t key_j =
                key_i + box_delta[collocation_row.stencil_index[k]];
              for (unsigned int p = 0; p < dim; ++p)
                {
                  k_sum[p] += collocation_row.kf[p][k];
                  for (unsigned int q = 0; q < dim; ++q)
                    {
                      const double w = collocation_row.w[p * dim + q][k];
                      block[key_j][p][q] += w;
                      block[key_i][p][q] -= w;
                    }
                }
            }
          for (std::size_t k = 0; k < n_row; ++k)
            {
              double factor[dim];
              for (unsigned int p = 0; p < dim; ++p)
                factor[p] = collocation_row.kf[p][k];
              add_theta_row(layout.node_of_slot(layout.slot[i] +
                                                collocation_row.offset[k]),
                            key_i + box_delta[collocation_row.stencil_index[k]],
                            factor,
                            block);
            }
          double minus_sum[dim];
          for (unsigned int p = 0; p < dim; ++p)
            minus_sum[p] = -k_sum[p];
          add_theta_row(i, key_i, minus_sum, block);
        };

      // The positive diagonal kept in the row of a prescribed DoF: the
      // pairwise part of K_kk (the scale of K_kk, one pass over the bonds).
      const auto prescribed_diagonal = [&](const unsigned int i,
                                           const unsigned int r) {
        double       d   = 0;
        const double s_i = s_slot[layout.slot[i]];
        for_each_bond_constants(
          i,
          0,
          box_delta,
          [&](const std::size_t slot_j,
              const std::ptrdiff_t,
              const double *n_ij,
              const double,
              const double,
              const double b) {
            d += std::abs(
                   BondKernel::extension_stiffness(b, s_i, s_slot[slot_j])) *
                 n_ij[r] * n_ij[r];
          });
        return d > 0 ? d : 1.;
      };

      // Bulk rows (uniform grid): the node and every neighbour on the shared
      // stencil. Their blocks are one block shifted: formed once.
      std::vector<std::uint8_t>   bulk_row(n_owned, 0);
      std::vector<Tensor<2, dim>> bulk_block;
      std::vector<std::uint32_t>  bulk_keys;
      if (layout.use_lattice)
        {
          int representative = -1;
          for (unsigned int i = 0; i < n_owned; ++i)
            if (layout.on_stencil(i) && !is_collocation_node(i))
              {
                bool all = true;
                for (unsigned int k = 0; k < stencil.g.size() && all; ++k)
                  {
                    const unsigned int j = layout.node_of_slot(
                      layout.slot[i] + layout.stencil_offset[k]);
                    all = layout.on_stencil(j) && !has_collocation_theta(j);
                  }
                bulk_row[i] = all;
                if (all && representative < 0)
                  representative = i;
              }
          if (representative >= 0)
            {
              std::vector<std::uint8_t> mark(n_keys, 0);
              row_structure(representative, mark, bulk_keys);
              bulk_block.assign(n_keys, Tensor<2, dim>());
              row_values(representative, bulk_block);
            }
        }

      // Collocation rows (use_collocation()): one row shifted, like the
      // bulk rows: dF_i/du_j = V W_k at the node o_k, -V sum_k W_k at i.
      std::vector<Tensor<2, dim>> collocation_block;
      std::vector<std::uint32_t>  collocation_keys;
      if (!collocation_row.offset.empty() && !lps_rows)
        {
          collocation_block.assign(n_keys, Tensor<2, dim>());
          collocation_keys.push_back(centre);
          for (std::size_t k = 0; k < collocation_row.offset.size(); ++k)
            {
              const std::ptrdiff_t key =
                centre + box_delta[collocation_row.stencil_index[k]];
              collocation_keys.push_back(key);
              for (unsigned int p = 0; p < dim; ++p)
                for (unsigned int q = 0; q < dim; ++q)
                  {
                    const double w = collocation_row.w[p * dim + q][k];
                    collocation_block[key][p][q] += w;
                    collocation_block[centre][p][q] -= w;
                  }
            }
          std::sort(collocation_keys.begin(), collocation_keys.end());
        }
      // (LPS collocation rows differ where a cloud node's dilatation is
      // standard: formed row by row.)
      const auto shared_collocation_row = [&](const unsigned int i) {
        return is_collocation_node(i) && !lps_rows && node_rows.node.empty();
      };
      const auto shared_row = [&](const unsigned int i) {
        return layout.use_lattice && (bulk_row[i] || shared_collocation_row(i));
      };

      // Columns: every node within two bonds of an owned node, dim columns
      // each; the owned nodes first in the order of the rows (solvers such
      // as AztecOO need the local columns first and matching the rows), then
      // the others.
      const IndexSet  &owned   = layout.partitioner->locally_owned_range();
      const Epetra_Map row_map = owned.make_trilinos_map(comm, false);
      std::vector<int> row_of_node(n_owned);
      for (unsigned int i = 0; i < n_owned; ++i)
        row_of_node[i] = row_map.LID(
          static_cast<TrilinosWrappers::types::int_type>(node_set[i].dofs[0]));
      std::vector<int>                               column_of_node(n, -1);
      std::vector<unsigned int>                      column_nodes;
      std::vector<TrilinosWrappers::types::int_type> column_gids;
      {
        std::vector<std::uint8_t> used(n, 0);
        const auto                mark_neighbours = [&](const unsigned int i,
                                         const std::uint8_t flag) {
          for_each_bond_constants(i,
                                  0,
                                  box_delta,
                                  [&](const std::size_t slot_j,
                                      const std::ptrdiff_t,
                                      const double *,
                                      const double,
                                      const double,
                                      const double) {
                                    used[layout.node_of_slot(slot_j)] |= flag;
                                  });
        };
        for (unsigned int i = 0; i < n_owned; ++i)
          {
            used[i] |= 1;
            mark_neighbours(i, 2);
            // A row of its own (irregular nodes) has no work list.
            if (!node_rows.node.empty() && is_collocation_node(i))
              {
                const int r = node_row_of[i];
                for (std::size_t e = node_rows.first[r];
                     e < node_rows.first[r + 1];
                     ++e)
                  used[layout.node_of_slot(node_rows.neighbor_slot[e])] |= 2;
              }
          }
        if (state_based)
          for (unsigned int j = 0; j < n; ++j)
            if (used[j] & 2)
              mark_neighbours(j, 4);
        column_nodes.resize(n_owned);
        for (unsigned int i = 0; i < n_owned; ++i)
          column_nodes[row_of_node[i] / dim] = i;
        for (unsigned int k = n_owned; k < n; ++k)
          if (used[k])
            column_nodes.push_back(k);
        column_gids.reserve(column_nodes.size() * dim);
        for (unsigned int c = 0; c < column_nodes.size(); ++c)
          {
            column_of_node[column_nodes[c]] = c;
            for (unsigned int d = 0; d < dim; ++d)
              column_gids.push_back(node_set[column_nodes[c]].dofs[d]);
          }
      }
      Epetra_MpiComm   epetra_comm(comm);
      const Epetra_Map column_map(-1,
                                  static_cast<int>(column_gids.size()),
                                  column_gids.data(),
                                  0,
                                  epetra_comm);

      // The structure of every row other than the bulk ones, as keys (one
      // per column node: a ninth of the graph in 3D), and the row lengths.
      std::vector<std::vector<std::uint32_t>> stored_keys(n_owned);
      const auto                              keys_of =
        [&](const unsigned int i) -> const std::vector<std::uint32_t> & {
        return shared_collocation_row(i)         ? collocation_keys :
               layout.use_lattice && bulk_row[i] ? bulk_keys :
                                                   stored_keys[i];
      };
      std::vector<int> row_length(owned.n_elements(), 0);
      {
        Threads::ThreadLocalStorage<std::vector<std::uint8_t>> thread_mark;
        parallel::apply_to_subranges(
          0u,
          n_owned,
          [&](const unsigned int begin, const unsigned int end) {
            auto &mark = thread_mark.get();
            if (mark.size() != n_keys)
              mark.assign(n_keys, 0);
            for (unsigned int i = begin; i < end; ++i)
              {
                int count = 0;
                if (!fully_prescribed[i])
                  {
                    if (!shared_row(i))
                      row_structure(i, mark, stored_keys[i]);
                    for (const auto key : keys_of(i))
                      {
                        const unsigned int k = node_of_key(i, key);
                        for (unsigned int c = 0; c < dim; ++c)
                          count += !prescribed[std::size_t(k) * dim + c];
                      }
                  }
                for (unsigned int r = 0; r < dim; ++r)
                  row_length[row_of_node[i] + r] =
                    prescribed[std::size_t(i) * dim + r] ? 1 : count;
              }
          },
          16);
      }

      // The graph, with exact row lengths and columns in ascending order:
      // the column lists of a block of rows are formed and sorted in
      // parallel, then inserted in order.
      Epetra_CrsGraph graph(Copy, row_map, column_map, row_length.data(), true);
      int             insert_error = 0; // the first failure, shared below
      {
        constexpr unsigned int        block_nodes = 1024;
        std::vector<std::vector<int>> columns(block_nodes);
        for (unsigned int first = 0; first < n_owned; first += block_nodes)
          {
            const unsigned int last = std::min(n_owned, first + block_nodes);
            parallel::apply_to_subranges(
              first,
              last,
              [&](const unsigned int begin, const unsigned int end) {
                for (unsigned int i = begin; i < end; ++i)
                  {
                    auto &list = columns[i - first];
                    list.clear();
                    if (fully_prescribed[i])
                      continue;
                    for (const auto key : keys_of(i))
                      list.push_back(column_of_node[node_of_key(i, key)]);
                    std::sort(list.begin(), list.end());
                    // Expand to components, prescribed ones left out.
                    const std::size_t n_nodes = list.size();
                    list.resize(n_nodes * (dim + 1));
                    std::size_t out = n_nodes;
                    for (std::size_t e = 0; e < n_nodes; ++e)
                      {
                        const unsigned int k = column_nodes[list[e]];
                        for (unsigned int c = 0; c < dim; ++c)
                          if (!prescribed[std::size_t(k) * dim + c])
                            list[out++] = list[e] * dim + c;
                      }
                    list.erase(list.begin(), list.begin() + n_nodes);
                    list.resize(out - n_nodes);
                  }
              },
              32);
            for (unsigned int i = first; i < last; ++i)
              for (unsigned int r = 0; r < dim; ++r)
                {
                  int error;
                  if (prescribed[std::size_t(i) * dim + r])
                    {
                      int diagonal = column_of_node[i] * dim + r;
                      error =
                        graph.InsertMyIndices(row_of_node[i] + r, 1, &diagonal);
                    }
                  else
                    error = graph.InsertMyIndices(row_of_node[i] + r,
                                                  columns[i - first].size(),
                                                  columns[i - first].data());
                  if (error != 0 && insert_error == 0)
                    insert_error = error;
                }
          }
      }
      // Epetra's calls return local error codes: shared before anyone
      // throws (FillComplete itself is collective).
      const auto check_epetra = [&](const int error, const std::string &call) {
        throw_on_any_rank(error == 0 ? std::string() :
                                       "BondOperator::assemble: " + call +
                                         " failed with error " +
                                         std::to_string(error) + ".",
                          comm);
      };
      check_epetra(insert_error, "Epetra_CrsGraph::InsertMyIndices");
      check_epetra(graph.FillComplete(row_map, row_map),
                   "Epetra_CrsGraph::FillComplete");
      {
        // deal.II's matrix shares the graph (Epetra graphs are reference
        // counted); the layout's own value array lives only here.
        Epetra_CrsMatrix layout(Copy, graph);
        check_epetra(layout.FillComplete(row_map, row_map),
                     "Epetra_CrsMatrix::FillComplete");
        matrix.reinit(layout, false);
      }
      const Epetra_CrsMatrix &epetra = matrix.trilinos_matrix();
      check_epetra(epetra.ColMap().SameAs(column_map) ? 0 : -1,
                   "the column map of the matrix");

      // Values, threaded over rows, each written in place.
      std::vector<double> rhs_add(constraints != nullptr ? owned.n_elements() :
                                                           0,
                                  0.);
      Threads::ThreadLocalStorage<std::vector<Tensor<2, dim>>> thread_block;
      parallel::apply_to_subranges(
        0u,
        n_owned,
        [&](const unsigned int begin, const unsigned int end) {
          auto &scratch = thread_block.get();
          if (scratch.size() != n_keys)
            scratch.assign(n_keys, Tensor<2, dim>());
          for (unsigned int i = begin; i < end; ++i)
            {
              const bool  use_bulk = shared_row(i);
              const auto &keys     = keys_of(i);
              if (!use_bulk && !fully_prescribed[i])
                {
                  if (!node_rows.node.empty() && is_collocation_node(i))
                    {
                      const int r = node_row_of[i];
                      for (std::size_t e = node_rows.first[r];
                           e < node_rows.first[r + 1];
                           ++e)
                        {
                          const unsigned int j =
                            layout.node_of_slot(node_rows.neighbor_slot[e]);
                          for (unsigned int p = 0; p < dim; ++p)
                            for (unsigned int q = 0; q < dim; ++q)
                              {
                                const double w =
                                  node_rows.w[(e * dim + p) * dim + q];
                                scratch[j][p][q] += w;
                                scratch[i][p][q] -= w;
                              }
                        }
                    }
                  else if (lps_rows && is_collocation_node(i))
                    collocation_lps_values(i, scratch);
                  else
                    row_values(i, scratch);
                }
              const auto &block = shared_collocation_row(i) ?
                                    collocation_block :
                                  use_bulk ? bulk_block :
                                             scratch;
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
                      if (constraints != nullptr)
                        rhs_add[row] +=
                          d * prescribed_value[std::size_t(i) * dim + r];
                      continue;
                    }
                  for (int e = 0; e < length; ++e)
                    {
                      const unsigned int k = column_nodes[columns[e] / dim];
                      values[e] =
                        -block[key_of_node(i, k)][r][columns[e] % dim];
                    }
                  if (constraints != nullptr)
                    {
                      double moved = 0;
                      for (const auto key : keys)
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
              if (!use_bulk)
                for (const auto key : keys)
                  scratch[key] = Tensor<2, dim>();
            }
        },
        8);

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
