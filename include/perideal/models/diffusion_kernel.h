#ifndef perideal_models_diffusion_kernel_h
#define perideal_models_diffusion_kernel_h

#include <deal.II/base/parameter_handler.h>

#include <perideal/models/influence_function.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Models
  {
    using namespace dealii;

    /**
     * The bond-based peridynamic diffusion kernel (hybrid-collocation paper,
     * Eqs. 22-24): the concentration flow density of a bond \f$\xi\f$ is
     * \f[
     *   J(\eta, \xi) = \kappa\, \omega(|\xi|/\delta)\,
     *                  \frac{\eta}{|\xi|^q},\qquad \eta = C(x') - C(x),
     * \f]
     * with \f$q \in \{0, 1, 2, 3\}\f$, an influence function \f$\omega\f$
     * and the micro-diffusivity \f$\kappa\f$ from the classical diffusivity
     * K by flux matching: for a quadratic field the nonlocal operator equals
     * \f$K\Delta C\f$ when
     * \f[
     *   \kappa = \frac{2 d K}{\int_{B_\delta} \omega\, r^{2-q}\, dV}
     *          = \frac{2 d K}{S_{d-1}\, \delta^{d+2-q}\, M_{d+1-q}},\qquad
     *   M_k = \int_0^1 \omega(s) s^k\, ds,
     * \f]
     * \f$S_0 = 2, S_1 = 2\pi, S_2 = 4\pi\f$ (derivation and the closed forms
     * for the constant and conical influence in doc/diffusion.md; 2D, q = 2
     * gives Eq. 25: \f$4K/(\pi\delta^2)\f$ and \f$12K/(\pi\delta^2)\f$).
     *
     * This class is the one place of the kernel: operators take
     * conductance() per bond.
     */
    class DiffusionKernel
    {
    public:
      /// Declare 'Diffusivity', 'Flux exponent' and 'Influence function'
      /// in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * Read the entries of the current subsection (@p section names it in
       * error messages) and check them: K > 0, q in {0, 1, 2, 3}.
       */
      void
      parse_parameters(ParameterHandler &prm, const std::string &section);

      /// Set the dimension and the horizon; computes \f$\kappa\f$ by flux
      /// matching on the continuous ball. A \f$\kappa\f$ out of the range
      /// of doubles (a diffusivity such as 1e308) is refused, naming
      /// 'Diffusivity'.
      void
      reinit(const unsigned int dim, const double horizon);

      /**
       * Whether 'Micro-diffusivity calibration = lattice': \f$\kappa\f$ is
       * to be matched on the discrete stencil of a uniform grid
       * (calibrate_on_lattice()) instead of the continuous ball.
       */
      bool
      calibrates_on_lattice() const
      {
        return on_lattice;
      }

      /**
       * Match \f$\kappa\f$ on a uniform grid of spacing @p h: with the
       * neighbours' offsets @p offsets (in cells) and partial-volume
       * fractions @p fractions, the discrete operator maps \f$|x|^2\f$ to
       * \f$2dK\f$ exactly:
       * \f$\kappa_h = 2dK / \sum_k \omega_k r_k^{2-q} \beta_k h^d\f$. The
       * discrete model then tends to classical diffusion with the
       * diffusivity K as the horizon shrinks at fixed m-ratio
       * (asymptotic compatibility), which the continuous calibration misses
       * by the one-point rule's error (e.g. \f$1/(\pi m^2)\f$ for q = 2 in
       * 2D).
       */
      template <int dim>
      void
      calibrate_on_lattice(const double                             h,
                           const std::vector<std::array<int, dim>> &offsets,
                           const std::vector<double>               &fractions);

      /// The classical diffusivity K.
      double
      diffusivity() const
      {
        return K;
      }

      /// The exponent q of \f$|\xi|\f$ in the flow density.
      unsigned int
      flux_exponent() const
      {
        return q;
      }

      /// The horizon \f$\delta\f$ (after reinit()).
      double
      get_horizon() const
      {
        return horizon;
      }

      /// The micro-diffusivity \f$\kappa\f$ (after reinit()).
      double
      micro_diffusivity() const
      {
        return kappa;
      }

      /**
       * \f$\kappa\,\max(\omega(r/\delta), 0)/r^q\f$: the conductance of a
       * bond of length @p r per unit volume of the neighbour, evaluated at
       * the neighbour's centre (the one-point rule with partial volumes:
       * cells cut by the horizon may have their centre beyond it).
       */
      double
      conductance(const double r) const;

      /**
       * \f$\int_{B_\delta} \omega(|\xi|/\delta)\, |\xi|^{p}\, dV\f$ in
       * dimension @p dim, in closed form through the influence function's
       * moments.
       */
      static double
      ball_moment(const unsigned int       dim,
                  const double             horizon,
                  const int                p,
                  const InfluenceFunction &omega);

      /// The influence function.
      const InfluenceFunction &
      influence() const
      {
        return *omega;
      }

      /// The name of the influence function.
      const std::string &
      influence_name() const
      {
        return omega_name;
      }

    private:
      double                             K          = 1;
      unsigned int                       q          = 2;
      double                             horizon    = 0;
      double                             kappa      = 0;
      bool                               on_lattice = false;
      std::string                        omega_name;
      std::unique_ptr<InfluenceFunction> omega;
      /// 'Diffusivity' as given and its subsection, for messages.
      std::string diffusivity_text, section_name;

      /// Throw naming 'Diffusivity' unless kappa is finite and positive.
      void
      check_kappa() const;
    };
  } // namespace Models
} // namespace PeriDEAL

#endif
