#ifndef perideal_problems_bond_failure_h
#define perideal_problems_bond_failure_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/parameter_handler.h>

#include <perideal/discretization/bond_state.h>
#include <perideal/discretization/crack_geometry.h>
#include <perideal/discretization/neighbor_list.h>
#include <perideal/problems/problem_type.h>
#include <perideal/problems/simulator.h>

#include <string>
#include <vector>

namespace PeriDEAL
{
  namespace Problems
  {
    /**
     * Where bonds may fail and where they start broken: the entries
     * 'Pre-cracks', 'No-fail boxes', 'No-fail boundary ids' and 'No-fail
     * layer thickness', declared in the subsection of each problem type
     * that breaks bonds (explicit dynamics, quasi-static) by this one class,
     * so that both read them, check them and apply them alike. The critical
     * stretch itself is the material model's (Models::Model::
     * critical_stretch(): 'Critical stretch' or 'Fracture energy').
     */
    template <int dim>
    class BondFailure
    {
    public:
      /// Declare the four entries in the current subsection.
      static void
      declare_parameters(ParameterHandler &prm);

      /// Read them from the current subsection, named @p section in
      /// messages ("explicit dynamics").
      void
      parse_parameters(ParameterHandler &prm, const std::string &section);

      /// 'No-fail layer thickness' without 'No-fail boundary ids'.
      std::vector<UnusedEntry>
      unused_entries() const;

      /**
       * The critical stretch of every node (owned and ghost) of the
       * simulator: the model's, infinite in the no-fail boxes and layers
       * (each of which must hold a node). Collective.
       */
      std::vector<double>
      critical_stretches(const Simulator<dim> &simulator) const;

      /**
       * Break the bonds of @p lists that cross the pre-cracks in
       * @p bond_state; every pre-crack must cut a bond (else the entry is
       * named). Returns the number of bonds cut on all processes.
       * Collective.
       */
      std::size_t
      cut_pre_cracks(const Simulator<dim>                    &simulator,
                     const Discretization::NeighborList<dim> &lists,
                     Discretization::BondState<dim>          &bond_state) const;

      bool
      has_pre_cracks() const
      {
        return !pre_cracks.empty();
      }

      /// Whether any no-fail region is given.
      bool
      has_no_fail_region() const
      {
        return !no_fail_boxes.empty() || !no_fail_ids.empty();
      }

      const std::vector<types::boundary_id> &
      no_fail_boundary_ids() const
      {
        return no_fail_ids;
      }

    private:
      std::string                     section;
      std::string                     pre_crack_text, no_fail_text;
      Discretization::PreCracks<dim>  pre_cracks;
      std::vector<BoundingBox<dim>>   no_fail_boxes;
      std::vector<types::boundary_id> no_fail_ids;
      std::string                     no_fail_ids_text, no_fail_thickness_text;
      double                          no_fail_thickness = 1;
    };
  } // namespace Problems
} // namespace PeriDEAL

#endif
