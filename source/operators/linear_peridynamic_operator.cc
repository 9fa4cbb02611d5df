#include <deal.II/base/mpi.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <perideal/operators/linear_peridynamic_operator.h>

#include <algorithm>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    LinearPeridynamicOperator<dim>::reinit(
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
                const unsigned int   j = bond.neighbor;
                const Tensor<1, dim> xi =
                  node_set[j].location - node_set[i].location;
                const double r = xi.norm();
                BondData     data;
                data.neighbor = j;
                data.n        = xi / r;
                data.weight   = bond.weight;
                data.theta_factor =
                  state_based ?
                    dim / m[i] * model.influence(r, horizon) * r * bond.weight :
                    0.;
                data.a_i   = model.dilatation_coefficient(m[i], r, horizon);
                data.a_j   = listed[j] ?
                               model.dilatation_coefficient(m[j], r, horizon) :
                               0.;
                data.b_sum = model.extension_coefficient(m[i], r, horizon) +
                             (listed[j] || !state_based ?
                                model.extension_coefficient(m[j], r, horizon) :
                                0.);
                bonds.push_back(data);
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
    LinearPeridynamicOperator<dim>::for_each_bond(const unsigned int i,
                                                  const Function    &f) const
    {
      for (std::size_t b = offsets[i]; b < offsets[i + 1]; ++b)
        f(bonds[b]);
    }


    template <int dim>
    const std::vector<double> &
    LinearPeridynamicOperator<dim>::weighted_volumes() const
    {
      return m;
    }


    template <int dim>
    const IndexSet &
    LinearPeridynamicOperator<dim>::owned_dofs() const
    {
      return owned;
    }


    template <int dim>
    void
    LinearPeridynamicOperator<dim>::compute_dilatation(
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
      for (unsigned int i = 0; i < node_set.size(); ++i)
        if (listed[i])
          {
            const Tensor<1, dim> u_i   = u(i);
            double               theta = 0;
            for_each_bond(i, [&](const BondData &bond) {
              theta += bond.theta_factor * (bond.n * (u(bond.neighbor) - u_i));
            });
            dilatation[i] = theta;
          }
    }


    template <int dim>
    void
    LinearPeridynamicOperator<dim>::apply(
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
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          const Tensor<1, dim> u_i = u(i);
          Tensor<1, dim>       f;
          for_each_bond(i, [&](const BondData &bond) {
            const double e = bond.n * (u(bond.neighbor) - u_i);
            f += (bond.a_i * theta[i] + bond.a_j * theta[bond.neighbor] +
                  bond.b_sum * e) *
                 bond.weight * bond.n;
          });
          f *= node_set[i].volume();
          for (unsigned int c = 0; c < dim; ++c)
            nodal_force[node_set[i].dofs[c]] = f[c];
        }
      nodal_force.compress(VectorOperation::insert);
    }


    template <int dim>
    void
    LinearPeridynamicOperator<dim>::assemble(
      TrilinosWrappers::SparseMatrix &matrix) const
    {
      const auto        &node_set = *nodes;
      const unsigned int n        = node_set.size();

      // Dense scratch over local node indices, with the list of touched
      // entries: no per-bond allocation.
      std::vector<Tensor<2, dim>> block(n);
      std::vector<bool>           touched(n, false);
      std::vector<unsigned int>   columns;
      auto add = [&](const unsigned int k, const Tensor<2, dim> &value) {
        if (!touched[k])
          {
            touched[k] = true;
            columns.push_back(k);
          }
        block[k] += value;
      };

      // dF_i/du for owned node i, into block[] (columns: local nodes).
      auto row_blocks = [&](const unsigned int i) {
        const double volume = node_set[i].volume();
        add(i, Tensor<2, dim>());
        Tensor<1, dim> s_i; // V_i sum_j w_ij a_i(r_ij) n_ij
        for_each_bond(i, [&](const BondData &bond) {
          const Tensor<2, dim> k =
            (volume * bond.weight * bond.b_sum) * outer_product(bond.n, bond.n);
          add(bond.neighbor, k);
          add(i, -k);
          if (state_based)
            {
              s_i += (volume * bond.weight * bond.a_i) * bond.n;
              // Through theta_j: V_i w_ij a_j n_ij (x) d theta_j / du.
              const Tensor<1, dim> t =
                (volume * bond.weight * bond.a_j) * bond.n;
              for_each_bond(bond.neighbor, [&](const BondData &second) {
                const Tensor<2, dim> k2 =
                  outer_product(t, second.theta_factor * second.n);
                add(second.neighbor, k2);
                add(bond.neighbor, -k2);
              });
            }
        });
        if (state_based)
          for_each_bond(i, [&](const BondData &bond) {
            const Tensor<2, dim> k =
              outer_product(s_i, bond.theta_factor * bond.n);
            add(bond.neighbor, k);
            add(i, -k);
          });
      };

      // The sparsity pattern: exactly the touched columns of each row.
      DynamicSparsityPattern dsp(owned.size(), owned.size(), owned);
      std::vector<std::vector<unsigned int>> row_columns(node_set.n_owned());
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          row_blocks(i);
          std::vector<types::global_dof_index> cols;
          for (const unsigned int k : columns)
            {
              cols.insert(cols.end(),
                          node_set[k].dofs.begin(),
                          node_set[k].dofs.end());
              touched[k] = false;
              block[k]   = Tensor<2, dim>();
            }
          std::sort(cols.begin(), cols.end());
          for (unsigned int c = 0; c < dim; ++c)
            dsp.add_entries(node_set[i].dofs[c],
                            cols.begin(),
                            cols.end(),
                            true);
          columns.clear();
        }
      matrix.reinit(owned, owned, dsp, nodes->get_communicator());

      std::vector<types::global_dof_index> cols;
      std::vector<double>                  values;
      for (unsigned int i = 0; i < node_set.n_owned(); ++i)
        {
          row_blocks(i);
          for (unsigned int r = 0; r < dim; ++r)
            {
              cols.clear();
              values.clear();
              for (const unsigned int k : columns)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    cols.push_back(node_set[k].dofs[c]);
                    values.push_back(-block[k][r][c]);
                  }
              matrix.add(node_set[i].dofs[r], cols, values);
            }
          for (const unsigned int k : columns)
            {
              touched[k] = false;
              block[k]   = Tensor<2, dim>();
            }
          columns.clear();
        }
      matrix.compress(VectorOperation::add);
    }


    template class LinearPeridynamicOperator<2>;
    template class LinearPeridynamicOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
