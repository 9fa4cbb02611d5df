// Throughput of the matrix-free DiffusionOperator (one scalar per node)
// against the BondOperator (dim components per node; bond-based PMB and the
// LPS, whose two passes are both counted) on the same uniform box, the same
// node set and the same neighbour lists: node x neighbour visits per second
// per core, on 1 thread and on all threads (MultithreadInfo::
// set_thread_limit).
//
//   perideal-diffusion-throughput [--quick] [--n2 N] [--n3 N] [--m M]
//                                 [--repetitions R] [--output-dir DIR]
//
// --n2, --n3: cells per side of the 2D and 3D unit box (defaults 1024 and
// 64; --quick: 128 and 16, 2 repetitions); 0 leaves that dimension out.
// --m: horizon over spacing (3). Each apply() is timed R times (default 5)
// after one warm-up call and the fastest is reported.
//
// Writes DIR/diffusion_throughput.csv (default results/diffusion), one
// line per dimension, operator and thread count. Two rates are given:
//  - visits: the operator's own count of one apply() (n_bond_visits();
//    the LPS counts its dilatation and force passes, so twice the pairs);
//  - pairs: node x neighbour pairs of the lists (NeighborList::
//    n_owned_bonds()), the same for every operator on a mesh, so that the
//    pair rates compare the cost of evaluating the same operator graph.
// Under mpirun every process works on its part and the figures are totals
// over all processes (per core: divided by processes x threads).

#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/timer.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/diffusion_kernel.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/operators/diffusion_operator.h>
#include <perideal/quadrature/exact_partial_volume.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;

namespace
{
  struct Row
  {
    std::string  name;
    unsigned int threads           = 1;
    double       seconds_per_apply = 0;
    std::size_t  visits            = 0;
    unsigned int stencil_nodes     = 0;
  };

  /// Fastest of @p repetitions calls of @p f (after one warm-up call), the
  /// largest over the processes.
  template <typename Function>
  double
  best_time(const Function &f, const unsigned int repetitions)
  {
    f();
    double best = 1e300;
    for (unsigned int r = 0; r < repetitions; ++r)
      {
        Timer timer;
        f();
        best = std::min(best, timer.wall_time());
      }
    return Utilities::MPI::max(best, MPI_COMM_WORLD);
  }

  /// The unit box with @p n cells per side: n = s 2^r as s^dim coarse cells
  /// refined r times (few coarse cells for p4est).
  template <int dim>
  void
  make_box(parallel::distributed::Triangulation<dim> &tria,
           const unsigned int                         n)
  {
    unsigned int s = n, r = 0;
    while (s % 2 == 0 && s > 1)
      {
        s /= 2;
        ++r;
      }
    GridGenerator::subdivided_hyper_cube(tria, s, 0, 1);
    tria.refine_global(r);
  }

  template <int dim>
  void
  measure(const unsigned int n_cells,
          const double       m_ratio,
          const unsigned int repetitions,
          const unsigned int max_threads,
          std::ostream      &csv,
          const bool         root)
  {
    const MPI_Comm                            comm = MPI_COMM_WORLD;
    const unsigned int                        n_ranks =
      Utilities::MPI::n_mpi_processes(comm);
    // 1 thread and all threads.
    std::vector<unsigned int> thread_counts = {1};
    if (max_threads > 1)
      thread_counts.push_back(max_threads);
    parallel::distributed::Triangulation<dim> tria(comm);
    make_box(tria, n_cells);
    DoFHandler<dim> dof_handler(tria);
    FESystem<dim>   fe(FE_DGQ<dim>(0), dim);
    dof_handler.distribute_dofs(fe);

    const double                 h       = 1. / n_cells;
    const double                 horizon = m_ratio * h;
    Discretization::NodeSet<dim> nodes;
    nodes.reinit(dof_handler, 2 * (horizon + std::sqrt(dim) * h));
    // One set of lists for all operators: with the lists of off-process
    // neighbours (the LPS needs them), full stencils not stored (as the
    // explicit-dynamics and diffusion problems build them).
    const PeriDEAL::Quadrature::ExactPartialVolume<dim> exact;
    Discretization::NeighborList<dim>                   lists;
    {
      Timer timer;
      lists.reinit(nodes, horizon, exact, true, false);
      if (root)
        std::cout << dim << "D: " << tria.n_global_active_cells()
                  << " nodes, m = " << m_ratio << ", lists in "
                  << timer.wall_time() << " s" << std::endl;
    }
    const std::size_t pairs =
      Utilities::MPI::sum(lists.n_owned_bonds(), comm);
    const unsigned int n_nodes = tria.n_global_active_cells();

    std::vector<Row> rows;

    // Diffusion: K = 1, q = 2, constant influence.
    {
      ParameterHandler prm;
      Models::DiffusionKernel::declare_parameters(prm);
      prm.set("Diffusivity", "1");
      prm.set("Flux exponent", "2");
      prm.set("Influence function", "constant");
      Models::DiffusionKernel kernel;
      kernel.parse_parameters(prm, "diffusion");
      kernel.reinit(dim, horizon);
      Operators::DiffusionOperator<dim> op;
      op.reinit(nodes, lists, kernel);
      typename Operators::DiffusionOperator<dim>::VectorType c, lc;
      op.initialize_vector(c);
      op.initialize_vector(lc);
      for (unsigned int k = 0; k < c.locally_owned_size(); ++k)
        c.local_element(k) = std::sin(0.1 * k);
      c.update_ghost_values();
      for (const unsigned int t : thread_counts)
        {
          MultithreadInfo::set_thread_limit(t);
          Row row;
          row.name              = "diffusion";
          row.threads           = t;
          row.seconds_per_apply = best_time([&]() { op.apply(c, lc); },
                                            repetitions);
          row.visits        = Utilities::MPI::sum(op.n_bond_visits(), comm);
          row.stencil_nodes = Utilities::MPI::sum(op.n_stencil_nodes(), comm);
          rows.push_back(row);
        }
    }

    // The BondOperator, bond-based (PMB) and LPS, constant influence.
    for (const std::string model_name :
         {"bond-based", "linear peridynamic solid"})
      {
        MultithreadInfo::set_thread_limit(max_threads);
        ParameterHandler prm;
        Models::ModelRegistry<dim>::declare_parameters(prm);
        prm.enter_subsection(model_name);
        prm.set("Poisson's ratio", model_name == "bond-based" ? "0.25" : "0.3");
        prm.set("Influence function", "constant");
        prm.leave_subsection();
        const auto model = Models::ModelRegistry<dim>::create(model_name, prm);
        Operators::BondOperator<dim> op;
        op.reinit(nodes, lists, *model, horizon);
        typename Operators::BondOperator<dim>::VectorType u, f;
        op.initialize_dof_vector(u);
        op.initialize_dof_vector(f);
        for (unsigned int k = 0; k < u.locally_owned_size(); ++k)
          u.local_element(k) = std::sin(0.1 * k);
        u.update_ghost_values();
        for (const unsigned int t : thread_counts)
          {
            MultithreadInfo::set_thread_limit(t);
            Row row;
            row.name = model_name == "bond-based" ? "bond-based (PMB)" : "LPS";
            row.threads           = t;
            row.seconds_per_apply = best_time([&]() { op.apply(u, f); },
                                              repetitions);
            row.visits        = Utilities::MPI::sum(op.n_bond_visits(), comm);
            row.stencil_nodes = Utilities::MPI::sum(op.n_stencil_nodes(), comm);
            rows.push_back(row);
          }
      }
    MultithreadInfo::set_thread_limit(max_threads);

    double diffusion_time[2] = {0, 0};
    for (const auto &row : rows)
      if (row.name == "diffusion")
        diffusion_time[row.threads == 1 ? 0 : 1] = row.seconds_per_apply;
    for (const auto &row : rows)
      {
        const double cores         = double(row.threads) * n_ranks;
        const double visit_rate    = row.visits / row.seconds_per_apply;
        const double pair_rate     = pairs / row.seconds_per_apply;
        const double vs_diffusion  =
          row.seconds_per_apply / diffusion_time[row.threads == 1 ? 0 : 1];
        if (root)
          {
            std::cout << "  " << std::setw(17) << std::left << row.name
                      << std::right << " ranks " << n_ranks << " threads "
                      << row.threads << ": " << std::scientific
                      << std::setprecision(3) << row.seconds_per_apply
                      << " s/apply, " << std::defaultfloat
                      << std::setprecision(4) << visit_rate / cores / 1e6
                      << " M visits/s/core, " << pair_rate / cores / 1e6
                      << " M pairs/s/core, " << std::setprecision(3)
                      << vs_diffusion << "x the diffusion apply" << std::endl;
            csv << dim << ",\"" << row.name << "\"," << m_ratio << ','
                << n_nodes << ',' << row.stencil_nodes << ',' << n_ranks << ','
                << row.threads << ',' << std::setprecision(6)
                << row.seconds_per_apply << ',' << row.visits << ',' << pairs
                << ',' << visit_rate << ',' << visit_rate / cores << ','
                << pair_rate / cores << ',' << vs_diffusion << '\n';
          }
      }
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
  std::string                      output_dir = "results/diffusion";
  int                              n2 = -1, n3 = -1, repetitions = -1;
  double                           m_ratio = 3;
  const auto usage = []() {
    std::cerr << "usage: perideal-diffusion-throughput [--quick] [--n2 N] "
                 "[--n3 N] [--m M] [--repetitions R] [--output-dir DIR]\n";
    return 1;
  };
  for (int a = 1; a < argc; ++a)
    {
      const std::string arg  = argv[a];
      const bool        more = a + 1 < argc;
      try
        {
          if (arg == "--quick")
            quick = true;
          else if (arg == "--output-dir" && more)
            output_dir = argv[++a];
          else if (arg == "--n2" && more)
            n2 = std::stoi(argv[++a]);
          else if (arg == "--n3" && more)
            n3 = std::stoi(argv[++a]);
          else if (arg == "--m" && more)
            m_ratio = std::stod(argv[++a]);
          else if (arg == "--repetitions" && more)
            repetitions = std::stoi(argv[++a]);
          else
            return usage();
        }
      catch (const std::exception &)
        {
          return usage();
        }
    }
  if (n2 < 0)
    n2 = quick ? 128 : 1024;
  if (n3 < 0)
    n3 = quick ? 16 : 64;
  if (repetitions < 0)
    repetitions = quick ? 2 : 5;
  if (repetitions < 1 || !(m_ratio > 0) ||
      (n2 > 0 && n2 < 2 * m_ratio + 2) || (n3 > 0 && n3 < 2 * m_ratio + 2))
    return usage();

  const bool         root        = Utilities::MPI::this_mpi_process(comm) == 0;
  const unsigned int max_threads = MultithreadInfo::n_threads();
  std::ofstream      csv;
  if (root)
    {
      std::filesystem::create_directories(output_dir);
      csv.open(output_dir + "/diffusion_throughput.csv");
      csv << "dim,operator,m_ratio,n_nodes,stencil_nodes,ranks,threads,"
             "seconds_per_apply,visits,pairs,visits_per_second,"
             "visits_per_second_per_core,pairs_per_second_per_core,"
             "time_over_diffusion\n";
    }
  if (n2 > 0)
    measure<2>(n2, m_ratio, repetitions, max_threads, csv, root);
  if (n3 > 0)
    measure<3>(n3, m_ratio, repetitions, max_threads, csv, root);
  if (root)
    {
      csv.close();
      if (!csv)
        {
          std::cerr << "could not write " << output_dir
                    << "/diffusion_throughput.csv\n";
          return 1;
        }
    }
  return 0;
}
