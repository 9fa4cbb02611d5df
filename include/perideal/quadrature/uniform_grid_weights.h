#ifndef perideal_quadrature_uniform_grid_weights_h
#define perideal_quadrature_uniform_grid_weights_h

#include <perideal/quadrature/partial_volume.h>

#include <array>
#include <vector>

namespace PeriDEAL
{
  namespace Quadrature
  {
    /**
     * One neighbour of a node on a uniform grid: its integer offset (in grid
     * spacings) and its quadrature coefficient \f$\beta\f$.
     */
    template <int dim>
    struct WeightedOffset
    {
      std::array<int, dim> offset;
      double               beta;
    };

    /**
     * The quadrature coefficients of all neighbours of a node on a uniform
     * grid of spacing h for a given m-ratio \f$\bar m = \delta / h\f$.
     *
     * On a uniform grid the coefficients depend on the offset only, and they
     * are invariant under the symmetries of the square (8) or the cube (48):
     * sign changes and permutations of the offset components. They are
     * therefore computed once, on the wedge
     * \f$0 \le x \le y\ [\le z]\f$, and looked up for every other offset
     * (Scabbia et al. 2022, Sect. 3.3).
     */
    template <int dim>
    class UniformGridWeights
    {
    public:
      /**
       * Compute the coefficients with @p algorithm for the m-ratio
       * @p m_ratio > 0.
       */
      UniformGridWeights(const PartialVolume<dim> &algorithm,
                         const double              m_ratio);

      /// The m-ratio the table was computed for.
      double
      m_ratio() const;

      /**
       * The largest offset component that can have a non-zero coefficient
       * with any algorithm: \f$\lceil \bar m + 1/2 \rceil\f$.
       */
      int
      max_offset() const;

      /**
       * The coefficient of the neighbour at @p offset (zero outside the
       * neighbourhood and for the origin itself).
       */
      double
      beta(const std::array<int, dim> &offset) const;

      /**
       * All offsets with \f$\beta > 0\f$ on the wedge
       * \f$0 \le x \le y\ [\le z]\f$, origin excluded, in lexicographic
       * order.
       */
      std::vector<WeightedOffset<dim>>
      wedge() const;

      /**
       * All offsets with \f$\beta > 0\f$ over the whole grid, origin
       * excluded, in lexicographic order.
       */
      std::vector<WeightedOffset<dim>>
      neighbours() const;

      /**
       * The numerical measure of the neighbourhood in units of the cell
       * measure, \f$1 + \sum_j \beta_j\f$ (the node's own cell counts fully;
       * Scabbia et al. 2022, Eq. 35) for \f$\bar m \ge \sqrt{d}/2\f$. For
       * smaller m-ratios the ball does not contain the node's own cell, and
       * that cell counts by its exact part inside the ball, so that the
       * measure compares with the ball's volume at every m-ratio.
       */
      double
      neighbourhood_measure() const;

      /**
       * The representative of @p offset on the wedge: absolute values,
       * sorted ascending.
       */
      static std::array<int, dim>
      canonical(const std::array<int, dim> &offset);

    private:
      double              ratio;
      int                 bound;
      std::vector<double> wedge_table; // dense over [0, bound]^dim

      unsigned int
      index(const std::array<int, dim> &canonical_offset) const;
    };
  } // namespace Quadrature
} // namespace PeriDEAL

#endif
