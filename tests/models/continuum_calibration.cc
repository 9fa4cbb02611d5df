// Kind of test: independent reference (classical linear elasticity) for the
// models' closed-form constants.
//
// For a displacement field u(x) = A x + (1/2) H[x, x] (any A, any symmetric
// second derivatives H^i), the linearised peridynamic force density at a
// point whose horizon lies inside the body,
//   f(x) = int_H n [alpha(r) s (theta(x) + theta(x')) + 2 beta(r) s e] dV',
//   theta(x) = (d/m) int_H omega(r) r e dV',   m = int_H omega r^2 dV,
// e = n . (u(x') - u(x)), with the model's kernel alpha, beta, s (exactly as
// BondOperator and the test oracle ReferenceBondOperator use it), must equal
// the classical div sigma(u) = mu Lap u + (lambda + mu) grad div u, with lambda
// and mu computed here from E and nu (plane strain, plane stress or 3D).
// That holds exactly only if the micromoduli constants of the model are
// right. The integrals are evaluated by a brute-force tensor product
// quadrature in polar (spherical) coordinates: Gauss-Legendre in r (and in
// cos(phi)), the trapezoidal rule in the periodic angle; the integrands are
// polynomials times the influence function, so the sums are exact to
// round-off. theta(x') = div u(x') in the bulk (the quadratic part is odd);
// theta(x) itself is checked against div u(x) by the quadrature.
//
// Cases: LPS with constant, conical and Gaussian influence in 3D, plane
// strain and plane stress; bond-based (its fixed Poisson ratio: 1/4 in 3D
// and plane strain, 1/3 in plane stress), constant and conical.

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <perideal/models/model.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <random>

using namespace dealii;
using namespace PeriDEAL;

// Quadrature points (unit direction, radius) and weights over the ball of
// radius delta.
template <int dim>
void
ball_quadrature(const double                 delta,
                std::vector<Tensor<1, dim>> &directions,
                std::vector<double>         &radii,
                std::vector<double>         &weights)
{
  const QGauss<1>    radial(40);
  const unsigned int n_angle = 64;
  const QGauss<1>    polar(32);
  for (unsigned int q = 0; q < radial.size(); ++q)
    {
      const double r  = delta * radial.point(q)[0];
      const double wr = delta * radial.weight(q) * std::pow(r, dim - 1);
      for (unsigned int a = 0; a < n_angle; ++a)
        {
          const double theta = 2 * M_PI * (a + 0.5) / n_angle;
          const double wa    = 2 * M_PI / n_angle;
          if (dim == 2)
            {
              Tensor<1, dim> n;
              n[0] = std::cos(theta);
              n[1] = std::sin(theta);
              directions.push_back(n);
              radii.push_back(r);
              weights.push_back(wr * wa);
            }
          else
            for (unsigned int p = 0; p < polar.size(); ++p)
              {
                const double   c = 2 * polar.point(p)[0] - 1; // cos(phi)
                const double   s = std::sqrt(1 - c * c);
                Tensor<1, dim> n;
                n[0]       = s * std::cos(theta);
                n[1]       = s * std::sin(theta);
                n[dim - 1] = c;
                directions.push_back(n);
                radii.push_back(r);
                weights.push_back(wr * wa * 2 * polar.weight(p));
              }
        }
    }
}

template <int dim>
void
check(const std::string &model_name,
      const std::string &plane_model,
      const double       nu,
      const std::string &influence)
{
  const double     E = 2.1, delta = 1.3;
  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(model_name);
  prm.set("Young's modulus", E);
  prm.set("Poisson's ratio", nu);
  prm.set("Plane model", plane_model);
  prm.set("Influence function", influence);
  prm.leave_subsection();
  const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

  // Classical Lame constants, from E and nu only.
  const double mu     = E / (2 * (1 + nu));
  const double lambda = (dim == 2 && plane_model == "plane stress") ?
                          E * nu / (1 - nu * nu) :
                          E * nu / ((1 + nu) * (1 - 2 * nu));

  // A random field.
  std::mt19937                           rng(7 + dim);
  std::uniform_real_distribution<double> unit(-1., 1.);
  Tensor<2, dim>                         A;
  Tensor<3, dim>                         H; // H[i][j][k] = d^2 u_i / dx_j dx_k
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = 0; j < dim; ++j)
      {
        A[i][j] = unit(rng);
        for (unsigned int k = 0; k <= j; ++k)
          H[i][j][k] = H[i][k][j] = unit(rng);
      }
  const auto u = [&](const Tensor<1, dim> &x) {
    Tensor<1, dim> value = A * x;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          value[i] += 0.5 * H[i][j][k] * x[j] * x[k];
    return value;
  };
  const auto div_u = [&](const Tensor<1, dim> &x) {
    double value = 0;
    for (unsigned int i = 0; i < dim; ++i)
      {
        value += A[i][i];
        for (unsigned int k = 0; k < dim; ++k)
          value += H[i][i][k] * x[k];
      }
    return value;
  };
  Tensor<1, dim> classical;
  for (unsigned int i = 0; i < dim; ++i)
    for (unsigned int j = 0; j < dim; ++j)
      classical[i] += mu * H[i][j][j] + (lambda + mu) * H[j][i][j];

  std::vector<Tensor<1, dim>> directions;
  std::vector<double>         radii, weights;
  ball_quadrature<dim>(delta, directions, radii, weights);

  double m = 0;
  for (unsigned int q = 0; q < weights.size(); ++q)
    m += weights[q] * model->influence(radii[q], delta) * radii[q] * radii[q];
  const double s = model->node_factor(m);

  // theta(0) by quadrature against div u(0).
  double theta_0 = 0;
  for (unsigned int q = 0; q < weights.size(); ++q)
    {
      const Tensor<1, dim> xi = radii[q] * directions[q];
      theta_0 += weights[q] * model->influence(radii[q], delta) * radii[q] *
                 (directions[q] * u(xi));
    }
  theta_0 *= dim / m;
  const double theta_error = std::abs(theta_0 - div_u(Tensor<1, dim>()));

  Tensor<1, dim> force;
  for (unsigned int q = 0; q < weights.size(); ++q)
    {
      const double          r  = radii[q];
      const Tensor<1, dim> &n  = directions[q];
      const Tensor<1, dim>  xi = r * n;
      const double          e  = n * u(xi);
      const double          t =
        (model->is_state_based() ? model->dilatation_constant(r, delta) * s *
                                     (div_u(Tensor<1, dim>()) + div_u(xi)) :
                                   0.) +
        2 * model->extension_constant(r, delta) * s * e;
      force += weights[q] * t * n;
    }
  const double relative = (force - classical).norm() / classical.norm();
  std::cout << std::setw(26) << std::left << model_name << " "
            << (dim == 3 ? std::string("3D") : plane_model) << ", " << influence
            << ", nu = " << nu << ":\n  theta = div u to 1e-12: "
            << (theta_error <= 1e-12 ? "yes" : "NO")
            << "\n  force density = div sigma to 1e-11 relative: "
            << (relative <= 1e-11 ? "yes" : "NO") << std::endl;
  if (relative > 1e-11 || theta_error > 1e-12)
    std::cout << "  (force " << force << ", div sigma " << classical
              << ", theta error " << theta_error << ")" << std::endl;
}

int
main()
{
  for (const std::string influence : {"constant", "conical", "gaussian"})
    {
      check<3>("linear peridynamic solid", "plane strain", 0.3, influence);
      check<2>("linear peridynamic solid", "plane strain", 0.3, influence);
      check<2>("linear peridynamic solid", "plane stress", 0.3, influence);
    }
  for (const std::string influence : {"constant", "conical"})
    {
      check<3>("bond-based", "plane strain", 0.25, influence);
      check<2>("bond-based", "plane strain", 0.25, influence);
      check<2>("bond-based", "plane stress", 1. / 3, influence);
    }
}
