// Taylor extrapolation weights (Discretization::taylor_extrapolation_weights):
// exact for every monomial of degree <= N on stencils like those of the
// surface node method (a surface node, the body nodes behind it and the
// neighbouring surface nodes, in units of h), inexact for degree N + 1, and
// empty for stencils that do not determine all derivatives. The reference
// values are the monomials themselves.

#include <perideal/discretization/taylor_extrapolation.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

using namespace dealii;
using namespace PeriDEAL::Discretization;

template <int dim>
double
monomial(const std::array<int, dim> &e, const Tensor<1, dim> &x)
{
  double v = 1;
  for (unsigned int d = 0; d < dim; ++d)
    v *= std::pow(x[d], e[d]);
  return v;
}

// Points of a face-node stencil: the face centre at the origin (normal -x),
// cell centres at x = 0.5, 1.5, ... behind it and face centres around it.
template <int dim>
std::vector<Tensor<1, dim>>
stencil(const int layers)
{
  std::vector<Tensor<1, dim>> points;
  Tensor<1, dim>              origin;
  points.push_back(origin);
  const int r = 2;
  for (int i = -r; i <= r; ++i)
    for (int j = (dim == 3 ? -r : 0); j <= (dim == 3 ? r : 0); ++j)
      {
        Tensor<1, dim> p;
        p[1] = i;
        if (dim == 3)
          p[2] = j;
        if (i != 0 || j != 0)
          points.push_back(p);
        for (int l = 0; l < layers; ++l)
          {
            Tensor<1, dim> q = p;
            q[0]             = 0.5 + l;
            points.push_back(q);
          }
      }
  return points;
}

template <int dim>
void
check(const unsigned int order)
{
  const auto     points = stencil<dim>(order + 1);
  Tensor<1, dim> target;
  target[0] = -2.5; // a fictitious node 2.5 h outside
  target[1] = 0.5;
  const auto w = taylor_extrapolation_weights<dim>(points, target, order);
  double     worst_exact = 0, next_degree = 0;
  std::array<int, dim> e{};
  for (e[0] = 0; e[0] <= int(order) + 1; ++e[0])
    for (e[1] = 0; e[1] <= int(order) + 1 - e[0]; ++e[1])
      for (int k = 0; k <= (dim == 3 ? int(order) + 1 - e[0] - e[1] : 0); ++k)
        {
          if (dim == 3)
            e[dim - 1] = k;
          int degree = 0;
          for (const int a : e)
            degree += a;
          double value = 0;
          for (std::size_t q = 0; q < points.size(); ++q)
            value += w[q] * monomial<dim>(e, points[q]);
          const double error = std::abs(value - monomial<dim>(e, target));
          if (degree <= int(order))
            worst_exact = std::max(worst_exact, error);
          else
            next_degree = std::max(next_degree, error);
        }
  double sum = 0;
  for (const double v : w)
    sum += v;
  std::cout << dim << "D, N = " << order << ", " << points.size()
            << " stencil points: monomials of degree <= N reproduced to 1e-10: "
            << (worst_exact < 1e-10 ? "yes" : "no")
            << "; degree N+1 reproduced: " << (next_degree > 1e-3 ? "no" : "yes")
            << "; weights sum to 1: " << (std::abs(sum - 1) < 1e-12 ? "yes" : "no")
            << std::endl;
}

int
main()
{
  for (unsigned int order = 1; order <= 3; ++order)
    {
      check<2>(order);
      check<3>(order);
    }
  // A stencil on the face only cannot give normal derivatives.
  std::vector<Tensor<1, 3>> flat;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      {
        Tensor<1, 3> p;
        p[1] = i;
        p[2] = j;
        flat.push_back(p);
      }
  Tensor<1, 3> target;
  target[0] = -1;
  std::cout << "face-only stencil rejected: "
            << (taylor_extrapolation_weights<3>(flat, target, 1).empty() ? "yes" :
                                                                          "no")
            << std::endl;
  std::cout << "order 0 copies the expansion point: "
            << (taylor_extrapolation_weights<3>(flat, target, 0)[0] == 1. ?
                  "yes" :
                  "no")
            << std::endl;
}
