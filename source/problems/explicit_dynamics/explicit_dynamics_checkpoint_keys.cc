/**
 * @file
 * What defines the state of an explicit dynamics checkpoint
 * (ExplicitDynamics::CheckpointKey): the input entries, read from the
 * whole parameter tree, and the properties of the discretisation (node
 * count, bounding box and hash, horizon, bonds, critical stretch, energy
 * columns, time step).
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_checkpoint_format.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <array>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsCheckpoint::Checksum;
    using internal::ExplicitDynamicsCheckpoint::hex;


    namespace
    {
      /// All the digits of a double: keys compare as text.
      std::string
      exact(const double x)
      {
        char buffer[32];
        std::snprintf(buffer, sizeof(buffer), "%.17g", x);
        return buffer;
      }

      /// An entry name of ParameterHandler's tree (every character but
      /// [a-zA-Z0-9] is written as '_' and two hexadecimal digits).
      std::string
      demangle(const std::string &name)
      {
        std::string result;
        for (std::size_t k = 0; k < name.size(); ++k)
          if (name[k] == '_' && k + 2 < name.size())
            {
              result += static_cast<char>(
                std::stoi(name.substr(k + 1, 2), nullptr, 16));
              k += 2;
            }
          else
            result += name[k];
        return result;
      }

      /// Every entry of the tree as 'subsection/.../entry' = value.
      void
      collect_entries(const boost::property_tree::ptree  &section,
                      const std::string                  &prefix,
                      std::map<std::string, std::string> &entries)
      {
        for (const auto &[key, child] : section)
          {
            const std::string name = prefix + demangle(key);
            if (const auto value = child.get_optional<std::string>("value"))
              entries[name] = *value;
            else
              collect_entries(child, name + "/", entries);
          }
      }
    } // namespace


    template <int dim>
    void
    ExplicitDynamics<dim>::parse_checkpoint_parameters(ParameterHandler &prm)
    {
      overwrite_checkpoint = prm.get_bool("Overwrite checkpoint");
      AssertThrow(!(resume && overwrite_checkpoint),
                  ExcInvalidInput("explicit dynamics/Overwrite checkpoint",
                                  "true",
                                  "a run with 'Resume from checkpoint = "
                                  "true' continues its checkpoint and "
                                  "replaces no other; set it to false (it "
                                  "lets a run that starts afresh replace a "
                                  "checkpoint)"));

      // The entries live all over the file, and this is called inside the
      // subsection 'explicit dynamics': read them from the whole tree.
      std::stringstream json;
      prm.print_parameters(json, ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      std::map<std::string, std::string> entries;
      collect_entries(tree, "", entries);

      checkpoint_inputs.clear();
      const auto add = [&](const std::string &name) {
        const auto entry = entries.find(name);
        AssertThrow(entry != entries.end(), ExcInternalError());
        checkpoint_inputs.push_back({name, entry->second, true, ""});
      };
      const auto add_all_under = [&](const std::string &section) {
        for (const auto &[name, value] : entries)
          if (name.rfind(section + "/", 0) == 0)
            checkpoint_inputs.push_back({name, value, true, ""});
      };
      add("Dimension");
      add("Material model/Model");
      add_all_under("Material model/" + entries["Material model/Model"]);
      add("Horizon/Specification");
      add(entries["Horizon/Specification"] == "m-ratio" ? "Horizon/m-ratio" :
                                                          "Horizon/Length");
      add("Partial volumes/Algorithm");
      add_all_under("Partial volumes/" + entries["Partial volumes/Algorithm"]);
      // The quadrature scheme and its entries (none for the standard
      // scheme: its checkpoints keep the keys they had before there were
      // others).
      if (entries["Quadrature/Scheme"] != "standard")
        {
          add("Quadrature/Scheme");
          add_all_under("Quadrature/collocation");
          add_all_under("Quadrature/hybrid");
        }
      // The mesh file's content is in the hash of the node positions.
      add("Geometry/Mesh");
      if (entries["Geometry/Mesh"] == "subdivided box")
        for (const char *name :
             {"Lower corner", "Upper corner", "Subdivisions"})
          add(std::string("Geometry/") + name);
      add("Geometry/Global refinements");
      // Irregular nodes (none for nodes at the centres: those checkpoints
      // keep their keys; the positions are in the hash as well).
      if (std::stod(entries["Geometry/Node perturbation"]) != 0)
        {
          add("Geometry/Node perturbation");
          add("Geometry/Random seed");
        }
      std::vector<std::string> own = {"Kinematics",
                                      "Pre-cracks",
                                      "No-fail boxes",
                                      "No-fail boundary ids",
                                      "Probe points",
                                      "Crack tip origin",
                                      "Crack tip region",
                                      "Crack tip damage",
                                      "End time",
                                      "Time step"};
      if (!failure.no_fail_boundary_ids().empty())
        own.push_back("No-fail layer thickness");
      if (given_time_step == 0)
        own.push_back("Safety factor");
      for (const auto &name : own)
        add("explicit dynamics/" + name);
    }


    template <int dim>
    const std::vector<typename ExplicitDynamics<dim>::CheckpointKey> &
    ExplicitDynamics<dim>::checkpoint_keys(Simulator<dim> &simulator)
    {
      if (!checkpoint_state_keys.empty())
        return checkpoint_state_keys;
      const auto    &nodes = simulator.get_nodes();
      const MPI_Comm comm  = simulator.get_communicator();

      // One checksum per node, of its position and volume, summed (mod
      // 2^64): the total does not depend on the partition.
      std::uint64_t           node_sum = 0;
      std::array<double, dim> lower, upper;
      lower.fill(std::numeric_limits<double>::infinity());
      upper.fill(-std::numeric_limits<double>::infinity());
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        {
          Checksum node;
          for (unsigned int d = 0; d < dim; ++d)
            {
              const double x = nodes[i].location[d];
              node.add(reinterpret_cast<const char *>(&x), sizeof(x));
              lower[d] = std::min(lower[d], x);
              upper[d] = std::max(upper[d], x);
            }
          const double volume = nodes[i].volume();
          node.add(reinterpret_cast<const char *>(&volume), sizeof(volume));
          // A final mix (splitmix64), so that sums of similar nodes do not
          // cancel.
          std::uint64_t z = node.value;
          z               = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
          z               = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
          node_sum += z ^ (z >> 31);
        }
      node_sum        = Utilities::MPI::sum(node_sum, comm);
      std::string box = "(";
      for (unsigned int d = 0; d < dim; ++d)
        box += (d > 0 ? ", " : "") + exact(Utilities::MPI::min(lower[d], comm));
      box += ") to (";
      for (unsigned int d = 0; d < dim; ++d)
        box += (d > 0 ? ", " : "") + exact(Utilities::MPI::max(upper[d], comm));
      box += ")";
      const std::uint64_t n_nodes =
        Utilities::MPI::sum<std::uint64_t>(nodes.n_owned(), comm);
      const std::uint64_t n_bonds = Utilities::MPI::sum<std::uint64_t>(
        simulator.get_neighbor_lists().n_owned_bonds(),
        comm);

      // The columns of the energy file, as write_output() writes them.
      std::string columns = "time,step,kinetic_energy,elastic_energy,"
                            "external_work,energy_balance,broken_bonds";
      if (hybrid != nullptr)
        columns += ",standard_nodes";
      for (unsigned int k = 0; k < probe_points.size(); ++k)
        for (unsigned int c = 0; c < dim; ++c)
          columns += ",probe" + std::to_string(k) + "_u" + "xyz"[c];
      if (crack_tip.enabled())
        for (const auto &name : crack_tip.column_names())
          columns += "," + name;

      const std::string mesh =
        "the mesh: 'Geometry/...' or the content of 'Geometry/Mesh file'";
      checkpoint_state_keys = checkpoint_inputs;
      const auto add        = [&](const std::string &name,
                           const std::string &value,
                           const std::string &hint) {
        checkpoint_state_keys.push_back({name, value, false, hint});
      };
      add("number of nodes", std::to_string(n_nodes), mesh);
      add("bounding box of the nodes", box, mesh);
      add("hash of the node positions and volumes", hex(node_sum), mesh);
      add("horizon",
          exact(simulator.get_horizon()),
          "'Horizon/...' and the mesh");
      add("number of bonds",
          std::to_string(n_bonds),
          "the horizon, the mesh and 'Partial volumes/Algorithm'");
      add("critical stretch",
          exact(
            simulator.get_model().critical_stretch(simulator.get_horizon())),
          "the failure constants of 'Material model' and the horizon");
      add("energy file columns",
          columns,
          "'explicit dynamics/Probe points' and 'Crack tip origin', and "
          "'Quadrature/Scheme' (hybrid: standard_nodes)");
      add("time step",
          exact(dt),
          "'explicit dynamics/End time', 'Time step' and 'Safety factor', "
          "the mesh and the material constants");
      add("number of steps",
          std::to_string(n_steps),
          "'explicit dynamics/End time' and the time step");
      return checkpoint_state_keys;
    }


    template void
    ExplicitDynamics<2>::parse_checkpoint_parameters(ParameterHandler &);
    template void
    ExplicitDynamics<3>::parse_checkpoint_parameters(ParameterHandler &);
    template const std::vector<ExplicitDynamics<2>::CheckpointKey> &
    ExplicitDynamics<2>::checkpoint_keys(Simulator<2> &);
    template const std::vector<ExplicitDynamics<3>::CheckpointKey> &
    ExplicitDynamics<3>::checkpoint_keys(Simulator<3> &);
  } // namespace Problems
} // namespace PeriDEAL
