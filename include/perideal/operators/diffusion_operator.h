#ifndef perideal_operators_diffusion_operator_h
#define perideal_operators_diffusion_operator_h

#include <deal.II/base/aligned_vector.h>
#include <deal.II/base/partitioner.h>

#include <deal.II/lac/la_parallel_vector.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/diffusion_kernel.h>
#include <perideal/operators/collocation_node_rows.h>
#include <perideal/operators/loop_layout.h>
#include <perideal/quadrature/quadrature_scheme.h>

#include <memory>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * The discrete nonlocal diffusion operator (hybrid-collocation paper,
     * Eq. 27), evaluated without a matrix:
     * \f[
     *   (LC)_i = \sum_{j\ \mathrm{intact}} \mu_{ij}\,(C_j - C_i),\qquad
     *   \mu_{ij} = \kappa\,\frac{\omega(|\xi_{ij}|/\delta)}{|\xi_{ij}|^q}\,
     *              w_{ij},
     * \f]
     * with the kernel of Models::DiffusionKernel and the partial volumes
     * \f$w_{ij}\f$ of the neighbour lists. One scalar per node; the vector
     * layout numbers node i of the mesh as the global index
     * dofs[0] / dim of the simulator's DoF handler (one FE_DGQ(0)^dim cell
     * per node), owned nodes and, as ghosts, every other node of the set.
     *
     * The loop has the structure of BondOperator's: values are copied into
     * scratch indexed by lattice slot on a uniform grid (node index
     * otherwise); every node with a full, intact stencil is evaluated with
     * ONE shared stencil (slot offset and conductance per offset),
     * vectorised over runs of up to 64 consecutive bulk slots; every other
     * node has a compact list of (slot, conductance). No map, global index,
     * MPI or allocation in the loop; threads through
     * parallel::apply_to_subranges; each node's sum in a fixed order, so
     * any number of threads gives bitwise the same result.
     */
    template <int dim>
    class DiffusionOperator
    {
    public:
      using VectorType = LinearAlgebra::distributed::Vector<double>;

      /**
       * Build the stencil, the lists and the vector layout. @p lists must
       * hold the lists of the owned nodes; @p bond_state (may be null: all
       * intact) must have been built on @p lists and stay alive.
       */
      void
      reinit(const Discretization::NodeSet<dim>      &nodes,
             const Discretization::NeighborList<dim> &lists,
             const Models::DiffusionKernel           &kernel,
             const Discretization::BondState<dim>    *bond_state = nullptr);

      /// Re-sort nodes between stencil and lists after bonds broke.
      void
      update_bond_state();

      /**
       * Evaluate every owned node with a full, intact stencil with the WLS
       * collocation quadrature of @p settings instead of the partial
       * volumes (doc/collocation.md Sects. 4 and 6): one shared bulk row
       * \f$(LC)_i = \sum_k w_k (C_{i+o_k} - C_i)\f$, \f$w_k = \sum_\alpha
       * L[\alpha] Q[\alpha, k]\f$ with the moments L of the kernel's
       * conductance over the full ball, evaluated by the same vectorised
       * bulk loop as the standard stencil; the other nodes keep the
       * standard scheme. The operator is then not symmetric
       * (is_symmetric()). Only on a uniform grid, without phases. Returns
       * the row's cond(A) (above CollocationSettings::condition_limit
       * the bulk keeps the standard scheme or the call throws, as
       * @p settings say; the returned value says which). Collective only in
       * that every process computes the same row.
       */
      double
      use_collocation(const Quadrature::CollocationSettings &settings);

      /**
       * The collocation quadrature off the lattice (irregular nodes,
       * 'Geometry/Node perturbation'; doc/collocation.md Sect. 11.1): every
       * owned node whose ball lies in the body and its layers, and none of
       * whose bonds is broken, gets a row of its own, fitted to its own
       * cloud (fit_node_rows()), \f$(LC)_i = \sum_j w_{ij} (C_j - C_i)\f$
       * over the cloud in its order; the other nodes keep the standard
       * scheme. Ill-conditioned clouds fall back or stop the run as
       * @p settings say. Collective.
       */
      CollocationReport
      use_collocation_per_node(const Quadrature::CollocationSettings &settings);

      /**
       * The hybrid scheme (doc/collocation.md Sect. 11.1, "Hybrid
       * diffusion"): the owned nodes flagged in @p standard_of_owned (one
       * flag per owned node: the fixed standard region) keep the standard
       * scheme for good, whatever rows use_collocation() or
       * use_collocation_per_node() give. Call before them (the rows per
       * node are not fitted for these nodes). Independently of this, a
       * node whose neighbourhood holds more than one phase (set_phases())
       * is always evaluated with its bonds, since a row has no phase
       * factors; with @p keep_interface_nodes such a node stays standard
       * for good (the adaptive hybrid: never switch back), otherwise it
       * returns to its row once its neighbourhood is of one phase again.
       */
      void
      set_standard_nodes(const std::vector<bool> &standard_of_owned,
                         const bool               keep_interface_nodes);

      /// Whether the bulk or single nodes use collocation rows
      /// (use_collocation(), use_collocation_per_node()).
      bool
      uses_collocation() const
      {
        return collocation;
      }

      /// Whether owned node @p i is evaluated with a collocation row now.
      bool
      is_collocation_node(const unsigned int i) const
      {
        return node_by_row[i];
      }

      /// The owned nodes evaluated with a collocation row now.
      unsigned int
      n_collocation_nodes_now() const
      {
        return n_row_nodes;
      }

      /// The largest eigenvalue of the bulk collocation row's Fourier
      /// symbol over the magnitude of the most negative one
      /// (Quadrature::largest_symbol_eigenvalue()): > 0 means growing
      /// modes. 0 without collocation.
      double
      collocation_symbol() const
      {
        return symbol;
      }

      /// The number of collocation nodes of the bulk row, the node itself
      /// included (0 without collocation).
      unsigned int
      n_collocation_nodes() const
      {
        return collocation ? bulk_offset.size() + 1 : 0;
      }

      /**
       * Phases (optional; without them every bond conducts with factor 1).
       * @p phase_of_node gives every node of the set (owned and ghosts, the
       * same on every process that holds the node) a phase below
       * @p n_phases; the conductance of bond (i, j) is multiplied by
       * @p factor[p_i * n_phases + p_j] (symmetric). A bond between phase 0
       * and another phase (an interface bond) conducts only while the value
       * at its phase-0 end is below @p gate (the salt film of corrosion;
       * +inf: always). With @p rate (optional, antisymmetric,
       * concentration units) a bond also carries the fixed flow
       * \f$\rho_{p_i p_j}\,\mu_{ij}\f$ into node i, independent of the
       * values (the dissolution of corrosion), under the same gate. Nodes
       * whose whole neighbourhood has their own phase keep the shared
       * stencil, scaled by the factor (and cost nothing for a factor 0).
       * Rebuilds the work lists: call again after phases changed.
       */
      void
      set_phases(const std::vector<unsigned char> &phase_of_node,
                 const unsigned int                n_phases,
                 const std::vector<double>        &factor,
                 const double                      gate,
                 const std::vector<double>        &rate = {});

      /// The largest row sum of the conductances without phase factors,
      /// \f$\max_i\sum_j\mu_{ij}\f$ over all processes. Collective.
      double
      largest_row_sum() const;

      const std::shared_ptr<const Utilities::MPI::Partitioner> &
      get_partitioner() const;

      /// Size @p v for this operator (one value per node, ghosted).
      void
      initialize_vector(VectorType &v) const;

      /// The index of node @p i of the set in vectors of this layout
      /// (owned nodes: below locally_owned_size()).
      unsigned int
      vector_index(const unsigned int i) const
      {
        return layout.vector_index[i];
      }

      /**
       * \f$(LC)_i\f$ of the owned nodes into @p result, from
       * @p concentration whose ghost values are up to date. Ghost entries of
       * @p result are left untouched.
       */
      void
      apply(const VectorType &concentration, VectorType &result) const;

      /// \f$\sum_j \mu_{ij}\f$ over the intact bonds of each owned node
      /// (minus the diagonal of L).
      void
      row_sums(VectorType &sums) const;

      /**
       * Gershgorin's bound \f$2\max_i\sum_j\mu_{ij}\f$ of the spectral
       * radius of L, with every bond at the largest phase factor (so that
       * it holds whatever the phases become). Collective.
       */
      double
      gershgorin_bound() const;

      /**
       * The spectral radius of L estimated by @p n_iterations steps of the
       * power method from a fixed start vector. Collective.
       */
      double
      estimate_spectral_radius(const unsigned int n_iterations) const;

      /**
       * Whether \f$V_i\mu_{ij} = V_j\mu_{ji}\f$ holds by construction (a
       * uniform lattice: equal volumes, and the partial volume of an
       * offset equals that of its opposite), so that L is symmetric in
       * the volume-weighted inner product and conjugate gradients apply.
       */
      bool
      is_symmetric() const
      {
        return layout.use_lattice && !collocation;
      }

      /// Owned nodes evaluated with the shared stencil.
      unsigned int
      n_stencil_nodes() const;

      /// Owned nodes evaluated with their own lists.
      unsigned int
      n_list_nodes() const;

      /// Bond visits of one apply() on this process.
      std::size_t
      n_bond_visits() const;

      /// Bytes held by the operator on this process (scratch included).
      std::size_t
      memory_consumption() const;

      /// Slots per run of the vectorised stencil loop.
      static constexpr unsigned int chunk_size = LoopLayout<dim>::chunk_size;

    private:
      using Chunk = typename LoopLayout<dim>::Chunk;

      struct ListBond
      {
        unsigned int  slot;
        unsigned char gated; // 0: always; 1 (2): gate on node (neighbour)
        double        mu;
        double        flow; // fixed flow rho mu into the node
      };

      void
      build_work_lists();

      /// switch_bound from the bonds and rows of every owned node (after
      /// the rows changed).
      void
      update_switch_bound();

      /// The work of the one pass.
      typename LoopLayout<dim>::Pass &
      work()
      {
        return layout.pass[0];
      }

      const typename LoopLayout<dim>::Pass &
      work() const
      {
        return layout.pass[0];
      }

      void
      copy_in(const VectorType &concentration) const;

      const Discretization::NodeSet<dim>      *nodes      = nullptr;
      const Discretization::NeighborList<dim> *lists      = nullptr;
      const Models::DiffusionKernel           *kernel     = nullptr;
      const Discretization::BondState<dim>    *bond_state = nullptr;

      /// Slots, chunks and list nodes: the loop's layout (one pass, work()).
      LoopLayout<dim> layout;

      // The shared stencil's conductances (its slot offsets are the
      // layout's).
      std::vector<double> stencil_mu;
      double              stencil_sum = 0;

      // The bulk row of the vectorised loop: the shared stencil's offsets
      // and conductances, or the collocation row's (use_collocation()),
      // its sum and the sum of magnitudes (for Gershgorin's bound).
      bool                        collocation = false, bulk_row = false;
      double                      symbol = 0;
      std::vector<std::ptrdiff_t> bulk_offset;
      std::vector<double>         bulk_mu;
      double                      bulk_sum = 0, bulk_abs_sum = 0;

      // Phases per slot, the factor table and the gate.
      std::vector<unsigned char> phase_slot;
      unsigned int               n_phases = 1;
      std::vector<double>        factor   = {1.};
      std::vector<double>        rate;
      double                     gate        = 0;
      bool                       with_phases = false, any_special = false;
      double                     largest_geometric_sum = 0;

      // The phase factor of each chunk of work().chunks, and its row (0:
      // the shared standard stencil, 1: the bulk collocation row).
      std::vector<double>        chunk_factor;
      std::vector<unsigned char> chunk_row;
      std::vector<std::size_t>   zero_slots;
      // Owned nodes off the shared stencil's neighbourhood (a stored list,
      // or any node off a lattice): the slot and conductance of each bond,
      // in bond order, computed once, so that re-sorting after phase
      // changes or broken bonds evaluates no kernel and looks nothing up.
      std::vector<std::size_t> stored_first; // per owned node, size + 1
      std::vector<ListBond>    stored_bonds;
      // Per owned node: whether it has a collocation row of its own
      // (use_collocation_per_node()): its entries are
      // [row_first[i], row_first[i + 1]) of row_entries (slot, weight).
      std::vector<bool>        row_node;
      std::vector<std::size_t> row_first;
      std::vector<ListBond>    row_entries;
      // Hybrid: owned nodes that keep the standard scheme (the fixed
      // region, and with keep_interface the nodes an interface reached).
      std::vector<bool> standard_node;
      bool              keep_interface = false;
      // With rows: the largest of a node's row and bond sums of |weight|
      // over the owned nodes, Gershgorin's row bound whatever each node
      // takes (update_switch_bound()).
      double switch_bound = 0;
      // Per owned node: whether it is evaluated with a row now (bulk or
      // its own), and how many are.
      std::vector<bool> node_by_row;
      unsigned int      n_row_nodes = 0;
      // The bonds of the q-th list node of work() (in bond order):
      // [list_bond_first[q], list_bond_first[q + 1]) of list_bonds.
      std::vector<std::size_t> list_bond_first;
      std::vector<ListBond>    list_bonds;
      std::vector<double>      list_sum;

      mutable AlignedVector<double> c_slot, r_slot;
    };
  } // namespace Operators
} // namespace PeriDEAL

#endif
