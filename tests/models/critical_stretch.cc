// Kind of test: closed forms and an independent quadrature.
//
// The critical stretch s0 that the bond-based (PMB) model derives from
// 'Fracture energy' G0 must
//  (a) equal the closed forms of doc/explicit-dynamics.md (3D, plane
//      stress, plane strain; constant and conical influence; the 3D
//      constant case is Silling & Askari's sqrt(5 G0 / (9 K delta)), the
//      plane-stress cases the hybrid-collocation paper's Eq. 20), and
//  (b) give back G0 when the energy of the bonds that cross a unit area of
//      a plane, each broken at s0 (c omega s0^2 |xi| / 2 per pair of unit
//      volumes, c omega = 2 r beta from the model's kernel), is summed by a
//      brute-force Gauss quadrature over the depth z, the bond length and
//      the angle.
// Also: 'Critical stretch' together with 'Fracture energy' is refused (LPS:
// tests/models/critical_stretch_lps).

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <perideal/models/model.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

template <int dim>
std::unique_ptr<Models::Model<dim>>
make(const std::string &name,
     const std::string &influence,
     const std::string &plane,
     const std::string &G0,
     const std::string &s0 = "0")
{
  ParameterHandler prm;
  Models::ModelRegistry<dim>::declare_parameters(prm);
  prm.enter_subsection(name);
  prm.set("Young's modulus", "72e9");
  prm.set("Poisson's ratio",
          plane == "plane stress" ? "0.3333333333333333" : "0.25");
  if (dim == 2)
    prm.set("Plane model", plane);
  prm.set("Influence function", influence);
  prm.set("Fracture energy", G0);
  prm.set("Critical stretch", s0);
  prm.leave_subsection();
  return Models::ModelRegistry<dim>::create(name, prm);
}

// G0 = int_0^delta dz (energy of the bonds from a point at depth z that
// cross the plane), by Gauss quadrature.
template <int dim>
double
fracture_energy(const Models::Model<dim> &model,
                const double              delta,
                const double              s0)
{
  const QGauss<1> gauss(400);
  const auto      bond_energy = [&](const double r) {
    const double c_omega = 2 * r * model.extension_constant(r, delta);
    return c_omega * s0 * s0 * r / 2;
  };
  double G = 0;
  for (unsigned int a = 0; a < gauss.size(); ++a)
    {
      const double z     = delta * gauss.point(a)[0];
      double       inner = 0;
      for (unsigned int b = 0; b < gauss.size(); ++b)
        {
          const double r = z + (delta - z) * gauss.point(b)[0];
          // 3D: 2 pi r^2 int_{z/r}^1 d(cos phi); 2D: r * 2 arccos(z/r).
          const double shell = dim == 3 ? 2 * M_PI * r * r * (1 - z / r) :
                                          2 * r * std::acos(z / r);
          inner += gauss.weight(b) * (delta - z) * shell * bond_energy(r);
        }
      G += gauss.weight(a) * delta * inner;
    }
  return G;
}

template <int dim>
void
check(const std::string &influence, const std::string &plane)
{
  const double G0 = 3.8, delta = 1e-3, E = 72e9;
  const auto   model = make<dim>("bond-based", influence, plane, "3.8");
  const double s0    = model->critical_stretch(delta);
  const double K     = model->bulk_modulus();
  double       closed;
  const bool   constant = influence == "constant";
  if (dim == 3)
    closed = constant ? std::sqrt(5 * G0 / (9 * K * delta)) :
                        std::sqrt(2 * G0 / (3 * K * delta));
  else if (plane == "plane stress")
    closed = constant ? std::sqrt(4 * M_PI * G0 / (9 * E * delta)) :
                        std::sqrt(5 * M_PI * G0 / (9 * E * delta));
  else
    closed = constant ? std::sqrt(5 * M_PI * G0 / (12 * E * delta)) :
                        std::sqrt(25 * M_PI * G0 / (48 * E * delta));
  const double back = fracture_energy<dim>(*model, delta, s0);
  std::cout << dim << "D " << (dim == 2 ? plane + ", " : std::string())
            << influence << ": s0 = closed form to 1e-12: "
            << (std::abs(s0 - closed) <= 1e-12 * closed ? "yes" : "NO")
            << "; quadrature of the broken-bond energy gives G0 to 1e-6: "
            << (std::abs(back - G0) <= 1e-6 * G0 ? "yes" : "NO") << std::endl;
}

int
main()
{
  check<3>("constant", "");
  check<3>("conical", "");
  for (const std::string plane : {"plane stress", "plane strain"})
    {
      check<2>("constant", plane);
      check<2>("conical", plane);
    }
  // Refusals name the entry.
  for (const auto &[name, s0] :
       {std::make_pair(std::string("bond-based"), std::string("0.01"))})
    {
      std::string message;
      try
        {
          make<3>(name, "constant", "", "3.8", s0)->critical_stretch(1e-3);
        }
      catch (const std::exception &e)
        {
          message = e.what();
        }
      std::cout << name << " with 'Fracture energy'"
                << (s0 != "0" ? " and 'Critical stretch'" : "")
                << ": refused naming 'Fracture energy': "
                << (message.find("Fracture energy") != std::string::npos ?
                      "yes" :
                      "NO")
                << std::endl;
    }
}
