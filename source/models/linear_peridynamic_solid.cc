#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_lib.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/influence_function.h>
#include <perideal/models/model.h>

#include <cmath>
#include <memory>
#include <string>
#include <utility>

namespace PeriDEAL
{
  namespace Models
  {
    /**
     * The ordinary state-based linear peridynamic solid (LPS; Silling et al.
     * 2007), linearised for small displacements (Scabbia et al. 2022,
     * Eqs. 18-20):
     * \f[
     *   t_{ij} = \frac{c_K\,\omega_{ij} r_{ij}}{m_i}\theta_i
     *          + \frac{c_\mu\,\omega_{ij}}{m_i} e_{ij},
     * \f]
     * with \f$c_K = 3K - 5\mu\f$, \f$c_\mu = 15\mu\f$ in 3D and
     * \f$c_K = 2\kappa - 4\mu\f$, \f$c_\mu = 8\mu\f$ in 2D, \f$\kappa\f$ the
     * planar bulk modulus (plane strain: \f$K + \mu/3\f$, plane stress:
     * \f$9K\mu/(3K+4\mu)\f$). The constants follow from equating the PD
     * energy density \f$\frac{\kappa}{2}\theta^2 + \frac{\alpha}{2}\int
     * \omega (e^d)^2\f$ with the classical one under homogeneous strain; the
     * derivation, for 2D as well, is in doc/models.md.
     */
    template <int dim>
    class LinearPeridynamicSolid : public IsotropicModel<dim>
    {
    public:
      static void
      declare_parameters(ParameterHandler &prm)
      {
        IsotropicModel<dim>::declare_parameters(prm, "gaussian");
      }

      void
      parse_parameters(ParameterHandler &prm) override
      {
        IsotropicModel<dim>::parse_parameters(prm);
        if constexpr (dim == 3)
          {
            c_bulk  = 3 * this->constants.bulk - 5 * this->constants.shear;
            c_shear = 15 * this->constants.shear;
          }
        else
          {
            c_bulk = 2 * this->constants.planar_bulk_modulus() -
                     4 * this->constants.shear;
            c_shear = 8 * this->constants.shear;
          }
      }

      bool
      is_state_based() const override
      {
        return true;
      }

      double
      dilatation_energy_modulus() const override
      {
        return c_bulk / dim;
      }

      double
      dilatation_constant(const double r, const double horizon) const override
      {
        return c_bulk * this->influence(r, horizon) * r;
      }

      double
      extension_constant(const double r, const double horizon) const override
      {
        return c_shear * this->influence(r, horizon);
      }

      double
      node_factor(const double m) const override
      {
        return 1. / m;
      }

    protected:
      /**
       * The critical stretch at which breaking the bonds that cross a unit
       * area of a plane releases @p G0 (doc/explicit-dynamics.md, "Critical
       * stretch from the fracture energy (LPS)"). Under the uniform stretch
       * s (e = s r on every bond) a node at depth \f$z = \zeta\delta\f$
       * whose crossing bonds break keeps its reference m; its dilatation
       * drops to \f$d\,s(1 - f)\f$ and its deviatoric sum to
       * \f$s^2 m (1 - f)\f$, f(ζ) the share of m held by the crossing bonds.
       * The energy of this model (the potential of its forces, broken bonds
       * included) then drops by
       * \f$\Delta W = s^2[\tfrac{d\,c_K}{2}(2f - f^2) + \tfrac{c_\mu}{2}f]\f$,
       * and both sides of the crack give
       * \f[
       *   G_0 = 2\int_0^\delta \Delta W\,dz
       *       = \delta s_0^2\,[d\,c_K\,(2I_1 - I_2) + c_\mu I_1],\qquad
       *   I_k = \int_0^1 f(\zeta)^k d\zeta,
       * \f]
       * with \f$I_1, I_2\f$ by Gauss quadrature for the influence function
       * (constant ω in 3D: 5/24 and 125/1848).
       */
      double
      critical_stretch_from_fracture_energy(const double G0,
                                            const double horizon) const override
      {
        const auto   integrals = crossing_share_integrals();
        const double factor =
          dim * c_bulk * (2 * integrals.first - integrals.second) +
          c_shear * integrals.first;
        AssertThrow(factor > 0,
                    ExcInvalidInput(this->input_path() + "Fracture energy",
                                    std::to_string(G0),
                                    "the elastic constants make the energy "
                                    "released by a crack non-positive; give "
                                    "'Critical stretch' instead"));
        return std::sqrt(G0 / (horizon * factor));
      }

    private:
      /**
       * \f$(I_1, I_2)\f$: the integrals over the depth ζ of the share f(ζ)
       * of the weighted volume held by the bonds that cross a plane at
       * depth ζδ, and of its square. 3D: \f$f = \int_\zeta^1 \omega\,
       * (\rho^4 - \zeta\rho^3)\,d\rho / (2M_4)\f$; 2D: \f$f =
       * \int_\zeta^1 \omega\,\rho^3 \arccos(\zeta/\rho)\,d\rho /
       * (\pi M_3)\f$. ρ = ζ + (1 - ζ)t² takes the square-root behaviour of
       * arccos at ρ = ζ out of the Gauss rule.
       */
      std::pair<double, double>
      crossing_share_integrals() const
      {
        const QGauss<1> gauss(64);
        const double    norm =
          dim == 3 ? 2 * this->omega->moment(4) : M_PI * this->omega->moment(3);
        double i1 = 0, i2 = 0;
        for (unsigned int a = 0; a < gauss.size(); ++a)
          {
            const double zeta  = gauss.point(a)[0];
            double       share = 0;
            for (unsigned int b = 0; b < gauss.size(); ++b)
              {
                const double t        = gauss.point(b)[0];
                const double rho      = zeta + (1 - zeta) * t * t;
                const double jacobian = 2 * (1 - zeta) * t;
                const double shape =
                  dim == 3 ?
                    rho * rho * rho * (rho - zeta) :
                    rho * rho * rho * std::acos(std::min(1., zeta / rho));
                share +=
                  gauss.weight(b) * jacobian * this->omega->value(rho) * shape;
              }
            share /= norm;
            i1 += gauss.weight(a) * share;
            i2 += gauss.weight(a) * share * share;
          }
        return {i1, i2};
      }

      double c_bulk  = 0;
      double c_shear = 0;
    };
  } // namespace Models
} // namespace PeriDEAL

PERIDEAL_REGISTER_MODEL(
  PeriDEAL::Models::LinearPeridynamicSolid,
  "linear peridynamic solid",
  "Ordinary state-based linear peridynamic solid (LPS), any Poisson's ratio; "
  "3D, and 2D in plane strain or plane stress.")
