// Kind of test: independent reference (classical diffusion, brute-force
// quadrature, closed forms) for the micro-diffusivity of the PD diffusion
// kernel (Models::DiffusionKernel).
//
// Flux matching: for a quadratic concentration p, the nonlocal operator at a
// point whose horizon lies inside the body,
//   L[p](x) = int_B kappa omega(|xi|/delta) (p(x + xi) - p(x)) / |xi|^q dV,
// must equal the classical K lap p. For a quartic it equals
//   K lap p + K I4 / (4 (d + 2) I2) lap^2 p,  I_k = int_B omega r^(k - q) dV,
// the formula the manufactured sources of tests/diffusion use (derivation in
// doc/diffusion.md). Both are checked here with kappa from the kernel and
// the integral evaluated by a brute-force quadrature in polar (spherical)
// coordinates (Gauss-Legendre in r and cos(phi), trapezoidal in the
// periodic angle), exact to round-off for these integrands, for d = 1, 2, 3,
// every admissible q (1D: q <= 2; the 1D integral diverges for q = 3) and
// constant, conical and Gaussian influence. kappa is also compared with the
// closed forms for the constant and conical influence,
//   constant: kappa = 2 d K (d + 2 - q) / (S_{d-1} delta^(d+2-q)),
//   conical:  kappa = 2 d K (d + 2 - q)(d + 3 - q) / (S_{d-1} delta^(d+2-q)),
// which for d = 2, q = 2 are the paper's Eq. 25: 4K/(pi delta^2) and
// 12K/(pi delta^2).

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <perideal/models/diffusion_kernel.h>

#include <cmath>
#include <iostream>
#include <random>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

struct BallPoint
{
  std::vector<double> xi; // d components
  double              weight;
};

std::vector<BallPoint>
ball_quadrature(const unsigned int dim, const double delta)
{
  const QGauss<1>        radial(40), polar(32);
  const unsigned int     n_angle = 64;
  std::vector<BallPoint> points;
  for (unsigned int k = 0; k < radial.size(); ++k)
    {
      const double r  = delta * radial.point(k)[0];
      const double wr = delta * radial.weight(k) * std::pow(r, dim - 1);
      if (dim == 1)
        for (const double s : {-1., 1.})
          points.push_back({{s * r}, wr});
      else
        for (unsigned int a = 0; a < n_angle; ++a)
          {
            const double phi = 2 * M_PI * (a + 0.5) / n_angle;
            const double wa  = 2 * M_PI / n_angle;
            if (dim == 2)
              points.push_back(
                {{r * std::cos(phi), r * std::sin(phi)}, wr * wa});
            else
              for (unsigned int b = 0; b < polar.size(); ++b)
                {
                  const double c = 2 * polar.point(b)[0] - 1;
                  const double s = std::sqrt(1 - c * c);
                  points.push_back(
                    {{r * s * std::cos(phi), r * s * std::sin(phi), r * c},
                     wr * wa * 2 * polar.weight(b)});
                }
          }
    }
  return points;
}

int
main()
{
  std::mt19937                           random(42);
  std::uniform_real_distribution<double> uniform(-1, 1);
  const double                           K = 2.5, delta = 0.3;
  const double                           sphere[] = {2, 2 * M_PI, 4 * M_PI};
  bool                                   all_ok   = true;
  for (const std::string omega : {"constant", "conical", "gaussian"})
    for (unsigned int dim = 1; dim <= 3; ++dim)
      for (unsigned int q = 0; q <= 3; ++q)
        {
          if (dim == 1 && q == 3)
            continue;
          ParameterHandler prm;
          Models::DiffusionKernel::declare_parameters(prm);
          prm.set("Diffusivity", std::to_string(K));
          prm.set("Flux exponent", std::to_string(q));
          prm.set("Influence function", omega);
          Models::DiffusionKernel kernel;
          kernel.parse_parameters(prm, "diffusion");
          kernel.reinit(dim, delta);
          const double kappa = kernel.micro_diffusivity();

          // A random polynomial of degree 4 in d variables: coefficients
          // of monomials x^a (|a| <= 4); value, Laplacian and bilaplacian
          // at 0 by finite formulas.
          std::vector<std::vector<unsigned int>> exponents;
          for (unsigned int a = 0; a <= 4; ++a)
            for (unsigned int b = 0; b <= (dim > 1 ? 4 - a : 0); ++b)
              for (unsigned int c = 0; c <= (dim > 2 ? 4 - a - b : 0); ++c)
                exponents.push_back({a, b, c});
          std::vector<double> quadratic(exponents.size()),
            quartic(exponents.size());
          for (unsigned int k = 0; k < exponents.size(); ++k)
            {
              const unsigned int degree =
                exponents[k][0] + exponents[k][1] + exponents[k][2];
              quartic[k]   = uniform(random);
              quadratic[k] = degree <= 2 ? quartic[k] : 0.;
            }
          const auto value = [&](const std::vector<double> &coefficients,
                                 const std::vector<double> &x) {
            double sum = 0;
            for (unsigned int k = 0; k < exponents.size(); ++k)
              {
                double term = coefficients[k];
                for (unsigned int d = 0; d < dim; ++d)
                  term *= std::pow(x[d], exponents[k][d]);
                sum += term;
              }
            return sum;
          };
          // Laplacian and bilaplacian at 0 of a polynomial: only the
          // monomials x_i^2 (2 c) and x_i^4 (24 c), x_i^2 x_j^2 (8 c) enter.
          const auto derivatives = [&](const std::vector<double> &coeff) {
            double lap = 0, bilap = 0;
            for (unsigned int k = 0; k < exponents.size(); ++k)
              {
                std::vector<unsigned int> e  = exponents[k];
                unsigned int              n2 = 0, n4 = 0, other = 0;
                for (unsigned int d = 0; d < dim; ++d)
                  if (e[d] == 2)
                    ++n2;
                  else if (e[d] == 4)
                    ++n4;
                  else if (e[d] != 0)
                    ++other;
                if (other > 0)
                  continue;
                if (n2 == 1 && n4 == 0)
                  lap += 2 * coeff[k];
                if (n4 == 1 && n2 == 0)
                  bilap += 24 * coeff[k];
                if (n2 == 2 && n4 == 0)
                  bilap += 8 * coeff[k];
              }
            return std::make_pair(lap, bilap);
          };

          const auto   points = ball_quadrature(dim, delta);
          const double origin_quadratic =
            value(quadratic, std::vector<double>(dim, 0.));
          const double origin_quartic =
            value(quartic, std::vector<double>(dim, 0.));
          double L2 = 0, L4 = 0, I2 = 0, I4 = 0;
          for (const auto &p : points)
            {
              double r2 = 0;
              for (const double x : p.xi)
                r2 += x * x;
              const double r = std::sqrt(r2);
              const double w = kernel.conductance(r) * p.weight;
              L2 += w * (value(quadratic, p.xi) - origin_quadratic);
              L4 += w * (value(quartic, p.xi) - origin_quartic);
              I2 += w / kappa * r2;
              I4 += w / kappa * r2 * r2;
            }
          const auto [lap2, bilap2] = derivatives(quadratic);
          const auto [lap4, bilap4] = derivatives(quartic);
          (void)bilap2;
          const double expected2 = K * lap2;
          const double expected4 =
            K * lap4 + K * I4 / (4 * (dim + 2) * I2) * bilap4;
          const bool ok2 = std::abs(L2 - expected2) <= 1e-11 * std::abs(K);
          const bool ok4 = std::abs(L4 - expected4) <= 1e-11 * std::abs(K);

          // Closed forms of kappa.
          bool         closed = true;
          const double base   = 2. * dim * K * (dim + 2. - q) /
                              (sphere[dim - 1] * std::pow(delta, dim + 2. - q));
          if (omega == "constant")
            closed = std::abs(kappa / base - 1) <= 1e-13;
          if (omega == "conical")
            closed = std::abs(kappa / (base * (dim + 3. - q)) - 1) <= 1e-13;
          std::cout << "d = " << dim << ", q = " << q << ", " << omega
                    << ": L[quadratic] = K lap p to 1e-11: "
                    << (ok2 ? "yes" : "no")
                    << "; L[quartic] = K (lap p + I4/(4(d+2) I2) lap^2 p) "
                       "to 1e-11: "
                    << (ok4 ? "yes" : "no");
          if (omega != "gaussian")
            std::cout << "; closed form of kappa to 1e-13: "
                      << (closed ? "yes" : "no");
          std::cout << std::endl;
          if (!ok2 || !ok4 || !closed)
            {
              std::cout << "  L2 " << L2 << " expected " << expected2 << ", L4 "
                        << L4 << " expected " << expected4 << ", kappa "
                        << kappa << std::endl;
              all_ok = false;
            }
        }
  // The paper's Eq. 25 (d = 2, q = 2).
  for (const std::string omega : {"constant", "conical"})
    {
      ParameterHandler prm;
      Models::DiffusionKernel::declare_parameters(prm);
      prm.set("Diffusivity", std::to_string(K));
      prm.set("Influence function", omega);
      Models::DiffusionKernel kernel;
      kernel.parse_parameters(prm, "diffusion");
      kernel.reinit(2, delta);
      const double eq25 =
        (omega == "constant" ? 4 : 12) * K / (M_PI * delta * delta);
      const bool ok = std::abs(kernel.micro_diffusivity() / eq25 - 1) < 1e-14;
      std::cout << "Eq. 25, " << omega << ": " << (ok ? "yes" : "no")
                << std::endl;
      all_ok = all_ok && ok;
    }
  return all_ok ? 0 : 1;
}
