// The exact intersection measure must be invariant under the symmetries of
// the problem: the 48 signed permutations of the axes (8 in 2D) applied
// about the ball's centre, and translations; and it must scale with the
// cube (square) of a length scaling. Boxes are general: off-grid, non-cubic,
// of all sizes, near the sphere, straddling the centre's coordinate planes.
//
// The kernel itself reduces every box to a canonical form (it splits boxes
// at the centre's coordinate planes, reflects the pieces into the first
// orthant and sorts corner coordinates), so the kernel-against-itself part
// below checks that reduction, not an independent symmetry. Kind of test:
//  - consistency of the kernel under symmetries, translation and scaling
//    (random boxes, kernel against kernel);
//  - independent reference: every signed permutation of each general box of
//    tests/quadrature/reference/boxes_*.csv (sides >= R/100) against the
//    reference measure of the untransformed box, computed by 30-digit
//    adaptive quadrature with no closed form and checked there to be
//    invariant under axis permutations (generate_reference.py); tolerance
//    1e-14 of the box measure times the conditioning of the rounded,
//    centred inputs.

#include <perideal/quadrature/ball_box_intersection.h>

#include "reference_data.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

using namespace dealii;
using namespace PeriDEAL::Quadrature;

template <int dim>
BoundingBox<dim>
make_box(const Point<dim> &lower, const Point<dim> &upper)
{
  return BoundingBox<dim>(std::make_pair(lower, upper));
}

// Apply the signed permutation (perm, signs) to a box, about the origin:
// exact in floating point.
template <int dim>
BoundingBox<dim>
transformed_box(const BoundingBox<dim>              &box,
                const std::array<unsigned int, dim> &perm,
                const unsigned int                   signs)
{
  Point<dim> lower, upper;
  for (unsigned int d = 0; d < dim; ++d)
    {
      lower[d] = box.lower_bound(perm[d]);
      upper[d] = box.upper_bound(perm[d]);
      if (signs & (1u << d))
        {
          const double lo = -upper[d];
          upper[d]        = -lower[d];
          lower[d]        = lo;
        }
    }
  return make_box(lower, upper);
}

template <int dim>
void
check(const unsigned int n_cases)
{
  std::mt19937                           rng(2022 + dim);
  std::uniform_real_distribution<double> unit(0., 1.);

  double worst_symmetry_small = 0, worst_symmetry = 0, worst_translation = 0,
         worst_scaling   = 0;
  unsigned int n_nonzero = 0;
  for (unsigned int c = 0; c < n_cases; ++c)
    {
      const double R = std::pow(10., -1 + 2.7 * unit(rng)); // 0.1 .. 50
      Point<dim>   centre, lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        centre[d] = 2 * unit(rng) - 1;
      // A box of side 1e-3 R .. 2 R placed around a random point at distance
      // 0 .. 1.3 R from the centre, mostly near the sphere.
      const double side = R * std::pow(10., -3 + 3.3 * unit(rng));
      Point<dim>   direction;
      for (unsigned int d = 0; d < dim; ++d)
        direction[d] = 2 * unit(rng) - 1;
      direction /= direction.norm();
      const double distance =
        R * (c % 3 == 0 ? 1.3 * unit(rng) : 1 + 0.2 * (unit(rng) - 0.5));
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double mid   = centre[d] + distance * direction[d];
          const double width = side * (0.3 + unit(rng));
          lower[d]           = mid - width * unit(rng);
          upper[d]           = lower[d] + width;
        }
      const BoundingBox<dim> box = make_box(lower, upper);
      const double reference = ball_box_intersection_measure(centre, R, box);
      // Errors are measured relative to the box measure (beta is a
      // fraction). Translating or scaling rounds the inputs, a perturbation
      // of relative size eps * (coordinates) / (smallest side), which any
      // algorithm inherits: those checks are normalised by it.
      const double scale    = box.volume();
      double       min_side = upper[0] - lower[0];
      for (unsigned int d = 1; d < dim; ++d)
        min_side = std::min(min_side, upper[d] - lower[d]);
      const double conditioning =
        (min_side + centre.norm() + 2 * R + 10) / min_side;
      n_nonzero += (reference > 0);

      // Symmetries about the ball's centre: move the centre to the origin
      // once, so that the transformations themselves are exact.
      const BoundingBox<dim> centred =
        make_box(Point<dim>(lower - centre), Point<dim>(upper - centre));
      const double centred_reference =
        ball_box_intersection_measure(Point<dim>(), R, centred);
      double                        symmetry_error = 0;
      std::array<unsigned int, dim> perm;
      for (unsigned int d = 0; d < dim; ++d)
        perm[d] = d;
      do
        for (unsigned int signs = 0; signs < (1u << dim); ++signs)
          symmetry_error =
            std::max(symmetry_error,
                     std::abs(ball_box_intersection_measure(
                                Point<dim>(),
                                R,
                                transformed_box<dim>(centred, perm, signs)) -
                              centred_reference) /
                       scale);
      while (std::next_permutation(perm.begin(), perm.end()));
      // The corner decomposition loses accuracy relative to the box measure
      // like (R / side)^2 (doc/partial-volumes.md): boxes smaller than
      // R/10 are held to a looser bound.
      double &worst =
        min_side < 0.1 * R ? worst_symmetry_small : worst_symmetry;
      worst = std::max(worst, symmetry_error);

      Point<dim> shift;
      for (unsigned int d = 0; d < dim; ++d)
        shift[d] = 10 * (unit(rng) - 0.5);
      worst_translation =
        std::max(worst_translation,
                 std::abs(ball_box_intersection_measure(
                            centre + shift,
                            R,
                            make_box(lower + shift, upper + shift)) -
                          reference) /
                   (scale * conditioning));

      // Scaling by 3 (not a power of two, so that rounding differs).
      const double factor = 3;
      worst_scaling =
        std::max(worst_scaling,
                 std::abs(ball_box_intersection_measure(
                            centre * factor,
                            R * factor,
                            make_box(lower * factor, upper * factor)) /
                            std::pow(factor, dim) -
                          reference) /
                   (scale * conditioning));
    }

  std::cout << dim << "D: " << n_cases << " random boxes, "
            << (n_nonzero > n_cases / 2 ? "most" : "FEW")
            << " of them cutting the ball\n";
  std::cout
    << dim << "D: " << (dim == 2 ? 8 : 48)
    << " symmetries of the cube agree to <= 1e-15 of the box measure (boxes >= R/10): "
    << (worst_symmetry <= 1e-15 ? "yes" : "NO") << '\n';
  std::cout << dim << "D: the same for boxes down to R/1000, to <= 1e-12: "
            << (worst_symmetry_small <= 1e-12 ? "yes" : "NO") << '\n';
  std::cout
    << dim
    << "D: translations agree to <= 1e-14 of the box measure (relative to conditioning): "
    << (worst_translation <= 1e-14 ? "yes" : "NO") << '\n';
  std::cout
    << dim
    << "D: scaling by 3 agrees to <= 1e-14 of the box measure (relative to conditioning): "
    << (worst_scaling <= 1e-14 ? "yes" : "NO") << '\n';
}

// Every signed permutation of the reference boxes against the reference.
template <int dim>
void
check_against_reference(const std::string &name)
{
  double       worst   = 0;
  unsigned int n_boxes = 0;
  for (const auto &row : read_csv(name, 3 * dim + 2))
    {
      Point<dim> centre, lower, upper;
      for (unsigned int d = 0; d < dim; ++d)
        {
          centre[d] = row[d];
          lower[d]  = row[dim + 1 + 2 * d];
          upper[d]  = row[dim + 2 + 2 * d];
        }
      const double R        = row[dim];
      double       min_side = upper[0] - lower[0];
      for (unsigned int d = 1; d < dim; ++d)
        min_side = std::min(min_side, upper[d] - lower[d]);
      const BoundingBox<dim> box = make_box(lower, upper);
      if (box.volume() == 0 || min_side < R / 100)
        continue;
      ++n_boxes;
      // Centring rounds the inputs: a relative perturbation of the size of
      // eps * (coordinates) / (smallest side), inherited by any algorithm.
      const double conditioning =
        (min_side + centre.norm() + 2 * R + 10) / min_side;
      const BoundingBox<dim> centred =
        make_box(Point<dim>(lower - centre), Point<dim>(upper - centre));
      std::array<unsigned int, dim> perm;
      for (unsigned int d = 0; d < dim; ++d)
        perm[d] = d;
      do
        for (unsigned int signs = 0; signs < (1u << dim); ++signs)
          worst =
            std::max(worst,
                     std::abs(ball_box_intersection_measure(
                                Point<dim>(),
                                R,
                                transformed_box<dim>(centred, perm, signs)) -
                              row[3 * dim + 1]) /
                       (box.volume() * conditioning));
      while (std::next_permutation(perm.begin(), perm.end()));
    }
  std::cout << name << ": " << n_boxes << " reference boxes (sides >= R/100), "
            << "every signed permutation against the independent reference, "
            << "<= 1e-14 of the box measure (relative to conditioning): "
            << (n_boxes > 100 && worst <= 1e-14 ? "yes" : "NO") << '\n';
}

int
main()
{
  check<2>(2000);
  check<3>(1000);
  check_against_reference<2>("boxes_2d.csv");
  check_against_reference<3>("boxes_3d.csv");
}
