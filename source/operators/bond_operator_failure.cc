// BondOperator's bond failure bookkeeping: the kinematics and critical
// stretches, the bonds found over it, their commit, and the re-sort of the
// work lists after bonds broke.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parallel.h>

#include <perideal/operators/bond_operator.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Operators
  {
    template <int dim>
    void
    BondOperator<dim>::set_kinematics(const bool finite_deformation,
                                      const std::vector<double> &stretch)
    {
      const unsigned int n    = nodes->size();
      const MPI_Comm     comm = nodes->get_communicator();
      AssertThrow(Utilities::MPI::min((stretch.empty() || stretch.size() == n) ?
                                        1 :
                                        0,
                                      comm) == 1,
                  ExcMessage("BondOperator::set_kinematics: one critical "
                             "stretch per node of the set."));
      finite           = finite_deformation;
      critical_stretch = stretch;
      with_failure     = false;
      for (const double s0 : critical_stretch)
        with_failure = with_failure || std::isfinite(s0);
      with_failure = Utilities::MPI::max(with_failure ? 1 : 0, comm) == 1;
      AssertThrow(collocation_theta.empty() || (!finite && !with_failure),
                  ExcMessage("The collocation rows of state-based models are "
                             "built for linear kinematics without failure."));
      s0_slot.resize_fast(0);
      if (finite || with_failure)
        {
          s0_slot.resize_fast(layout.n_slots);
          std::fill(s0_slot.begin(),
                    s0_slot.end(),
                    std::numeric_limits<double>::infinity());
          if (with_failure)
            for (unsigned int i = 0; i < n; ++i)
              s0_slot[layout.slot[i]] = critical_stretch[i];
        }
      std::lock_guard<std::mutex> lock(exceeded_mutex);
      exceeded.clear();
    }


    template <int dim>
    void
    BondOperator<dim>::record_exceeded(
      const std::vector<ExceededBond> &found) const
    {
      std::lock_guard<std::mutex> lock(exceeded_mutex);
      exceeded.insert(exceeded.end(), found.begin(), found.end());
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::commit_broken_bonds(
      Discretization::BondState<dim> &state)
    {
      const std::size_t ends = commit_broken_bond_ends(state);
      const MPI_Comm    comm = nodes->get_communicator();
      return (Utilities::MPI::n_mpi_processes(comm) == 1 ?
                ends :
                Utilities::MPI::sum(ends, comm)) /
             2;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::commit_broken_bond_ends(
      Discretization::BondState<dim> &state)
    {
      AssertThrow(&state == bond_state,
                  ExcMessage("commit_broken_bonds() needs the bond state "
                             "given to reinit()."));
      {
        std::lock_guard<std::mutex> lock(exceeded_mutex);
        if (layout.use_lattice)
          // Each record names its bond by node and stencil index: both
          // ends' bond numbers come from the layout (no search, no sort;
          // a bond found from both ends or in both passes is set once).
          // Only pairs that another process may hold go to it.
          for (const auto &[i, k] : exceeded)
            {
              if (!lists->has_list(i))
                continue;
              const int ki = layout.bond_number(i, k);
              Assert(ki >= 0, ExcInternalError());
              if (state.is_broken(i, ki))
                continue;
              const unsigned int j =
                layout.node_of_slot(layout.slot[i] + layout.stencil_offset[k]);
              const int kj =
                lists->has_list(j) ?
                  layout.bond_number(j, layout.stencil_opposite[k]) :
                  -1;
              Assert(kj >= 0 || !lists->has_list(j), ExcInternalError());
              state.break_pair(i,
                               ki,
                               j,
                               kj,
                               layout.on_partition_boundary[i] ||
                                 layout.on_partition_boundary[j]);
            }
        else
          {
            std::sort(exceeded.begin(), exceeded.end());
            exceeded.erase(std::unique(exceeded.begin(), exceeded.end()),
                           exceeded.end());
            for (const auto &[i, j] : exceeded)
              if (lists->has_list(i))
                {
                  const int k = state.bond_index(i, j);
                  Assert(k >= 0, ExcInternalError());
                  state.break_bond(i, k);
                }
          }
        exceeded.clear();
      }
      // Without a critical stretch nothing breaks (with_failure is the
      // same on every process): no exchange.
      if (!with_failure)
        return 0;
      const std::size_t               n_ends  = state.exchange();
      const std::vector<unsigned int> changed = state.take_changed_nodes();
      // Local decisions only, except the one reduction with collocation
      // nodes (with_collocation is the same on every process).
      if (!changed.empty() || with_collocation)
        {
          // A collocation node whose bond broke (from the standard end:
          // the switch of Eq. 65 missed it) becomes standard, counted.
          std::vector<unsigned int> missed;
          for (const unsigned int i : changed)
            if (i < nodes->n_owned() && is_collocation_node(i))
              missed.push_back(i);
          missed_switches += missed.size();
          // The work lists take the broken bonds on every process first:
          // make_standard() rebuilds them only where a node it switches
          // lost a bond, so a process that has changed nodes but no
          // missed one kept its old lists, and computed forces through
          // broken bonds, when another process had a missed node (1 and 2
          // processes broke different bonds on the Kalthoff-Winkler
          // impact).
          if (!changed.empty())
            update_work_lists(changed);
          const bool any_missed =
            with_collocation &&
            Utilities::MPI::max(missed.empty() ? 0 : 1,
                                nodes->get_communicator()) == 1;
          if (any_missed)
            make_standard(missed);
        }
      return n_ends;
    }


    template <int dim>
    std::size_t
    BondOperator<dim>::count_exceeded_bonds()
    {
      std::size_t owned_ends = 0;
      {
        std::lock_guard<std::mutex> lock(exceeded_mutex);
        std::sort(exceeded.begin(), exceeded.end());
        exceeded.erase(std::unique(exceeded.begin(), exceeded.end()),
                       exceeded.end());
        for (const auto &bond : exceeded)
          if (bond.first < nodes->n_owned())
            ++owned_ends;
        exceeded.clear();
      }
      return Utilities::MPI::sum(owned_ends, nodes->get_communicator()) / 2;
    }


    template <int dim>
    void
    BondOperator<dim>::update_work_lists(
      const std::vector<unsigned int> &changed)
    {
      if (!layout.use_lattice)
        {
          build_work_lists();
          return;
        }
      // The nodes of full chunks and runs keep their place, their broken
      // bonds masked.
      for (const unsigned int i : changed)
        if (layout.masks_bonds(i))
          layout.set_broken_bits(i);
      const unsigned int n_owned     = nodes->n_owned();
      const auto         needs_theta = [&](const unsigned int i) {
        return needs_dilatation(i);
      };
      std::vector<unsigned int> listed, newcomers;
      for (const unsigned int i : changed)
        if (needs_theta(i) || i < n_owned)
          (layout.is_listed[i] ? listed : newcomers).push_back(i);

      const auto write_intact = [&](const unsigned int i, std::size_t pos) {
        return layout.write_intact_stencil_indices(i, pos);
      };
      // Nodes already on lists lost bonds: their segments shrink in place
      // (bonds only break), independently, on the thread pool.
      parallel::apply_to_subranges(
        std::size_t(0),
        listed.size(),
        [&](const std::size_t begin, const std::size_t end) {
          for (std::size_t q = begin; q < end; ++q)
            layout.list_end[listed[q]] =
              write_intact(listed[q], layout.list_first[listed[q]]);
        },
        64);
      if (!newcomers.empty())
        {
          // Nodes that leave the shared stencil get a segment at the end.
          std::sort(newcomers.begin(), newcomers.end());
          const double m0            = stencil_weighted_volume;
          const auto   sorted_insert = [&](std::vector<unsigned int> &work,
                                         const bool needed_theta) {
            const std::size_t old_size = work.size();
            for (const unsigned int i : newcomers)
              if (needed_theta ? needs_theta(i) : i < n_owned)
                work.push_back(i);
            std::inplace_merge(work.begin(),
                               work.begin() + old_size,
                               work.end());
          };
          for (const unsigned int i : newcomers)
            {
              layout.list_first[i] = layout.list_stencil_index.size();
              layout.list_stencil_index.resize(layout.list_first[i] +
                                               lists->n_bonds(i));
              layout.list_end[i] = write_intact(i, layout.list_first[i]);
              layout.list_stencil_index.resize(layout.list_end[i]);
              list_theta_scale[i] = m[i] > 0 ? m0 / m[i] : 0.;
              if (state_based)
                theta_run_factor[layout.slot[i]] =
                  s_slot[layout.slot[i]] * list_theta_scale[i];
              layout.is_listed[i] = 1;
              if (i < n_owned && lists->has_full_stencil(i))
                --layout.n_owned_stencil;
            }
          if (state_based)
            sorted_insert(theta_work().list_nodes, true);
          sorted_insert(force_work().list_nodes, false);
          make_stencil_chunks();
        }

      // Runs and gather nodes stay as they are: broken bonds leave every
      // node of a run in it (masked; measured on the 40^3 cube with heavy
      // damage, lanes over masked bonds beat gathers over the intact ones
      // even at half the bonds broken), newcomers come from the full
      // stencil (in the full chunks), and gathers read their lists as they
      // run.
      layout.bond_visits = layout.count_bond_visits();
    }


#define PERIDEAL_INSTANTIATE(dim)                                  \
  template void BondOperator<dim>::set_kinematics(                 \
    const bool,                                                    \
    const std::vector<double> &);                                  \
  template void BondOperator<dim>::record_exceeded(                \
    const std::vector<ExceededBond> &) const;                      \
  template std::size_t BondOperator<dim>::commit_broken_bonds(     \
    Discretization::BondState<dim> &);                             \
  template std::size_t BondOperator<dim>::commit_broken_bond_ends( \
    Discretization::BondState<dim> &);                             \
  template std::size_t BondOperator<dim>::count_exceeded_bonds();  \
  template void        BondOperator<dim>::update_work_lists(       \
    const std::vector<unsigned int> &);
    PERIDEAL_INSTANTIATE(2)
    PERIDEAL_INSTANTIATE(3)
#undef PERIDEAL_INSTANTIATE
  } // namespace Operators
} // namespace PeriDEAL
