#include <perideal/base/exceptions.h>
#include <perideal/discretization/crack_geometry.h>
#include <perideal/io/crack_tip_tracker.h>

#include <array>

namespace PeriDEAL
{
  namespace IO
  {
    template <int dim>
    void
    CrackTipTracker<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Crack tip origin",
        "",
        Patterns::Anything(),
        "A point 'x, y[, z]', usually the tip of the pre-crack: the damaged "
        "node farthest from it is tracked as the crack tip and written to "
        "the energy file (columns tip_x, tip_y[, tip_z], tip_distance, "
        "front_spread) and the progress line. Empty: no tracking.");
      prm.declare_entry(
        "Crack tip region",
        "",
        Patterns::Anything(),
        "Boxes 'xmin, ymin[, zmin], xmax, ymax[, zmax]' (separated by ';'): "
        "only damaged nodes inside them count for the crack tip, to follow "
        "one of several cracks. Empty: the whole body.");
      prm.declare_entry("Crack tip damage",
                        "0.35",
                        Patterns::Double(0, 1),
                        "A node counts as cracked for the crack tip when its "
                        "damage (the lost fraction of its bonds' weight) is "
                        "at least this.");
    }


    template <int dim>
    void
    CrackTipTracker<dim>::parse_parameters(ParameterHandler  &prm,
                                           const std::string &section)
    {
      const std::string text = prm.get("Crack tip origin");
      const auto        points =
        Discretization::parse_points<dim>(text, section + "/Crack tip origin");
      AssertThrow(points.size() <= 1,
                  ExcInvalidInput(section + "/Crack tip origin",
                                  text,
                                  "give one point"));
      active = points.size() == 1;
      if (active)
        origin = points[0];
      origin_text = text;
      region_text = prm.get("Crack tip region");
      region      = Discretization::parse_boxes<dim>(region_text,
                                                section + "/Crack tip region");
      threshold = prm.get_double("Crack tip damage");
      AssertThrow(threshold > 0,
                  ExcInvalidInput(section + "/Crack tip damage",
                                  prm.get("Crack tip damage"),
                                  "give a damage above 0 (undamaged nodes "
                                  "would count), for instance 0.35"));
    }


    template <int dim>
    void
    CrackTipTracker<dim>::check_on_body(
      const Discretization::NodeSet<dim> &nodes,
      const std::string                  &section) const
    {
      if (!active)
        return;
      Discretization::check_points_in_body(nodes,
                                           {origin},
                                           section + "/Crack tip origin",
                                           origin_text);
      Discretization::nodes_in_boxes(nodes,
                                     region,
                                     section + "/Crack tip region",
                                     region_text,
                                     "counts no node for the crack tip");
    }


    template <int dim>
    std::vector<std::string>
    CrackTipTracker<dim>::column_names() const
    {
      std::vector<std::string> names;
      for (unsigned int d = 0; d < dim; ++d)
        names.push_back(std::string("tip_") + "xyz"[d]);
      names.emplace_back("tip_distance");
      names.emplace_back("front_spread");
      return names;
    }


    template <int dim>
    std::vector<double>
    CrackTipTracker<dim>::evaluate(
      const Discretization::NodeSet<dim>        &nodes,
      const std::function<double(unsigned int)> &damage,
      const double                               front_band,
      const MPI_Comm                             comm) const
    {
      const auto counts = [&](const Point<dim> &x) {
        if (region.empty())
          return true;
        for (const auto &box : region)
          if (box.point_inside(x))
            return true;
        return false;
      };
      // The cracked nodes of this process, and its candidate tip:
      // (distance, coordinates), the largest distance, ties to the lowest
      // coordinates.
      std::vector<unsigned int> cracked;
      for (unsigned int i = 0; i < nodes.n_owned(); ++i)
        if (damage(i) >= threshold && counts(nodes[i].location))
          cracked.push_back(i);
      std::array<double, dim + 1> best;
      best[0] = -1;
      for (unsigned int d = 0; d < dim; ++d)
        best[d + 1] = origin[d];
      const auto better = [](const std::array<double, dim + 1> &a,
                             const std::array<double, dim + 1> &b) {
        if (a[0] != b[0])
          return a[0] > b[0];
        for (unsigned int d = 1; d <= dim; ++d)
          if (a[d] != b[d])
            return a[d] < b[d];
        return false;
      };
      for (const unsigned int i : cracked)
        {
          std::array<double, dim + 1> candidate;
          candidate[0] = nodes[i].location.distance(origin);
          for (unsigned int d = 0; d < dim; ++d)
            candidate[d + 1] = nodes[i].location[d];
          if (better(candidate, best))
            best = candidate;
        }
      for (const auto &other : Utilities::MPI::all_gather(comm, best))
        if (better(other, best))
          best = other;

      std::vector<double> values(dim + 2, 0.);
      for (unsigned int d = 0; d < dim; ++d)
        values[d] = best[d + 1];
      if (best[0] < 0)
        return values;
      const double R = best[0];
      values[dim]    = R;

      Tensor<1, dim> direction;
      for (unsigned int d = 0; d < dim; ++d)
        direction[d] = best[d + 1] - origin[d];
      if (R > 0)
        direction /= R;
      double spread = 0;
      for (const unsigned int i : cracked)
        {
          const Tensor<1, dim> r = nodes[i].location - origin;
          if (r.norm() >= R - front_band)
            spread = std::max(spread, (r - (r * direction) * direction).norm());
        }
      values[dim + 1] = Utilities::MPI::max(spread, comm);
      return values;
    }


    template class CrackTipTracker<2>;
    template class CrackTipTracker<3>;
  } // namespace IO
} // namespace PeriDEAL
