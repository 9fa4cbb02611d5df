// The corner measures behind the exact kernel against closed forms that do
// not go through it: octant, quarter and half caps in 3D; quadrant and
// segments in 2D; for radii from 0.01 to 1000 and cut heights from the
// centre to 1e-9 R below the sphere. The references are evaluated without
// cancellation (the segment through a series for small angles).

#include <perideal/quadrature/ball_box_intersection.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL::Quadrature;

int
main()
{
  double worst_3d = 0, worst_2d = 0;
  for (const double R : {0.01, 0.7, 3.5, 50., 1000.})
    for (const double depth : {1., 0.5, 0.1, 1e-3, 1e-6, 1e-9})
      {
        // Cut at height c = R - h, h = depth R; R - c is exact in floating
        // point, so the closed forms use the h of the actual cut.
        const double c = R - depth * R, h = R - c;

        // 3D: V(0,0,c) is a quarter of the cap of height h,
        // pi h^2 (3R - h) / 12; V(0,0,0) the octant.
        const double cap = M_PI * h * h * (3 * R - h) / 12;
        // The closed form balances terms of size R^2 h against each other
        // for a result of size R h^2: relative rounding ~ u / depth, with
        // u = 5.4e-20 in extended precision.
        const double bound = 1e-15 + 5e-19 / depth;
        worst_3d =
          std::max(worst_3d,
                   std::abs(ball_corner_measure(Point<3>(0, 0, c), R) - cap) /
                     cap / bound);

        worst_3d = std::max(worst_3d,
                            std::abs(ball_corner_measure(Point<3>(), R) -
                                     M_PI * R * R * R / 6) /
                              (M_PI * R * R * R / 6) / 1e-15);

        // 2D: A(0, c) is half the circular segment of height h,
        // R^2 (t - sin t cos t) / 2 with cos t = c/R; t - sin t cos t is
        // evaluated as (2t - sin 2t)/2 through a series for small t.
        const double t = 2 * std::asin(std::sqrt(h / (2 * R))); // 1-cos t = h/R
        const double u = 2 * t;
        double       u3 = 0; // u - sin u without cancellation
        if (u < 0.1)
          {
            double term = u * u * u / 6;
            for (int k = 1; k < 12; ++k)
              {
                u3 += term;
                term *= -u * u / ((2 * k + 2) * (2 * k + 3));
              }
          }
        else
          u3 = u - std::sin(u);
        const double half_segment = R * R * u3 / 4;
        worst_2d                  = std::max(worst_2d,
                            std::abs(ball_corner_measure(Point<2>(0, c), R) -
                                     half_segment) /
                              half_segment / bound);
      }
  std::cout << "3D corner measures = octant (to 1e-15) and quarter caps "
               "(to 1e-15 + 5e-19/depth) relative: "
            << (worst_3d <= 1 ? "yes" : "NO") << '\n';
  std::cout << "2D corner measures = half segments to 1e-15 + 5e-19/depth "
               "relative: "
            << (worst_2d <= 1 ? "yes" : "NO") << '\n';
}
