#ifndef perideal_operators_fictitious_layer_layer_data_h
#define perideal_operators_fictitious_layer_layer_data_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/types.h>

#include <perideal/discretization/extended_lattice.h>
#include <perideal/discretization/node_set.h>
#include <perideal/discretization/surface_nodes.h>
#include <perideal/operators/fictitious_layer/sparse_entries.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <memory>
#include <vector>

class Epetra_CrsMatrix;

namespace PeriDEAL
{
  namespace Operators
  {
    /**
     * The parts of FictitiousLayerOperator: what reinit() sets up, and the
     * builders of the rows of its sparse factors \f$K = A E + B X D E\f$
     * (see FictitiousLayerOperator for the equations). Not meant for use
     * outside the operator.
     */
    namespace FictitiousLayer
    {
      using namespace dealii;

      /// The set-up of one FictitiousLayerOperator.
      template <int dim>
      struct LayerData
      {
        MPI_Comm comm = MPI_COMM_SELF;

        /// The body's nodes (owned and ghost), and the lattice around them.
        const Discretization::NodeSet<dim>  *nodes = nullptr;
        Discretization::ExtendedLattice<dim> lattice;

        /// The surface nodes; absent for the fictitious layer alone.
        std::unique_ptr<Discretization::SurfaceNodes<dim>> surface;

        /// Unknown numbering: per process, its first DoF and its first
        /// unknown (owned body DoFs, then dim per owned surface node).
        std::vector<types::global_dof_index> dof_start, sys_start;
        types::global_dof_index              n_sys = 0;
        IndexSet                             owned_sys;

        /// Bond data: the bulk stencil (offsets and partial volumes) with,
        /// per offset, the dilatation and extension stiffnesses of the
        /// bond and its weight in the dilatation. Every node has the bulk
        /// weighted volume m0.
        unsigned int                                 order       = 1;
        double                                       m_ratio     = 0;
        double                                       m0          = 0;
        bool                                         state_based = true;
        std::vector<Quadrature::WeightedOffset<dim>> neighbours;
        std::vector<double>                          a_r, b2_r, g_r;

        /// The factors of the operator, kept by build_factors() for
        /// apply() and assemble() (B, X, D only for state-based models).
        std::unique_ptr<Epetra_CrsMatrix> e_matrix, a_matrix, d_matrix,
          x_matrix, b_matrix;

        /// The unknown of DoF @p dof owned by process @p owner.
        types::global_dof_index
        sys_of_dof(const types::global_dof_index dof,
                   const unsigned int            owner) const
        {
          return dof - dof_start[owner] + sys_start[owner];
        }
      };


      /**
       * The rows of E (lattice displacements dim*key+c from the unknowns)
       * and X (lattice dilatations from body dilatations, both by key):
       * the identity on the owned body nodes (@p owned_body_keys, sorted),
       * Taylor extrapolation on the owned fictitious nodes. A fictitious
       * node's displacement is expanded about its nearest surface node
       * (surface and body nodes in the stencil) when there are surface
       * nodes, else about its nearest body node; its dilatation, one order
       * lower, about its nearest body node from body nodes.
       */
      template <int dim>
      void
      add_extrapolation_rows(const LayerData<dim>   &data,
                             const std::vector<int> &owned_body_keys,
                             SparseEntries          &e_rows,
                             SparseEntries          &x_rows);

      /**
       * The rows of the owned body nodes (paper Eq. 33): D (their
       * dilatations from lattice displacements), A (extension part of the
       * bond forces on lattice displacements) and B (dilatation part, on
       * lattice dilatations).
       */
      template <int dim>
      void
      add_body_rows(const LayerData<dim> &data,
                    SparseEntries        &d_rows,
                    SparseEntries        &a_rows,
                    SparseEntries        &b_rows);

      /**
       * The rows of A and B of the owned surface nodes: the force flux
       * through their faces (paper Eq. 36). Needs data.surface.
       */
      template <int dim>
      void
      add_surface_flux_rows(const LayerData<dim> &data,
                            SparseEntries        &a_rows,
                            SparseEntries        &b_rows);
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL

#endif
