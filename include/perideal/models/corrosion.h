#ifndef perideal_models_corrosion_h
#define perideal_models_corrosion_h

#include <deal.II/base/parsed_function.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/models/diffusion_model.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Models
  {
    /**
     * Peridynamic pitting corrosion (diffusion model `corrosion`; Chen &
     * Bobaru 2015, PeriFast/Corrosion 2023; derivations and sources in
     * doc/corrosion-model.md). Every node is electrolyte (phase 0), metal
     * (1) or passive film (2). The concentration C of dissolved metal
     * diffuses between electrolyte nodes with the kernel of `diffusion`;
     * metal and passive film conduct nothing. Metal dissolves through the
     * bonds between metal and electrolyte nodes (interface bonds), in one
     * of two forms ('Interface model'):
     *
     * - `dissolution rate` (PeriFast): each interface bond carries the fixed
     *   flow \f$\rho\,\mu_{ij}\f$ from the metal to the electrolyte node,
     *   \f$\rho = q\,\delta/(K G)\f$, calibrated so that a flat interface
     *   dissolves \f$q = i/(nF)\f$ mol per m^2 and s for the current density
     *   i (activation control; diffusion control emerges for large i);
     * - `interface diffusivity` (Chen & Bobaru): interface bonds conduct
     *   like electrolyte bonds with the interface diffusivity \f$K_{LS}\f$,
     *   driven by the difference \f$C_\mathrm{metal} -
     * C_\mathrm{electrolyte}\f$.
     *
     * With `Salt film` an interface bond carries nothing while its
     * electrolyte end is at or above \f$C_\mathrm{sat}\f$: diffusion out of
     * the pit then controls the rate. A metal node whose concentration
     * drops below \f$C_\mathrm{sat}\f$ becomes electrolyte for good (it keeps
     * its concentration), so the interface moves by itself; each process
     * decides it for all nodes it holds from the same values, without
     * communication.
     *
     * Optional mechanical damage: mechanical bonds on the same families
     * break by a concentration rule, reproducible with a seed and
     * independent of the partition: bond (i, j) breaks when
     * \f$\max(\varphi_i, \varphi_j) > u_{ij}\f$, \f$\varphi = (C_\mathrm{solid}
     * - C)/(C_\mathrm{solid} - C_\mathrm{sat})\f$ clamped to [0, 1] for metal,
     * 1 for electrolyte, and \f$u_{ij}\in[0, 1)\f$ a hash of the seed and the
     * two global node indices.
     *
     * History columns: pit volume (initially metal, now electrolyte), the
     * same plus the damaged fraction of metal, pit depth along a direction,
     * converted nodes and the amount of metal left.
     */
    template <int dim>
    class Corrosion : public DiffusionModel<dim>
    {
    public:
      using VectorType = typename DiffusionModel<dim>::VectorType;

      static void
      declare_parameters(ParameterHandler &prm);

      void
      parse_parameters(ParameterHandler &prm) override;

      /// 'Initial concentration' (the phases set it), and the constants of
      /// the interface model or the damage that are not selected.
      std::vector<UnusedEntry>
      unused_entries() const override;

      bool
      supports_implicit() const override
      {
        return false;
      }

      /// True: metal nodes dissolve into electrolyte.
      bool
      changes_phases() const override
      {
        return true;
      }

      void
      initialize(const DiffusionSetup<dim> &setup, VectorType &c) override;

      double
      largest_time_step(const DiffusionSetup<dim> &setup) const override;

      /// 'Current density' through the dissolution rate.
      typename DiffusionModel<dim>::TimeStepLimit
      time_step_limit() const override;

      void
      after_step(const DiffusionSetup<dim> &setup,
                 const double               time,
                 VectorType                &c,
                 const bool                 record) override;

      std::vector<std::string>
      history_columns() const override;

      std::vector<double>
      history_values(const DiffusionSetup<dim> &setup,
                     const VectorType          &c) const override;

      std::vector<NodeField>
      node_fields(const DiffusionSetup<dim> &setup,
                  const VectorType          &c) const override;

      std::string
      progress_text(const std::vector<double> &values) const override;

      /**
       * The flat-interface factor G: an interface bond kernel
       * \f$a\,\omega(|\xi|/\delta)/|\xi|^q\f$ carries
       * \f$\int_{\xi_n > 0}\xi_n\,a\,\omega/|\xi|^q\,dV =
       * a\,G\,\delta/\kappa\f$ through a flat interface per unit area (with
       * \f$\kappa\f$ of diffusivity K: \f$G K/\delta\f$ per unit of
       * a/\f$\kappa\f$). Finite for q <= d.
       */
      static double
      flat_interface_factor(const unsigned int       dim_,
                            const unsigned int       q,
                            const InfluenceFunction &omega);

    private:
      /// Phases of all nodes of the set to the operator.
      void
      configure_operator(const DiffusionSetup<dim> &setup) const;

      /// Break mechanical bonds by the damage rule (collective).
      void
      update_damage(const DiffusionSetup<dim> &setup, const VectorType &c);

      /// The damage variable of node i of the set.
      double
      damage_variable(const unsigned int i, const double c) const;

      // Input.
      double        c_solid = 0, c_sat = 0, c_electrolyte = 0;
      std::string   interface_model;
      double        interface_diffusivity = 0;
      double        current_density = 0, valence = 2;
      bool          salt_film = true, with_damage = false;
      std::uint64_t seed = 0;
      std::unique_ptr<Functions::ParsedFunction<dim>> initial_phase;
      Point<dim>                                      depth_origin;
      Tensor<1, dim>                                  depth_direction;
      std::string c_sat_text, phase_text, current_density_text;

      // State.
      std::vector<unsigned char>     phase;           // per node of the set
      std::vector<bool>              initially_metal; // per node of the set
      std::vector<double>            factor, rate;
      double                         rho = 0;
      Discretization::BondState<dim> mechanical;
      unsigned int                   n_converted_local = 0;
    };
  } // namespace Models
} // namespace PeriDEAL

#endif
