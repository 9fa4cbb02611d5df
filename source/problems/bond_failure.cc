// The failure entries shared by the problem types that break bonds.

#include <deal.II/base/mpi.h>

#include <perideal/base/exceptions.h>
#include <perideal/boundary/boundary_layers.h>
#include <perideal/problems/bond_failure.h>
#include <perideal/problems/node_region.h>

#include <cmath>
#include <limits>

namespace PeriDEAL
{
  namespace Problems
  {
    template <int dim>
    void
    BondFailure<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Pre-cracks",
        "",
        Patterns::Anything(),
        "Bonds that cross these start broken. 2D: segments 'x1, y1, x2, y2', "
        "3D: planar polygons 'x1, y1, z1, x2, y2, z2, x3, y3, z3, ...'; "
        "several separated by ';'. Empty: none.");
      prm.declare_entry(
        "No-fail boxes",
        "",
        Patterns::Anything(),
        "Bonds with an end node in one of these boxes never break. 'xmin, "
        "ymin[, zmin], xmax, ymax[, zmax]', several separated by ';'.");
      prm.declare_entry(
        "No-fail boundary ids",
        "",
        Patterns::List(Patterns::Integer(0, 254)),
        "Bonds with an end node closer than 'No-fail layer thickness' to a "
        "boundary face with one of these ids never break: keeps loaded or "
        "gripped edges from shattering.");
      prm.declare_entry("No-fail layer thickness",
                        "1",
                        Patterns::Double(0),
                        "Thickness of the no-fail layers along 'No-fail "
                        "boundary ids', in horizons.");
    }


    template <int dim>
    void
    BondFailure<dim>::parse_parameters(ParameterHandler  &prm,
                                       const std::string &section_name)
    {
      section        = section_name;
      pre_crack_text = prm.get("Pre-cracks");
      pre_cracks.parse(pre_crack_text, section + "/Pre-cracks");
      no_fail_text = prm.get("No-fail boxes");
      no_fail_boxes =
        Discretization::parse_boxes<dim>(no_fail_text,
                                         section + "/No-fail boxes");
      no_fail_ids_text       = prm.get("No-fail boundary ids");
      no_fail_ids            = Boundary::parse_boundary_ids(no_fail_ids_text);
      no_fail_thickness_text = prm.get("No-fail layer thickness");
      no_fail_thickness      = prm.get_double("No-fail layer thickness");
      AssertThrow(no_fail_ids.empty() || no_fail_thickness > 0,
                  ExcInvalidInput(section + "/No-fail layer thickness",
                                  no_fail_thickness_text,
                                  "give a thickness > 0 (in horizons), for "
                                  "instance 1"));
    }


    template <int dim>
    std::vector<UnusedEntry>
    BondFailure<dim>::unused_entries() const
    {
      if (!no_fail_ids.empty())
        return {};
      return {{section + "/No-fail layer thickness",
               "it is the thickness of the layers along 'No-fail boundary "
               "ids', and none are given; give them, or remove the entry"}};
    }


    template <int dim>
    std::vector<double>
    BondFailure<dim>::critical_stretches(const Simulator<dim> &simulator) const
    {
      const auto  &nodes = simulator.get_nodes();
      const double s0 =
        simulator.get_model().critical_stretch(simulator.get_horizon());
      std::vector<double> critical(nodes.size(), s0);
      const auto          no_fail =
        nodes_in_region(simulator,
                        NodeRegion<dim>{no_fail_boxes,
                                        section + "/No-fail boxes",
                                        no_fail_text,
                                        "keeps no bond from failing",
                                        no_fail_ids,
                                        section + "/No-fail boundary ids",
                                        no_fail_ids_text,
                                        no_fail_thickness,
                                        section + "/No-fail layer thickness",
                                        no_fail_thickness_text,
                                        "no-fail layer"});
      for (unsigned int i = 0; i < nodes.size(); ++i)
        if (no_fail[i])
          critical[i] = std::numeric_limits<double>::infinity();
      return critical;
    }


    template <int dim>
    std::size_t
    BondFailure<dim>::cut_pre_cracks(
      const Simulator<dim>                    &simulator,
      const Discretization::NeighborList<dim> &lists,
      Discretization::BondState<dim>          &bond_state) const
    {
      const auto &nodes = simulator.get_nodes();
      double      h     = 0;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        h = std::max(h, std::pow(nodes[i].volume(), 1. / dim));
      h = Utilities::MPI::max(h, simulator.get_communicator());
      std::vector<std::size_t> cut_per_crack;
      const std::size_t        n_cut =
        pre_cracks.break_bonds(nodes,
                               lists,
                               bond_state,
                               simulator.get_horizon() + 2 * std::sqrt(dim) * h,
                               &cut_per_crack);
      AssertThrow(pre_cracks.empty() || n_cut > 0,
                  ExcInvalidInput(section + "/Pre-cracks",
                                  pre_crack_text,
                                  "no bond crosses the pre-cracks: they lie "
                                  "outside the body"));
      for (std::size_t k = 0; k < cut_per_crack.size(); ++k)
        AssertThrow(cut_per_crack[k] > 0,
                    ExcInvalidInput(section + "/Pre-cracks",
                                    pre_crack_text,
                                    "pre-crack " + std::to_string(k + 1) +
                                      " crosses no bond (that another "
                                      "pre-crack does not cross already): it "
                                      "lies outside the body; move it onto "
                                      "the body, or remove it"));
      return n_cut;
    }


    template class BondFailure<2>;
    template class BondFailure<3>;
  } // namespace Problems
} // namespace PeriDEAL
