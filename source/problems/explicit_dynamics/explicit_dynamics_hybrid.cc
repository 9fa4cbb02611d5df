/**
 * @file
 * The hybrid quadrature scheme in explicit dynamics (ExplicitDynamics,
 * `Quadrature/Scheme = hybrid`; hybrid-collocation paper Sect. 4, Eq. 65;
 * doc/collocation.md Sect. 11): the fixed standard region, the collocation
 * rows of the other nodes (linearised), the scan for bonds that near
 * failure at the end of each step where the displacement bound says one
 * may (BondOperator::critical_bond_possible()), and what the run reports.
 */

#include <deal.II/base/mpi.h>

#include <perideal/base/exceptions.h>
#include <perideal/problems/explicit_dynamics.h>
#include <perideal/problems/explicit_dynamics/explicit_dynamics_internal.h>
#include <perideal/problems/node_region.h>

#include <iomanip>
#include <sstream>

namespace PeriDEAL
{
  namespace Problems
  {
    using internal::ExplicitDynamicsImplementation::to_string;


    template <int dim>
    void
    ExplicitDynamics<dim>::check_input(const Simulator<dim> &simulator) const
    {
      TimeSteppingProblem<dim>::check_input(simulator);
      if (simulator.get_quadrature_scheme().hybrid() == nullptr)
        return;
      this->check_collocation_model(simulator);
      AssertThrow(simulator.get_node_perturbation() == 0,
                  ExcInvalidInput(
                    "Geometry/Node perturbation",
                    format_number(simulator.get_node_perturbation()),
                    "the hybrid scheme of explicit dynamics shares one "
                    "collocation row over a uniform grid (its switch bounds "
                    "the stretches on the lattice), so it needs the nodes at "
                    "the cell centres; set 0, or 'Quadrature/Scheme = "
                    "standard' (which runs on perturbed nodes)"));
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::setup_hybrid(Simulator<dim> &simulator)
    {
      hybrid = simulator.get_quadrature_scheme().hybrid();
      if (hybrid == nullptr)
        return;
      const double rho = simulator.get_model().density();
      // The time step must stay stable whatever switches later: every row
      // is then either a standard row or a collocation row, so the larger
      // of the two operators' bounds covers them all (choose_time_step()).
      standard_lambda = bond_operator.gershgorin_eigenvalue_bound(rho);
      // The power-method estimate is information only (choose_time_step()
      // prints it when a step is given or may be unstable).
      standard_power = given_time_step > 0 || allow_unstable ?
                         bond_operator.estimate_largest_eigenvalue(rho, 60) :
                         0.;

      // The fixed standard region: boxes and boundary layers, each of which
      // must hold a node.
      const auto standard = hybrid_standard_region(simulator);
      // The energy balance counts every node's bonds (positive, and no
      // jump when a node switches); the collocation nodes' forces do the
      // work, so the balance holds to the difference of the quadratures.
      bond_operator.set_collocation_energy(true);
      const auto report = bond_operator.use_collocation(
        *simulator.get_quadrature_scheme().collocation(),
        standard);
      const auto &settings = *simulator.get_quadrature_scheme().collocation();
      // Explicit steps amplify any growing mode of the rows.
      AssertThrow(report.symbol <= 1e-10,
                  ExcInvalidInput(
                    "Quadrature/collocation/Order",
                    std::to_string(settings.order),
                    "the bulk collocation row of this order at this m-ratio "
                    "has growing modes (largest symbol eigenvalue " +
                      format_number(report.symbol) +
                      " of the most negative; doc/collocation.md Sect. 7), "
                      "which explicit time stepping amplifies at any step; "
                      "use 'Order = 2'" +
                      settings.stabilisation_hint()));
      n_total_nodes    = simulator.get_summary().n_nodes;
      n_standard_nodes = n_total_nodes - report.n_collocation_nodes;
      n_switch_scans   = 0;
      std::ostringstream line;
      line << "quadrature '" << simulator.get_quadrature_scheme_name()
           << "': order " << settings.order << ", " << report.n_collocation
           << " collocation nodes (" << report.n_monomials
           << " monomials), cond(A) " << std::setprecision(2) << std::scientific
           << report.condition << std::defaultfloat << "; "
           << report.n_collocation_nodes << " nodes by collocation, "
           << report.n_fixed_standard << " standard (fixed region), "
           << n_standard_nodes - report.n_fixed_standard
           << " standard (ball cut by the surface or a pre-crack"
           << (report.n_ill_conditioned > 0 ? ", or ill-conditioned cloud" : "")
           << "); "
           << (hybrid->adaptive ?
                 "adaptive, critical stretch fraction " +
                   to_string(hybrid->alpha) + ", scan " +
                   (hybrid->scan_every_step ? "every step" :
                                              "by the displacement bound") :
                 std::string("fixed"));
      simulator.get_pcout() << "           " << line.str() << std::endl;
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::update_hybrid(Simulator<dim> &simulator)
    {
      if (hybrid == nullptr)
        return;
      TimerOutput::Scope scope(simulator.get_timer(), "hybrid switch");
      // The count for the energy row and the progress line (the nodes
      // that commit_broken_bonds() switched included).
      if (records_energies())
        {
          n_standard_nodes =
            n_total_nodes - bond_operator.n_collocation_nodes();
          // Late switches, checked with the energy rows (a reduction there
          // already): the first one is reported while the run goes on.
          if (hybrid->adaptive && !late_switch_warned &&
              bond_operator.n_missed_switches() > 0)
            {
              late_switch_warned = true;
              simulator.get_pcout()
                << "Warning: by step " << step_number
                << " (t = " << to_string(time)
                << " s) a bond of a collocation node "
                << "broke or passed its critical stretch before the node "
                   "switched (a late switch: the bond went from below "
                   "'Quadrature/hybrid/Critical stretch fraction' = "
                << to_string(hybrid->alpha)
                << " of its critical stretch to beyond it within one step, "
                   "or broke from its standard end first, so it broke up "
                   "to one step late). A smaller fraction switches earlier; "
                   "the count is in the summary at the end."
                << std::endl;
            }
        }
      // Fixed: a bond of a collocation node that broke from its standard
      // end this step (commit_broken_bonds() then switched the node) means
      // the crack has left the region, as a scan would find.
      const std::size_t broken_at_collocation =
        hybrid->adaptive ? 0 : bond_operator.n_missed_switches();
      // With the bound, only the chunks it found due are scanned.
      const bool by_bound =
        broken_at_collocation == 0 && !hybrid->scan_every_step;
      if (by_bound && !bond_operator.critical_bond_possible(u))
        return;
      ++n_switch_scans;
      const double      fraction = hybrid->adaptive ? hybrid->alpha : 1.;
      const std::size_t n =
        bond_operator.switch_critical_nodes(u,
                                            fraction,
                                            hybrid->adaptive,
                                            by_bound);
      if (hybrid->adaptive)
        n_standard_nodes = n_total_nodes - bond_operator.n_collocation_nodes();
      else
        AssertThrow(n + broken_at_collocation == 0,
                    ExcMessage(
                      "At step " + std::to_string(step_number) +
                      " (t = " + to_string(time) + " s) " +
                      std::to_string(n + broken_at_collocation) +
                      " collocation node(s) have a bond at its critical "
                      "stretch: the crack has left the fixed standard region "
                      "of 'Quadrature/hybrid' (collocation nodes cannot "
                      "break bonds). Enlarge 'Standard boxes', or set "
                      "'Configuration = adaptive'. The output written before "
                      "is complete."));
    }


    template <int dim>
    void
    ExplicitDynamics<dim>::print_hybrid_summary(Simulator<dim> &simulator)
    {
      if (hybrid == nullptr)
        return;
      const std::size_t missed  = bond_operator.n_missed_switches();
      const auto        scanned = bond_operator.n_scanned_nodes();
      simulator.get_pcout()
        << "           hybrid: " << n_standard_nodes << " of " << n_total_nodes
        << " nodes standard at the end (" << std::setprecision(3)
        << 100. * n_standard_nodes / std::max<std::size_t>(n_total_nodes, 1)
        << " %), " << n_switch_scans << " bond scans in "
        << step_number - loop_start_step << " steps, " << scanned.first
        << " node scans (" << std::setprecision(3)
        << 100. * scanned.first / std::max<std::size_t>(scanned.second, 1)
        << " % of a scan of every collocation node at every step), " << missed
        << " late switches (a bond of a collocation node broke or was past "
           "its critical stretch when found)"
        << std::defaultfloat << std::endl;
      if (missed > 0 && hybrid->adaptive)
        simulator.get_pcout()
          << "Warning: " << missed
          << " late switches: those bonds broke up to one step later than "
             "the standard scheme would break them. Lower "
             "'Quadrature/hybrid/Critical stretch fraction' (now "
          << to_string(hybrid->alpha)
          << ") to switch earlier (doc/collocation.md, 'Late switches')."
          << std::endl;
    }


    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, setup_hybrid, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, update_hybrid, )
    PERIDEAL_INSTANTIATE_EXPLICIT_DYNAMICS(void, print_hybrid_summary, )
    template void
    ExplicitDynamics<2>::check_input(const Simulator<2> &) const;
    template void
    ExplicitDynamics<3>::check_input(const Simulator<3> &) const;
  } // namespace Problems
} // namespace PeriDEAL
