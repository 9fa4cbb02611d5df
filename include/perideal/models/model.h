#ifndef perideal_models_model_h
#define perideal_models_model_h

#include <perideal/base/input_checks.h>
#include <perideal/base/plugin_registry.h>
#include <perideal/models/influence_function.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace PeriDEAL
{
  namespace Models
  {
    using namespace dealii;

    /**
     * A linear(ised) ordinary peridynamic material model. In the small
     * displacement setting, with bond \f$\xi = x_j - x_i\f$, \f$r=|\xi|\f$,
     * \f$n = \xi/r\f$, extension \f$e_{ij} = n\cdot(u_j - u_i)\f$, weighted
     * volume and dilatation
     * \f[
     *   m_i = \sum_j \omega_{ij} r_{ij}^2 w_{ij},\qquad
     *   \theta_i = \frac{d}{m_i}\sum_j \omega_{ij} r_{ij} e_{ij} w_{ij}
     * \f]
     * (\f$d\f$ the dimension, \f$w_{ij} = \beta_{ij} V_j\f$ the quadrature
     * weight), a model defines the scalar force state of bond ij at node i as
     * \f[
     *   t_{ij} = a_i(r_{ij})\,\theta_i + b_i(r_{ij})\,e_{ij},
     * \f]
     * and the internal force density is
     * \f$ f_i = \sum_j (t_{ij} + t_{ji})\, n_{ij}\, w_{ij}\f$
     * (Scabbia et al. 2022, Eq. 20: equilibrium is \f$-f_i = b_i\f$).
     *
     * Models register themselves with PERIDEAL_REGISTER_MODEL and read their
     * material constants from their own parameter subsection.
     */
    template <int dim>
    class Model
    {
    public:
      virtual ~Model() = default;

      /// Read the material constants.
      virtual void
      parse_parameters(ParameterHandler &prm) = 0;

      /**
       * Say where the model's entries are in the input file (for instance
       * "Material model/bond-based/"), before parse_parameters(), so that
       * its messages name an entry by its full path (input_path() +
       * entry). Empty by default: a model created outside an input file
       * names its entries alone.
       */
      void
      set_input_path(const std::string &path);

      /// The path given to set_input_path().
      const std::string &
      input_path() const;

      /**
       * Entries of the model's subsection (paths relative to it) that have
       * no effect with the parameters read, e.g. the bulk modulus when the
       * material is given by Young's modulus and Poisson's ratio; the
       * simulator refuses them when set (Problems::ProblemType::
       * unused_entries()). Default: none.
       */
      virtual std::vector<UnusedEntry>
      unused_entries() const;

      /**
       * Whether forces depend on the neighbours' weighted volumes and
       * dilatations, so that a node couples to nodes up to two horizons away.
       */
      virtual bool
      is_state_based() const = 0;

      /// The influence function at bond length @p r for horizon @p horizon.
      virtual double
      influence(const double r, const double horizon) const = 0;

      /**
       * The kernel of the force state factorised for a shared stencil: the
       * coefficients of the force state are
       * \f$a_i(r) = \alpha(r)\,s(m_i)\f$ and
       * \f$b_i(r) = \beta(r)\,s(m_i)\f$, with bond constants
       * \f$\alpha(r)\f$ (dilatation_constant()), \f$\beta(r)\f$
       * (extension_constant()) that depend on the bond length only, and a
       * node factor \f$s(m_i)\f$ (node_factor()) that depends on the node's
       * weighted volume only. On a uniform grid the bond constants are
       * per-offset constants of one stencil, and the node factors one value
       * per node (LPS: \f$\alpha = c_K\omega r\f$,
       * \f$\beta = c_\mu\omega\f$, \f$s = 1/m\f$; bond-based:
       * \f$\alpha = 0\f$, \f$\beta = c\,\omega/(2r)\f$, \f$s = 1\f$).
       */
      virtual double
      dilatation_constant(const double r, const double horizon) const = 0;

      /// \f$\beta(r)\f$: see dilatation_constant().
      virtual double
      extension_constant(const double r, const double horizon) const = 0;

      /// \f$s(m)\f$: see dilatation_constant().
      virtual double
      node_factor(const double weighted_volume) const = 0;

      /**
       * \f$a_i(r) = \alpha(r)\,s(m_i)\f$: the factor of the dilatation in
       * the force state, for a node with weighted volume @p weighted_volume.
       */
      double
      dilatation_coefficient(const double weighted_volume,
                             const double r,
                             const double horizon) const
      {
        return dilatation_constant(r, horizon) * node_factor(weighted_volume);
      }

      /// \f$b_i(r) = \beta(r)\,s(m_i)\f$: the factor of the bond extension.
      double
      extension_coefficient(const double weighted_volume,
                            const double r,
                            const double horizon) const
      {
        return extension_constant(r, horizon) * node_factor(weighted_volume);
      }

      /// The bulk modulus K (3D) of the material, for reports.
      virtual double
      bulk_modulus() const = 0;

      /// The shear modulus of the material.
      virtual double
      shear_modulus() const = 0;

      /// In 2D: whether the model is in plane stress (false: plane strain).
      virtual bool
      plane_stress() const
      {
        return false;
      }

      /**
       * The elastic energy of node i per unit volume,
       * \f[
       *   W_i = \tfrac12\, s(m_i) \sum_j \beta(r_{ij})\, e_{ij}^2\, w_{ij}
       *       + \tfrac12\,\lambda_\theta\,\theta_i^2 ,
       * \f]
       * with the kernel's \f$\beta, s\f$ (dilatation_constant()) and
       * \f$\lambda_\theta\f$ = dilatation_energy_modulus(), is the
       * potential of the kernel's force state: \f$\partial W_i/\partial
       * e_{ij} = t_{ij}/w_{ij}\f$ for any set of intact bonds (the sums run
       * over them, \f$m_i\f$ over all bonds). Bond-based:
       * \f$\lambda_\theta = 0\f$; LPS: \f$\lambda_\theta = c_K/d\f$,
       * i.e. \f$K - 5\mu/3\f$ in 3D and \f$\kappa - 2\mu\f$ in 2D
       * (doc/explicit-dynamics.md).
       */
      virtual double
      dilatation_energy_modulus() const = 0;

      /**
       * The critical stretch \f$s_0\f$ of bond failure for horizon
       * @p horizon: a bond whose stretch \f$|y_j - y_i|/|x_j - x_i| - 1\f$
       * reaches it breaks for good. Infinite (the default) when the model has
       * no failure criterion.
       */
      virtual double
      critical_stretch(const double horizon) const;

      /// Mass density \f$\rho\f$ (for dynamics).
      virtual double
      density() const;

      /**
       * The entry of the model's subsection that sets its stiffness, and
       * its value as given (e.g. {"Young's modulus", "1e308"}), for
       * messages about the scale of the model; empty where there is none.
       */
      virtual std::pair<std::string, std::string>
      stiffness_entry() const;

      static std::string
      family_name();

    private:
      std::string path;
    };

    template <int dim>
    using ModelRegistry = PluginRegistry<Model<dim>>;

    /**
     * Isotropic linear elastic constants as a user gives them: Young's
     * modulus and Poisson's ratio, or bulk and shear modulus. Declares and
     * parses the entries "Elastic constants", "Young's modulus",
     * "Poisson's ratio", "Bulk modulus", "Shear modulus" and, for 2D,
     * "Plane model" (plane strain or plane stress).
     */
    struct ElasticConstants
    {
      /// Three-dimensional bulk modulus K.
      double bulk = 0;
      /// Shear modulus mu.
      double shear = 0;
      /// In 2D: plane stress (true) or plane strain (false).
      bool plane_stress = false;
      /**
       * The entry that sets the stiffness ("Young's modulus", or the larger
       * of "Bulk modulus" and "Shear modulus") and its value as given.
       */
      std::pair<std::string, std::string> stiffness_entry;

      double
      youngs_modulus() const;

      double
      poissons_ratio() const;

      /**
       * The bulk modulus of the 2D model: $\kappa = K + \mu/3$ in plane
       * strain, $9K\mu/(3K + 4\mu)$ in plane stress.
       */
      double
      planar_bulk_modulus() const;

      static void
      declare_parameters(ParameterHandler &prm);

      /// Read the entries; messages name them as @p path + entry.
      void
      parse_parameters(ParameterHandler &prm, const std::string &path = "");
    };

    /**
     * What the isotropic linear elastic models share: the elastic
     * constants (ElasticConstants) and an influence function, with their
     * parameters, and the Model functions that only depend on them.
     */
    template <int dim>
    class IsotropicModel : public Model<dim>
    {
    public:
      /// Declare the elastic constants and "Influence function".
      static void
      declare_parameters(ParameterHandler  &prm,
                         const std::string &default_influence);

      void
      parse_parameters(ParameterHandler &prm) override;

      /// The pair of elastic constants that 'Elastic constants' does not
      /// select.
      std::vector<UnusedEntry>
      unused_entries() const override;

      double
      influence(const double r, const double horizon) const override;

      /**
       * 'Critical stretch' when given; otherwise from 'Fracture energy'
       * through critical_stretch_from_fracture_energy(); infinite when
       * neither is given.
       */
      double
      critical_stretch(const double horizon) const override;

      double
      density() const override;

      std::pair<std::string, std::string>
      stiffness_entry() const override;

      double
      bulk_modulus() const override;

      double
      shear_modulus() const override;

      bool
      plane_stress() const override;

    protected:
      /**
       * The critical stretch that dissipates the fracture energy @p G0 (per
       * unit crack area) when a crack separates the body (Silling & Askari
       * 2005); models without such a relation throw ExcInvalidInput naming
       * 'Fracture energy'.
       */
      virtual double
      critical_stretch_from_fracture_energy(const double G0,
                                            const double horizon) const;

      ElasticConstants                   constants;
      std::unique_ptr<InfluenceFunction> omega;
      double                             given_critical_stretch = 0;
      double                             fracture_energy        = 0;
      double                             mass_density           = 1;
      /// Whether 'Elastic constants' selects the bulk and shear modulus.
      bool given_as_moduli = false;
    };
  } // namespace Models

  extern template class PluginRegistry<Models::Model<1>>;
  extern template class PluginRegistry<Models::Model<2>>;
  extern template class PluginRegistry<Models::Model<3>>;
} // namespace PeriDEAL

/// Register the model @p Class (a template over dim) under @p name.
#define PERIDEAL_REGISTER_MODEL(Class, name, description) \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::Model<2>,   \
                          Class<2>,                       \
                          name,                           \
                          description)                    \
  PERIDEAL_REGISTER_CLASS(::PeriDEAL::Models::Model<3>,   \
                          Class<3>,                       \
                          name,                           \
                          description)

#endif
