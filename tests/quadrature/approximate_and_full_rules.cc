// The "approximate" rule (Algorithm 1 of Scabbia et al. 2022: 1 if
// xi + h/2 <= delta, (delta - (xi - h/2))/h if xi - h/2 < delta, else 0) and
// the "full" rule (1 if the cell centre is in the closed ball, else 0) on
// hand-computed cases in 2D and 3D, including the exact boundaries of each
// branch, a non-cubic cell (h = measure^(1/dim)) and a scaled, shifted grid.

#include <perideal/quadrature/partial_volume.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

using namespace dealii;
using namespace PeriDEAL::Quadrature;

template <int dim>
std::string
to_string(const Point<dim> &p)
{
  std::string s = "(";
  for (unsigned int d = 0; d < dim; ++d)
    {
      std::ostringstream c;
      c << p[d];
      s += c.str() + (d + 1 < dim ? "," : ")");
    }
  return s;
}

// Cell of side h centred at node + h * offset, horizon delta.
template <int dim>
void
check(const std::string &rule,
      const Point<dim>  &offset,
      const double       delta,
      const double       expected,
      const std::string &why,
      const double       h    = 1,
      const Point<dim>  &node = Point<dim>())
{
  const auto       algorithm = PartialVolumeRegistry<dim>::create(rule);
  const Point<dim> centre    = node + h * offset;
  Point<dim>       half;
  for (unsigned int d = 0; d < dim; ++d)
    half[d] = h / 2;
  const BoundingBox<dim> cell(
    std::make_pair(Point<dim>(centre - half), Point<dim>(centre + half)));
  const double beta = algorithm->weight(node, delta, cell);
  // Branch boundaries must come out exactly; h != 1 rounds the inputs.
  const double tolerance = (h == 1 ? 1e-15 : 1e-12);
  std::cout << dim << "D " << std::setw(11) << rule << " offset "
            << to_string(offset) << ", delta/h=" << delta / h
            << ": beta = " << std::setprecision(12) << expected
            << std::setprecision(6) << " [" << why << "]: "
            << (std::abs(beta - expected) <= tolerance ? "ok" : "WRONG")
            << '\n';
  if (std::abs(beta - expected) > tolerance)
    std::cerr << "  got " << std::setprecision(17) << beta << '\n';
}

int
main()
{
  // 3D, delta = 3 (m = 3).
  check<3>("approximate", Point<3>(0, 0, 3), 3, 0.5, "xi=3: (3-2.5)/1");
  check<3>("full", Point<3>(0, 0, 3), 3, 1, "xi=3 <= 3, closed ball");
  check<3>("approximate", Point<3>(0, 0, 4), 3, 0, "xi-1/2=3.5 >= 3");
  check<3>("full", Point<3>(0, 0, 4), 3, 0, "xi=4 > 3");
  check<3>("approximate", Point<3>(1, 1, 2), 3, 1, "xi=sqrt6, xi+1/2=2.95<=3");
  check<3>("full", Point<3>(1, 1, 2), 3, 1, "xi=sqrt6 <= 3");
  check<3>("approximate", Point<3>(1, 2, 2), 3, 0.5, "xi=3: (3-2.5)/1");
  check<3>("approximate",
           Point<3>(2, 2, 2),
           3,
           3.5 - 2 * std::sqrt(3.),
           "xi=2sqrt3: 3.5-2sqrt3");
  check<3>("full", Point<3>(2, 2, 2), 3, 0, "xi=2sqrt3 > 3");
  check<3>("approximate", Point<3>(0, 0, 0), 3, 1, "own cell");

  // 3D branch boundaries.
  check<3>("approximate", Point<3>(0, 0, 2), 2.5, 1, "xi+1/2 = delta");
  check<3>("approximate", Point<3>(0, 0, 3), 2.5, 0, "xi-1/2 = delta");
  check<3>("approximate", Point<3>(0, 0, 2), 2.25, 0.75, "(2.25-1.5)/1");
  check<3>("full", Point<3>(0, 3, 4), 5, 1, "xi = delta = 5");
  check<3>("full", Point<3>(0, 3, 4), 5 - 1e-12, 0, "xi = delta + 1e-12");
  check<3>("approximate", Point<3>(0, 3, 4), 5.5, 1, "xi+1/2 = delta = 5.5");

  // 3D on a grid of spacing 0.1 around (1, 2, 3).
  check<3>("approximate",
           Point<3>(0, 0, 3),
           0.3,
           0.5,
           "scaled grid, xi=3h",
           0.1,
           Point<3>(1, 2, 3));
  check<3>("full",
           Point<3>(2, 2, 2),
           0.3,
           0,
           "scaled grid, xi=2sqrt3 h",
           0.1,
           Point<3>(1, 2, 3));

  // 2D, delta = 3.
  check<2>("approximate", Point<2>(0, 3), 3, 0.5, "xi=3: (3-2.5)/1");
  check<2>("full", Point<2>(0, 3), 3, 1, "xi=3 <= 3");
  check<2>("approximate", Point<2>(1, 2), 3, 1, "xi=sqrt5, xi+1/2<=3");
  check<2>("approximate",
           Point<2>(2, 2),
           3,
           3.5 - 2 * std::sqrt(2.),
           "xi=2sqrt2: 3.5-2sqrt2");
  check<2>("full", Point<2>(2, 2), 3, 1, "xi=2sqrt2 <= 3");
  check<2>("approximate", Point<2>(0, 4), 3, 0, "xi-1/2=3.5 >= 3");
  check<2>("full", Point<2>(0, 4), 3, 0, "xi=4 > 3");

  // 2D branch boundaries.
  check<2>("approximate", Point<2>(3, 4), 5.5, 1, "xi+1/2 = delta = 5.5");
  check<2>("approximate", Point<2>(3, 4), 5, 0.5, "xi=5: (5-4.5)/1");
  check<2>("approximate", Point<2>(3, 4), 4.5, 0, "xi-1/2 = delta = 4.5");
  check<2>("full", Point<2>(3, 4), 5, 1, "xi = delta = 5");
  check<2>("full", Point<2>(3, 4), 5 - 1e-12, 0, "xi = delta + 1e-12");

  // Non-cubic cells: h = measure^(1/dim).
  {
    const auto approximate2 = PartialVolumeRegistry<2>::create("approximate");
    const BoundingBox<2> rectangle(
      std::make_pair(Point<2>(1, -0.5), Point<2>(3, 0.5)));
    // xi = 2, h = sqrt2: (2.5 - (2 - sqrt2/2)) / sqrt2 = 1/2 + 1/(2 sqrt2).
    const double expected2 = 0.5 + 0.5 / std::sqrt(2.);
    std::cout << "2D approximate, 2 x 1 rectangle at xi=2, delta=2.5: beta = "
              << std::setprecision(12) << expected2 << std::setprecision(6)
              << " [h = sqrt2]: "
              << (std::abs(approximate2->weight(Point<2>(), 2.5, rectangle) -
                           expected2) <= 1e-15 ?
                    "ok" :
                    "WRONG")
              << '\n';

    const auto approximate3 = PartialVolumeRegistry<3>::create("approximate");
    const BoundingBox<3> slab(
      std::make_pair(Point<3>(-1, -1, 2.75), Point<3>(1, 1, 3.25)));
    // measure 2 x 2 x 0.5 = 2, h = 2^(1/3); xi = 3, delta = 3.
    const double h3        = std::cbrt(2.);
    const double expected3 = (3 - (3 - h3 / 2)) / h3;
    std::cout << "3D approximate, 2 x 2 x 0.5 slab at xi=3, delta=3: beta = "
              << expected3 << " [h = cbrt2]: "
              << (std::abs(approximate3->weight(Point<3>(), 3, slab) -
                           expected3) <= 1e-15 ?
                    "ok" :
                    "WRONG")
              << '\n';

    const auto full3 = PartialVolumeRegistry<3>::create("full");
    std::cout << "3D full, same slab: beta = 1 [centre at xi = delta]: "
              << (full3->weight(Point<3>(), 3, slab) == 1 ? "ok" : "WRONG")
              << '\n';
  }

  // The uniform-grid entry point is the unit cell at the offset.
  {
    const auto approximate = PartialVolumeRegistry<3>::create("approximate");
    const auto full        = PartialVolumeRegistry<3>::create("full");
    std::cout << "uniform_grid_weight((0,0,3), m=3): approximate "
              << approximate->uniform_grid_weight({{0, 0, 3}}, 3) << ", full "
              << full->uniform_grid_weight({{0, 0, 3}}, 3) << '\n';
  }
}
