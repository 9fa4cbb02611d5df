/**
 * @file
 * Every s-th node of a uniform lattice: numbering, interpolation weights,
 * restriction and prolongation (Operators::CoarseLattice).
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/base/exceptions.h>
#include <perideal/operators/coarse_lattice.h>

#include <algorithm>
#include <array>
#include <cstdint>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      /// Calls f(i, p, k) for component p of each owned node i whose DoF
      /// is free, k the DoF's local index in @p fine.
      template <int dim, typename VectorType, typename Function>
      void
      for_each_free_dof(const VectorType                           &fine,
                        const std::vector<types::global_dof_index> &fine_dof,
                        const std::vector<char> &fine_constrained,
                        const Function          &f)
      {
        const auto &partitioner = *fine.get_partitioner();
        for (unsigned int i = 0; i < fine_dof.size(); ++i)
          {
            const unsigned int local = partitioner.global_to_local(fine_dof[i]);
            for (unsigned int p = 0; p < dim; ++p)
              if (!fine_constrained[std::size_t(i) * dim + p])
                f(i, p, local + p);
          }
      }


      /// x mod s in [0, s) for negative x too.
      std::int64_t
      remainder(const std::int64_t x, const std::int64_t s)
      {
        const std::int64_t r = x % s;
        return r < 0 ? r + s : r;
      }
    } // namespace


    template <int dim>
    std::vector<std::uint8_t>
    owner_constraint_masks(const Discretization::NodeSet<dim> &nodes,
                           const AffineConstraints<double>    &constraints)
    {
      LinearAlgebra::distributed::Vector<double> exchanged(
        nodes.node_partitioner());
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          unsigned int mask = 0;
          for (unsigned int p = 0; p < dim; ++p)
            if (constraints.is_constrained(nodes[i].dofs[p]))
              mask |= 1u << p;
          exchanged(nodes[i].dofs[0] / dim) = mask;
        }
      exchanged.update_ghost_values();
      std::vector<std::uint8_t> masks(nodes.size());
      for (unsigned int i = 0; i < nodes.size(); ++i)
        masks[i] = static_cast<std::uint8_t>(exchanged(nodes[i].dofs[0] / dim));
      return masks;
    }


    template <int dim>
    void
    CoarseLattice<dim>::reinit(
      const Discretization::NodeSet<dim> &nodes,
      const Discretization::Lattice<dim> &lattice,
      const AffineConstraints<double>    &constraints,
      const unsigned int                  stride,
      const AffineConstraints<double>    *boundary_constraints)
    {
      AssertThrow(lattice.is_uniform(),
                  ExcMessage("A coarse lattice needs a uniform grid of cubes "
                             "(the cell centres must form a lattice)."));
      AssertThrow(stride >= 1 && stride <= 2,
                  ExcMessage(
                    "The coarse lattice's stride must be 1 or 2 "
                    "(the off-process nodes reach two lattice steps)."));
      s                                   = stride;
      const MPI_Comm comm                 = nodes.get_communicator();
      const auto     is_on_coarse_lattice = [&](const unsigned int i) {
        const auto &x = lattice.coordinates(i);
        for (unsigned int d = 0; d < dim; ++d)
          if (remainder(x[d], s) != 0)
            return false;
        return true;
      };

      // Number the owned coarse nodes in the order of the owned nodes,
      // after those of the lower ranks.
      types::global_dof_index n_owned_coarse = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        n_owned_coarse += is_on_coarse_lattice(i) ? 1 : 0;
      types::global_dof_index first = 0;
      {
        const int ierr = MPI_Exscan(
          &n_owned_coarse,
          &first,
          1,
          Utilities::MPI::mpi_type_id_for_type<types::global_dof_index>,
          MPI_SUM,
          comm);
        AssertThrowMPI(ierr);
        if (Utilities::MPI::this_mpi_process(comm) == 0)
          first = 0;
      }
      n_global = Utilities::MPI::sum(n_owned_coarse, comm);

      // The components that boundary conditions prescribe, for every node
      // of the set as its owner has them (the rule below reads
      // off-process nodes; the owned nodes' own flags come from
      // @p constraints directly).
      const std::vector<std::uint8_t> boundary_mask =
        owner_constraint_masks(nodes,
                               boundary_constraints != nullptr ?
                                 *boundary_constraints :
                                 constraints);

      // The prescribed components of an owned coarse node c: those a
      // boundary condition prescribes at its own node, and each component p of
      // a node j in its support (within s - 1 steps) that a boundary condition
      // prescribes while none of j's coarse corners has p prescribed. The
      // corners of j lie within 2 (s - 1) steps of c: in the node set.
      constexpr unsigned int n_corners = 1u << dim;
      const auto for_each_corner = [&](const std::array<std::int64_t, dim> &x,
                                       const auto                          &f) {
        std::array<std::int64_t, dim> lower, r;
        for (unsigned int d = 0; d < dim; ++d)
          {
            r[d]     = remainder(x[d], s);
            lower[d] = x[d] - r[d];
          }
        for (unsigned int c = 0; c < n_corners; ++c)
          {
            double                        w = 1;
            std::array<std::int64_t, dim> y = lower;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const bool upper = (c >> d) & 1;
                w *= upper ? double(r[d]) / s : double(s - r[d]) / s;
                y[d] += upper ? s : 0;
              }
            if (w == 0)
              continue;
            const int j = lattice.node_at(y);
            if (j >= 0)
              f(j, w);
          }
      };
      const auto owned_coarse_mask = [&](const unsigned int c) {
        // A hold (a node whose bonds all broke) prescribes its own fine
        // DoF only: its coarse DoF stays free for the nodes around it.
        unsigned int       mask      = boundary_mask[c];
        const auto        &x         = lattice.coordinates(c);
        const unsigned int width     = 2 * s - 1,
                           n_support = Utilities::pow(width, dim);
        for (unsigned int o = 0; o < n_support; ++o)
          {
            std::array<std::int64_t, dim> y = x;
            for (unsigned int d = 0, q = o; d < dim; ++d, q /= width)
              y[d] += std::int64_t(q % width) - std::int64_t(s - 1);
            const int j = lattice.node_at(y);
            if (j < 0)
              continue;
            const unsigned int unrepresented = boundary_mask[j] & ~mask;
            if (unrepresented == 0)
              continue;
            unsigned int represented = 0;
            for_each_corner(lattice.coordinates(j),
                            [&](const int k, const double) {
                              represented |= boundary_mask[k];
                            });
            mask |= unrepresented & ~represented;
          }
        return mask;
      };

      // The numbers and prescribed components of the off-process coarse
      // nodes, from their owners (a vector with one entry per node:
      // number * 8 + mask, exact in a double; -1 for nodes that are not
      // coarse).
      coarse_number.assign(nodes.size(), numbers::invalid_dof_index);
      coarse_mask.assign(nodes.size(), 0);
      {
        LinearAlgebra::distributed::Vector<double> numbers_of_nodes(
          nodes.node_partitioner());
        types::global_dof_index next = first;
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            const bool coarse = is_on_coarse_lattice(i);
            if (coarse)
              {
                coarse_number[i] = next++;
                coarse_mask[i]   = owned_coarse_mask(i);
              }
            numbers_of_nodes(nodes[i].dofs[0] / dim) =
              coarse ? double(coarse_number[i]) * 8 + coarse_mask[i] : -1.;
          }
        numbers_of_nodes.update_ghost_values();
        for (unsigned int i = nodes.n_owned(); i < nodes.size(); ++i)
          {
            const double v = numbers_of_nodes(nodes[i].dofs[0] / dim);
            if (v >= 0)
              {
                static_assert(dim <= 3, "the mask takes three bits");
                const auto packed = static_cast<std::uint64_t>(v);
                coarse_number[i] =
                  static_cast<types::global_dof_index>(packed / 8);
                coarse_mask[i] = static_cast<std::uint8_t>(packed % 8);
              }
          }
      }

      owned.clear();
      owned.set_size(n_global * dim);
      owned.add_range(first * dim, (first + n_owned_coarse) * dim);

      // The interpolation weights of the owned nodes: multilinear on the
      // coarse cube that holds the node, over the corners present,
      // rescaled to sum to one.
      row_start.assign(1, 0);
      corner_local.clear();
      corner_weight.clear();
      std::vector<int> corner_node;
      const auto is_owned_number = [&](const types::global_dof_index number) {
        return number >= first && number < first + n_owned_coarse;
      };
      // The off-process corners' numbers, gathered, then sorted once: one
      // add_indices() (IndexSet::add_range() out of order inserts into a
      // sorted list, quadratic over many nodes).
      std::vector<types::global_dof_index> ghost_numbers;
      std::vector<double>                  weights;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          weights.clear();
          const std::size_t row_begin = corner_node.size();
          double            sum       = 0;
          for_each_corner(lattice.coordinates(i),
                          [&](const int j, const double w) {
                            // A corner's owner marks it coarse from the
                            // same global coordinates (an invariant: no
                            // check that one process could fail alone
                            // before the collective calls below).
                            Assert(coarse_number[j] !=
                                     numbers::invalid_dof_index,
                                   ExcInternalError());
                            corner_node.push_back(j);
                            weights.push_back(w);
                            sum += w;
                          });
          for (std::size_t k = 0; k < weights.size(); ++k)
            {
              corner_weight.push_back(weights[k] / sum);
              const auto number = coarse_number[corner_node[row_begin + k]];
              if (!is_owned_number(number))
                ghost_numbers.push_back(number);
            }
          row_start.push_back(corner_weight.size());
        }
      std::sort(ghost_numbers.begin(), ghost_numbers.end());
      ghost_numbers.erase(std::unique(ghost_numbers.begin(),
                                      ghost_numbers.end()),
                          ghost_numbers.end());
      std::vector<types::global_dof_index> ghost_dofs;
      ghost_dofs.reserve(ghost_numbers.size() * dim);
      for (const auto number : ghost_numbers)
        for (unsigned int p = 0; p < dim; ++p)
          ghost_dofs.push_back(number * dim + p);
      IndexSet ghosts(n_global * dim);
      ghosts.add_indices(ghost_dofs.begin(), ghost_dofs.end());
      ghosts.compress();
      partitioner =
        std::make_shared<Utilities::MPI::Partitioner>(owned, ghosts, comm);
      corner_local.resize(corner_node.size());
      for (std::size_t k = 0; k < corner_node.size(); ++k)
        corner_local[k] =
          partitioner->global_to_local(coarse_number[corner_node[k]] * dim);

      // Which DoFs take no part.
      fine_constrained.resize(std::size_t(nodes.n_owned()) * dim);
      fine_dof.resize(nodes.n_owned());
      coarse_constrained.assign(partitioner->locally_owned_size() +
                                  partitioner->n_ghost_indices(),
                                0);
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          fine_dof[i] = nodes[i].dofs[0];
          for (unsigned int p = 0; p < dim; ++p)
            fine_constrained[std::size_t(i) * dim + p] =
              constraints.is_constrained(nodes[i].dofs[p]);
        }
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (coarse_number[i] != numbers::invalid_dof_index)
          {
            const auto global = coarse_number[i] * dim;
            if (!partitioner->in_local_range(global) &&
                !partitioner->is_ghost_entry(global))
              continue;
            const unsigned int local = partitioner->global_to_local(global);
            for (unsigned int p = 0; p < dim; ++p)
              coarse_constrained[local + p] = (coarse_mask[i] >> p) & 1;
          }
    }


    template <int dim>
    unsigned int
    CoarseLattice<dim>::stride() const
    {
      return s;
    }


    template <int dim>
    bool
    CoarseLattice<dim>::is_coarse(const unsigned int i) const
    {
      return coarse_number[i] != numbers::invalid_dof_index;
    }


    template <int dim>
    bool
    CoarseLattice<dim>::is_prescribed(const unsigned int i,
                                      const unsigned int component) const
    {
      return (coarse_mask[i] >> component) & 1;
    }


    template <int dim>
    types::global_dof_index
    CoarseLattice<dim>::dof(const unsigned int i,
                            const unsigned int component) const
    {
      return coarse_number[i] * dim + component;
    }


    template <int dim>
    const IndexSet &
    CoarseLattice<dim>::owned_dofs() const
    {
      return owned;
    }


    template <int dim>
    types::global_dof_index
    CoarseLattice<dim>::n_global_nodes() const
    {
      return n_global;
    }


    template <int dim>
    std::vector<std::vector<bool>>
    CoarseLattice<dim>::constant_modes() const
    {
      const std::size_t              n = owned.n_elements();
      std::vector<std::vector<bool>> modes(dim, std::vector<bool>(n, false));
      for (std::size_t k = 0; k < n; ++k)
        modes[k % dim][k] = true;
      return modes;
    }


    template <int dim>
    void
    CoarseLattice<dim>::initialize_coarse_vector(VectorType &coarse) const
    {
      coarse.reinit(partitioner);
    }


    template <int dim>
    void
    CoarseLattice<dim>::restrict_residual(VectorType       &coarse,
                                          const VectorType &fine) const
    {
      coarse = 0;
      for_each_free_dof<dim>(
        fine,
        fine_dof,
        fine_constrained,
        [&](const unsigned int i, const unsigned int p, const unsigned int k) {
          const double v = fine.local_element(k);
          for (unsigned int e = row_start[i]; e < row_start[i + 1]; ++e)
            {
              const unsigned int c = corner_local[e] + p;
              if (!coarse_constrained[c])
                coarse.local_element(c) += corner_weight[e] * v;
            }
        });
      coarse.compress(VectorOperation::add);
    }


    template <int dim>
    void
    CoarseLattice<dim>::prolongate_add(VectorType       &fine,
                                       const VectorType &coarse) const
    {
      coarse.update_ghost_values();
      for_each_free_dof<dim>(
        fine,
        fine_dof,
        fine_constrained,
        [&](const unsigned int i, const unsigned int p, const unsigned int k) {
          double v = 0;
          for (unsigned int e = row_start[i]; e < row_start[i + 1]; ++e)
            {
              const unsigned int c = corner_local[e] + p;
              if (!coarse_constrained[c])
                v += corner_weight[e] * coarse.local_element(c);
            }
          fine.local_element(k) += v;
        });
      coarse.zero_out_ghost_values();
    }


    template <int dim>
    std::size_t
    CoarseLattice<dim>::memory_consumption() const
    {
      return coarse_number.capacity() * sizeof(types::global_dof_index) +
             coarse_mask.capacity() +
             row_start.capacity() * sizeof(unsigned int) +
             corner_local.capacity() * sizeof(unsigned int) +
             corner_weight.capacity() * sizeof(double) +
             fine_constrained.capacity() + coarse_constrained.capacity() +
             fine_dof.capacity() * sizeof(types::global_dof_index);
    }


    template std::vector<std::uint8_t>
    owner_constraint_masks(const Discretization::NodeSet<2> &,
                           const AffineConstraints<double> &);
    template std::vector<std::uint8_t>
    owner_constraint_masks(const Discretization::NodeSet<3> &,
                           const AffineConstraints<double> &);
    template class CoarseLattice<2>;
    template class CoarseLattice<3>;
  } // namespace Operators
} // namespace PeriDEAL
