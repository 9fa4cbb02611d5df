#include <deal.II/base/mpi.h>

#include <perideal/discretization/bond_state.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace PeriDEAL
{
  namespace Discretization
  {
    template <int dim>
    void
    BondState<dim>::reinit(const NodeSet<dim>      &node_set,
                           const NeighborList<dim> &neighbor_lists)
    {
      nodes                = &node_set;
      lists                = &neighbor_lists;
      const unsigned int n = node_set.size();
      first.assign(n + 1, 0);
      for (unsigned int i = 0; i < n; ++i)
        first[i + 1] = first[i] + neighbor_lists.n_bonds(i);
      bits.assign((first[n] + 63) / 64, 0);
      n_broken_of.assign(n, 0);
      pending.clear();
      local.clear();
      changed.clear();
      is_changed.assign(n, false);
      new_owned_bits = 0;
    }


    template <int dim>
    bool
    BondState<dim>::set(const unsigned int i, const unsigned int k)
    {
      const std::size_t   b    = first[i] + k;
      const std::uint64_t mask = std::uint64_t(1) << (b & 63);
      if (bits[b >> 6] & mask)
        return false;
      bits[b >> 6] |= mask;
      ++n_broken_of[i];
      if (i < nodes->n_owned())
        ++new_owned_bits;
      if (!is_changed[i])
        {
          is_changed[i] = true;
          changed.push_back(i);
        }
      return true;
    }


    template <int dim>
    void
    BondState<dim>::break_bond(const unsigned int i, const unsigned int k)
    {
      AssertIndexRange(k, first[i + 1] - first[i]);
      if (!set(i, k))
        return;
      pending.emplace_back((*nodes)[i].dofs[0],
                           (*nodes)[neighbor(i, k)].dofs[0]);
    }


    template <int dim>
    void
    BondState<dim>::break_pair(const unsigned int i,
                               const unsigned int ki,
                               const unsigned int j,
                               const int          kj,
                               const bool         send)
    {
      AssertIndexRange(ki, first[i + 1] - first[i]);
      const bool new_i = set(i, ki);
      if (kj >= 0)
        {
          AssertIndexRange(static_cast<unsigned int>(kj),
                           first[j + 1] - first[j]);
          set(j, kj);
        }
      if (new_i && send)
        pending.emplace_back((*nodes)[i].dofs[0], (*nodes)[j].dofs[0]);
    }


    template <int dim>
    double
    BondState<dim>::damage(const unsigned int i) const
    {
      if (n_broken_of[i] == 0)
        return 0;
      double       total = 0, broken = 0;
      const bool   full  = lists->has_full_stencil(i);
      const double cell  = std::pow(lists->lattice().spacing(), dim);
      const auto   bonds = full ? ArrayView<const Bond>() : lists->bonds(i);
      for (unsigned int k = 0; k < first[i + 1] - first[i]; ++k)
        {
          const double w =
            full ? lists->stencil()[k].beta * cell : bonds[k].weight;
          total += w;
          if (is_broken(i, k))
            broken += w;
        }
      return total > 0 ? broken / total : 0.;
    }


    template <int dim>
    unsigned int
    BondState<dim>::neighbor(const unsigned int i, const unsigned int k) const
    {
      if (!lists->has_full_stencil(i))
        return lists->bonds(i)[k].neighbor;
      std::array<std::int64_t, dim> x = lists->lattice().coordinates(i);
      for (unsigned int d = 0; d < dim; ++d)
        x[d] += lists->stencil()[k].offset[d];
      return static_cast<unsigned int>(lists->lattice().node_at(x));
    }


    template <int dim>
    int
    BondState<dim>::bond_index(const unsigned int i, const unsigned int j) const
    {
      if (lists->has_full_stencil(i))
        return lists->stencil_index(i, j);
      const auto  list = lists->bonds(i);
      const auto  key  = (*nodes)[j].dofs[0];
      const auto *it =
        std::lower_bound(list.begin(),
                         list.end(),
                         key,
                         [&](const Bond &b, const auto value) {
                           return (*nodes)[b.neighbor].dofs[0] < value;
                         });
      if (it == list.end() || it->neighbor != j)
        return -1;
      return it - list.begin();
    }


    template <int dim>
    std::size_t
    BondState<dim>::synchronize()
    {
      const MPI_Comm     comm    = nodes->get_communicator();
      const unsigned int n_procs = Utilities::MPI::n_mpi_processes(comm);
      // Pairs without orientation, each once, from every process: a raw
      // MPI_Allgatherv (Utilities::MPI::all_gather() would serialise and
      // compress the pairs, which cost 15 % of a heavily breaking run even
      // on one process). On one process only break_bond()'s pairs need
      // their reverse here; break_pair() set both ends already.
      std::vector<std::uint64_t> mine;
      mine.reserve(2 * pending.size());
      for (const auto &p : pending)
        {
          mine.push_back(std::min(p.first, p.second));
          mine.push_back(std::max(p.first, p.second));
        }
      pending.clear();
      std::vector<std::uint64_t> gathered;
      if (n_procs == 1)
        gathered.swap(mine);
      else
        {
          const int        n_mine = static_cast<int>(mine.size());
          std::vector<int> counts(n_procs), displacements(n_procs + 1, 0);
          int              ierr =
            MPI_Allgather(&n_mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
          AssertThrowMPI(ierr);
          for (unsigned int p = 0; p < n_procs; ++p)
            displacements[p + 1] = displacements[p] + counts[p];
          if (displacements[n_procs] > 0)
            {
              gathered.resize(displacements[n_procs]);
              ierr = MPI_Allgatherv(mine.data(),
                                    n_mine,
                                    MPI_UINT64_T,
                                    gathered.data(),
                                    counts.data(),
                                    displacements.data(),
                                    MPI_UINT64_T,
                                    comm);
              AssertThrowMPI(ierr);
            }
        }
      std::vector<std::pair<std::uint64_t, std::uint64_t>> all;
      all.reserve(gathered.size() / 2);
      for (std::size_t q = 0; q + 1 < gathered.size(); q += 2)
        all.emplace_back(gathered[q], gathered[q + 1]);
      std::sort(all.begin(), all.end());
      all.erase(std::unique(all.begin(), all.end()), all.end());

      if (!all.empty())
        {
          // Global key -> local node, built once (the first time pairs
          // arrive).
          if (local.empty())
            {
              local.reserve(nodes->size());
              for (unsigned int i = 0; i < nodes->size(); ++i)
                local.emplace((*nodes)[i].dofs[0], i);
            }
          auto break_here = [&](const std::uint64_t a, const std::uint64_t b) {
            const auto ia = local.find(a), ib = local.find(b);
            if (ia == local.end() || ib == local.end() ||
                !lists->has_list(ia->second))
              return;
            const int k = bond_index(ia->second, ib->second);
            if (k >= 0)
              set(ia->second, k);
          };
          for (const auto &p : all)
            {
              break_here(p.first, p.second);
              break_here(p.second, p.first);
            }
        }
      // Every newly broken pair has set one bit at each of its two owned
      // ends (in break_bond(), break_pair() or just now), on whichever
      // processes own them.
      const std::uint64_t twice = new_owned_bits;
      new_owned_bits            = 0;
      return (n_procs == 1 ? twice : Utilities::MPI::sum(twice, comm)) / 2;
    }


    template <int dim>
    void
    BondState<dim>::save(std::ostream &out) const
    {
      const std::uint64_t sizes[2] = {first.size(), bits.size()};
      out.write(reinterpret_cast<const char *>(sizes), sizeof(sizes));
      out.write(reinterpret_cast<const char *>(bits.data()),
                bits.size() * sizeof(std::uint64_t));
      out.write(reinterpret_cast<const char *>(n_broken_of.data()),
                n_broken_of.size() * sizeof(unsigned int));
    }


    template <int dim>
    void
    BondState<dim>::load(std::istream &in)
    {
      std::uint64_t sizes[2] = {0, 0};
      in.read(reinterpret_cast<char *>(sizes), sizeof(sizes));
      AssertThrow(in && sizes[0] == first.size() && sizes[1] == bits.size(),
                  ExcMessage("The bond state of the checkpoint does not fit "
                             "the bonds of this run (another mesh, horizon, "
                             "partial-volume rule or number of processes)."));
      in.read(reinterpret_cast<char *>(bits.data()),
              bits.size() * sizeof(std::uint64_t));
      in.read(reinterpret_cast<char *>(n_broken_of.data()),
              n_broken_of.size() * sizeof(unsigned int));
      AssertThrow(in, ExcMessage("The checkpoint's bond state is truncated."));
      pending.clear();
      changed.clear();
      is_changed.assign(is_changed.size(), false);
      new_owned_bits = 0;
    }


    template <int dim>
    std::vector<unsigned int>
    BondState<dim>::take_changed_nodes()
    {
      std::vector<unsigned int> result;
      result.swap(changed);
      // In increasing index: bonds are broken in the order the threads
      // found them, and nothing may depend on that.
      std::sort(result.begin(), result.end());
      for (const unsigned int i : result)
        is_changed[i] = false;
      return result;
    }


    template <int dim>
    std::size_t
    BondState<dim>::n_broken_global() const
    {
      std::size_t n = 0;
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        n += n_broken_of[i];
      return Utilities::MPI::sum(n, nodes->get_communicator());
    }


    template class BondState<1>;
    template class BondState<2>;
    template class BondState<3>;
  } // namespace Discretization
} // namespace PeriDEAL
