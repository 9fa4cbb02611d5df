#include <perideal/operators/fictitious_layer/sparse_entries.h>

#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>

#include <string>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace FictitiousLayer
    {
      std::unique_ptr<Epetra_CrsMatrix>
      make_matrix(SparseEntries &&entries,
                  const IndexSet &row_set,
                  const IndexSet &domain_set,
                  const MPI_Comm  comm)
      {
        const Epetra_Map row_map    = row_set.make_trilinos_map(comm, false);
        const Epetra_Map domain_map = domain_set.make_trilinos_map(comm, false);
        const int        n_rows     = row_map.NumMyElements();
        std::vector<int> counts(n_rows, 0), lids;
        lids.reserve(entries.list.size());
        for (const auto &e : entries.list)
          {
            const int lid = row_map.LID(e.row);
            AssertThrow(lid >= 0, ExcInternalError());
            lids.push_back(lid);
            ++counts[lid];
          }
        std::vector<std::size_t> start(n_rows + 1, 0);
        for (int l = 0; l < n_rows; ++l)
          start[l + 1] = start[l] + counts[l];
        std::vector<int>    cols(entries.list.size());
        std::vector<double> vals(entries.list.size());
        {
          std::vector<std::size_t> next(start.begin(), start.end() - 1);
          for (std::size_t k = 0; k < entries.list.size(); ++k)
            {
              const std::size_t at = next[lids[k]]++;
              cols[at]             = entries.list[k].column;
              vals[at]             = entries.list[k].value;
            }
        }
        entries.list = std::vector<typename SparseEntries::Entry>();
        auto matrix  = std::make_unique<Epetra_CrsMatrix>(Copy,
                                                         row_map,
                                                         counts.data(),
                                                         false);
        for (int l = 0; l < n_rows; ++l)
          if (counts[l] > 0)
            {
              const int ierr =
                matrix->InsertGlobalValues(row_map.GID(l),
                                           counts[l],
                                           vals.data() + start[l],
                                           cols.data() + start[l]);
              AssertThrow(ierr >= 0, ExcMessage("Epetra insertion failed."));
            }
        const int ierr = matrix->FillComplete(domain_map, row_map);
        AssertThrow(ierr == 0, ExcMessage("Epetra FillComplete failed."));
        return matrix;
      }


      std::unique_ptr<Epetra_CrsMatrix>
      multiply(const Epetra_CrsMatrix &a, const Epetra_CrsMatrix &b)
      {
        auto      c = std::make_unique<Epetra_CrsMatrix>(Copy, a.RowMap(), 0);
        const int ierr =
          EpetraExt::MatrixMatrix::Multiply(a, false, b, false, *c, true);
        AssertThrow(ierr == 0,
                    ExcMessage("EpetraExt matrix product failed (error " +
                               std::to_string(ierr) + ")."));
        return c;
      }
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL
