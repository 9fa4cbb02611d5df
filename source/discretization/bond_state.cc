#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>

#include <perideal/discretization/bond_state.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
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
      new_owned_bits   = 0;
      routes_built     = false;
      exchange_seconds = 0;
      sent_pairs       = 0;
      send_rank.clear();
      receive_rank.clear();
      send_first.clear();
      send_to.clear();
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
      pending.push_back({i, neighbor(i, k), true});
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
        pending.push_back({i, j, false});
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
      const std::uint64_t twice = exchange();
      const MPI_Comm      comm  = nodes->get_communicator();
      return (Utilities::MPI::n_mpi_processes(comm) == 1 ?
                twice :
                Utilities::MPI::sum(twice, comm)) /
             2;
    }


    template <int dim>
    void
    BondState<dim>::build_routes()
    {
      // One entry per node: the partitioner's import lists are the owned
      // nodes that other processes hold as ghosts, and who; its ghost
      // targets the owners of the ghosts here.
      const auto partitioner_ptr = nodes->node_partitioner();
      const Utilities::MPI::Partitioner &partitioner = *partitioner_ptr;

      // Owned nodes by their place in the owned range.
      std::vector<unsigned int> node_at(nodes->n_owned());
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        node_at[partitioner.global_to_local((*nodes)[i].dofs[0] / dim)] = i;
      send_rank.clear();
      std::vector<std::vector<unsigned int>> to(nodes->n_owned());
      const auto &ranges = partitioner.import_indices();
      std::size_t r      = 0;
      for (const auto &[rank, count] : partitioner.import_targets())
        {
          const unsigned int target = send_rank.size();
          send_rank.push_back(rank);
          for (unsigned int left = count; left > 0; ++r)
            {
              for (unsigned int e = ranges[r].first; e < ranges[r].second; ++e)
                to[node_at[e]].push_back(target);
              left -= ranges[r].second - ranges[r].first;
            }
        }
      send_first.assign(nodes->n_owned() + 1, 0);
      send_to.clear();
      for (unsigned int i = 0; i < nodes->n_owned(); ++i)
        {
          send_to.insert(send_to.end(), to[i].begin(), to[i].end());
          send_first[i + 1] = send_to.size();
        }
      receive_rank.clear();
      for (const auto &[rank, count] : partitioner.ghost_targets())
        receive_rank.push_back(rank);
      routes_built = true;
    }


    template <int dim>
    std::size_t
    BondState<dim>::exchange()
    {
      const auto         start   = std::chrono::steady_clock::now();
      const MPI_Comm     comm    = nodes->get_communicator();
      const unsigned int n_procs = Utilities::MPI::n_mpi_processes(comm);
      // The reverse bonds of break_bond()'s pairs, here (break_pair() set
      // both ends already).
      for (const auto &p : pending)
        if (p.reverse && lists->has_list(p.j))
          if (const int k = bond_index(p.j, p.i); k >= 0)
            set(p.j, k);

      if (n_procs > 1)
        {
          if (!routes_built)
            build_routes();
          // One message to each process that holds owned nodes of this one
          // (possibly empty: it waits for one from each): the pairs with an
          // owned end it holds, as the ends' global keys.
          std::vector<std::vector<std::uint64_t>> out(send_rank.size());
          std::vector<std::size_t>                last(
            send_rank.size(),
            std::numeric_limits<std::size_t>::max());
          for (std::size_t q = 0; q < pending.size(); ++q)
            for (const unsigned int e : {pending[q].i, pending[q].j})
              if (e < nodes->n_owned())
                for (std::size_t t = send_first[e]; t < send_first[e + 1]; ++t)
                  if (last[send_to[t]] != q)
                    {
                      last[send_to[t]] = q;
                      out[send_to[t]].push_back((*nodes)[pending[q].i].dofs[0]);
                      out[send_to[t]].push_back((*nodes)[pending[q].j].dofs[0]);
                    }
          // A tag of its own, above deal.II's (mpi_tags.h).
          constexpr int            tag = 7349;
          std::vector<MPI_Request> requests(send_rank.size());
          for (std::size_t t = 0; t < send_rank.size(); ++t)
            {
              sent_pairs += out[t].size() / 2;
              const int ierr = MPI_Isend(out[t].data(),
                                         static_cast<int>(out[t].size()),
                                         MPI_UINT64_T,
                                         send_rank[t],
                                         tag,
                                         comm,
                                         &requests[t]);
              AssertThrowMPI(ierr);
            }
          std::vector<std::uint64_t> in;
          for (const int source : receive_rank)
            {
              MPI_Status status;
              int        ierr = MPI_Probe(source, tag, comm, &status);
              AssertThrowMPI(ierr);
              int count = 0;
              ierr      = MPI_Get_count(&status, MPI_UINT64_T, &count);
              AssertThrowMPI(ierr);
              in.resize(count);
              ierr = MPI_Recv(in.data(),
                              count,
                              MPI_UINT64_T,
                              source,
                              tag,
                              comm,
                              MPI_STATUS_IGNORE);
              AssertThrowMPI(ierr);
              if (count == 0)
                continue;
              // Global key -> local node, built once (the first time pairs
              // arrive).
              if (local.empty())
                {
                  local.reserve(nodes->size());
                  for (unsigned int i = 0; i < nodes->size(); ++i)
                    local.emplace((*nodes)[i].dofs[0], i);
                }
              const auto break_here = [&](const std::uint64_t a,
                                          const std::uint64_t b) {
                const auto ia = local.find(a), ib = local.find(b);
                if (ia == local.end() || ib == local.end() ||
                    !lists->has_list(ia->second))
                  return;
                const int k = bond_index(ia->second, ib->second);
                if (k >= 0)
                  set(ia->second, k);
              };
              for (std::size_t q = 0; q + 1 < in.size(); q += 2)
                {
                  break_here(in[q], in[q + 1]);
                  break_here(in[q + 1], in[q]);
                }
            }
          const int ierr = MPI_Waitall(static_cast<int>(requests.size()),
                                       requests.data(),
                                       MPI_STATUSES_IGNORE);
          AssertThrowMPI(ierr);
        }
      pending.clear();
      exchange_seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      // Every newly broken pair has set one bit at each of its two owned
      // ends (in break_bond(), break_pair() or just now), on whichever
      // processes own them.
      const std::size_t twice = new_owned_bits;
      new_owned_bits          = 0;
      return twice;
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
