#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/influence_function.h>
#include <perideal/models/model.h>

#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

namespace PeriDEAL
{
  namespace Models
  {
    /**
     * The bond-based linear microelastic model, the linearised prototype
     * microelastic brittle (PMB) material without failure
     * (hybrid-collocation paper, Eqs. 12-17): the pairwise force density is
     * \f$ c\,\omega(|\xi|)\, e_{ij}/|\xi|\, n_{ij}\f$, i.e.
     * \f$ t_{ij} = \tfrac12 c\,\omega\, e_{ij} / r_{ij}\f$.
     *
     * The micromodulus follows from equating energy densities under
     * homogeneous strain:
     * \f$ c = 15\mu / (2\pi\delta^4 M_3)\f$ in 3D and
     * \f$ c = 8\mu / (\pi\delta^3 M_2)\f$ in 2D, with
     * \f$M_k = \int_0^1 \omega(s) s^k ds\f$ (constant influence, plane
     * stress: \f$c = 9E/(\pi\delta^3)\f$). A central pair force fixes
     * Poisson's ratio: 1/4 in 3D and plane strain, 1/3 in plane stress.
     * Another Poisson's ratio is an error, not a silent change.
     */
    template <int dim>
    class BondBased : public IsotropicModel<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        IsotropicModel<dim>::declare_parameters(prm, "constant");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        IsotropicModel<dim>::parse_parameters(prm);
        const double required =
          (dim == 2 && this->constants.plane_stress) ? 1. / 3 : 1. / 4;
        const double nu = this->constants.poissons_ratio();
        if (std::abs(nu - required) > 1e-4)
          {
            std::ostringstream value, fix;
            value << nu;
            const std::string exact = required > 0.3 ? "1/3" : "1/4";
            fix << "a bond-based model has Poisson's ratio " << exact
                << (dim == 3 ?
                      " in 3D" :
                      (this->constants.plane_stress ? " in plane stress" :
                                                      " in plane strain"))
                << "; set \"Poisson's ratio = " << std::setprecision(16)
                << required
                << "\" or use the \"linear peridynamic solid\" model";
            AssertThrow(false,
                        ExcInvalidInput(this->input_path() + "Poisson's ratio",
                                        value.str(),
                                        fix.str()));
          }
        moment = this->omega->moment(dim);
      }

      bool
      is_state_based() const override
      {
        return false;
      }

      double
      dilatation_constant(const double, const double) const override
      {
        return 0;
      }

      double
      extension_constant(const double r, const double horizon) const override
      {
        return 0.5 * micromodulus(horizon) * this->influence(r, horizon) / r;
      }

      double
      dilatation_energy_modulus() const override
      {
        return 0;
      }

      /// The micromodulus c of the pair force c omega s.
      double
      micromodulus(const double horizon) const
      {
        const double mu = this->constants.shear;
        return dim == 3 ? 15 * mu / (2 * M_PI * std::pow(horizon, 4) * moment) :
                          8 * mu / (M_PI * std::pow(horizon, 3) * moment);
      }

    protected:
      /**
       * The energy of the bonds that cross a unit area of a plane crack,
       * each broken at stretch s0 (bond energy \f$c\,\omega s_0^2 r/2\f$ per
       * pair of unit volumes), equals G0:
       * \f$G_0 = \tfrac{\pi}{2} c\, s_0^2 \delta^5 M_4\f$ in 3D and
       * \f$G_0 = c\, s_0^2 \delta^4 M_3\f$ in 2D (per unit thickness),
       * \f$M_k = \int_0^1\omega(s) s^k ds\f$. Constant influence, 3D:
       * \f$s_0 = \sqrt{5G_0/(9K\delta)}\f$; plane stress:
       * \f$\sqrt{4\pi G_0/(9E\delta)}\f$ (constant),
       * \f$\sqrt{5\pi G_0/(9E\delta)}\f$ (conical), as in the paper's
       * Eq. 20. Derivation: doc/explicit-dynamics.md.
       */
      double
      critical_stretch_from_fracture_energy(const double G0,
                                            const double horizon) const override
      {
        const double c = micromodulus(horizon);
        return dim == 3 ?
                 std::sqrt(
                   2 * G0 /
                   (M_PI * c * std::pow(horizon, 5) * this->omega->moment(4))) :
                 std::sqrt(G0 /
                           (c * std::pow(horizon, 4) * this->omega->moment(3)));
      }

      double
      node_factor(const double) const override
      {
        return 1;
      }

    private:
      double moment = 0;
    };
  } // namespace Models
} // namespace PeriDEAL

PERIDEAL_REGISTER_MODEL(
  PeriDEAL::Models::BondBased,
  "bond-based",
  "Bond-based linear microelastic model (linearised PMB); Poisson's ratio "
  "fixed at 1/4 (3D, plane strain) or 1/3 (plane stress).")
