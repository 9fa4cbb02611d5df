#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <perideal/discretization/taylor_extrapolation.h>
#include <perideal/discretization/lattice.h>
#include <perideal/operators/bond/bond_kernel.h>
#include <perideal/operators/fictitious_layer_operator.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <EpetraExt_MatrixMatrix.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <Epetra_Vector.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace
    {
      /**
       * The entries of a sparse matrix under construction, as (row, column,
       * value) in any order; entries at the same position add up (Epetra
       * merges them when the matrix is completed). Appending is all the
       * build loops do: no tree, no per-entry allocation.
       */
      struct Entries
      {
        struct Entry
        {
          int    row, column;
          double value;
        };
        std::vector<Entry> list;

        void
        add(const int row, const int column, const double value)
        {
          list.push_back({row, column, value});
        }
      };

      /// A lattice position in units of h/2: cell centres have odd
      /// coordinates, face centres an even one along their normal.
      template <int dim>
      using HalfPoint = std::array<int, dim>;

      template <int dim>
      long long
      squared_distance(const HalfPoint<dim> &a, const HalfPoint<dim> &b)
      {
        long long s = 0;
        for (unsigned int d = 0; d < dim; ++d)
          s += static_cast<long long>(a[d] - b[d]) * (a[d] - b[d]);
        return s;
      }

      /// Build a distributed Epetra matrix from owned rows (the entries are
      /// bucketed by row, then each row inserted once).
      std::unique_ptr<Epetra_CrsMatrix>
      make_matrix(Entries       &&entries,
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
        entries.list = std::vector<typename Entries::Entry>();
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
    } // namespace


    template <int dim>
    struct FictitiousLayerOperator<dim>::Impl
    {
      MPI_Comm comm = MPI_COMM_SELF;

      // Lattice.
      double                     h = 0;
      Point<dim>                 origin;
      int                        margin = 0;
      std::array<int, dim>       extent{};
      std::array<long long, dim> stride{};
      long long                  n_lattice = 0;

      // Body nodes known here (owned and ghost), by lattice key.
      const Discretization::NodeSet<dim>   *nodes = nullptr;
      std::unordered_map<int, unsigned int> body;

      // Unknown numbering.
      std::vector<types::global_dof_index> dof_start, sys_start;
      types::global_dof_index              n_sys = 0;
      IndexSet                             owned_sys;

      // Surface nodes: all of them on every process (their number grows
      // like the surface only), with a lookup by half-lattice position.
      bool                                 with_surface = false;
      std::vector<SurfaceNode>             owned_surface;
      std::vector<HalfPoint<dim>>          surface_position;
      std::vector<types::global_dof_index> surface_unknown;
      std::unordered_map<long long, std::vector<unsigned int>> surface_buckets;
      int                                                      bucket_size = 1;

      // Fictitious nodes owned here: lattice key and nearest body node.
      std::vector<std::pair<int, unsigned int>> owned_fictitious;
      unsigned int                              n_fictitious_global = 0;

      // Bond data.
      unsigned int                                 order       = 1;
      double                                       m_ratio     = 0;
      double                                       m0          = 0;
      bool                                         state_based = true;
      std::vector<Quadrature::WeightedOffset<dim>> neighbours;
      std::vector<std::array<int, dim>>            search_offsets;
      std::vector<long long>                       search_length2;
      long long                                    reach2 = 0;
      std::vector<double> omega_r, a_r, b2_r, g_r; // per neighbour offset
      std::unordered_map<int, signed char> status_cache;

      // The factors of the operator, K = A E + B X D E, kept by assemble()
      // for apply() (B, X, D only for state-based models).
      std::unique_ptr<Epetra_CrsMatrix> e_matrix, a_matrix, d_matrix, x_matrix,
        b_matrix;


      int
      key(const std::array<int, dim> &cell) const
      {
        long long k = 0;
        for (unsigned int d = 0; d < dim; ++d)
          k += (cell[d] + margin) * stride[d];
        return static_cast<int>(k);
      }

      std::array<int, dim>
      cell_of(const int k) const
      {
        std::array<int, dim> c;
        long long            rest = k;
        for (int d = dim - 1; d >= 0; --d)
          {
            c[d] = static_cast<int>(rest / stride[d]) - margin;
            rest = rest % stride[d];
          }
        return c;
      }

      static HalfPoint<dim>
      half_of_cell(const std::array<int, dim> &c)
      {
        HalfPoint<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = 2 * c[d] + 1;
        return p;
      }

      bool
      inside_lattice(const std::array<int, dim> &c) const
      {
        for (unsigned int d = 0; d < dim; ++d)
          if (c[d] < -margin || c[d] >= extent[d] + margin)
            return false;
        return true;
      }

      long long
      half_key(const HalfPoint<dim> &p) const
      {
        long long k = 0, s = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            k += (p[d] + 2 * margin + 2) * s;
            s *= 2 * (extent[d] + 2 * margin) + 5;
          }
        return k;
      }

      long long
      bucket_key(const HalfPoint<dim> &p) const
      {
        long long k = 0, s = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            const int b = (p[d] + 2 * margin + 2) / bucket_size; // non-negative
            k += b * s;
            s *= (2 * (extent[d] + 2 * margin) + 5) / bucket_size + 2;
          }
        return k;
      }

      Point<dim>
      location(const HalfPoint<dim> &p) const
      {
        Point<dim> x;
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = origin[d] + 0.5 * h * p[d];
        return x;
      }

      types::global_dof_index
      sys_of_dof(const types::global_dof_index dof,
                 const unsigned int            owner) const
      {
        return dof - dof_start[owner] + sys_start[owner];
      }

      /// Nearest body node of the lattice cell @p c within the fictitious
      /// layer's reach; ties go to the smallest key. Returns the body's
      /// NodeSet index, or invalid.
      unsigned int
      nearest_body(const std::array<int, dim> &c) const
      {
        long long    best_length = -1;
        int          best_key    = INT_MAX;
        unsigned int best        = numbers::invalid_unsigned_int;
        for (unsigned int s = 0; s < search_offsets.size(); ++s)
          {
            if (best_length >= 0 && search_length2[s] > best_length)
              break;
            std::array<int, dim> q;
            for (unsigned int d = 0; d < dim; ++d)
              q[d] = c[d] + search_offsets[s][d];
            if (!inside_lattice(q))
              continue;
            const int  k  = key(q);
            const auto it = body.find(k);
            if (it != body.end() && k < best_key)
              {
                best_length = search_length2[s];
                best_key    = k;
                best        = it->second;
              }
          }
        return best;
      }

      /// 1: body node, 2: fictitious node, 0: neither.
      signed char
      status(const std::array<int, dim> &c)
      {
        if (!inside_lattice(c))
          return 0;
        const int k = key(c);
        if (body.count(k))
          return 1;
        const auto it = status_cache.find(k);
        if (it != status_cache.end())
          return it->second;
        const signed char s =
          nearest_body(c) != numbers::invalid_unsigned_int ? 2 : 0;
        status_cache[k] = s;
        return s;
      }

      HalfPoint<dim>
      body_half(const unsigned int i) const
      {
        HalfPoint<dim> p;
        for (unsigned int d = 0; d < dim; ++d)
          p[d] = static_cast<int>(
            std::lround(2 * ((*nodes)[i].location[d] - origin[d]) / h));
        return p;
      }

      /// Nearest surface node of a half-lattice point (ties: smallest
      /// position key).
      unsigned int
      nearest_surface(const HalfPoint<dim> &p) const
      {
        unsigned int best        = numbers::invalid_unsigned_int;
        long long    best_length = LLONG_MAX, best_key = LLONG_MAX;
        for_each_surface_near(p, [&](const unsigned int s) {
          const long long l = squared_distance<dim>(p, surface_position[s]);
          const long long k = half_key(surface_position[s]);
          if (l < best_length || (l == best_length && k < best_key))
            {
              best_length = l;
              best_key    = k;
              best        = s;
            }
        });
        return best;
      }

      template <typename F>
      void
      for_each_surface_near(const HalfPoint<dim> &p, const F &f) const
      {
        std::array<int, dim> b0;
        for (unsigned int d = 0; d < dim; ++d)
          b0[d] = (p[d] + 2 * margin + 2) / bucket_size;
        const unsigned int n_neighbours = (dim == 2 ? 9 : 27);
        for (unsigned int n = 0; n < n_neighbours; ++n)
          {
            HalfPoint<dim> q;
            unsigned int   rest = n;
            bool           ok   = true;
            for (unsigned int d = 0; d < dim; ++d)
              {
                const int b = b0[d] + static_cast<int>(rest % 3) - 1;
                rest /= 3;
                ok   = ok && b >= 0;
                q[d] = b * bucket_size - 2 * margin - 2;
              }
            if (!ok)
              continue;
            const auto it = surface_buckets.find(bucket_key(q));
            if (it != surface_buckets.end())
              for (const unsigned int s : it->second)
                f(s);
          }
      }

      /// A stencil point: its position and the unknowns (or lattice keys)
      /// of its value.
      struct StencilPoint
      {
        long long               length2;
        int                     type; // 0 surface, 1 body
        long long               order_key;
        HalfPoint<dim>          position;
        types::global_dof_index index;
      };

      /**
       * The Taylor weights for @p target about the stencil point first in
       * @p candidates (sorted by distance to it): whole distance shells are
       * added until all derivatives up to @p taylor_order are determined.
       */
      std::vector<std::pair<types::global_dof_index, double>>
      extrapolate(std::vector<StencilPoint> &candidates,
                  const HalfPoint<dim>      &target,
                  const unsigned int         taylor_order) const
      {
        std::sort(candidates.begin(),
                  candidates.end(),
                  [](const StencilPoint &a, const StencilPoint &b) {
                    return std::tie(a.length2, a.type, a.order_key) <
                           std::tie(b.length2, b.type, b.order_key);
                  });
        std::vector<Tensor<1, dim>> points;
        const auto                  scaled = [](const HalfPoint<dim> &p) {
          Tensor<1, dim> x;
          for (unsigned int d = 0; d < dim; ++d)
            x[d] = 0.5 * p[d];
          return x;
        };
        const Tensor<1, dim> t = scaled(target);
        std::vector<double>  w;
        const unsigned int needed = Discretization::n_taylor_terms(dim, taylor_order);
        std::size_t        end    = 0;
        while (end < candidates.size())
          {
            const long long shell = candidates[end].length2;
            while (end < candidates.size() && candidates[end].length2 == shell)
              points.push_back(scaled(candidates[end++].position));
            if (points.size() < needed)
              continue;
            w = Discretization::taylor_extrapolation_weights<dim>(points,
                                                            t,
                                                            taylor_order);
            if (!w.empty())
              break;
          }
        AssertThrow(!w.empty(),
                    ExcMessage("The Taylor extrapolation of order " +
                               std::to_string(taylor_order) +
                               " found no stencil that determines all "
                               "derivatives near " +
                               Utilities::to_string(location(target)[0]) +
                               ", ...: the body is too thin for this order. "
                               "Fix: lower the Taylor order or refine the "
                               "mesh."));
        std::vector<std::pair<types::global_dof_index, double>> result;
        for (std::size_t q = 0; q < w.size(); ++q)
          if (w[q] != 0.)
            result.emplace_back(candidates[q].index, w[q]);
        return result;
      }

      /// Body nodes within @p radius2 (half units squared) of @p centre.
      void
      add_body_candidates(const HalfPoint<dim>      &centre,
                          const long long            radius2,
                          const bool                 as_unknowns,
                          std::vector<StencilPoint> &out) const
      {
        // Lattice cells around the centre.
        const int r = static_cast<int>(std::ceil(std::sqrt(radius2) / 2)) + 1;
        std::array<int, dim> c0;
        for (unsigned int d = 0; d < dim; ++d)
          c0[d] = static_cast<int>(std::floor(0.5 * (centre[d] - 1)));
        std::array<int, dim> o;
        const auto visit = [&](const auto &self, const unsigned int d) -> void {
          if (d == dim)
            {
              std::array<int, dim> c;
              for (unsigned int e = 0; e < dim; ++e)
                c[e] = c0[e] + o[e];
              if (!inside_lattice(c))
                return;
              const int  k  = key(c);
              const auto it = body.find(k);
              if (it == body.end())
                return;
              const HalfPoint<dim> p = half_of_cell(c);
              const long long      l = squared_distance<dim>(p, centre);
              if (l > radius2)
                return;
              const auto &node = (*nodes)[it->second];
              out.push_back({l,
                             1,
                             k,
                             p,
                             as_unknowns ?
                               sys_of_dof(node.dofs[0], node.owner) :
                               static_cast<types::global_dof_index>(k)});
              return;
            }
          for (o[d] = -r; o[d] <= r; ++o[d])
            self(self, d + 1);
        };
        visit(visit, 0);
      }
    };


    template <int dim>
    FictitiousLayerOperator<dim>::FictitiousLayerOperator()
      : impl(std::make_unique<Impl>())
    {}


    template <int dim>
    FictitiousLayerOperator<dim>::~FictitiousLayerOperator() = default;


    template <int dim>
    void
    FictitiousLayerOperator<dim>::reinit(
      const DoFHandler<dim>                &dof_handler,
      const Discretization::NodeSet<dim>   &nodes,
      const Models::Model<dim>             &model,
      const double                          horizon,
      const Quadrature::PartialVolume<dim> &algorithm,
      const bool                            with_surface_nodes,
      const unsigned int                    taylor_order)
    {
      impl                       = std::make_unique<Impl>();
      Impl &s                    = *impl;
      s.comm                     = nodes.get_communicator();
      s.nodes                    = &nodes;
      s.order                    = taylor_order;
      s.with_surface             = with_surface_nodes;
      s.state_based              = model.is_state_based();
      const MPI_Comm     comm    = s.comm;
      const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
      const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);

      // A uniform grid of cubes on one lattice.
      double     h_min = std::numeric_limits<double>::max(), h_max = 0;
      Point<dim> lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = std::numeric_limits<double>::max();
          upper[d] = -std::numeric_limits<double>::max();
        }
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          const auto &box = nodes[i].cell;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double side = box.get_boundary_points().second[d] -
                                  box.get_boundary_points().first[d];
              h_min    = std::min(h_min, side);
              h_max    = std::max(h_max, side);
              lower[d] = std::min(lower[d], box.get_boundary_points().first[d]);
              upper[d] =
                std::max(upper[d], box.get_boundary_points().second[d]);
            }
        }
      h_min = Utilities::MPI::min(h_min, comm);
      h_max = Utilities::MPI::max(h_max, comm);
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] = Utilities::MPI::min(lower[d], comm);
          upper[d] = Utilities::MPI::max(upper[d], comm);
        }
      // Uniformity is decided in one place (Discretization::Lattice,
      // collectively, with its tolerances); the sides are only for the
      // message.
      Discretization::Lattice<dim> lattice;
      lattice.reinit(nodes);
      AssertThrow(lattice.is_uniform(),
                  ExcMessage(
                    "The fictitious layer and the surface nodes need a "
                    "uniform grid of equal cubes (squares in 2D) on one "
                    "lattice, but the cell sides range from " +
                    Utilities::to_string(h_min) + " to " +
                    Utilities::to_string(h_max) +
                    " (or a cell corner is off the lattice). Fix: choose "
                    "Subdivisions that give equal sides, no local "
                    "refinement, or a mesh file of equal, aligned cubes; or "
                    "set 'Boundary treatment/Treatment = none'."));
      s.h            = lattice.spacing();
      s.origin       = lower;
      const double h = s.h;

      const double                              m_ratio = horizon / h;
      const Quadrature::UniformGridWeights<dim> table(algorithm, m_ratio);
      s.m_ratio       = m_ratio;
      s.neighbours    = table.neighbours();
      s.margin        = table.max_offset() + 6;
      long long total = 1;
      for (unsigned int d = 0; d < dim; ++d)
        {
          s.extent[d] =
            static_cast<int>(std::lround((upper[d] - lower[d]) / h));
          s.stride[d] = total;
          total *= s.extent[d] + 2 * s.margin;
        }
      s.n_lattice = total;
      AssertThrow(dim * total < INT_MAX,
                  ExcMessage("The lattice around the body is too large for "
                             "32-bit Trilinos indices."));

      // Body nodes by lattice key.
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          for (unsigned int c = 1; c < dim; ++c)
            AssertThrow(nodes[i].dofs[c] == nodes[i].dofs[0] + c,
                        ExcInternalError());
          const HalfPoint<dim> p = s.body_half(i);
          std::array<int, dim> c;
          for (unsigned int d = 0; d < dim; ++d)
            c[d] = (p[d] - 1) / 2;
          if (s.inside_lattice(c))
            s.body[s.key(c)] = i;
        }

      // Offsets for the nearest-body search, up to the layer's reach
      // delta + h sqrt(d)/2, sorted by length.
      {
        const double reach = m_ratio + 0.5 * std::sqrt(double(dim));
        const int    r     = static_cast<int>(std::ceil(reach));
        // squared lengths in cell units; compare with a small tolerance
        const double         bound = reach * reach * (1 + 1e-12);
        std::array<int, dim> o;
        std::vector<std::pair<long long, std::array<int, dim>>> list;
        const auto visit = [&](const auto &self, const unsigned int d) -> void {
          if (d == dim)
            {
              long long l = 0;
              for (unsigned int e = 0; e < dim; ++e)
                l += o[e] * o[e];
              if (l <= bound)
                list.emplace_back(l, o);
              return;
            }
          for (o[d] = -r; o[d] <= r; ++o[d])
            self(self, d + 1);
        };
        visit(visit, 0);
        std::sort(list.begin(), list.end());
        for (const auto &e : list)
          {
            s.search_length2.push_back(e.first);
            s.search_offsets.push_back(e.second);
          }
      }

      // Bond constants; every node has the bulk weighted volume.
      const double volume = std::pow(h, dim);
      s.m0                = 0;
      for (const auto &n : s.neighbours)
        {
          double r2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            r2 += n.offset[d] * n.offset[d];
          const double r = std::sqrt(r2) * h;
          s.m0 += model.influence(r, horizon) * r * r * n.beta * volume;
        }
      for (const auto &n : s.neighbours)
        {
          double r2 = 0;
          for (unsigned int d = 0; d < dim; ++d)
            r2 += n.offset[d] * n.offset[d];
          const double r = std::sqrt(r2) * h;
          // Every node has the bulk weighted volume, so the same node
          // factor: the bond's stiffness from the kernel.
          const double s_0 = model.node_factor(s.m0);
          s.omega_r.push_back(model.influence(r, horizon));
          s.a_r.push_back(s.state_based ?
                            BondKernel::dilatation_stiffness(
                              model.dilatation_constant(r, horizon), s_0) :
                            0.);
          s.b2_r.push_back(BondKernel::extension_stiffness(
            model.extension_constant(r, horizon), s_0, s_0));
          s.g_r.push_back(s.state_based ?
                            dim / s.m0 * model.influence(r, horizon) * r *
                              n.beta * volume :
                            0.);
        }

      // Owned surface nodes: external faces of owned cells.
      if (with_surface_nodes)
        {
          std::vector<std::pair<HalfPoint<dim>, SurfaceNode>> local;
          for (const auto &cell : dof_handler.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const unsigned int f : cell->face_indices())
                if (cell->face(f)->at_boundary())
                  {
                    const Point<dim>     centre = cell->face(f)->center();
                    const Tensor<1, dim> out    = centre - cell->center();
                    unsigned int         axis   = 0;
                    for (unsigned int d = 1; d < dim; ++d)
                      if (std::abs(out[d]) > std::abs(out[axis]))
                        axis = d;
                    SurfaceNode node;
                    node.location    = centre;
                    node.axis        = axis;
                    node.side        = out[axis] > 0 ? 1 : -1;
                    node.boundary_id = cell->face(f)->boundary_id();
                    node.area        = std::pow(h, dim - 1);
                    HalfPoint<dim> p;
                    for (unsigned int d = 0; d < dim; ++d)
                      p[d] = static_cast<int>(
                        std::lround(2 * (centre[d] - lower[d]) / h));
                    local.emplace_back(p, node);
                  }
          std::sort(local.begin(),
                    local.end(),
                    [](const auto &a, const auto &b) {
                      return a.first < b.first;
                    });
          for (const auto &e : local)
            s.owned_surface.push_back(e.second);
        }

      // Unknown numbering: owned body DoFs, then owned surface unknowns.
      const IndexSet &owned_dofs = dof_handler.locally_owned_dofs();
      AssertThrow(owned_dofs.is_contiguous(), ExcInternalError());
      const types::global_dof_index first_dof =
        owned_dofs.n_elements() > 0 ? *owned_dofs.begin() : 0;
      const types::global_dof_index n_local_sys =
        owned_dofs.n_elements() + dim * s.owned_surface.size();
      s.dof_start            = Utilities::MPI::all_gather(comm, first_dof);
      const auto n_local_all = Utilities::MPI::all_gather(comm, n_local_sys);
      s.sys_start.assign(n_ranks + 1, 0);
      for (unsigned int r = 0; r < n_ranks; ++r)
        s.sys_start[r + 1] = s.sys_start[r] + n_local_all[r];
      s.n_sys     = s.sys_start[n_ranks];
      s.owned_sys = IndexSet(s.n_sys);
      s.owned_sys.add_range(s.sys_start[rank], s.sys_start[rank + 1]);
      s.owned_sys.compress();
      for (unsigned int k = 0; k < s.owned_surface.size(); ++k)
        s.owned_surface[k].first_unknown =
          s.sys_start[rank] + owned_dofs.n_elements() + dim * k;

      // All surface nodes everywhere, for the extrapolation stencils.
      if (with_surface_nodes)
        {
          // Flattened: dim half-lattice coordinates and the first unknown.
          std::vector<long long> mine;
          for (const auto &node : s.owned_surface)
            {
              for (unsigned int d = 0; d < dim; ++d)
                mine.push_back(
                  std::llround(2 * (node.location[d] - lower[d]) / h));
              mine.push_back(node.first_unknown);
            }
          const auto all = Utilities::MPI::all_gather(comm, mine);
          s.bucket_size =
            2 * static_cast<int>(std::ceil(
                  std::max<double>(m_ratio + 1.5 * std::sqrt(double(dim)) + 1,
                                   taylor_order + 3)));
          for (const auto &part : all)
            for (std::size_t e = 0; e < part.size(); e += dim + 1)
              {
                HalfPoint<dim> p;
                for (unsigned int d = 0; d < dim; ++d)
                  p[d] = static_cast<int>(part[e + d]);
                const unsigned int index = s.surface_position.size();
                s.surface_position.push_back(p);
                s.surface_unknown.push_back(part[e + dim]);
                s.surface_buckets[s.bucket_key(p)].push_back(index);
              }
        }

      // Owned fictitious nodes: those whose nearest body node is owned.
      {
        std::unordered_map<int, bool> seen;
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            const HalfPoint<dim> p = s.body_half(i);
            std::array<int, dim> ci;
            for (unsigned int d = 0; d < dim; ++d)
              ci[d] = (p[d] - 1) / 2;
            for (const auto &o : s.search_offsets)
              {
                std::array<int, dim> c;
                for (unsigned int d = 0; d < dim; ++d)
                  c[d] = ci[d] + o[d];
                const int k = s.key(c);
                if (s.body.count(k) || seen.count(k))
                  continue;
                seen[k]              = true;
                const unsigned int b = s.nearest_body(c);
                s.status_cache[k] =
                  (b != numbers::invalid_unsigned_int) ? 2 : 0;
                if (b != numbers::invalid_unsigned_int && b < nodes.n_owned())
                  s.owned_fictitious.emplace_back(k, b);
              }
          }
        std::sort(s.owned_fictitious.begin(), s.owned_fictitious.end());
        s.n_fictitious_global =
          Utilities::MPI::sum(static_cast<unsigned int>(
                                s.owned_fictitious.size()),
                              comm);
      }
    }


    template <int dim>
    const IndexSet &
    FictitiousLayerOperator<dim>::owned_unknowns() const
    {
      return impl->owned_sys;
    }


    template <int dim>
    types::global_dof_index
    FictitiousLayerOperator<dim>::unknown_index(
      const Discretization::Node<dim> &node,
      const unsigned int               c) const
    {
      return impl->sys_of_dof(node.dofs[c], node.owner);
    }


    template <int dim>
    const std::vector<typename FictitiousLayerOperator<dim>::SurfaceNode> &
    FictitiousLayerOperator<dim>::owned_surface_nodes() const
    {
      return impl->owned_surface;
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_surface_nodes() const
    {
      return Utilities::MPI::sum(static_cast<unsigned int>(
                                   impl->owned_surface.size()),
                                 impl->comm);
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_fictitious_nodes() const
    {
      return impl->n_fictitious_global;
    }


    template <int dim>
    unsigned int
    FictitiousLayerOperator<dim>::n_neighbours_per_node() const
    {
      return impl->neighbours.size();
    }


    template <int dim>
    double
    FictitiousLayerOperator<dim>::bulk_weighted_volume() const
    {
      return impl->m0;
    }


    template <int dim>
    void
    FictitiousLayerOperator<dim>::build_factors() const
    {
      Impl              &s       = *impl;
      const auto        &nodes   = *s.nodes;
      const MPI_Comm     comm    = s.comm;
      const double       h       = s.h;
      const double       V       = std::pow(h, dim);
      const unsigned int n_owned = nodes.n_owned();
      using Cell                 = std::array<int, dim>;

      const auto cell_of_body = [&](const unsigned int i) {
        const HalfPoint<dim> p = s.body_half(i);
        Cell                 c;
        for (unsigned int d = 0; d < dim; ++d)
          c[d] = (p[d] - 1) / 2;
        return c;
      };

      // Index spaces of the product: lattice DoFs dim*key+c, lattice
      // scalars key; body keys owned here, and fictitious keys owned here.
      std::vector<int> owned_body_keys, owned_ext_keys;
      for (unsigned int i = 0; i < n_owned; ++i)
        owned_body_keys.push_back(s.key(cell_of_body(i)));
      std::sort(owned_body_keys.begin(), owned_body_keys.end());
      owned_ext_keys = owned_body_keys;
      for (const auto &f : s.owned_fictitious)
        owned_ext_keys.push_back(f.first);
      std::sort(owned_ext_keys.begin(), owned_ext_keys.end());

      const auto make_set = [](const std::vector<int> &keys,
                               const long long         size,
                               const unsigned int      block) {
        IndexSet                             set(size * block);
        std::vector<types::global_dof_index> list;
        for (const int k : keys)
          for (unsigned int c = 0; c < block; ++c)
            list.push_back(static_cast<types::global_dof_index>(k) * block + c);
        set.add_indices(list.begin(), list.end());
        set.compress();
        return set;
      };
      const IndexSet ext_dofs    = make_set(owned_ext_keys, s.n_lattice, dim);
      const IndexSet ext_scalar  = make_set(owned_ext_keys, s.n_lattice, 1);
      const IndexSet body_scalar = make_set(owned_body_keys, s.n_lattice, 1);

      // E: lattice displacements from the unknowns.
      Entries e_rows;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          const int k = s.key(cell_of_body(i));
          for (unsigned int c = 0; c < dim; ++c)
            e_rows.add(dim * k + c,
                       s.sys_of_dof(nodes[i].dofs[c], nodes[i].owner),
                       1.);
        }
      // X: lattice dilatations from body dilatations.
      Entries x_rows;
      for (const int k : owned_body_keys)
        x_rows.add(k, k, 1.);

      const long long stencil_radius2 =
        4LL * (s.order + 2) * (s.order + 2); // (order+2) h, in half units
      for (const auto &f : s.owned_fictitious)
        {
          const Cell           cf = s.cell_of(f.first);
          const HalfPoint<dim> pf = Impl::half_of_cell(cf);
          const HalfPoint<dim> pb = s.body_half(f.second);

          // Displacement: about the nearest surface node (surface and body
          // nodes in the stencil), or about the nearest body node.
          std::vector<typename Impl::StencilPoint> candidates;
          if (s.with_surface)
            {
              const unsigned int base = s.nearest_surface(pf);
              AssertThrow(base != numbers::invalid_unsigned_int,
                          ExcInternalError());
              const HalfPoint<dim> ps = s.surface_position[base];
              s.for_each_surface_near(ps, [&](const unsigned int q) {
                const long long l =
                  squared_distance<dim>(s.surface_position[q], ps);
                if (l <= stencil_radius2)
                  candidates.push_back({l,
                                        0,
                                        s.half_key(s.surface_position[q]),
                                        s.surface_position[q],
                                        s.surface_unknown[q]});
              });
              s.add_body_candidates(ps, stencil_radius2, true, candidates);
            }
          else
            s.add_body_candidates(pb, stencil_radius2, true, candidates);
          const auto u_weights = s.extrapolate(candidates, pf, s.order);
          for (const auto &w : u_weights)
            for (unsigned int c = 0; c < dim; ++c)
              e_rows.add(dim * f.first + c, w.first + c, w.second);

          if (s.state_based)
            {
              candidates.clear();
              s.add_body_candidates(pb, stencil_radius2, false, candidates);
              const auto t_weights = s.extrapolate(candidates, pf, s.order - 1);
              for (const auto &w : t_weights)
                x_rows.add(f.first, w.first, w.second);
            }
        }

      // D (body dilatations), A and B (bond forces) for owned body nodes.
      Entries d_rows, a_rows, b_rows;
      for (unsigned int i = 0; i < n_owned; ++i)
        {
          const Cell                               ci = cell_of_body(i);
          const int                                ki = s.key(ci);
          std::array<types::global_dof_index, dim> row;
          for (unsigned int c = 0; c < dim; ++c)
            row[c] = s.sys_of_dof(nodes[i].dofs[c], nodes[i].owner);
          // The node's own columns collect a term from every bond: summed
          // here and added once.
          Tensor<2, dim> self_a;
          Tensor<1, dim> self_b, self_d;
          for (unsigned int q = 0; q < s.neighbours.size(); ++q)
            {
              const auto &nb = s.neighbours[q];
              Cell        cj;
              double      r = 0;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  cj[d] = ci[d] + nb.offset[d];
                  r += nb.offset[d] * nb.offset[d];
                }
              r = std::sqrt(r);
              Tensor<1, dim> n;
              for (unsigned int d = 0; d < dim; ++d)
                n[d] = nb.offset[d] / r;
              const int kj = s.key(cj);
              // -F_i = -V_i sum_j [a (theta_i + theta_j) + b2 e_ij] w_ij n
              const double w = nb.beta * V * V;
              for (unsigned int c = 0; c < dim; ++c)
                {
                  for (unsigned int c2 = 0; c2 < dim; ++c2)
                    {
                      const double v = s.b2_r[q] * w * n[c] * n[c2];
                      a_rows.add(row[c], dim * kj + c2, -v);
                      self_a[c][c2] += v;
                    }
                  if (s.state_based)
                    {
                      b_rows.add(row[c], kj, -s.a_r[q] * w * n[c]);
                      self_b[c] -= s.a_r[q] * w * n[c];
                    }
                }
              if (s.state_based)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    d_rows.add(ki, dim * kj + c, s.g_r[q] * n[c]);
                    self_d[c] -= s.g_r[q] * n[c];
                  }
            }
          for (unsigned int c = 0; c < dim; ++c)
            {
              for (unsigned int c2 = 0; c2 < dim; ++c2)
                a_rows.add(row[c], dim * ki + c2, self_a[c][c2]);
              if (s.state_based)
                {
                  b_rows.add(row[c], ki, self_b[c]);
                  d_rows.add(ki, dim * ki + c, self_d[c]);
                }
            }
        }

      // Force flux of every owned surface node (paper Eq. 36).
      if (s.with_surface)
        {
          const int reach =
            static_cast<int>(std::ceil(s.m_ratio + std::sqrt(double(dim)))) + 1;
          for (const auto &node : s.owned_surface)
            {
              HalfPoint<dim> ps;
              for (unsigned int d = 0; d < dim; ++d)
                ps[d] = static_cast<int>(
                  std::lround(2 * (node.location[d] - s.origin[d]) / h));
              const unsigned int a    = node.axis;
              const int          side = node.side;
              const int          F    = ps[a];
              // The cell behind the face.
              Cell c0;
              for (unsigned int d = 0; d < dim; ++d)
                c0[d] = (d == a) ? (F - side - 1) / 2 : (ps[d] - 1) / 2;

              Cell       o;
              const auto visit = [&](const auto        &self,
                                     const unsigned int d) -> void {
                if (d < dim)
                  {
                    for (o[d] = -reach; o[d] <= reach; ++o[d])
                      self(self, d + 1);
                    return;
                  }
                Cell cj;
                for (unsigned int e = 0; e < dim; ++e)
                  cj[e] = c0[e] + o[e];
                const HalfPoint<dim> pj = Impl::half_of_cell(cj);
                if (side * (pj[a] - F) >= 0)
                  return; // not on the inner side
                if (s.status(cj) == 0)
                  return;
                const int kj = s.key(cj);
                for (unsigned int q = 0; q < s.neighbours.size(); ++q)
                  {
                    const auto &nb = s.neighbours[q];
                    if (side * nb.offset[a] <= 0)
                      continue;
                    const int pk_a = pj[a] + 2 * nb.offset[a];
                    if (side * (pk_a - F) <= 0)
                      continue; // does not cross the plane
                    // Crossing point, tangential coordinates times |D|.
                    const long long D     = 2LL * nb.offset[a];
                    const long long Dabs  = D > 0 ? D : -D;
                    double          alpha = 1;
                    bool            hit   = true;
                    for (unsigned int t = 0; t < dim && hit; ++t)
                      if (t != a)
                        {
                          long long x = static_cast<long long>(pj[t]) * D +
                                        static_cast<long long>(F - pj[a]) *
                                          (2LL * nb.offset[t]);
                          if (D < 0)
                            x = -x;
                          const long long lo = (ps[t] - 1LL) * Dabs;
                          const long long hi = (ps[t] + 1LL) * Dabs;
                          if (x < lo || x > hi)
                            hit = false;
                          else if (x == lo || x == hi)
                            alpha *= 0.5;
                        }
                    if (!hit)
                      continue;
                    Cell ck;
                    for (unsigned int e = 0; e < dim; ++e)
                      ck[e] = cj[e] + nb.offset[e];
                    if (s.status(ck) == 0)
                      continue;
                    const int kk = s.key(ck);
                    double    r  = 0;
                    for (unsigned int e = 0; e < dim; ++e)
                      r += nb.offset[e] * nb.offset[e];
                    r = std::sqrt(r);
                    Tensor<1, dim> n;
                    for (unsigned int e = 0; e < dim; ++e)
                      n[e] = nb.offset[e] / r;
                    const double w = alpha * nb.beta * V * V;
                    for (unsigned int c = 0; c < dim; ++c)
                      {
                        const auto row = node.first_unknown + c;
                        for (unsigned int c2 = 0; c2 < dim; ++c2)
                          {
                            const double v = s.b2_r[q] * w * n[c] * n[c2];
                            a_rows.add(row, dim * kk + c2, v);
                            a_rows.add(row, dim * kj + c2, -v);
                          }
                        if (s.state_based)
                          {
                            b_rows.add(row, kj, s.a_r[q] * w * n[c]);
                            b_rows.add(row, kk, s.a_r[q] * w * n[c]);
                          }
                      }
                  }
              };
              visit(visit, 0);
            }
        }

      s.e_matrix = make_matrix(std::move(e_rows), ext_dofs, s.owned_sys, comm);
      s.a_matrix = make_matrix(std::move(a_rows), s.owned_sys, ext_dofs, comm);
      if (s.state_based)
        {
          s.d_matrix =
            make_matrix(std::move(d_rows), body_scalar, ext_dofs, comm);
          s.x_matrix =
            make_matrix(std::move(x_rows), ext_scalar, body_scalar, comm);
          s.b_matrix =
            make_matrix(std::move(b_rows), s.owned_sys, ext_scalar, comm);
        }
    }


    template <int dim>
    void
    FictitiousLayerOperator<dim>::assemble(
      const std::map<types::global_dof_index, double> &prescribed,
      TrilinosWrappers::SparseMatrix                  &matrix,
      TrilinosWrappers::MPI::Vector                   &rhs) const
    {
      Impl          &s    = *impl;
      const MPI_Comm comm = s.comm;
      // The products.
      if (!s.e_matrix)
        build_factors();
      const auto product_extension = multiply(*s.a_matrix, *s.e_matrix);
      std::unique_ptr<Epetra_CrsMatrix> product_dilatation;
      if (s.state_based)
        {
          const auto de      = multiply(*s.d_matrix, *s.e_matrix);
          const auto xde     = multiply(*s.x_matrix, *de);
          product_dilatation = multiply(*s.b_matrix, *xde);
        }

      // Elimination of the prescribed unknowns.
      const Epetra_Map sys_map = s.owned_sys.make_trilinos_map(comm, false);
      Epetra_Vector    g(sys_map), kg(sys_map), tmp(sys_map);
      for (const auto &p : prescribed)
        g[sys_map.LID(static_cast<int>(p.first))] = p.second;
      product_extension->Multiply(false, g, kg);
      if (product_dilatation)
        {
          product_dilatation->Multiply(false, g, tmp);
          kg.Update(1., tmp, 1.);
        }

      // Which columns are prescribed: a ghosted flag vector.
      IndexSet relevant(s.n_sys);
      {
        std::vector<types::global_dof_index> cols;
        for (const Epetra_CrsMatrix *m :
             {product_extension.get(), product_dilatation.get()})
          if (m)
            for (int l = 0; l < m->ColMap().NumMyElements(); ++l)
              cols.push_back(m->ColMap().GID(l));
        std::sort(cols.begin(), cols.end());
        cols.erase(std::unique(cols.begin(), cols.end()), cols.end());
        relevant.add_indices(cols.begin(), cols.end());
        relevant.add_indices(s.owned_sys);
        relevant.compress();
      }
      TrilinosWrappers::MPI::Vector flags(s.owned_sys, comm),
        ghosted_flags(s.owned_sys, relevant, comm);
      for (const auto &p : prescribed)
        flags[p.first] = 1.;
      flags.compress(VectorOperation::insert);
      ghosted_flags = flags;
      // Read once: the loop below touches every nonzero.
      std::unordered_map<int, bool> column_prescribed;
      for (const auto k : relevant)
        if (ghosted_flags[k] != 0.)
          column_prescribed[static_cast<int>(k)] = true;

      Epetra_CrsMatrix      result(Copy, sys_map, 0);
      std::map<int, double> row;
      std::vector<int>      cols;
      std::vector<double>   vals;
      for (int l = 0; l < sys_map.NumMyElements(); ++l)
        {
          const int gid = sys_map.GID(l);
          row.clear();
          for (const Epetra_CrsMatrix *m :
               {product_extension.get(), product_dilatation.get()})
            if (m)
              {
                int     n;
                double *v;
                int    *idx;
                m->ExtractMyRowView(m->RowMap().LID(gid), n, v, idx);
                for (int e = 0; e < n; ++e)
                  row[m->ColMap().GID(idx[e])] += v[e];
              }
          cols.clear();
          vals.clear();
          const auto fixed = prescribed.find(gid);
          if (fixed != prescribed.end())
            {
              const double diagonal =
                row.count(gid) && row[gid] != 0. ? std::abs(row[gid]) : 1.;
              cols.push_back(gid);
              vals.push_back(diagonal);
              rhs(gid) = diagonal * fixed->second;
            }
          else
            {
              for (const auto &e : row)
                if (column_prescribed.count(e.first) == 0)
                  {
                    cols.push_back(e.first);
                    vals.push_back(e.second);
                  }
              const double load = rhs(gid);
              rhs(gid)          = load - kg[l];
            }
          result.InsertGlobalValues(gid, cols.size(), vals.data(), cols.data());
        }
      result.FillComplete(sys_map, sys_map);
      rhs.compress(VectorOperation::insert);
      matrix.reinit(result, true);
    }


    template <int dim>
    void
    FictitiousLayerOperator<dim>::apply(const TrilinosWrappers::MPI::Vector &u,
                                        TrilinosWrappers::MPI::Vector &ku) const
    {
      const Impl &s = *impl;
      AssertThrow(s.e_matrix && s.a_matrix,
                  ExcMessage("FictitiousLayerOperator::apply() needs the "
                             "factors: call build_factors() or assemble() "
                             "first."));
      const Epetra_MultiVector &x = u.trilinos_vector();
      Epetra_MultiVector       &y = ku.trilinos_vector();
      // Lattice displacements, then bond forces: y = A (E u).
      Epetra_Vector eu(s.e_matrix->RangeMap());
      AssertThrow(s.e_matrix->Multiply(false, x, eu) == 0, ExcInternalError());
      AssertThrow(s.a_matrix->Multiply(false, eu, y) == 0, ExcInternalError());
      if (s.b_matrix)
        {
          // Body dilatations, extrapolated to the lattice: + B (X (D (E u))).
          Epetra_Vector theta(s.d_matrix->RangeMap()),
            lattice_theta(s.x_matrix->RangeMap());
          Epetra_MultiVector by(y.Map(), 1);
          AssertThrow(s.d_matrix->Multiply(false, eu, theta) == 0,
                      ExcInternalError());
          AssertThrow(s.x_matrix->Multiply(false, theta, lattice_theta) == 0,
                      ExcInternalError());
          AssertThrow(s.b_matrix->Multiply(false, lattice_theta, by) == 0,
                      ExcInternalError());
          y.Update(1., by, 1.);
        }
    }


    template class FictitiousLayerOperator<2>;
    template class FictitiousLayerOperator<3>;
  } // namespace Operators
} // namespace PeriDEAL
