#include <deal.II/base/utilities.h>

#include <perideal/discretization/taylor_extrapolation.h>
#include <perideal/operators/fictitious_layer/layer_data.h>

#include <algorithm>
#include <tuple>

namespace PeriDEAL
{
  namespace Operators
  {
    namespace FictitiousLayer
    {
      namespace
      {
        /// A stencil point: its position and the unknown (or lattice key)
        /// of its value.
        template <int dim>
        struct StencilPoint
        {
          long long               length2;
          int                     type; // 0 surface, 1 body
          long long               order_key;
          std::array<int, dim>    position;
          types::global_dof_index index;
        };


        /**
         * The Taylor weights for @p target about the stencil point first in
         * @p candidates (sorted by distance to it): whole distance shells
         * are added until all derivatives up to @p taylor_order are
         * determined.
         */
        template <int dim>
        std::vector<std::pair<types::global_dof_index, double>>
        extrapolate(const Discretization::ExtendedLattice<dim> &lattice,
                    std::vector<StencilPoint<dim>>             &candidates,
                    const std::array<int, dim>                 &target,
                    const unsigned int                          taylor_order)
        {
          std::sort(candidates.begin(),
                    candidates.end(),
                    [](const StencilPoint<dim> &a, const StencilPoint<dim> &b) {
                      return std::tie(a.length2, a.type, a.order_key) <
                             std::tie(b.length2, b.type, b.order_key);
                    });
          std::vector<Tensor<1, dim>> points;
          const auto scaled = [](const std::array<int, dim> &p) {
            Tensor<1, dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              x[d] = 0.5 * p[d];
            return x;
          };
          const Tensor<1, dim> t = scaled(target);
          std::vector<double>  w;
          const unsigned int   needed =
            Discretization::n_taylor_terms(dim, taylor_order);
          std::size_t end = 0;
          while (end < candidates.size())
            {
              const long long shell = candidates[end].length2;
              while (end < candidates.size() &&
                     candidates[end].length2 == shell)
                points.push_back(scaled(candidates[end++].position));
              if (points.size() < needed)
                continue;
              w =
                Discretization::taylor_extrapolation_weights<dim>(points,
                                                                  t,
                                                                  taylor_order);
              if (!w.empty())
                break;
            }
          AssertThrow(!w.empty(),
                      ExcMessage(
                        "The Taylor extrapolation of order " +
                        std::to_string(taylor_order) +
                        " found no stencil that determines all "
                        "derivatives near " +
                        Utilities::to_string(lattice.location(target)[0]) +
                        ", ...: the body is too thin for this "
                        "order. Fix: lower the Taylor order or "
                        "refine the mesh."));
          std::vector<std::pair<types::global_dof_index, double>> result;
          for (std::size_t q = 0; q < w.size(); ++q)
            if (w[q] != 0.)
              result.emplace_back(candidates[q].index, w[q]);
          return result;
        }


        /// Body nodes within @p radius2 (half units squared) of @p centre,
        /// indexed by their first unknown or, if not @p as_unknowns, by
        /// their lattice key.
        template <int dim>
        void
        add_body_candidates(const LayerData<dim>           &data,
                            const std::array<int, dim>     &centre,
                            const long long                 radius2,
                            const bool                      as_unknowns,
                            std::vector<StencilPoint<dim>> &out)
        {
          data.lattice.for_each_body_near(
            centre,
            radius2,
            [&](const long long             l,
                const int                   k,
                const std::array<int, dim> &p,
                const unsigned int          i) {
              const auto &node = (*data.nodes)[i];
              out.push_back({l,
                             1,
                             k,
                             p,
                             as_unknowns ?
                               data.sys_of_dof(node.dofs[0], node.owner) :
                               static_cast<types::global_dof_index>(k)});
            });
        }


        /// The surface nodes within @p radius2 of the nearest surface node
        /// of @p target, and the body nodes within @p radius2 of it.
        template <int dim>
        void
        add_surface_candidates(const LayerData<dim>           &data,
                               const std::array<int, dim>     &target,
                               const long long                 radius2,
                               std::vector<StencilPoint<dim>> &out)
        {
          const auto        &surface = *data.surface;
          const unsigned int base    = surface.nearest(target);
          AssertThrow(base != numbers::invalid_unsigned_int,
                      ExcInternalError());
          const std::array<int, dim> ps = surface.position(base);
          surface.for_each_near(ps, [&](const unsigned int q) {
            const long long l =
              Discretization::squared_distance<dim>(surface.position(q), ps);
            if (l <= radius2)
              out.push_back({l,
                             0,
                             data.lattice.half_key(surface.position(q)),
                             surface.position(q),
                             surface.first_unknown(q)});
          });
          add_body_candidates<dim>(data, ps, radius2, true, out);
        }
      } // namespace


      template <int dim>
      void
      add_extrapolation_rows(const LayerData<dim>   &data,
                             const std::vector<int> &owned_body_keys,
                             SparseEntries          &e_rows,
                             SparseEntries          &x_rows)
      {
        const auto &lattice = data.lattice;
        const auto &nodes   = *data.nodes;
        for (unsigned int i = 0; i < nodes.n_owned(); ++i)
          {
            const int k = lattice.key(lattice.cell_of_node(i));
            for (unsigned int c = 0; c < dim; ++c)
              e_rows.add(dim * k + c,
                         data.sys_of_dof(nodes[i].dofs[c], nodes[i].owner),
                         1.);
          }
        for (const int k : owned_body_keys)
          x_rows.add(k, k, 1.);

        const long long stencil_radius2 =
          4LL * (data.order + 2) *
          (data.order + 2); // (order+2) h, in half units
        std::vector<StencilPoint<dim>> candidates;
        for (const auto &f : lattice.owned_fictitious())
          {
            const auto pf = lattice.half_of_cell(lattice.cell_of(f.first));
            const auto pb = lattice.half_point(f.second);

            candidates.clear();
            if (data.surface)
              add_surface_candidates<dim>(data,
                                          pf,
                                          stencil_radius2,
                                          candidates);
            else
              add_body_candidates<dim>(data,
                                       pb,
                                       stencil_radius2,
                                       true,
                                       candidates);
            const auto u_weights =
              extrapolate<dim>(lattice, candidates, pf, data.order);
            for (const auto &w : u_weights)
              for (unsigned int c = 0; c < dim; ++c)
                e_rows.add(dim * f.first + c, w.first + c, w.second);

            if (data.state_based)
              {
                candidates.clear();
                add_body_candidates<dim>(data,
                                         pb,
                                         stencil_radius2,
                                         false,
                                         candidates);
                const auto t_weights =
                  extrapolate<dim>(lattice, candidates, pf, data.order - 1);
                for (const auto &w : t_weights)
                  x_rows.add(f.first, w.first, w.second);
              }
          }
      }


      template void
      add_extrapolation_rows<2>(const LayerData<2> &,
                                const std::vector<int> &,
                                SparseEntries &,
                                SparseEntries &);
      template void
      add_extrapolation_rows<3>(const LayerData<3> &,
                                const std::vector<int> &,
                                SparseEntries &,
                                SparseEntries &);
    } // namespace FictitiousLayer
  }   // namespace Operators
} // namespace PeriDEAL
