#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>

#include "reference_bond_operator.h"

namespace PeriDEAL
{
  namespace Testing
  {
    template <int dim>
    ReferenceBond<dim>
    make_reference_bond(const Models::Model<dim> &model,
                        const double              horizon,
                        const unsigned int        neighbor,
                        const Tensor<1, dim>     &xi,
                        const double              weight,
                        const double              m_i,
                        const bool                j_listed,
                        const double              m_j)
    {
      const bool         state_based = model.is_state_based();
      const double       r           = xi.norm();
      ReferenceBond<dim> bond;
      bond.neighbor = neighbor;
      bond.n        = xi / r;
      bond.weight   = weight;
      bond.theta_factor =
        state_based ? dim / m_i * model.influence(r, horizon) * r * weight : 0.;
      bond.a_i = model.dilatation_coefficient(m_i, r, horizon);
      bond.a_j = j_listed ? model.dilatation_coefficient(m_j, r, horizon) : 0.;
      bond.b_sum = model.extension_coefficient(m_i, r, horizon) +
                   (j_listed || !state_based ?
                      model.extension_coefficient(m_j, r, horizon) :
                      0.);
      return bond;
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::reinit(
      const Discretization::NodeSet<dim>      &node_set,
      const Discretization::NeighborList<dim> &lists,
      const Models::Model<dim>                &model,
      const double                             horizon)
    {
      nodes            = &node_set;
      state_based      = model.is_state_based();
      const unsigned n = node_set.size();

      listed.assign(n, false);
      m.assign(n, 0.);
      for (unsigned int i = 0; i < n; ++i)
        if (lists.has_list(i))
          {
            listed[i] = true;
            for (const auto &bond : lists.bonds(i))
              {
                const double r = node_set[i].location.distance(
                  node_set[bond.neighbor].location);
                m[i] += model.influence(r, horizon) * r * r * bond.weight;
              }
          }

      // State-based forces of owned nodes need the weighted volume and
      // dilatation of every neighbour: their lists must be there.
      if (state_based)
        for (unsigned int i = 0; i < node_set.n_owned(); ++i)
          for (const auto &bond : lists.bonds(i))
            AssertThrow(listed[bond.neighbor],
                        ExcMessage("A state-based model needs neighbour "
                                   "lists of the off-process neighbours of "
                                   "owned nodes: build the NeighborList with "
                                   "with_ghost_lists = true, and the NodeSet "
                                   "with a coupling range of at least twice "
                                   "the horizon plus two cell diameters."));

      offsets.assign(n + 1, 0);
      bonds.clear();
      for (unsigned int i = 0; i < n; ++i)
        {
          if (listed[i])
            for (const auto &bond : lists.bonds(i))
              {
                const unsigned int j = bond.neighbor;
                bonds.push_back(make_reference_bond<dim>(model,
                                                         horizon,
                                                         j,
                                                         node_set[j].location -
                                                           node_set[i].location,
                                                         bond.weight,
                                                         m[i],
                                                         listed[j],
                                                         m[j]));
              }
          offsets[i + 1] = bonds.size();
        }

      owned = IndexSet(node_set.relevant_dofs().size());
      std::vector<types::global_dof_index> dofs;
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        dofs.insert(dofs.end(),
                    node_set[i].dofs.begin(),
                    node_set[i].dofs.end());
      std::sort(dofs.begin(), dofs.end());
      owned.add_indices(dofs.begin(), dofs.end());
      owned.compress();
    }


    template <int dim>
    template <typename Function>
    void
    ReferenceBondOperator<dim>::for_each_bond(const unsigned int i,
                                              const Function    &f) const
    {
      for (std::size_t b = offsets[i]; b < offsets[i + 1]; ++b)
        f(bonds[b]);
    }


    template <int dim>
    typename ReferenceBondOperator<dim>::BondRange
    ReferenceBondOperator<dim>::bonds_of(const unsigned int i) const
    {
      return {bonds.data() + offsets[i], bonds.data() + offsets[i + 1]};
    }


    template <int dim>
    const std::vector<double> &
    ReferenceBondOperator<dim>::weighted_volumes() const
    {
      return m;
    }


    template <int dim>
    const IndexSet &
    ReferenceBondOperator<dim>::owned_dofs() const
    {
      return owned;
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::compute_dilatation(
      const TrilinosWrappers::MPI::Vector &displacement,
      std::vector<double>                 &dilatation) const
    {
      const auto &node_set = *nodes;
      dilatation.assign(node_set.size(), 0.);
      if (!state_based)
        return;
      auto u = [&](const unsigned int k) {
        Tensor<1, dim> value;
        for (unsigned int c = 0; c < dim; ++c)
          value[c] = displacement[node_set[k].dofs[c]];
        return value;
      };
      const auto u_far = [&](const BondData &bond) { return u(bond.neighbor); };
      for (unsigned int i = 0; i < node_set.size(); ++i)
        if (listed[i])
          dilatation[i] = reference_dilatation<dim>(bonds_of(i), u(i), u_far);
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::apply(
      const TrilinosWrappers::MPI::Vector &displacement,
      TrilinosWrappers::MPI::Vector       &nodal_force) const
    {
      const auto         &node_set = *nodes;
      std::vector<double> theta;
      compute_dilatation(displacement, theta);
      auto u = [&](const unsigned int k) {
        Tensor<1, dim> value;
        for (unsigned int c = 0; c < dim; ++c)
          value[c] = displacement[node_set[k].dofs[c]];
        return value;
      };
      const auto u_far = [&](const BondData &bond) { return u(bond.neighbor); };
      const auto theta_far = [&](const BondData &bond) {
        return theta[bond.neighbor];
      };
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          Tensor<1, dim> f = reference_force_density<dim>(bonds_of(i),
                                                          u(i),
                                                          theta[i],
                                                          u_far,
                                                          theta_far);
          f *= node_set[i].volume();
          for (unsigned int c = 0; c < dim; ++c)
            nodal_force[node_set[i].dofs[c]] = f[c];
        }
      nodal_force.compress(VectorOperation::insert);
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::assemble_with(
      TrilinosWrappers::SparseMatrix  &matrix,
      const AffineConstraints<double> *constraints,
      TrilinosWrappers::MPI::Vector   *rhs) const
    {
      const auto        &node_set = *nodes;
      const unsigned int n        = node_set.size();

      // Rows of constrained DoFs keep a diagonal entry; columns of
      // constrained DoFs go to the right-hand side. Which components of each
      // local node are prescribed, and to what, is looked up once here: the
      // loops below touch every nonzero and must not search the constraints.
      const bool          with_constraints = (constraints != nullptr);
      std::vector<bool>   prescribed(with_constraints ? n * dim : 0, false);
      std::vector<double> prescribed_value(prescribed.size(), 0.);
      std::vector<bool>   fully_constrained(n, false);
      if (with_constraints)
        for (unsigned int k = 0; k < n; ++k)
          {
            bool all = true;
            for (unsigned int c = 0; c < dim; ++c)
              {
                const auto dof = node_set[k].dofs[c];
                if (constraints->is_constrained(dof))
                  {
                    AssertThrow(
                      constraints->get_constraint_entries(dof)->empty(),
                      ExcMessage("The PD operator eliminates only prescribed "
                                 "values u_k = g_k, not constraints that "
                                 "couple DoFs."));
                    prescribed[k * dim + c] = true;
                    prescribed_value[k * dim + c] =
                      constraints->get_inhomogeneity(dof);
                  }
                else
                  all = false;
              }
            fully_constrained[k] = all;
          }
      auto is_prescribed = [&](const unsigned int k, const unsigned int c) {
        return with_constraints && prescribed[k * dim + c];
      };

      // The dilatation of node j is theta_j = sum_k g_jk . (u_k - u_j) with
      // g_jk = theta_factor_jk n_jk; G_j = sum_k g_jk.
      std::vector<Tensor<1, dim>> g_sum(state_based ? n : 0);
      if (state_based)
        for (unsigned int j = 0; j < n; ++j)
          if (listed[j])
            for_each_bond(j, [&](const BondData &bond) {
              g_sum[j] += bond.theta_factor * bond.n;
            });

      // Dense scratch over local node indices, with the list of touched
      // entries: no per-bond allocation.
      std::vector<Tensor<2, dim>> block(n);
      std::vector<bool>           touched(n, false);
      std::vector<unsigned int>   columns;
      auto                        touch = [&](const unsigned int k) {
        if (!touched[k])
          {
            touched[k] = true;
            columns.push_back(k);
          }
      };
      auto clear_columns = [&]() {
        for (const unsigned int k : columns)
          {
            touched[k] = false;
            block[k]   = Tensor<2, dim>();
          }
        columns.clear();
      };

      // The columns of row i: i, its neighbours and (state-based) theirs.
      auto row_columns = [&](const unsigned int i) {
        touch(i);
        for_each_bond(i, [&](const BondData &bond) {
          touch(bond.neighbor);
          if (state_based)
            for_each_bond(bond.neighbor, [&](const BondData &second) {
              touch(second.neighbor);
            });
        });
      };

      // dF_i/du for owned node i, into block[] (columns: local nodes).
      auto row_blocks = [&](const unsigned int i) {
        const double volume = node_set[i].volume();
        touch(i);
        Tensor<1, dim> s_i; // V_i sum_j w_ij a_i(r_ij) n_ij
        Tensor<2, dim> diagonal;
        for_each_bond(i, [&](const BondData &bond) {
          const unsigned int   j = bond.neighbor;
          const Tensor<2, dim> k =
            (volume * bond.weight * bond.b_sum) * outer_product(bond.n, bond.n);
          touch(j);
          block[j] += k;
          diagonal -= k;
          if (state_based)
            {
              s_i += (volume * bond.weight * bond.a_i) * bond.n;
              // Through theta_j: t (x) d theta_j / du, with
              // t = V_i w_ij a_j n_ij.
              const Tensor<1, dim> t =
                (volume * bond.weight * bond.a_j) * bond.n;
              block[j] -= outer_product(t, g_sum[j]);
              for (std::size_t b = offsets[j]; b < offsets[j + 1]; ++b)
                {
                  const BondData &second = bonds[b];
                  touch(second.neighbor);
                  const double c = second.theta_factor;
                  for (unsigned int p = 0; p < dim; ++p)
                    for (unsigned int q = 0; q < dim; ++q)
                      block[second.neighbor][p][q] += c * t[p] * second.n[q];
                }
            }
        });
        if (state_based)
          {
            for_each_bond(i, [&](const BondData &bond) {
              block[bond.neighbor] +=
                outer_product(s_i, bond.theta_factor * bond.n);
            });
            diagonal -= outer_product(s_i, g_sum[i]);
          }
        block[i] += diagonal;
      };

      // The positive diagonal kept in the row of a constrained DoF: the
      // pairwise (bond) part of K_kk, which has the scale of K_kk and costs
      // one pass over the node's bonds.
      auto constrained_diagonal = [&](const unsigned int i,
                                      const unsigned int r) {
        double d = 0;
        for_each_bond(i, [&](const BondData &bond) {
          d += node_set[i].volume() * bond.weight * std::abs(bond.b_sum) *
               bond.n[r] * bond.n[r];
        });
        return d > 0 ? d : 1.;
      };

      // The sparsity pattern: exactly the free columns of each free row.
      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      std::vector<types::global_dof_index> cols;
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          if (!fully_constrained[i])
            row_columns(i);
          cols.clear();
          for (const unsigned int k : columns)
            for (unsigned int c = 0; c < dim; ++c)
              if (!is_prescribed(k, c))
                cols.push_back(node_set[k].dofs[c]);
          clear_columns();
          std::sort(cols.begin(), cols.end());
          for (unsigned int r = 0; r < dim; ++r)
            {
              const auto row = node_set[i].dofs[r];
              if (is_prescribed(i, r))
                dsp.add(row, row);
              else
                dsp.add_entries(row, cols.begin(), cols.end(), true);
            }
        }
      matrix.reinit(owned, owned, dsp, nodes->get_communicator());

      std::vector<double> values;
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          if (!fully_constrained[i])
            row_blocks(i);
          for (unsigned int r = 0; r < dim; ++r)
            {
              const auto row = node_set[i].dofs[r];
              if (is_prescribed(i, r))
                {
                  const double diagonal = constrained_diagonal(i, r);
                  matrix.add(row, row, diagonal);
                  (*rhs)[row] += diagonal * prescribed_value[i * dim + r];
                  continue;
                }
              cols.clear();
              values.clear();
              double moved = 0;
              for (const unsigned int k : columns)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    if (is_prescribed(k, c))
                      moved += block[k][r][c] * prescribed_value[k * dim + c];
                    else
                      {
                        cols.push_back(node_set[k].dofs[c]);
                        values.push_back(-block[k][r][c]);
                      }
                  }
              matrix.add(row, cols, values);
              if (with_constraints)
                (*rhs)[row] += moved;
            }
          clear_columns();
        }
      matrix.compress(VectorOperation::add);
      if (with_constraints)
        rhs->compress(VectorOperation::add);
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::assemble(
      TrilinosWrappers::SparseMatrix &matrix) const
    {
      assemble_with(matrix, nullptr, nullptr);
    }


    template <int dim>
    void
    ReferenceBondOperator<dim>::assemble(
      TrilinosWrappers::SparseMatrix  &matrix,
      const AffineConstraints<double> &constraints,
      TrilinosWrappers::MPI::Vector   &rhs) const
    {
      assemble_with(matrix, &constraints, &rhs);
    }


    template <int dim>
    std::size_t
    ReferenceBondOperator<dim>::n_owned_bonds() const
    {
      return offsets.empty() ? 0 : offsets[nodes->n_owned()];
    }


    template ReferenceBond<2>
    make_reference_bond(const Models::Model<2> &,
                        const double,
                        const unsigned int,
                        const Tensor<1, 2> &,
                        const double,
                        const double,
                        const bool,
                        const double);
    template ReferenceBond<3>
    make_reference_bond(const Models::Model<3> &,
                        const double,
                        const unsigned int,
                        const Tensor<1, 3> &,
                        const double,
                        const double,
                        const bool,
                        const double);
    template class ReferenceBondOperator<2>;
    template class ReferenceBondOperator<3>;
  } // namespace Testing
} // namespace PeriDEAL
