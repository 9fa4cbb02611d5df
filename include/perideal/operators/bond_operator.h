#ifndef perideal_operators_bond_operator_h
#define perideal_operators_bond_operator_h

#include <deal.II/base/aligned_vector.h>
#include <deal.II/base/partitioner.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/collocation_node_rows.h>
#include <perideal/operators/loop_layout.h>
#include <perideal/quadrature/quadrature_scheme.h>

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace dealii
{
  template <typename number>
  class AffineConstraints;
  namespace TrilinosWrappers
  {
    class SparseMatrix;
    namespace MPI
    {
      class Vector;
    }
  } // namespace TrilinosWrappers
} // namespace dealii

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * The linearised peridynamic internal force of a linear ordinary model,
     * evaluated without a matrix, threaded and vectorised: nodal forces
     * \f[
     *   F_i(u) = V_i \sum_{j\ \mathrm{intact}} w_{ij}\, n_{ij}
     *            \big[\alpha(r_{ij})(s_i\theta_i + s_j\theta_j)
     *                 + \beta(r_{ij})(s_i + s_j)\, e_{ij}\big],\qquad
     *   \theta_i = \frac{d}{m_i}\sum_{j\ \mathrm{intact}}
     *              \omega_{ij} r_{ij} w_{ij}\, e_{ij},
     * \f]
     * with \f$e_{ij} = n_{ij}\cdot(u_j - u_i)\f$, the model's kernel
     * \f$\alpha, \beta, s\f$ (Models::Model::dilatation_constant()) and the
     * reference weighted volume \f$m_i\f$ (all bonds, broken or not). The
     * test oracle of tests/common evaluates the same operator bond by bond;
     * broken bonds (Discretization::BondState) leave the sums.
     *
     * <h3>Data layout</h3>
     * Values are copied from the deal.II vector into structure-of-arrays
     * scratch indexed by *slot*: on a uniform grid the node's place in the
     * process's lattice box (Discretization::Lattice), otherwise its local
     * node index. Every node with a full, intact stencil (the uniform bulk)
     * is evaluated with ONE shared stencil: constant slot offsets and
     * per-offset constants, vectorised over runs of consecutive bulk nodes
     * (up to 64 at a time) with the offsets in the outer loop. Every other
     * node (near a boundary, a refinement interface, a broken bond, or any
     * node of a non-uniform mesh) has its own compact list of bonds (slot of
     * the neighbour, unit vector and constants). The loops touch no map, no
     * global index, no MPI and allocate nothing; they run on deal.II's TBB
     * thread pool (parallel::apply_to_subranges), and every node's sum is
     * formed in a fixed order, so 1 and any number of threads give bitwise
     * identical results.
     *
     * State-based models take two passes: dilatations (of owned nodes and of
     * their off-process neighbours, recomputed here from the ghosted
     * displacement instead of communicated), then forces.
     */
    template <int dim>
    class BondOperator
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /**
       * Build the stencil, the lists and the index maps. @p lists must hold
       * lists of the owned nodes and, for state-based models, of their
       * off-process neighbours; @p bond_state (may be null: all intact) must
       * have been built on @p lists and stay alive.
       */
      void
      reinit(const Discretization::NodeSet<dim>      &nodes,
             const Discretization::NeighborList<dim> &lists,
             const Models::Model<dim>                &model,
             const double                             horizon,
             const Discretization::BondState<dim>    *bond_state = nullptr);

      /**
       * Kinematics and bond failure of apply() (the defaults: linearised
       * kinematics, no failure, are the quasi-static operator).
       *
       * With @p finite_deformation the bond extension is
       * \f$e_{ij} = |\xi + \eta| - |\xi|\f$ and the pair force acts along
       * the deformed bond \f$(\xi + \eta)/|\xi + \eta|\f$
       * (\f$\eta = u_j - u_i\f$; hybrid-collocation paper Eq. 15 for PMB, the
       * same kernel constants for LPS), otherwise \f$e_{ij} = n\cdot\eta\f$
       * along n. With @p critical_stretch (one value per node of the set,
       * +inf where bonds must not fail; empty: no failure) a bond whose
       * stretch \f$e_{ij}/|\xi|\f$ reaches
       * \f$\min(s_{0,i}, s_{0,j})\f$ is left out of the dilatation and the
       * forces of that evaluation on every process that evaluates it (the
       * stretch of (i, j) and (j, i) is the same to the bit), and recorded;
       * commit_broken_bonds() then breaks it for good.
       */
      void
      set_kinematics(const bool                 finite_deformation,
                     const std::vector<double> &critical_stretch = {});

      /**
       * Break the bonds that apply() found over their critical stretch in
       * @p state (the state given to reinit()), synchronise it over the
       * processes and re-sort the nodes between stencil and lists.
       * Collective. Returns the number of bond pairs newly broken on all
       * processes together.
       */
      std::size_t
      commit_broken_bonds(Discretization::BondState<dim> &state);

      /**
       * commit_broken_bonds() without a collective over all processes (the
       * time loops, every step): the broken pairs go to the neighbouring
       * processes only (BondState::exchange()), and the return value is
       * this process's share of the count, the bond ends newly broken at
       * its owned nodes; summed over all processes it is twice the pairs.
       * With collocation nodes, one reduction still tells every process
       * whether any of them must switch (make_standard()).
       */
      std::size_t
      commit_broken_bond_ends(Discretization::BondState<dim> &state);

      /**
       * The bonds that apply() found over their critical stretch since
       * set_kinematics() or the last commit, each counted once on all
       * processes together (each end of a bond is owned by one process and
       * sees the same stretch to the bit), and then forgotten: nothing
       * breaks. Collective.
       */
      std::size_t
      count_exceeded_bonds();

      /**
       * The elastic energy \f$\sum_i V_i W_i\f$ of the owned nodes of all
       * processes (Models::Model::dilatation_energy_modulus() gives \f$W_i\f$),
       * with the kinematics of apply() and the intact bonds. Collective.
       */
      double
      elastic_energy(const VectorType &displacement) const;

      /**
       * The largest eigenvalue of \f$M^{-1}K\f$ (K the linearised stiffness
       * of the intact bonds, M the lumped mass \f$\rho V_i\f$), estimated
       * by @p n_iterations steps of the power method from a fixed start
       * vector. Collective.
       */
      double
      estimate_largest_eigenvalue(const double       density,
                                  const unsigned int n_iterations) const;

      /**
       * An upper bound of the largest eigenvalue of \f$M^{-1}K\f$ (same K
       * and M as estimate_largest_eigenvalue()) by Gershgorin's theorem,
       * each entry of K bounded term by term from the kernel (derivation in
       * doc/explicit-dynamics.md). For bond-based models it is the bound of
       * Silling & Askari (2005) with the direction cosines kept. Collective.
       */
      double
      gershgorin_eigenvalue_bound(const double density) const;

      /**
       * Re-sort nodes between the stencil and the lists after bonds broke
       * (BondState::synchronize() called on all processes before).
       */
      void
      update_bond_state();

      /// The partitioner of displacement vectors: owned DoFs, and the DoFs
      /// of every node of the set as ghosts.
      const std::shared_ptr<const Utilities::MPI::Partitioner> &
      get_partitioner() const;

      /// Size @p v for this operator (ghosted layout).
      void
      initialize_dof_vector(VectorType &v) const;

      /**
       * Nodal internal forces \f$F_i\f$ of the owned nodes into @p force,
       * from @p displacement whose ghost values are up to date. Ghost
       * entries of @p force are left untouched.
       */
      void
      apply(const VectorType &displacement, VectorType &force) const;

      /**
       * apply() with the linearised kinematics whatever set_kinematics()
       * chose, and without failure: \f$-K u\f$ with K the stiffness of the
       * intact bonds at the reference configuration (the operator of the
       * Krylov solves in a modified Newton method for finite deformation,
       * and of the eigenvalue estimate of dynamic relaxation). The same
       * passes, to the bit, as apply() without finite kinematics or failure.
       */
      void
      apply_linearised(const VectorType &displacement, VectorType &force) const;

      /// Whether apply() uses finite kinematics (set_kinematics()).
      bool
      finite_kinematics() const
      {
        return finite;
      }

      /**
       * apply(), and the elastic energy of the same state as
       * elastic_energy() gives it (to round-off; before
       * commit_broken_bonds(), whose bonds over their critical stretch this
       * evaluation already leaves out). With finite kinematics or failure
       * the force pass sums the bond energies on the way, which saves the
       * energy's own pass over the bonds; otherwise it is that pass.
       * Collective.
       */
      double
      apply_with_energy(const VectorType &displacement,
                        VectorType       &force) const;

      /**
       * The dilatation of every node with a list (0 elsewhere), from
       * @p displacement with up-to-date ghost values.
       */
      void
      compute_dilatation(const VectorType    &displacement,
                         std::vector<double> &dilatation) const;

      /**
       * The diagonal of the stiffness \f$K = -\partial F/\partial u\f$ at the
       * owned DoFs, exactly (including the coupling through the
       * neighbours' dilatations).
       */
      void
      compute_diagonal(VectorType &diagonal) const;

      /**
       * Assemble the stiffness \f$K = -\partial F/\partial u\f$ of the
       * owned DoFs into @p matrix (rows, range and domain: the owned DoFs),
       * from the same kernel, stencil, lists and bond state as apply(), so
       * that \f$K u = -F(u)\f$ to round-off. With @p constraints (prescribed
       * values \f$u_k = g_k\f$ only), the columns of prescribed DoFs move to
       * @p rhs (\f$b_r \mathrel{-}= K_{rk} g_k\f$, i.e. added as
       * \f$\partial F_r/\partial u_k\, g_k\f$) and their rows keep a
       * positive diagonal \f$d\f$ with \f$b_k \mathrel{+}= d\, g_k\f$.
       *
       * The pattern of a row is exactly its intact coupling (neighbours and,
       * state-based, their neighbours) minus prescribed columns; it is built
       * once into a Trilinos graph with exact row lengths (no second copy of
       * the pattern). On a uniform grid, rows whose whole coupling range is
       * the shared stencil (bulk rows) copy one precomputed block row; the
       * others are formed in a dense scratch box around the node. Values are
       * written in place into the matrix's rows, threaded.
       */
      void
      assemble(TrilinosWrappers::SparseMatrix  &matrix,
               const AffineConstraints<double> *constraints = nullptr,
               TrilinosWrappers::MPI::Vector   *rhs         = nullptr) const;

      /// Reference weighted volume \f$m_i\f$ of every node with a list.
      /// What use_collocation() and use_collocation_per_node() did.
      using CollocationReport = Operators::CollocationReport;

      /**
       * Evaluate every owned node whose neighbourhood is the full lattice
       * stencil (a full ball inside the body and its layers) with the WLS
       * collocation quadrature of @p settings instead of the partial-volume
       * weights (doc/collocation.md Sects. 6 and 11): the force of such a
       * node is
       * \f[
       *   F_i = V_i \sum_{k} W_k\,(u_{i + o_k} - u_i),\qquad
       *   W_k = \sum_\alpha L[\alpha]\, Q[\alpha, k],
       * \f]
       * over the collocation nodes o_k of one shared bulk row (one fit on
       * the uniform lattice; L the moments of the linearised bond-based
       * pair stiffness 2 beta(r) n (x) n). The other nodes keep the
       * standard scheme. State-based (LPS) models take two rows
       * (doc/collocation.md Sect. 5.2): every node with a full stencil
       * (owned or ghost, not in @p standard) gets its dilatation from the
       * fit of its own cloud, \f$\theta_i = \sum_k T_k \cdot (u_{i+o_k} -
       * u_i)\f$, and the force of a collocation node adds
       * \f$V_i \sum_k K_k (\theta_{i+o_k} - \theta_i)\f$ to the
       * deviatoric row (whose moments are those of 2 c_mu omega / m n (x) n,
       * m the continuum weighted volume); the other nodes' dilatations stay
       * standard. Linear kinematics and no failure only (the bond-based rows
       * also run beside the nonlinear passes of standard nodes); on a
       * uniform lattice; apply() and assemble() both evaluate the rows; the
       * operator is not symmetric. Off the lattice (irregular nodes,
       * bond-based models) every owned node whose ball lies in the body and
       * its layers (its cells' exact partial volumes fill the ball) gets a
       * row of its own, fitted to its own cloud; an ill-conditioned cloud
       * makes its node standard (counted) or throws, as @p settings say. An
       * ill-conditioned bulk cloud falls back to the standard scheme everywhere
       * or throws, as
       * @p settings say. Nodes flagged in @p standard (owned and ghost
       * indices; empty: none) keep the standard scheme (the fixed region
       * of the hybrid scheme). Collective (the report's counts are sums over
       * the processes).
       */
      CollocationReport
      use_collocation(const Quadrature::CollocationSettings &settings,
                      const std::vector<bool> &standard = std::vector<bool>());

      /**
       * The adaptive switch of the hybrid scheme (hybrid-collocation paper
       * Eq. 65): every owned collocation node with a bond whose stretch
       * under @p displacement (ghost values up to date; the kinematics of
       * set_kinematics()) reaches @p fraction times the bond's critical
       * stretch \f$\min(s_{0,i}, s_{0,j})\f$ becomes standard for good,
       * and the work lists are rebuilt. Each process decides for its own
       * nodes from the bond's stretch, which is the same to the bit seen
       * from either end, so every partition switches the same nodes.
       * Without a failure criterion (set_kinematics()) nothing switches and no
       * scan is due again. Collective; returns the number of nodes switched on
       * all processes. With
       * @p switch_nodes false nothing switches: it returns the number of
       * nodes that would (the fixed configuration, which stops then).
       *
       * With @p only_due, right after critical_bond_possible() returned
       * true for the same displacement, only the chunks of collocation nodes
       * that it found due are scanned; otherwise all are. A scanned node's
       * margin \f$\min(\text{fraction}\, s_0 - s)\f$ over its bonds is
       * recorded and its drift restarts from zero.
       */
      std::size_t
      switch_critical_nodes(const VectorType &displacement,
                            const double      fraction,
                            const bool        switch_nodes = true,
                            const bool        only_due     = false);

      /**
       * Whether a bond of a collocation node may have reached the fraction
       * of switch_critical_nodes() since the node's last scan, under
       * @p displacement (ghost values up to date), called once per step
       * (doc/collocation.md Sect. 11.1). A stretch \f$s = e/r\f$ with
       * \f$|e(\eta) - e(\eta')| \le |\eta - \eta'|\f$ (linearised and
       * finite kinematics alike) changes in one step by at most
       * \f$|\delta u_j - \delta u_i| / r\f$; along a lattice path of
       * \f$|k|_1\f$ edges inside the node's stencil box that is at most
       * \f$|k|_1 E / r_k\f$, E the largest change \f$|\delta u_a -
       * \delta u_b|\f$ of a lattice edge in the 3^dim tiles (of the
       * stencil's reach) around the node's own. Each node sums these bounds
       * since its last scan (its drift); a chunk of nodes is due once a
       * node's drift reaches its margin. A scan of the due chunks at the
       * steps where this is true switches the same nodes at the same steps
       * as a scan of every node at every step. O(nodes) work; collective
       * (one reduction) unless no collocation node is left.
       */
      bool
      critical_bond_possible(const VectorType &displacement);

      /// The collocation nodes scanned by switch_critical_nodes() and the
      /// number a scan of every collocation node at every step would have
      /// scanned, summed over the steps and processes. Collective.
      std::pair<std::size_t, std::size_t>
      n_scanned_nodes() const;

      /**
       * Make the owned collocation nodes @p switched standard for good, and
       * re-cut the work lists and the collocation chunks if any process
       * switched one (a resumed hybrid run restores its switched nodes so).
       * Collective; returns the number switched on all processes.
       */
      std::size_t
      make_standard(const std::vector<unsigned int> &switched);

      /// After the last scan (switch_critical_nodes()): the smallest margin
      /// left (fraction s_0 - s at the node's scan, minus its drift since)
      /// over the remaining collocation nodes, on all processes (infinite:
      /// none).
      double
      switch_margin() const
      {
        return scan_margin;
      }

      /**
       * Owned nodes whose switch came late, summed over the processes
       * since use_collocation(): a collocation node that lost a bond
       * (broken from its standard end; commit_broken_bonds() then switches
       * it) or that switch_critical_nodes() found with a bond already past
       * its critical stretch. Zero when the switch saw every breaking bond
       * coming. Collective.
       */
      std::size_t
      n_missed_switches() const;

      /// Owned collocation nodes on all processes. Collective.
      std::size_t
      n_collocation_nodes() const;

      /**
       * How elastic_energy() and apply_with_energy() count a collocation
       * node: false (default) as its share -1/2 u_i . F_i of the quadratic
       * form 1/2 u.K u of the (linear) collocation rows, exact for static
       * problems; true as the pair energy of its bonds (the standard
       * scheme's), which stays positive and does not jump when the node
       * switches: the energy that explicit dynamics balances with the
       * hybrid scheme (doc/collocation.md Sect. 11).
       */
      void
      set_collocation_energy(const bool bond_energy)
      {
        bond_energy_at_collocation_nodes = bond_energy;
      }

      /// Whether node @p i is evaluated by collocation (use_collocation()).
      bool
      is_collocation_node(const unsigned int i) const
      {
        return !collocation_node.empty() && collocation_node[i] != 0;
      }

      const std::vector<double> &
      weighted_volumes() const;

      /// Owned nodes evaluated with the shared stencil.
      unsigned int
      n_stencil_nodes() const;

      /// Owned nodes evaluated with their own lists.
      unsigned int
      n_list_nodes() const;

      /// Of those, the nodes that finite kinematics and failure evaluate in
      /// runs of consecutive slots (Run) rather than one by one.
      unsigned int
      n_run_nodes() const;

      /// The most nodes in one run of the force pass (0 without runs); 1
      /// would mean that no run found a partner, i.e. nothing vectorised.
      unsigned int
      max_run_length() const;

      /// Bond visits of one apply() on this process (both passes).
      std::size_t
      n_bond_visits() const;

      /// Whether the state-based (two-pass) kernel is used.
      bool
      is_state_based() const;

      /// Bytes held by the operator on this process (scratch included).
      std::size_t
      memory_consumption() const;

      /// Slots per run of the vectorised stencil loop.
      static constexpr unsigned int chunk_size = LoopLayout<dim>::chunk_size;

    private:
      /**
       * A bond that reached its critical stretch: its node (local index)
       * and, on the lattice, its stencil index, otherwise the neighbour's
       * local index.
       */
      using ExceededBond = std::pair<unsigned int, unsigned int>;
      using Chunk        = typename LoopLayout<dim>::Chunk;
      using Run          = typename LoopLayout<dim>::Run;
      using Block        = typename LoopLayout<dim>::Block;
      using Pass         = typename LoopLayout<dim>::Pass;

      /// One bond of a node outside the shared stencil.
      struct ListBond
      {
        unsigned int neighbor_slot;
        double       n[dim];
        double       r;
        double       g; // (d / m_i) omega r w
        double       a; // V_i w alpha(r)
        double       b; // V_i w beta(r)
      };

      /// The shared stencil's constants: one entry per offset (the slot
      /// offsets are the layout's).
      struct Stencil
      {
        std::array<std::vector<double>, dim> n, xi;
        std::vector<double>                  r, inv_r;
        std::vector<double>                  g, a, b;
        double                               node_factor = 0;
      };

      /// Raw views of the stencil's constants and the slot arrays, for the
      /// gather loops of the list nodes.
      struct GatherViews
      {
        const std::uint16_t  *index;
        const std::ptrdiff_t *offset;
        const double         *r, *inv_r, *g, *a, *b, *t, *s, *s0;
        const double         *xi[dim], *n[dim], *u[dim];
      };

      GatherViews
      gather_views() const
      {
        GatherViews v{layout.list_stencil_index.data(),
                      layout.stencil_offset.data(),
                      stencil.r.data(),
                      stencil.inv_r.data(),
                      stencil.g.data(),
                      stencil.a.data(),
                      stencil.b.data(),
                      t_slot.data(),
                      s_slot.data(),
                      s0_slot.data(),
                      {},
                      {},
                      {}};
        for (unsigned int d = 0; d < dim; ++d)
          {
            v.xi[d] = stencil.xi[d].data();
            v.n[d]  = stencil.n[d].data();
            v.u[d]  = u_slot[d].data();
          }
        return v;
      }

      const Discretization::NodeSet<dim>      *nodes        = nullptr;
      const Discretization::NeighborList<dim> *lists        = nullptr;
      const Models::Model<dim>                *model        = nullptr;
      const Discretization::BondState<dim>    *bond_state   = nullptr;
      double                                   horizon      = 0;
      bool                                     state_based  = true;
      bool                                     finite       = false;
      bool                                     with_failure = false;

      /// Slots, chunks, runs, lists and masks: the loops' layout, with two
      /// passes (theta_work(): the dilatations, force_work(): the forces).
      LoopLayout<dim>     layout;
      std::vector<double> m;
      double  stencil_weighted_volume = 0; // m of a full neighbourhood
      Stencil stencil;

      // Off a lattice: one ListBond per bond, in the layout's list
      // segments. On a lattice the bonds of a node off the shared stencil
      // are a subset of the stencil (the layout's list_stencil_index), the
      // constants shared.
      /// The shared collocation row: slot offsets of the collocation nodes
      /// other than the node itself, the d x d blocks V W_k (component
      /// pair (c, d) in w[c * dim + d]) and their sum, in the order of the
      /// fit's cloud (fixed by the bond vectors).
      struct CollocationRow
      {
        std::vector<std::ptrdiff_t>                offset;
        std::vector<unsigned int>                  stencil_index;
        std::array<std::vector<double>, dim * dim> w;
        Tensor<2, dim>                             sum;
        /// State-based models: the dilatation row T_k (theta_w[c][k]) and
        /// the dilatation force row V K_k (kf[c][k]), in the same order.
        std::array<std::vector<double>, dim> theta_w, kf;
        /// Per stencil offset: its index in the row, or -1.
        std::vector<int> of_stencil_index;
      };

      /**
       * Off the lattice (irregular nodes, 'Geometry/Node perturbation'):
       * one collocation row per node, fitted to its own cloud
       * (use_collocation_per_node()): the nodes with a row, the entries of
       * row r in [first[r], first[r + 1]), each a neighbour slot and the
       * d x d block V W_k (dim * dim doubles).
       */
      struct NodeRows
      {
        std::vector<unsigned int> node;
        std::vector<std::size_t>  first{0};
        std::vector<std::size_t>  neighbor_slot;
        std::vector<double>       w;
      };
      NodeRows         node_rows;
      std::vector<int> node_row_of;

      /// Whether any node is evaluated by a collocation row.
      bool
      has_collocation_rows() const
      {
        return !collocation_chunks.empty() || !node_rows.node.empty();
      }

      /// State-based models with collocation: 1 for the nodes (owned and
      /// ghost) whose dilatation comes from the collocation row, and the
      /// chunks of their slots; the plain dilatation theta of every node
      /// with a list, per slot (the collocation rows read it).
      std::vector<char>             collocation_theta;
      std::vector<Chunk>            collocation_theta_chunks;
      mutable AlignedVector<double> theta_slot;

      /// 1 for the nodes evaluated by collocation; empty without.
      std::vector<char> collocation_node;
      /// Whether use_collocation() (or its per-node variant) was called:
      /// the same on every process (collocation_node may be empty on a
      /// process without nodes).
      bool        with_collocation                 = false;
      std::size_t missed_switches                  = 0;
      bool        bond_energy_at_collocation_nodes = false;
      /// The smallest margin left (margin minus drift) over the remaining
      /// collocation nodes after the last scan, on all processes (infinite:
      /// none left).
      double scan_margin = 0;
      /**
       * The state of critical_bond_possible() (bond_operator_switch.cc):
       * tiles of lattice cells (the stencil's reach on a side) over the local
       * nodes, each node's tile and lattice neighbours, per slot the margin
       * of the node's last scan and its drift since, the displacement of the
       * last step, and scratch for this step's change and the largest edge
       * change per tile and per 3^dim block of tiles.
       */
      struct SwitchTracking
      {
        bool                          active    = false;
        std::int64_t                  tile_side = 1;
        std::array<std::int64_t, dim> n_tiles{};
        double                        path_factor = 0;
        std::vector<unsigned int>     node_tile, slot_tile;
        // The nodes of each tile (tile_nodes[tile_first[t]...]).
        std::vector<std::size_t>  tile_first;
        std::vector<unsigned int> tile_nodes;
        std::vector<int>          node_neighbor;
        std::vector<char>         chunk_due;
        std::vector<double>       slot_margin, slot_drift;
        std::vector<double>       previous_displacement, step_change;
        std::vector<double>       tile_edge, tile_block;
        std::size_t               n_scanned = 0, n_possible = 0;
      };
      SwitchTracking     tracking;
      CollocationRow     collocation_row;
      std::vector<Chunk> collocation_chunks;

      std::vector<ListBond> list_bonds;
      std::vector<double>   list_theta_scale; // m_0 / m_i per node
      // s_i m_0 / m_i per slot, for the runs of the dilatation pass.
      AlignedVector<double> theta_run_factor;

      // Scratch: displacement, force, s * theta and s per slot; the
      // critical stretch per slot (with failure).
      mutable std::array<AlignedVector<double>, dim> u_slot, f_slot;
      mutable AlignedVector<double>                  t_slot;
      mutable AlignedVector<double>                  e_slot;
      AlignedVector<double>                          s_slot;
      AlignedVector<double>                          s0_slot;
      std::vector<double>                            critical_stretch;
      // Bonds over their critical stretch, until committed (rare events:
      // a lock per record).
      mutable std::vector<ExceededBond> exceeded;
      mutable std::mutex                exceeded_mutex;

      /// The work of the dilatation pass.
      Pass &
      theta_work()
      {
        return layout.pass[0];
      }

      const Pass &
      theta_work() const
      {
        return layout.pass[0];
      }

      /// The work of the force pass.
      Pass &
      force_work()
      {
        return layout.pass[1];
      }

      const Pass &
      force_work() const
      {
        return layout.pass[1];
      }

      /// Whether node i needs the dilatation pass (state-based models: every
      /// node with a list).
      bool
      needs_dilatation(const unsigned int i) const
      {
        return state_based && lists->has_list(i);
      }

      /// Whether node i's dilatation comes from the collocation row.
      bool
      has_collocation_theta(const unsigned int i) const
      {
        return !collocation_theta.empty() && collocation_theta[i] != 0;
      }

      /// Call f(j, w_ij) for every intact bond of node i.
      template <typename Function>
      void
      for_each_intact_bond(const unsigned int i, const Function &f) const;

      /// Off the lattice: call f(bond, xi) for every list bond of node i,
      /// with xi = r n its reference bond vector.
      template <typename Function>
      void
      for_each_list_bond(const unsigned int i, const Function &f) const;

      /**
       * The vectorised sweep of a nonlinear pass: f(block, found) for every
       * masked chunk of the shared stencil and every run of @p pass
       * (LoopLayout::sweep_chunks_and_runs()), threaded, with the
       * subrange's list of bonds found over their critical stretch,
       * recorded once per subrange (record_exceeded()).
       *
       * Not always_inline, and neither is @p f: forcing the fracture
       * passes' lambdas inline (before GCC lowers their "omp simd" loops)
       * made those passes 2.5 times slower (measured with
       * perideal-bond-operator-throughput).
       */
      template <typename Function>
      void
      sweep_blocks(const Pass &pass, const Function &f) const;

      /**
       * The gather loop of a nonlinear pass: f(i, si, views, failed, found)
       * for every gather node i of @p pass (slot si), threaded, with
       * gather_views(), a scratch array @p failed of one entry per stencil
       * offset (on the lattice) and the subrange's list of bonds found over
       * their critical stretch, recorded once per subrange
       * (record_exceeded()).
       */
      template <typename Function>
      void
      for_each_gather_node(const Pass &pass, const Function &f) const;

      /**
       * Call f(sj, n, g, a, b, e) for every list bond of node i (slot
       * @p si), on the lattice or off it: the neighbour's slot, the bond's
       * direction (n(d): its d-th component), its constants and its
       * small-strain extension e = n . (u_j - u_i). (On the lattice g is
       * the stencil's, without the node's list_theta_scale.)
       *
       * always_inline (and so are the callers' lambdas): left out of line
       * by GCC, it cost the 3D linear apply 20-30 % (measured with
       * perideal-bond-operator-throughput).
       */
      template <typename Function>
      PERIDEAL_BOND_KERNEL_INLINE void
      for_each_linear_list_bond(const unsigned int i,
                                const std::size_t  si,
                                const Function    &f) const;

      /**
       * Call f(slot_j, key, n, g, a, b) for every intact bond of node i
       * (which must be on the stencil or have a list in the work lists),
       * with the neighbour's slot and the bond's constants as apply() uses
       * them. On the lattice, key is @p base plus the box-index offset of
       * the bond's stencil entry (@p box_delta); off it, the neighbour's
       * node index (= its slot).
       */
      template <typename Function>
      void
      for_each_bond_constants(const unsigned int                 i,
                              const std::ptrdiff_t               base,
                              const std::vector<std::ptrdiff_t> &box_delta,
                              const Function                    &f) const;

      /// Build the lists, chunks, runs and masks of both passes from the
      /// bond state (reinit(), update_bond_state()).
      void
      build_work_lists();

      /// The chunks of the intact stencil nodes of both passes.
      void
      make_stencil_chunks();

      /**
       * After bonds of the nodes @p changed broke: shrink their list
       * segments in place (in parallel), give the nodes that leave the
       * shared stencil a segment at the end and re-cut the stencil runs.
       * Costs the bonds of the changed nodes plus O(nodes), instead of the
       * bonds of every list node as build_work_lists() does.
       */
      void
      update_work_lists(const std::vector<unsigned int> &changed);

      void
      copy_in(const VectorType &displacement) const;

      void
      dilatation_pass() const;

      void
      force_pass() const;

      /// The forces of the collocation nodes into f_slot
      /// (bond_operator_collocation.cc).
      void
      collocation_pass() const;

      /// use_collocation() off the lattice: a row per node
      /// (bond_operator_collocation_rows.cc).
      CollocationReport
      use_collocation_per_node(const Quadrature::CollocationSettings &settings,
                               const std::vector<bool>               &standard);

      /// The forces of the nodes with a row of their own into f_slot.
      void
      node_rows_pass() const;

      /// State-based models: the dilatations of the nodes of
      /// collocation_theta_chunks into theta_slot and t_slot (s theta),
      /// after dilatation_pass() (bond_operator_collocation.cc).
      void
      collocation_dilatation_pass() const;

      /// The tiles and per-slot state of critical_bond_possible(), after
      /// use_collocation() (bond_operator_switch.cc).
      void
      setup_switch_tracking();

      /// The owned collocation nodes (no reduction).
      std::size_t
      n_owned_collocation_nodes() const;


      /// 2 sum_j (pair energy) of the intact bonds of node @p i from u_slot
      /// (bond_operator_energy.cc).
      double
      node_bond_energy(const unsigned int i) const;

      /// node_bond_energy() of every owned collocation node into
      /// @p energy (indexed by node, sized n_owned), threaded, on the
      /// lattice vectorised over the collocation chunks (the same
      /// operations in the same order, lane by lane).
      void
      collocation_bond_energies(std::vector<double> &energy) const;

      /// The force of collocation node @p i (slot @p si) from u_slot.
      Tensor<1, dim>
      collocation_force(const std::size_t si) const;

      /// The passes with finite kinematics and/or failure
      /// (bond_operator_fracture.cc).
      template <bool finite_kinematics>
      void
      nonlinear_dilatation_pass() const;

      /// With @p with_energy, also b e^2 summed over each owned node's
      /// intact bonds into e_slot.
      template <bool finite_kinematics, bool with_energy = false>
      void
      nonlinear_force_pass() const;

      /// The force passes of apply() and the copy into @p force; with
      /// @p linearised, the linear passes whatever the kinematics and
      /// failure (apply_linearised()).
      template <bool with_energy>
      void
      apply_passes(const VectorType &displacement,
                   VectorType       &force,
                   const bool        linearised = false) const;

      /// Record bonds (node, neighbour) found over their critical stretch
      /// (thread-safe; one lock per subrange in which bonds failed).
      void
      record_exceeded(const std::vector<ExceededBond> &found) const;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
