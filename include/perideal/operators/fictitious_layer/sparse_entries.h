#ifndef perideal_operators_fictitious_layer_sparse_entries_h
#define perideal_operators_fictitious_layer_sparse_entries_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <memory>
#include <vector>

class Epetra_CrsMatrix;

namespace PeriDEAL
{
  namespace Operators
  {
    namespace FictitiousLayer
    {
      using namespace dealii;

      /**
       * The entries of a sparse matrix under construction, as (row, column,
       * value) in any order; entries at the same position add up (Epetra
       * merges them when the matrix is completed, in the order they were
       * added). Appending is all the build loops do: no tree, no per-entry
       * allocation.
       */
      struct SparseEntries
      {
        struct Entry
        {
          int    row, column;
          double value;
        };
        std::vector<Entry> list;

        void
        add(const int row, const int column, const double value)
        {
          list.push_back({row, column, value});
        }
      };

      /**
       * A distributed Epetra matrix with the rows @p row_set (owned here,
       * every entry's row among them) and the domain @p domain_set, from
       * @p entries (emptied). The entries are bucketed by row, then each
       * row is inserted once.
       */
      std::unique_ptr<Epetra_CrsMatrix>
      make_matrix(SparseEntries &&entries,
                  const IndexSet &row_set,
                  const IndexSet &domain_set,
                  const MPI_Comm  comm);

      /// The product @p a times @p b (EpetraExt, in parallel).
      std::unique_ptr<Epetra_CrsMatrix>
      multiply(const Epetra_CrsMatrix &a, const Epetra_CrsMatrix &b);
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL

#endif
