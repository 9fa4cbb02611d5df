#ifndef perideal_discretization_bond_state_h
#define perideal_discretization_bond_state_h

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>

#include <cstdint>
#include <istream>
#include <ostream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Discretization
  {
    /**
     * Intact or broken: one bit per bond, for every node that has a
     * neighbour list (owned nodes and, for state-based models, their
     * off-process neighbours).
     *
     * Bonds of a node are numbered as NeighborList enumerates them: a node
     * with a full stencil in the stencil's order, any other node in the
     * order of its stored list. A bond is a pair: breaking bond (i, j)
     * breaks (j, i) too, on whichever process holds j's list, after
     * synchronize(). The bulk of an undamaged uniform grid costs one bit per
     * bond and nothing else.
     */
    template <int dim>
    class BondState
    {
    public:
      /// All bonds intact, sized for @p lists.
      void
      reinit(const NodeSet<dim> &nodes, const NeighborList<dim> &lists);

      /// Whether bond @p k of node @p i is broken.
      bool
      is_broken(const unsigned int i, const unsigned int k) const
      {
        const std::size_t b = first[i] + k;
        return (bits[b >> 6] >> (b & 63)) & 1u;
      }

      /// Whether any bond of node @p i is broken.
      bool
      any_broken(const unsigned int i) const
      {
        return n_broken_of[i] > 0;
      }

      /**
       * The damage of node @p i (hybrid-collocation paper, Eq. 21, with the
       * quadrature weights): \f$\varphi_i = 1 - \sum_{j\ \mathrm{intact}}
       * w_{ij} / \sum_j w_{ij}\f$; 0 for a node without bonds.
       */
      double
      damage(const unsigned int i) const;

      /// Number of broken bonds of node @p i.
      unsigned int
      n_broken(const unsigned int i) const
      {
        return n_broken_of[i];
      }

      /**
       * Break bond @p k of node @p i here. Call synchronize() on all
       * processes afterwards, so that the reverse bond and every copy of
       * this one are broken as well. Only pairs with an end owned here are
       * sent (exchange()): a bond broken at a ghost node only must be
       * broken by the owner of one of its ends too (every caller decides
       * from data that is the same on every process holding the bond).
       */
      void
      break_bond(const unsigned int i, const unsigned int k);

      /**
       * Break bond @p ki of node @p i and, with @p kj >= 0, the reverse
       * bond @p kj of its neighbour @p j here, for a caller that knows both
       * bonds' numbers (BondOperator on the lattice: no search per bond).
       * Only with @p send does the pair go to the other processes at
       * synchronize(): set it when another process may hold a list for
       * either end (an end that is a ghost here, or an owned node that is a
       * ghost elsewhere). Only its owned ends are sent (see exchange()).
       */
      void
      break_pair(const unsigned int i,
                 const unsigned int ki,
                 const unsigned int j,
                 const int          kj,
                 const bool         send);

      /**
       * Calls @p f(k) for every broken bond k of node @p i, in increasing
       * k, reading the bits a word at a time.
       */
      template <typename Function>
      void
      for_each_broken(const unsigned int i, const Function &f) const
      {
        for_each_word(i, [&](const unsigned int k0, std::uint64_t w) {
          for (; w != 0; w &= w - 1)
            f(k0 + static_cast<unsigned int>(__builtin_ctzll(w)));
        });
      }

      /**
       * Calls @p f(k) for every intact bond k of node @p i, in increasing
       * k, reading the bits a word at a time.
       */
      template <typename Function>
      void
      for_each_intact(const unsigned int i, const Function &f) const
      {
        const std::size_t n = first[i + 1] - first[i];
        for_each_word(i, [&](const unsigned int k0, const std::uint64_t w) {
          const std::size_t   left = n - k0;
          const std::uint64_t all =
            left >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << left) - 1;
          for (std::uint64_t v = ~w & all; v != 0; v &= v - 1)
            f(k0 + static_cast<unsigned int>(__builtin_ctzll(v)));
        });
      }

      /**
       * Make the bond state consistent (collective): every bond broken on
       * any process since the last call is broken in both directions on
       * every process that has a list for either end. Returns the number of
       * bonds (pairs) that were newly broken on all processes together
       * (counted at their owned ends: half the bits newly set there, by
       * break_bond(), break_pair() or here).
       */
      std::size_t
      synchronize();

      /**
       * synchronize() without the global count: the pairs broken here go
       * to the neighbouring processes only, point to point (no collective
       * over all processes), and the return value is this process's share
       * of the count, the bits newly set at its owned nodes (twice the
       * pairs once summed over all processes). Collective over the
       * neighbours: every process calls it the same number of times.
       *
       * A pair goes, for each of its ends that this process owns, to the
       * processes that hold that end as a ghost. A pair with no owned end
       * here is not sent: the owner of an end finds the same broken bond
       * from it (the failure test reads both ends' values and is the same
       * bit for bit from either end), or, for an end that does not test
       * its bonds (a collocation node), the owner of the other end finds
       * it and sends it to every process holding that end, which includes
       * every process holding a list of the first one.
       */
      std::size_t
      exchange();

      /// Wall time spent in exchange() on this process, and the pairs it
      /// sent (counted once per receiving process), since reinit().
      std::pair<double, std::size_t>
      exchange_statistics() const
      {
        return {exchange_seconds, sent_pairs};
      }

      /// The local index of the neighbour at the end of bond @p k of @p i.
      unsigned int
      neighbor(const unsigned int i, const unsigned int k) const;

      /**
       * The index of the bond from node @p i to node @p j among i's bonds,
       * or -1 when j is not a neighbour of i (set-up cost: a binary search
       * or a table look-up, not for hot loops).
       */
      int
      bond_index(const unsigned int i, const unsigned int j) const;

      /**
       * Write the state of this process (the bits of every node with a
       * list) for a checkpoint.
       */
      void
      save(std::ostream &out) const;

      /**
       * Read what save() wrote on a process with the same nodes and lists
       * (same mesh, same partition); throws if the sizes differ.
       */
      void
      load(std::istream &in);

      /// Number of broken bond pairs over all processes, counted at owned
      /// nodes (each pair once per end).
      std::size_t
      n_broken_global() const;

      /**
       * The nodes (local indices) that lost a bond since the last call, in
       * the order their first new bond broke, each once; clears the record.
       * Lets a consumer update what depends on a node's bonds for those
       * nodes only.
       */
      std::vector<unsigned int>
      take_changed_nodes();

    private:
      const NodeSet<dim>        *nodes = nullptr;
      const NeighborList<dim>   *lists = nullptr;
      std::vector<std::size_t>   first;
      std::vector<std::uint64_t> bits;
      std::vector<unsigned int>  n_broken_of;
      /// A pair broken here since the last exchange(): local indices of
      /// its ends, and whether the bond of j back to i still has to be set.
      struct PendingPair
      {
        unsigned int i, j;
        bool         reverse;
      };
      std::vector<PendingPair>                        pending;
      std::vector<unsigned int>                       changed;
      std::vector<bool>                               is_changed;
      std::unordered_map<std::uint64_t, unsigned int> local;

      /**
       * The routes of exchange(), built at its first call on more than one
       * process: the processes that hold owned nodes of this one as ghosts
       * (send_rank) and, per owned node i, which of them hold it
       * (send_to[send_first[i], send_first[i + 1]), indices into
       * send_rank); the processes whose owned nodes are ghosts here
       * (receive_rank).
       */
      bool                      routes_built     = false;
      double                    exchange_seconds = 0;
      std::size_t               sent_pairs       = 0;
      std::vector<int>          send_rank, receive_rank;
      std::vector<std::size_t>  send_first;
      std::vector<unsigned int> send_to;

      void
      build_routes();

      /// Bits newly set at owned nodes since the last synchronize().
      std::size_t new_owned_bits = 0;

      /// Set the bit of bond k of node i; whether it was intact.
      bool
      set(const unsigned int i, const unsigned int k);

      /// Calls @p f(k0, word) with the bits of bonds k0, k0 + 1, ... of
      /// node @p i (bit l: bond k0 + l; bits past the last bond are 0).
      template <typename Function>
      void
      for_each_word(const unsigned int i, const Function &f) const
      {
        const std::size_t b0 = first[i], b1 = first[i + 1];
        for (std::size_t b = b0; b < b1; b += 64)
          {
            const std::size_t  w     = b >> 6;
            const unsigned int shift = b & 63;
            std::uint64_t      word  = bits[w] >> shift;
            if (shift != 0 && w + 1 < bits.size())
              word |= bits[w + 1] << (64 - shift);
            if (b1 - b < 64)
              word &= (std::uint64_t(1) << (b1 - b)) - 1;
            f(static_cast<unsigned int>(b - b0), word);
          }
      }
    };
  } // namespace Discretization
} // namespace PeriDEAL

#endif
