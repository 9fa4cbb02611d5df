#include <perideal/operators/fictitious_layer/layer_data.h>
#include <perideal/operators/fictitious_layer_operator.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <unordered_map>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    FictitiousLayerOperator<dim>::build_factors() const
    {
      using namespace FictitiousLayer;
      LayerData<dim>    &s       = *data;
      const auto        &lattice = s.lattice;
      const MPI_Comm     comm    = s.comm;
      const unsigned int n_owned = s.nodes->n_owned();

      // Index spaces of the product: lattice DoFs dim*key+c, lattice
      // scalars key; body keys owned here, and fictitious keys owned here.
      std::vector<int> owned_body_keys, owned_ext_keys;
      for (unsigned int i = 0; i < n_owned; ++i)
        owned_body_keys.push_back(lattice.key(lattice.cell_of_node(i)));
      std::sort(owned_body_keys.begin(), owned_body_keys.end());
      owned_ext_keys = owned_body_keys;
      for (const auto &f : lattice.owned_fictitious())
        owned_ext_keys.push_back(f.first);
      std::sort(owned_ext_keys.begin(), owned_ext_keys.end());

      const auto make_set = [](const std::vector<int> &keys,
                               const long long         size,
                               const unsigned int      block) {
        IndexSet                             set(size * block);
        std::vector<types::global_dof_index> list;
        for (const int k : keys)
          for (unsigned int c = 0; c < block; ++c)
            list.push_back(static_cast<types::global_dof_index>(k) * block + c);
        set.add_indices(list.begin(), list.end());
        set.compress();
        return set;
      };
      const long long n_cells     = lattice.n_cells();
      const IndexSet  ext_dofs    = make_set(owned_ext_keys, n_cells, dim);
      const IndexSet  ext_scalar  = make_set(owned_ext_keys, n_cells, 1);
      const IndexSet  body_scalar = make_set(owned_body_keys, n_cells, 1);

      // The order of the entries is the order of their sums: body rows
      // before the surface fluxes, as the factors have always been built.
      SparseEntries e_rows, x_rows, d_rows, a_rows, b_rows;
      add_extrapolation_rows(s, owned_body_keys, e_rows, x_rows);
      add_body_rows(s, d_rows, a_rows, b_rows);
      if (s.surface)
        add_surface_flux_rows(s, a_rows, b_rows);

      s.e_matrix = make_matrix(std::move(e_rows), ext_dofs, s.owned_sys, comm);
      s.a_matrix = make_matrix(std::move(a_rows), s.owned_sys, ext_dofs, comm);
      if (s.state_based)
        {
          s.d_matrix =
            make_matrix(std::move(d_rows), body_scalar, ext_dofs, comm);
          s.x_matrix =
            make_matrix(std::move(x_rows), ext_scalar, body_scalar, comm);
          s.b_matrix =
            make_matrix(std::move(b_rows), s.owned_sys, ext_scalar, comm);
        }
    }


    template <int dim>
    void
    FictitiousLayerOperator<dim>::assemble(
      const std::map<types::global_dof_index, double> &prescribed,
      TrilinosWrappers::SparseMatrix                  &matrix,
      TrilinosWrappers::MPI::Vector                   &rhs) const
    {
      auto          &s    = *data;
      const MPI_Comm comm = s.comm;
      // The products.
      if (!s.e_matrix)
        build_factors();
      const auto product_extension =
        FictitiousLayer::multiply(*s.a_matrix, *s.e_matrix);
      std::unique_ptr<Epetra_CrsMatrix> product_dilatation;
      if (s.state_based)
        {
          const auto de  = FictitiousLayer::multiply(*s.d_matrix, *s.e_matrix);
          const auto xde = FictitiousLayer::multiply(*s.x_matrix, *de);
          product_dilatation = FictitiousLayer::multiply(*s.b_matrix, *xde);
        }

      // Elimination of the prescribed unknowns.
      const Epetra_Map sys_map = s.owned_sys.make_trilinos_map(comm, false);
      Epetra_Vector    g(sys_map), kg(sys_map), tmp(sys_map);
      for (const auto &p : prescribed)
        g[sys_map.LID(static_cast<int>(p.first))] = p.second;
      product_extension->Multiply(false, g, kg);
      if (product_dilatation)
        {
          product_dilatation->Multiply(false, g, tmp);
          kg.Update(1., tmp, 1.);
        }

      // Which columns are prescribed: a ghosted flag vector.
      IndexSet relevant(s.n_sys);
      {
        std::vector<types::global_dof_index> cols;
        for (const Epetra_CrsMatrix *m :
             {product_extension.get(), product_dilatation.get()})
          if (m)
            for (int l = 0; l < m->ColMap().NumMyElements(); ++l)
              cols.push_back(m->ColMap().GID(l));
        std::sort(cols.begin(), cols.end());
        cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
        relevant.add_indices(cols.begin(), cols.end());
        relevant.add_indices(s.owned_sys);
        relevant.compress();
      }
      TrilinosWrappers::MPI::Vector flags(s.owned_sys, comm),
        ghosted_flags(s.owned_sys, relevant, comm);
      for (const auto &p : prescribed)
        flags[p.first] = 1.;
      flags.compress(VectorOperation::insert);
      ghosted_flags = flags;
      // Read once: the loop below touches every nonzero.
      std::unordered_map<int, bool> column_prescribed;
      for (const auto k : relevant)
        if (ghosted_flags[k] != 0.)
          column_prescribed[static_cast<int>(k)] = true;

      Epetra_CrsMatrix      result(Copy, sys_map, 0);
      std::map<int, double> row;
      std::vector<int>      cols;
      std::vector<double>   vals;
      for (int l = 0; l < sys_map.NumMyElements(); ++l)
        {
          const int gid = sys_map.GID(l);
          row.clear();
          for (const Epetra_CrsMatrix *m :
               {product_extension.get(), product_dilatation.get()})
            if (m)
              {
                int     n;
                double *v;
                int    *idx;
                m->ExtractMyRowView(m->RowMap().LID(gid), n, v, idx);
                for (int e = 0; e < n; ++e)
                  row[m->ColMap().GID(idx[e])] += v[e];
              }
          cols.clear();
          vals.clear();
          const auto fixed = prescribed.find(gid);
          if (fixed != prescribed.end())
            {
              const double diagonal =
                row.count(gid) && row[gid] != 0. ? std::abs(row[gid]) : 1.;
              cols.push_back(gid);
              vals.push_back(diagonal);
              rhs(gid) = diagonal * fixed->second;
            }
          else
            {
              for (const auto &e : row)
                if (column_prescribed.count(e.first) == 0)
                  {
                    cols.push_back(e.first);
                    vals.push_back(e.second);
                  }
              const double load = rhs(gid);
              rhs(gid)          = load - kg[l];
            }
          result.InsertGlobalValues(gid, cols.size(), vals.data(), cols.data());
        }
      result.FillComplete(sys_map, sys_map);
      rhs.compress(VectorOperation::insert);
      matrix.reinit(result, true);
    }


    template <int dim>
    void
    FictitiousLayerOperator<dim>::apply(const TrilinosWrappers::MPI::Vector &u,
                                        TrilinosWrappers::MPI::Vector &ku) const
    {
      const auto &s = *data;
      AssertThrow(s.e_matrix && s.a_matrix,
                  ExcMessage("FictitiousLayerOperator::apply() needs the "
                             "factors: call build_factors() or assemble() "
                             "first."));
      const Epetra_MultiVector &x = u.trilinos_vector();
      Epetra_MultiVector       &y = ku.trilinos_vector();
      // Lattice displacements, then bond forces: y = A (E u).
      Epetra_Vector eu(s.e_matrix->RangeMap());
      AssertThrow(s.e_matrix->Multiply(false, x, eu) == 0, ExcInternalError());
      AssertThrow(s.a_matrix->Multiply(false, eu, y) == 0, ExcInternalError());
      if (s.b_matrix)
        {
          // Body dilatations, extrapolated to the lattice: + B (X (D (E u))).
          Epetra_Vector theta(s.d_matrix->RangeMap()),
            lattice_theta(s.x_matrix->RangeMap());
          Epetra_MultiVector by(y.Map(), 1);
          AssertThrow(s.d_matrix->Multiply(false, eu, theta) == 0,
                      ExcInternalError());
          AssertThrow(s.x_matrix->Multiply(false, theta, lattice_theta) == 0,
                      ExcInternalError());
          AssertThrow(s.b_matrix->Multiply(false, lattice_theta, by) == 0,
                      ExcInternalError());
          y.Update(1., by, 1.);
        }
    }


    template void
    FictitiousLayerOperator<2>::build_factors() const;
    template void
    FictitiousLayerOperator<2>::assemble(
      const std::map<types::global_dof_index, double> &,
      TrilinosWrappers::SparseMatrix &,
      TrilinosWrappers::MPI::Vector &) const;
    template void
    FictitiousLayerOperator<2>::apply(const TrilinosWrappers::MPI::Vector &,
                                      TrilinosWrappers::MPI::Vector &) const;
    template void
    FictitiousLayerOperator<3>::build_factors() const;
    template void
    FictitiousLayerOperator<3>::assemble(
      const std::map<types::global_dof_index, double> &,
      TrilinosWrappers::SparseMatrix &,
      TrilinosWrappers::MPI::Vector &) const;
    template void
    FictitiousLayerOperator<3>::apply(const TrilinosWrappers::MPI::Vector &,
                                      TrilinosWrappers::MPI::Vector &) const;
  } // namespace Operators
} // namespace PeriDEAL
