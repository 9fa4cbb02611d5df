#include <deal.II/base/mpi.h>

#include <perideal/base/exceptions.h>
#include <perideal/discretization/crack_geometry.h>
#include <perideal/models/corrosion.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Models
  {
    namespace
    {
      const std::string section = "diffusion/corrosion";

      constexpr double faraday = 96485.33212; // C/mol

      enum Phase : unsigned char
      {
        electrolyte = 0,
        metal       = 1,
        passive     = 2
      };

      std::uint64_t
      mix(std::uint64_t z)
      {
        // splitmix64's finaliser.
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
      }

      /// A key of a node from the bits of its coordinates: the same on every
      /// process and for every partition (DoF indices are not: they follow
      /// the partition).
      template <int dim>
      std::uint64_t
      node_key(const Point<dim> &x)
      {
        std::uint64_t key = 0x243f6a8885a308d3ULL;
        for (unsigned int d = 0; d < dim; ++d)
          {
            std::uint64_t bits;
            const double  value = x[d] + 0.; // -0 and +0 alike
            std::memcpy(&bits, &value, sizeof(bits));
            key = mix(key ^ bits);
          }
        return key;
      }

      /// A uniform number in [0, 1) per unordered pair of node keys.
      double
      bond_uniform(const std::uint64_t seed, std::uint64_t a, std::uint64_t b)
      {
        if (a > b)
          std::swap(a, b);
        std::uint64_t h = mix(seed ^ 0x9e3779b97f4a7c15ULL);
        h               = mix(h ^ a);
        h               = mix(h ^ b);
        return (h >> 11) * 0x1.0p-53;
      }
    } // namespace


    template <int dim>
    void
    Corrosion<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Solid concentration",
                        "142900",
                        Patterns::Double(),
                        "C_solid (mol/m^3): the concentration of metal "
                        "nodes (SS304: 142,900).");
      prm.declare_entry("Saturation concentration",
                        "4600",
                        Patterns::Double(),
                        "C_sat (mol/m^3), 0 < C_sat < C_solid: a metal node "
                        "below it becomes electrolyte; with 'Salt film' no "
                        "metal dissolves into electrolyte at or above it.");
      prm.declare_entry("Initial electrolyte concentration",
                        "0",
                        Patterns::Double(),
                        "C of the initial electrolyte (mol/m^3), in [0, "
                        "C_sat).");
      prm.declare_entry(
        "Interface model",
        "dissolution rate",
        Patterns::Selection("dissolution rate|interface diffusivity"),
        "dissolution rate: each metal-electrolyte bond carries a fixed flow "
        "calibrated to 'Current density' on a flat interface (PeriFast/"
        "Corrosion); interface diffusivity: metal-electrolyte bonds conduct "
        "with 'Interface diffusivity' (Chen & Bobaru 2015).");
      prm.declare_entry("Current density",
                        "5.1e3",
                        Patterns::Double(),
                        "i (A/m^2) of the dissolution rate q = i / (n F); "
                        "> 0.");
      prm.declare_entry("Valence",
                        "2.19",
                        Patterns::Double(),
                        "n, the mean charge number of the dissolved metal "
                        "(SS304: 2.19); > 0.");
      prm.declare_entry("Interface diffusivity",
                        "0",
                        Patterns::Double(),
                        "K_LS (m^2/s) of the metal-electrolyte bonds ('"
                        "Interface model = interface diffusivity'); > 0.");
      prm.declare_entry("Salt film",
                        "true",
                        Patterns::Bool(),
                        "No dissolution into electrolyte at or above C_sat "
                        "(diffusion control emerges).");
      prm.enter_subsection("Initial phase");
      Functions::ParsedFunction<dim>::declare_parameters(prm, 1);
      prm.leave_subsection();
      prm.declare_entry("Mechanical damage",
                        "false",
                        Patterns::Bool(),
                        "Break mechanical bonds on the diffusion families by "
                        "the concentration rule (output 'damage').");
      prm.declare_entry("Damage seed",
                        "0",
                        Patterns::Integer(0),
                        "Seed of the per-bond random thresholds.");
      prm.declare_entry("Pit depth origin",
                        "",
                        Patterns::Anything(),
                        "A point on the initial metal surface, one "
                        "coordinate per dimension of the run: 'x' (1D), "
                        "'x, y' (2D), 'x, y, z' (3D); empty: the origin.");
      prm.declare_entry(
        "Pit depth direction",
        "",
        Patterns::Anything(),
        "The direction into the metal along which the pit depth is "
        "measured, one component per dimension of the run: 'x' (1D), "
        "'x, y' (2D), 'x, y, z' (3D); empty: -x (1D), -y (2D), -z (3D).");
    }


    template <int dim>
    void
    Corrosion<dim>::parse_parameters(ParameterHandler &prm)
    {
      c_solid    = prm.get_double("Solid concentration");
      c_sat      = prm.get_double("Saturation concentration");
      c_sat_text = prm.get("Saturation concentration");
      AssertThrow(c_solid > 0,
                  ExcInvalidInput(section + "/Solid concentration",
                                  prm.get("Solid concentration"),
                                  "give a concentration > 0 (mol/m^3)"));
      AssertThrow(c_sat > 0 && c_sat < c_solid,
                  ExcInvalidInput(section + "/Saturation concentration",
                                  c_sat_text,
                                  "give 0 < C_sat < 'Solid concentration' (" +
                                    prm.get("Solid concentration") + ")"));
      c_electrolyte = prm.get_double("Initial electrolyte concentration");
      AssertThrow(c_electrolyte >= 0 && c_electrolyte < c_sat,
                  ExcInvalidInput(section +
                                    "/Initial electrolyte concentration",
                                  prm.get("Initial electrolyte concentration"),
                                  "give a value in [0, C_sat)"));
      interface_model       = prm.get("Interface model");
      current_density       = prm.get_double("Current density");
      current_density_text  = prm.get("Current density");
      valence               = prm.get_double("Valence");
      interface_diffusivity = prm.get_double("Interface diffusivity");
      if (interface_model == "dissolution rate")
        {
          AssertThrow(current_density > 0,
                      ExcInvalidInput(section + "/Current density",
                                      prm.get("Current density"),
                                      "give a current density > 0 (A/m^2)"));
          AssertThrow(valence > 0,
                      ExcInvalidInput(section + "/Valence",
                                      prm.get("Valence"),
                                      "give a charge number > 0"));
        }
      else
        AssertThrow(interface_diffusivity > 0,
                    ExcInvalidInput(section + "/Interface diffusivity",
                                    prm.get("Interface diffusivity"),
                                    "give K_LS > 0 (m^2/s) for 'Interface "
                                    "model = interface diffusivity'"));
      salt_film = prm.get_bool("Salt film");
      prm.enter_subsection("Initial phase");
      initial_phase = std::make_unique<Functions::ParsedFunction<dim>>(1);
      initial_phase->parse_parameters(prm);
      phase_text = prm.get("Function expression");
      prm.leave_subsection();
      with_damage = prm.get_bool("Mechanical damage");
      seed        = static_cast<std::uint64_t>(prm.get_integer("Damage seed"));

      depth_origin         = Point<dim>();
      const auto origin    = prm.get("Pit depth origin");
      const auto direction = prm.get("Pit depth direction");
      if (!origin.empty())
        {
          const auto points =
            Discretization::parse_points<dim>(origin,
                                              section + "/Pit depth origin");
          AssertThrow(points.size() == 1,
                      ExcInvalidInput(section + "/Pit depth origin",
                                      origin,
                                      "give one point"));
          depth_origin = points[0];
        }
      depth_direction          = Tensor<1, dim>();
      depth_direction[dim - 1] = -1;
      if (!direction.empty())
        {
          const auto points =
            Discretization::parse_points<dim>(direction,
                                              section + "/Pit depth direction");
          AssertThrow(points.size() == 1 && points[0].norm() > 0,
                      ExcInvalidInput(section + "/Pit depth direction",
                                      direction,
                                      "give one non-zero vector"));
          depth_direction = points[0] / points[0].norm();
        }
    }


    template <int dim>
    std::vector<UnusedEntry>
    Corrosion<dim>::unused_entries() const
    {
      std::vector<UnusedEntry> unused = {
        {"Initial concentration/",
         "with 'Model = corrosion' the initial concentration follows from "
         "'corrosion/Initial phase' ('Initial electrolyte concentration' in "
         "the electrolyte, 'Solid concentration' in the metal); remove the "
         "subsection"}};
      const std::string own = "corrosion/";
      if (interface_model == "dissolution rate")
        unused.push_back({own + "Interface diffusivity",
                          "'Interface model = dissolution rate' takes the "
                          "rate from 'Current density' and 'Valence'; set "
                          "'Interface model = interface diffusivity' to use "
                          "it, or remove the entry"});
      else
        for (const char *entry : {"Current density", "Valence"})
          unused.push_back({own + entry,
                            "'Interface model = interface diffusivity' "
                            "takes the flow from 'Interface diffusivity'; "
                            "set 'Interface model = dissolution rate' to use "
                            "it, or remove the entry"});
      if (!with_damage)
        unused.push_back({own + "Damage seed",
                          "'Mechanical damage' is false, so no bond "
                          "thresholds are drawn; set it to true, or remove "
                          "the entry"});
      return unused;
    }


    template <int dim>
    double
    Corrosion<dim>::flat_interface_factor(const unsigned int       d,
                                          const unsigned int       q,
                                          const InfluenceFunction &omega)
    {
      // G = 2 d c_d M_{d-q} / (S_{d-1} M_{d+1-q}), c_d the integral of the
      // normal component over the unit half-sphere (1, 2, pi), S_{d-1} the
      // measure of the unit sphere (2, 2 pi, 4 pi); doc/corrosion-model.md.
      AssertThrow(q <= d, ExcInternalError());
      static const double half[]   = {1, 2, numbers::PI};
      static const double sphere[] = {2, 2 * numbers::PI, 4 * numbers::PI};
      return 2. * d * half[d - 1] * omega.moment(d - q) /
             (sphere[d - 1] * omega.moment(d + 1 - q));
    }


    template <int dim>
    void
    Corrosion<dim>::initialize(const DiffusionSetup<dim> &setup, VectorType &c)
    {
      const auto    &nodes = setup.nodes;
      const MPI_Comm comm  = nodes.get_communicator();
      const double   K     = setup.kernel.diffusivity();
      const unsigned q     = setup.kernel.flux_exponent();

      // Pair tables over (electrolyte, metal, passive).
      factor.assign(9, 0.);
      rate.clear();
      factor[electrolyte * 3 + electrolyte] = 1;
      if (interface_model == "interface diffusivity")
        factor[electrolyte * 3 + metal] = factor[metal * 3 + electrolyte] =
          interface_diffusivity / K;
      else
        {
          AssertThrow(q <= dim,
                      ExcInvalidInput("diffusion/Flux exponent",
                                      std::to_string(q),
                                      "the dissolution rate through a flat "
                                      "interface is finite only for q <= " +
                                        std::to_string(dim) +
                                        "; use a smaller q"));
          const double flux    = current_density / (valence * faraday);
          const auto  &lattice = setup.lists.lattice();
          if (lattice.is_uniform() && !setup.lists.stencil().empty())
            {
              // Calibrated on the lattice itself: a flat interface between
              // two layers of nodes, normal to an axis, passes
              // rho h sum_{k: o_k > 0} o_k mu_k per unit area (metal node
              // rows r = 1, 2, ... reach the electrolyte through the
              // offsets with o_k >= r). The continuous value below misses
              // the node's own cell, which for q = 2 costs O(1/m) (25 % at
              // m = 3).
              const double h   = lattice.spacing();
              double       sum = 0;
              for (const auto &o : setup.lists.stencil())
                if (o.offset[0] > 0)
                  {
                    double r2 = 0;
                    for (unsigned int d = 0; d < dim; ++d)
                      r2 += double(o.offset[d]) * o.offset[d];
                    sum += o.offset[0] *
                           setup.kernel.conductance(std::sqrt(r2) * h) *
                           o.beta * std::pow(h, dim);
                  }
              rho = flux / (h * sum);
            }
          else
            {
              // The continuous flat interface: G K rho / delta per unit area.
              const double G =
                flat_interface_factor(dim, q, setup.kernel.influence());
              rho = flux * setup.horizon / (K * G);
            }
          rate.assign(9, 0.);
          rate[electrolyte * 3 + metal] = rho;  // into the electrolyte node
          rate[metal * 3 + electrolyte] = -rho; // out of the metal node
        }

      // Phases of every node of the set (the same function on every
      // process: ghosts agree with their owners).
      phase.assign(nodes.size(), metal);
      initially_metal.assign(nodes.size(), false);
      unsigned int bad = 0, counts[3] = {0, 0, 0};
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          const double value = initial_phase->value(nodes[i].location);
          const long   p     = std::lround(value);
          if (!(std::abs(value - p) < 1e-12 && p >= 0 && p <= 2))
            {
              bad += i < nodes.n_owned();
              continue;
            }
          phase[i]           = static_cast<unsigned char>(p);
          initially_metal[i] = p == metal;
          if (i < nodes.n_owned())
            ++counts[p];
        }
      AssertThrow(Utilities::MPI::sum(bad, comm) == 0,
                  ExcInvalidInput(section + "/Initial phase/Function "
                                            "expression",
                                  phase_text,
                                  "the initial phase must be 0 (electrolyte), "
                                  "1 (metal) or 2 (passive film) at every "
                                  "node"));
      AssertThrow(Utilities::MPI::sum(counts[electrolyte], comm) > 0,
                  ExcInvalidInput(section + "/Initial phase/Function "
                                            "expression",
                                  phase_text,
                                  "no node starts as electrolyte (phase 0): "
                                  "corrosion needs an initial electrolyte "
                                  "region (a pit, a layer over the metal)"));
      AssertThrow(Utilities::MPI::sum(counts[metal], comm) > 0,
                  ExcInvalidInput(section + "/Initial phase/Function "
                                            "expression",
                                  phase_text,
                                  "no node starts as metal (phase 1): there "
                                  "is nothing to corrode"));
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        c.local_element(setup.vector_index[i]) =
          phase[i] == electrolyte ? c_electrolyte : c_solid;
      n_converted_local = 0;
      configure_operator(setup);

      if (with_damage)
        {
          mechanical.reinit(nodes, setup.lists);
          c.update_ghost_values();
          update_damage(setup, c);
          c.zero_out_ghost_values();
        }
    }


    template <int dim>
    void
    Corrosion<dim>::configure_operator(const DiffusionSetup<dim> &setup) const
    {
      setup.set_phases(
        {phase,
         3,
         factor,
         salt_film ? c_sat : std::numeric_limits<double>::infinity(),
         rate});
    }


    template <int dim>
    double
    Corrosion<dim>::largest_time_step(const DiffusionSetup<dim> &setup) const
    {
      // No node may gain more than C_sat by dissolution in one step.
      if (rho > 0)
        return c_sat / (rho * setup.largest_row_sum());
      return std::numeric_limits<double>::infinity();
    }


    template <int dim>
    typename DiffusionModel<dim>::TimeStepLimit
    Corrosion<dim>::time_step_limit() const
    {
      return {"no node may gain more than '" + section +
                "/Saturation concentration' = " + c_sat_text +
                " by dissolution in one step at 'Current density' = " +
                current_density_text,
              section + "/Current density",
              current_density_text};
    }


    template <int dim>
    double
    Corrosion<dim>::damage_variable(const unsigned int i, const double ci) const
    {
      if (phase[i] == electrolyte)
        return 1;
      if (phase[i] == passive)
        return 0;
      return std::clamp((c_solid - ci) / (c_solid - c_sat), 0., 1.);
    }


    template <int dim>
    void
    Corrosion<dim>::after_step(const DiffusionSetup<dim> &setup,
                               const double,
                               VectorType &c,
                               const bool  record)
    {
      // Phase change: every process decides for every node it holds from
      // the same (ghost-exchanged) values.
      c.update_ghost_values();
      bool changed = false;
      for (unsigned int i = 0; i < setup.nodes.size(); ++i)
        if (phase[i] == metal && c.local_element(setup.vector_index[i]) < c_sat)
          {
            phase[i] = electrolyte;
            changed  = true;
            if (i < setup.nodes.n_owned())
              ++n_converted_local;
          }
      if (changed)
        configure_operator(setup);
      if (with_damage && record)
        update_damage(setup, c);
      // The ghost values stay: they are those of this state, which the
      // next step's evaluation needs (no second exchange).
    }


    template <int dim>
    void
    Corrosion<dim>::update_damage(const DiffusionSetup<dim> &setup,
                                  const VectorType          &c)
    {
      const auto &nodes = setup.nodes;
      const auto  value = [&](const unsigned int i) {
        return c.local_element(setup.vector_index[i]);
      };
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          const double       phi_i   = damage_variable(i, value(i));
          const unsigned int n_bonds = setup.lists.n_bonds(i);
          if (phi_i <= 0 || mechanical.n_broken(i) == n_bonds)
            continue;
          const std::uint64_t gi = node_key(nodes[i].location);
          for (unsigned int k = 0; k < n_bonds; ++k)
            if (!mechanical.is_broken(i, k))
              {
                const unsigned int j     = mechanical.neighbor(i, k);
                const double       phi_j = damage_variable(j, value(j));
                const double       u =
                  bond_uniform(seed, gi, node_key(nodes[j].location));
                if (std::max(phi_i, phi_j) > u)
                  mechanical.break_bond(i, k);
              }
        }
      mechanical.synchronize();
    }


    template <int dim>
    std::vector<std::string>
    Corrosion<dim>::history_columns() const
    {
      return {"pit_depth",
              "pit_volume",
              "pit_volume_with_damage",
              "converted_nodes",
              "metal_amount",
              "broken_mechanical_bonds"};
    }


    template <int dim>
    std::vector<double>
    Corrosion<dim>::history_values(const DiffusionSetup<dim> &setup,
                                   const VectorType          &c) const
    {
      const auto    &nodes = setup.nodes;
      const MPI_Comm comm  = nodes.get_communicator();
      double         depth = 0, volume = 0, damaged = 0, amount = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          const double ci = c.local_element(setup.vector_index[i]);
          const double v  = nodes[i].volume();
          if (initially_metal[i] && phase[i] == electrolyte)
            {
              volume += v;
              // The far side of the node's cell along the direction.
              double reach = 0;
              for (unsigned int d = 0; d < dim; ++d)
                reach +=
                  0.5 * std::abs(depth_direction[d]) *
                  (nodes[i].cell.upper_bound(d) - nodes[i].cell.lower_bound(d));
              depth =
                std::max(depth,
                         depth_direction * (nodes[i].location - depth_origin) +
                           reach);
            }
          if (phase[i] == metal)
            {
              damaged += v * damage_variable(i, ci);
              amount += v * ci;
            }
        }
      return {Utilities::MPI::max(depth, comm),
              Utilities::MPI::sum(volume, comm),
              Utilities::MPI::sum(volume + damaged, comm),
              double(Utilities::MPI::sum(n_converted_local, comm)),
              Utilities::MPI::sum(amount, comm),
              with_damage ? double(mechanical.n_broken_global()) : 0.};
    }


    template <int dim>
    std::vector<NodeField>
    Corrosion<dim>::node_fields(const DiffusionSetup<dim> &setup,
                                const VectorType          &c) const
    {
      NodeField phase_field{"phase", {}}, corrosion{"corrosion_damage", {}},
        damage{"damage", {}};
      for (unsigned int i = 0; i < setup.nodes.n_owned(); ++i)
        {
          phase_field.values.push_back(phase[i]);
          corrosion.values.push_back(
            damage_variable(i, c.local_element(setup.vector_index[i])));
          if (with_damage)
            damage.values.push_back(mechanical.damage(i));
        }
      std::vector<NodeField> fields = {phase_field, corrosion};
      if (with_damage)
        fields.push_back(damage);
      return fields;
    }


    template <int dim>
    std::string
    Corrosion<dim>::progress_text(const std::vector<double> &values) const
    {
      std::ostringstream s;
      s << std::scientific << std::setprecision(4) << "pit depth " << values[0]
        << " m, pit volume " << values[1] << ", " << std::lround(values[3])
        << " nodes dissolved";
      return s.str();
    }


    template class Corrosion<1>;
    template class Corrosion<2>;
    template class Corrosion<3>;
  } // namespace Models
} // namespace PeriDEAL

PERIDEAL_REGISTER_DIFFUSION_MODEL(
  PeriDEAL::Models::Corrosion,
  "corrosion",
  "Pitting corrosion: metal, electrolyte and passive-film phases, "
  "dissolution at the metal-electrolyte interface (fixed rate from a "
  "current density, or an interface diffusivity), salt film, phase change "
  "below C_sat, optional mechanical damage; pit depth and volume.")
