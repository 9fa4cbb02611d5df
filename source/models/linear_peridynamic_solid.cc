#include <deal.II/base/parameter_handler.h>

#include <perideal/base/exceptions.h>
#include <perideal/models/crack_plane_integrals.h>
#include <perideal/models/influence_function.h>
#include <perideal/models/model.h>

#include <cmath>
#include <memory>
#include <string>

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
       * The critical stretch at which separating two half-spaces across a
       * plane costs @p G0 per unit area (doc/explicit-dynamics.md, "Critical
       * stretch from the fracture energy (LPS)"). The halves move apart
       * rigidly, normal to the plane, so only the crossing bonds stretch; a
       * bond breaks when its stretch reaches s0, and the work done until
       * every crossing bond has broken is the fracture energy. With the
       * energy split as \f$W = \frac{K_a}{2}\theta^2 + \frac{c_\mu}{2m}
       * \sum \omega e^2 w\f$ (\f$d K_a = c_K\f$), the extension part is the
       * energy of each crossing bond at s0 and the dilatation part follows
       * the node's dilatation as its bonds break one by one:
       * \f[
       *   G_0 = \delta s_0^2\,[d\,c_K\,J + c_\mu I_1],
       * \f]
       * \f$I_1\f$ the depth integral of the crossing share of m and J the
       * separation integral (CrackPlaneIntegrals; 3D constant ω: I1 = 5/24,
       * J = 0.04258858425). At \f$c_K = 0\f$ (ν = 1/4 in 3D, 1/3 in plane
       * stress) it is the Silling & Askari sum of the energies of the crossing
       * bonds.
       */
      double
      critical_stretch_from_fracture_energy(const double G0,
                                            const double horizon) const override
      {
        const double factor =
          dim * c_bulk *
            CrackPlaneIntegrals::separation_dilatation<dim>(*this->omega) +
          c_shear * CrackPlaneIntegrals::crossing_share<dim>(*this->omega);
        AssertThrow(factor > 0,
                    ExcInvalidInput(this->input_path() + "Fracture energy",
                                    std::to_string(G0),
                                    "the elastic constants make the work of "
                                    "separation non-positive; give "
                                    "'Critical stretch' instead"));
        return std::sqrt(G0 / (horizon * factor));
      }

    private:
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
