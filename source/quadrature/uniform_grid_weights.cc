#include <perideal/base/exceptions.h>
#include <perideal/quadrature/exact_partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace PeriDEAL
{
  namespace Quadrature
  {
    namespace
    {
      /// Call @p f for every wedge offset 0 <= o[0] <= ... <= o[dim-1] <= n.
      template <int dim, typename Function>
      void
      for_each_wedge_offset(const int n, const Function &f)
      {
        std::array<int, dim> o;
        if constexpr (dim == 1)
          {
            for (o[0] = 0; o[0] <= n; ++o[0])
              f(o);
          }
        else if constexpr (dim == 2)
          {
            for (o[1] = 0; o[1] <= n; ++o[1])
              for (o[0] = 0; o[0] <= o[1]; ++o[0])
                f(o);
          }
        else
          {
            for (o[2] = 0; o[2] <= n; ++o[2])
              for (o[1] = 0; o[1] <= o[2]; ++o[1])
                for (o[0] = 0; o[0] <= o[1]; ++o[0])
                  f(o);
          }
      }
    } // namespace


    template <int dim>
    UniformGridWeights<dim>::UniformGridWeights(
      const PartialVolume<dim> &algorithm,
      const double              m_ratio)
      : ratio(m_ratio)
    {
      AssertThrow(std::isfinite(m_ratio) && m_ratio > 0,
                  ExcInvalidInput("m-ratio",
                                  format_number(m_ratio),
                                  "the ratio of horizon to grid spacing "
                                  "must be a finite number > 0"));
      bound = static_cast<int>(std::ceil(m_ratio + 0.5));
      wedge_table.assign(std::pow(bound + 1, dim), 0.);
      std::vector<std::array<int, dim>> offsets;
      for_each_wedge_offset<dim>(bound, [&](const std::array<int, dim> &o) {
        if (o[dim - 1] != 0)
          offsets.push_back(o);
      });
      const std::vector<double> betas =
        algorithm.uniform_grid_weights(offsets, m_ratio);
      for (unsigned int i = 0; i < offsets.size(); ++i)
        {
          std::string offset;
          for (unsigned int d = 0; d < dim; ++d)
            offset += (d > 0 ? ", " : "") + std::to_string(offsets[i][d]);
          AssertThrow(std::isfinite(betas[i]),
                      ExcMessage("The partial-volume algorithm returned a "
                                 "non-finite coefficient for the offset (" +
                                 offset + ") at m-ratio " +
                                 format_number(m_ratio) +
                                 "; use the \"exact\" algorithm."));
          wedge_table[index(offsets[i])] = betas[i];
        }
    }


    template <int dim>
    double
    UniformGridWeights<dim>::m_ratio() const
    {
      return ratio;
    }


    template <int dim>
    int
    UniformGridWeights<dim>::max_offset() const
    {
      return bound;
    }


    template <int dim>
    unsigned int
    UniformGridWeights<dim>::index(
      const std::array<int, dim> &canonical_offset) const
    {
      unsigned int i = 0;
      for (int d = dim - 1; d >= 0; --d)
        i = i * (bound + 1) + canonical_offset[d];
      return i;
    }


    template <int dim>
    std::array<int, dim>
    UniformGridWeights<dim>::canonical(const std::array<int, dim> &offset)
    {
      std::array<int, dim> c;
      for (unsigned int d = 0; d < dim; ++d)
        c[d] = std::abs(offset[d]);
      std::sort(c.begin(), c.end());
      return c;
    }


    template <int dim>
    double
    UniformGridWeights<dim>::beta(const std::array<int, dim> &offset) const
    {
      const std::array<int, dim> c = canonical(offset);
      if (c[dim - 1] > bound)
        return 0;
      return wedge_table[index(c)];
    }


    template <int dim>
    std::vector<WeightedOffset<dim>>
    UniformGridWeights<dim>::wedge() const
    {
      std::vector<WeightedOffset<dim>> result;
      for_each_wedge_offset<dim>(bound, [&](const std::array<int, dim> &o) {
        const double b = wedge_table[index(o)];
        if (b > 0)
          result.push_back({o, b});
      });
      std::sort(result.begin(), result.end(), [](const auto &l, const auto &r) {
        return l.offset < r.offset;
      });
      return result;
    }


    template <int dim>
    std::vector<WeightedOffset<dim>>
    UniformGridWeights<dim>::neighbours() const
    {
      // Every signed permutation of every wedge offset; std::set removes the
      // duplicates that zero or equal components create, and sorts.
      std::set<std::array<int, dim>> offsets;
      for (const auto &entry : wedge())
        {
          std::array<int, dim> p = entry.offset;
          do
            for (unsigned int signs = 0; signs < (1u << dim); ++signs)
              {
                std::array<int, dim> o = p;
                for (unsigned int d = 0; d < dim; ++d)
                  if (signs & (1u << d))
                    o[d] = -o[d];
                offsets.insert(o);
              }
          while (std::next_permutation(p.begin(), p.end()));
        }

      std::vector<WeightedOffset<dim>> result;
      result.reserve(offsets.size());
      for (const auto &o : offsets)
        result.push_back({o, beta(o)});
      return result;
    }


    template <int dim>
    double
    UniformGridWeights<dim>::neighbourhood_measure() const
    {
      // The node's own cell counts fully where the ball contains it
      // (m >= sqrt(d)/2, the half diagonal); below that only its part inside
      // the ball, in closed form, so that the measure still compares with
      // the ball's volume.
      long double sum = 1;
      if (ratio < 0.5 * std::sqrt(double(dim)))
        {
          Point<dim> lower, upper;
          for (unsigned int d = 0; d < dim; ++d)
            {
              lower[d] = -0.5;
              upper[d] = 0.5;
            }
          sum =
            ExactPartialVolume<dim>().weight(Point<dim>(),
                                             ratio,
                                             BoundingBox<dim>(
                                               std::make_pair(lower, upper)));
        }
      for (const auto &entry : neighbours())
        sum += entry.beta;
      return static_cast<double>(sum);
    }


    template class UniformGridWeights<1>;
    template class UniformGridWeights<2>;
    template class UniformGridWeights<3>;
  } // namespace Quadrature
} // namespace PeriDEAL
