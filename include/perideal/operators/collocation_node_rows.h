#ifndef perideal_operators_collocation_node_rows_h
#define perideal_operators_collocation_node_rows_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/full_matrix.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/quadrature/collocation.h>
#include <perideal/quadrature/quadrature_scheme.h>

#include <cstddef>
#include <functional>
#include <vector>

namespace PeriDEAL
{
  namespace Operators
  {
    using namespace dealii;

    /**
     * What an operator's switch to the collocation quadrature did
     * (BondOperator::use_collocation(), use_collocation_per_node(),
     * DiffusionOperator::use_collocation_per_node()): how many owned nodes
     * (of all processes) it evaluates by collocation and how many stay
     * standard because their ball is cut by the surface or their cloud is
     * ill-conditioned, and the rows' size, conditioning and stability.
     */
    struct CollocationReport
    {
      /// Owned nodes of all processes evaluated by collocation.
      std::size_t n_collocation_nodes = 0;
      /// Owned nodes that keep the standard scheme because their
      /// neighbourhood is not a full ball inside the body and its layers.
      std::size_t n_cut_nodes = 0;
      /// Owned nodes that fell back to the standard scheme because the
      /// cloud's cond(A) exceeds CollocationSettings::condition_limit.
      std::size_t n_ill_conditioned = 0;
      /// Owned nodes whose cloud was bad for the order asked (above 2) and
      /// that took an order-2 row instead ('fall back';
      /// fit_node_rows_with_fallback()); counted in n_collocation_nodes.
      std::size_t n_lower_order = 0;
      /// Owned full-stencil nodes kept standard because the caller said
      /// so (the fixed standard region of the hybrid scheme).
      std::size_t n_fixed_standard = 0;
      /// The shared bulk row: collocation nodes n_c (the node itself
      /// included), monomials n_p, cond_2(A).
      unsigned int n_collocation = 0, n_monomials = 0;
      /// Rows per node (irregular nodes): n_collocation is then the
      /// largest cloud, n_collocation_min the smallest, and condition
      /// the largest cond_2(A) of the nodes' clouds.
      bool         per_node          = false;
      unsigned int n_collocation_min = 0;
      double       condition         = 0;
      /// The largest eigenvalue of the bulk row's Fourier symbol over
      /// the magnitude of the most negative one
      /// (Quadrature::largest_symbol_eigenvalue()): > 0 means growing
      /// modes (an indefinite static operator).
      double symbol = 0;
    };


    /**
     * The collocation rows of single nodes (irregular nodes,
     * 'Geometry/Node perturbation'; doc/collocation.md Sects. 6 and 11.1),
     * fitted node by node to each node's own cloud: the part that the
     * elasticity and the diffusion operators share. @p Entry is the weight
     * of one neighbour: a d × d block (elasticity) or a number (diffusion).
     */
    template <int dim, typename Entry>
    struct NodeRowFits
    {
      /// Per owned node: whether it has a row.
      std::vector<bool> has_row;
      /// Per owned node: the row's neighbours (the node itself left out:
      /// its weight is minus the sum of the others) and their weights, in
      /// the order of the cloud (fixed by the bond vectors, the same on
      /// every partition).
      std::vector<std::vector<unsigned int>> neighbors;
      std::vector<std::vector<Entry>>        weights;
    };


    /// The row of one node from its cloud and fit (fit_node_rows()).
    template <int dim, typename Entry>
    using RowOfFit =
      std::function<std::vector<Entry>(const unsigned int,
                                       const std::vector<Tensor<1, dim>> &,
                                       const FullMatrix<double> &)>;


    /**
     * Fit a collocation row for every owned node of @p nodes that is not
     * @p standard and whose ball lies in the body and its layers (the exact
     * partial volumes of the cells fill it to 1e-10): the node's family is
     * every neighbour within the horizon of its (moved) position, its cloud
     * the family nodes that @p fit selects, and its row
     * `row_of_fit(i, cloud, Q_i)`, one Entry per cloud node (the node
     * itself, the zero vector, included), from the cloud's bond vectors
     * and their fit Q_i.
     *
     * A cloud with cond(A) > CollocationSettings::condition_limit, or too
     * few nodes, or (order 2) a row whose diagonal (minus the sum of the
     * neighbours' weights) is not positive, falls back to the standard
     * scheme or stops the run, as `Ill-conditioned clouds` says; a
     * non-positive diagonal of a higher order stops the run naming
     * `Order`. The errors are decided on every process alike (collective).
     */
    template <int dim, typename Entry>
    CollocationReport
    fit_node_rows(const Discretization::NodeSet<dim>      &nodes,
                  const Discretization::NeighborList<dim> &lists,
                  const double                             horizon,
                  const Quadrature::CollocationSettings   &settings,
                  const Quadrature::CollocationFit<dim>   &fit,
                  const std::vector<bool>                 &standard,
                  const RowOfFit<dim, Entry>              &row_of_fit,
                  NodeRowFits<dim, Entry>                 &rows);


    /**
     * fit_node_rows() with the fit of @p settings for rows per node
     * (CollocationSettings::RowKind::per_node), and, with 'fall back' and
     * an order above 2, a second pass at order 2 over the nodes whose
     * cloud was bad for that order: they keep a collocation row (exact for
     * quadratics, stabilised as order-2 rows per node are) instead of the
     * standard scheme, counted in CollocationReport::n_lower_order. Only
     * the nodes bad at order 2 as well fall back to the standard scheme.
     * @p row_maker gives the row of one node for the settings and fit of a
     * pass (so that it computes the moments of that fit's basis once).
     */
    template <int dim, typename Entry>
    CollocationReport
    fit_node_rows_with_fallback(
      const Discretization::NodeSet<dim>          &nodes,
      const Discretization::NeighborList<dim>     &lists,
      const double                                 horizon,
      const Quadrature::CollocationSettings       &settings,
      const std::vector<bool>                     &standard,
      const std::function<RowOfFit<dim, Entry>(
        const Quadrature::CollocationSettings &,
        const Quadrature::CollocationFit<dim> &)> &row_maker,
      NodeRowFits<dim, Entry>                     &rows);
  } // namespace Operators
} // namespace PeriDEAL

#endif
