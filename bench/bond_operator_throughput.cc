// Throughput of the matrix-free BondOperator: bond visits per second per
// core in the uniform bulk, for the LPS (two passes, both counted) and the
// bond-based model in 2D and 3D (standard quadrature, and the bond-based
// linear operator with the collocation quadrature of its full-ball nodes,
// kernel 'collocation': a visit is then one entry of the row), on 1 and 2
// threads, next to the memory
// bandwidth of the machine measured in the same run (a STREAM-like triad),
// and next to the apply() of the test oracle (Testing::ReferenceBondOperator
// of tests/common: explicit bond data, Trilinos vectors).
//
//   perideal-bond-operator-throughput [--quick] [--output-dir DIR]
//
// Writes DIR/bond_operator_throughput.csv (one line per case and thread
// count). Run under mpirun for the 1 -> 2 process comparison: every process
// works on its part, and the figures are totals over all processes.

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parallel.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include "tests/common/reference_bond_operator.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  /// Triad a = b + s c over arrays much larger than the caches: bytes per
  /// second (24 bytes per entry), on the current thread count.
  double
  stream_triad(const std::size_t n)
  {
    std::vector<double> a(n), b(n, 1.), c(n, 2.);
    auto                triad = [&]() {
      parallel::apply_to_subranges(
        std::size_t(0),
        n,
        [&](const std::size_t begin, const std::size_t end) {
          double *__restrict pa       = a.data();
          const double *__restrict pb = b.data();
          const double *__restrict pc = c.data();
          for (std::size_t k = begin; k < end; ++k)
            pa[k] = pb[k] + 3. * pc[k];
        },
        1 << 16);
    };
    triad(); // first touch
    double best = 1e300;
    for (unsigned int r = 0; r < 5; ++r)
      {
        Timer timer;
        triad();
        best = std::min(best, timer.wall_time());
      }
    return 24. * n / best;
  }

  struct Result
  {
    double       seconds_per_apply = 0;
    double       reference_seconds = 0;
    std::size_t  visits            = 0;
    unsigned int stencil           = 0; // standard or collocation bulk
    unsigned int n_nodes           = 0;
    double       bytes_per_apply   = 0;
  };

  template <int dim>
  Result
  measure(const std::string &model_name,
          const unsigned int refinements,
          const double       m_ratio,
          const unsigned int repetitions,
          const bool         with_reference,
          const bool         fracture,
          const bool         collocation)
  {
    const MPI_Comm                            comm = MPI_COMM_WORLD;
    parallel::distributed::Triangulation<dim> tria(comm);
    GridGenerator::hyper_cube(tria, 0, 1);
    tria.refine_global(refinements);
    DoFHandler<dim> dof_handler(tria);
    FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
    dof_handler.distribute_dofs(fe);

    ParameterHandler prm;
    Models::ModelRegistry<dim>::declare_parameters(prm);
    prm.enter_subsection(model_name);
    prm.set("Poisson's ratio", model_name == "bond-based" ? "0.25" : "0.3");
    prm.set("Influence function", "constant");
    prm.leave_subsection();
    const auto model = Models::ModelRegistry<dim>::create(model_name, prm);

    const double                 h       = 1. / (1u << refinements);
    const double                 horizon = m_ratio * h;
    Discretization::NodeSet<dim> nodes;
    nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim) * h));
    const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
    Discretization::NeighborList<dim>                   lists;
    lists.reinit(nodes,
                 horizon,
                 exact,
                 model->is_state_based(),
                 with_reference);
    Operators::BondOperator<dim> op;
    op.reinit(nodes, lists, *model, horizon);
    // The fracture kernel: finite kinematics and the failure test on every
    // bond (a critical stretch no bond reaches here).
    if (fracture)
      op.set_kinematics(true, std::vector<double>(nodes.size(), 1.));
    // The collocation rows (order 2, the default number of nodes) of every
    // node with a full ball.
    std::size_t n_collocation = 0;
    if (collocation)
      n_collocation =
        op.use_collocation(PeriDEAL::Quadrature::CollocationSettings())
          .n_collocation_nodes;

    typename Operators::BondOperator<dim>::VectorType u, f;
    op.initialize_dof_vector(u);
    op.initialize_dof_vector(f);
    for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
      u.local_element(k) = (fracture ? 1e-3 * h : 1.) * std::sin(0.1 * k);
    u.update_ghost_values();
    op.apply(u, f);
    double best = 1e300;
    for (unsigned int r = 0; r < repetitions; ++r)
      {
        Timer timer;
        op.apply(u, f);
        best = std::min(best, timer.wall_time());
      }
    Result result;
    result.seconds_per_apply = Utilities::MPI::max(best, comm);
    result.visits            = Utilities::MPI::sum(op.n_bond_visits(), comm);
    result.stencil =
      Utilities::MPI::sum(op.n_stencil_nodes(), comm) + n_collocation;
    result.n_nodes = tria.n_global_active_cells();
    // Least traffic of one application per owned node: copy in (read the
    // vector, write the slots), dilatation pass (read u, write s theta),
    // force pass (read u, s theta, s; write f), copy out.
    const double doubles   = model->is_state_based() ?
                               (2 * dim) + (dim + 1) + (dim + 2 + dim) + 2 * dim :
                               (2 * dim) + (dim + dim) + 2 * dim;
    result.bytes_per_apply = 8. * doubles * result.n_nodes;

    if (with_reference)
      {
        Testing::ReferenceBondOperator<dim> reference;
        reference.reinit(nodes, lists, *model, horizon);
        TrilinosWrappers::MPI::Vector ut(reference.owned_dofs(),
                                         nodes.relevant_dofs(),
                                         comm),
          uo(reference.owned_dofs(), comm), ft(reference.owned_dofs(), comm);
        for (const auto dof : reference.owned_dofs())
          uo[dof] = u[dof];
        uo.compress(VectorOperation::insert);
        ut = uo;
        Timer timer;
        reference.apply(ut, ft);
        result.reference_seconds = Utilities::MPI::max(timer.wall_time(), comm);
      }
    return result;
  }
} // namespace


int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc,
                                       argv,
                                       numbers::invalid_unsigned_int);
  const MPI_Comm                   comm       = MPI_COMM_WORLD;
  bool                             quick      = false;
  std::string                      output_dir = "results/bond_operator";
  std::vector<unsigned int>        selected;
  for (int a = 1; a < argc; ++a)
    {
      const std::string arg = argv[a];
      if (arg == "--quick")
        quick = true;
      else if (arg == "--output-dir" && a + 1 < argc)
        output_dir = argv[++a];
      else if (arg == "--case" && a + 1 < argc)
        selected.push_back(std::stoul(argv[++a]));
      else
        {
          std::cerr << "usage: perideal-bond-operator-throughput [--quick] "
                       "[--output-dir DIR] [--case I]...\n"
                       "  --case I: only the I-th case (from 0) of the list; "
                       "repeatable\n";
          return 1;
        }
    }
  const bool         root        = Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int n_ranks     = Utilities::MPI::n_mpi_processes(comm);
  const unsigned int max_threads = MultithreadInfo::n_threads();
  if (root)
    std::filesystem::create_directories(output_dir);
  std::ofstream csv;
  if (root)
    {
      csv.open(output_dir + "/bond_operator_throughput.csv");
      csv << "dim,model,kernel,m_ratio,n_nodes,stencil_nodes,ranks,threads,"
             "seconds_per_apply,bond_visits,visits_per_second,"
             "visits_per_second_per_core,stream_bytes_per_second,"
             "fraction_of_bandwidth,reference_seconds_per_apply\n";
    }

  struct Case
  {
    int          dim;
    std::string  model;
    unsigned int refinements;
    double       m_ratio;
    bool         fracture    = false;
    bool         collocation = false;
  };
  std::vector<Case> cases =
    quick ? std::vector<Case>{{3, "linear peridynamic solid", 4, 3},
                              {3, "bond-based", 4, 3},
                              {3, "bond-based", 4, 3, true},
                              {3, "bond-based", 4, 3, false, true},
                              {2, "linear peridynamic solid", 6, 3}} :
            std::vector<Case>{{3, "linear peridynamic solid", 5, 3},
                              {3, "linear peridynamic solid", 6, 3},
                              {3, "bond-based", 5, 3},
                              {3, "bond-based", 6, 3},
                              {3, "bond-based", 6, 3, true},
                              {3, "linear peridynamic solid", 6, 3, true},
                              {2, "linear peridynamic solid", 9, 3},
                              {2, "bond-based", 9, 3},
                              {2, "bond-based", 9, 3, true},
                              // Standard against collocation (issue 23):
                              // m = 4 in 3D, two grids (the share of the
                              // boundary nodes, standard in both, differs).
                              {3, "bond-based", 5, 4},
                              {3, "bond-based", 5, 4, false, true},
                              {3, "bond-based", 6, 4},
                              {3, "bond-based", 6, 4, false, true},
                              {2, "bond-based", 9, 4},
                              {2, "bond-based", 9, 4, false, true}};
  const unsigned int repetitions = quick ? 2 : 5;
  if (!selected.empty())
    {
      std::vector<Case> chosen;
      for (const unsigned int k : selected)
        {
          AssertThrow(k < cases.size(),
                      ExcMessage(
                        "--case " + std::to_string(k) + ": there are only " +
                        std::to_string(cases.size()) + " cases (0 to " +
                        std::to_string(cases.size() - 1) + ")."));
          chosen.push_back(cases[k]);
        }
      cases = chosen;
    }

  std::vector<double> bandwidth(max_threads + 1, 0.);
  for (unsigned int t = 1; t <= max_threads; ++t)
    {
      MultithreadInfo::set_thread_limit(t);
      bandwidth[t] =
        Utilities::MPI::sum(stream_triad(quick ? (1u << 22) : (1u << 25)),
                            comm);
    }

  for (const auto &c : cases)
    for (unsigned int t = 1; t <= max_threads; ++t)
      {
        MultithreadInfo::set_thread_limit(t);
        const bool reference =
          (t == 1) && c.refinements <= (c.dim == 3 ? 5 : 8) && !c.collocation;
        const Result r     = c.dim == 3 ? measure<3>(c.model,
                                                 c.refinements,
                                                 c.m_ratio,
                                                 repetitions,
                                                 reference,
                                                 c.fracture,
                                                 c.collocation) :
                                          measure<2>(c.model,
                                                 c.refinements,
                                                 c.m_ratio,
                                                 repetitions,
                                                 reference,
                                                 c.fracture,
                                                 c.collocation);
        const double rate  = r.visits / r.seconds_per_apply;
        const double cores = double(t) * n_ranks;
        const double fraction =
          r.bytes_per_apply / r.seconds_per_apply / bandwidth[t];
        if (root)
          {
            std::cout << c.dim << "D " << std::setw(25) << std::left << c.model
                      << (c.collocation ? " colloc." :
                          c.fracture    ? " fracture" :
                                          "   linear")
                      << std::right << " nodes " << std::setw(8) << r.n_nodes
                      << "  ranks " << n_ranks << "  threads " << t << ": "
                      << std::setprecision(3) << std::scientific
                      << r.seconds_per_apply << " s/apply ("
                      << r.seconds_per_apply / r.n_nodes * 1e9 << " ns/node, "
                      << r.stencil << " bulk nodes), " << rate / cores / 1e6
                      << std::defaultfloat << " M bond visits/s/core, "
                      << std::setprecision(3) << 100 * fraction
                      << " % of triad bandwidth (" << bandwidth[t] / 1e9
                      << " GB/s)";
            if (r.reference_seconds > 0)
              std::cout << "; assembled-path apply " << r.reference_seconds
                        << " s (" << r.reference_seconds / r.seconds_per_apply
                        << "x)";
            std::cout << std::endl;
            csv << c.dim << ",\"" << c.model << "\","
                << (c.collocation ? "collocation" :
                    c.fracture    ? "fracture" :
                                    "linear")
                << ',' << c.m_ratio << ',' << r.n_nodes << ',' << r.stencil
                << ',' << n_ranks << ',' << t << ',' << std::setprecision(6)
                << r.seconds_per_apply << ',' << r.visits << ',' << rate << ','
                << rate / cores << ',' << bandwidth[t] << ',' << fraction << ','
                << r.reference_seconds << '\n';
          }
      }
  return 0;
}
