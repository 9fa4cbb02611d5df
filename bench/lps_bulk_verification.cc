// perideal-lps-bulk-verification: the bulk-node verification of Sect. 4 of
// Scabbia, Zaccariotto, Galvanetto (2022), "Accurate computation of partial
// volumes in 3D peridynamics" (Figs. 11-13), for PeriDEAL's linear
// peridynamic solid and its 3D partial-volume algorithms.
//
//   perideal-lps-bulk-verification [--output-dir DIR] [--quick]
//
// Units. Everything is computed on the infinite uniform grid in scaled
// units: grid spacing h = 1 (cell volume V = 1), node i at the origin,
// horizon delta = m (the m-ratio). Lengths and displacements are in units of
// h, the field coefficients c_* of Eq. (45) in 1/h, moduli in Pa, force
// densities in Pa/h. Both the discrete and the analytical quantities scale
// the same way with h, so the relative errors written are unit-free.
//
// For m = (20 + k)/20, k = 0..180, and the algorithms "approximate",
// "quasi-analytical" (Taylor order N = 4) and "exact", with the beta table of
// Quadrature::UniformGridWeights<3> and the registered "linear peridynamic
// solid" (E = 1 GPa, nu = 0.2, Gaussian influence function):
//  - err_volume: Eq. (34), |(1 + sum_j beta_j) / (4/3 pi m^3) - 1|;
//  - err_weighted_volume: Eq. (37), m_i = sum_j omega_j r_j^2 beta_j against
//    m_an = (3/2 sqrt(pi) erf(1) - 5/e) pi m^5 (Eq. 36);
//  - err_C1111, err_C1122: Eq. (44), the bulk elasticity tensor of Eq. (43)
//    against K + 4 mu/3 and K - 2 mu/3 (Eq. 42);
//  - err_b1..3: Eq. (47), the force density b = -f at node i under the
//    quadratic field of Eq. (45), with the discrete LPS force of Eq. (20),
//    against b_an = -[(K + mu/3) grad div u + mu Laplace u] (the Navier
//    operator; doc/verification-bulk.md derives it and shows that the factor
//    (3K - 5 mu)/3, not /2, is right in Eq. 46 for b_1).
// All relative errors are |x / x_an - 1|; `seconds` is the wall time of the
// row (table and sums). The model enters only through its interface
// (influence, dilatation_coefficient, extension_coefficient), so the
// constants 3K - 5 mu and 15 mu of the library are what is verified; the
// analytical values use K and mu computed here from E and nu.
//
// The force is the bond sum of the test oracle (tests/common,
// Testing::reference_force_density()) on the infinite grid. Before the
// sweep, the force of the library's BondOperator at the centre node of a
// finite grid (m = 2, exact weights) is compared with this sum, so that the
// sum verified here is the library's.
//
// With --quick (m = 1, 1.25, ..., 2) the program is a smoke test that fails
// (exit code 1) unless, for exact weights, err_volume <= 1e-13 at every m and
// the C and b errors at m = 2 are within 10 % of the full sweep's values
// (QuickBounds), and the operator cross-check agrees to 1e-12.

#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/grid_generator.h>

#include <perideal/discretization/neighbor_list.h>
#include <perideal/discretization/node_set.h>
#include <perideal/models/model.h>
#include <perideal/operators/bond_operator.h>
#include <perideal/quadrature/partial_volume.h>
#include <perideal/quadrature/uniform_grid_weights.h>

#include "tests/common/reference_bond_operator.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

using namespace dealii;
using namespace PeriDEAL;
using namespace PeriDEAL::Quadrature;

namespace
{
  const char *usage =
    "Usage: perideal-lps-bulk-verification [options]\n"
    "Neighbourhood volume, weighted volume, elasticity coefficients C1111 and\n"
    "C1122 and the force density of a quadratic manufactured field at a bulk\n"
    "node, LPS with Gaussian influence (Figs. 11-13 of Scabbia et al. 2022).\n"
    "\n"
    "Options:\n"
    "  --output-dir DIR  where lps_bulk_verification.csv is written\n"
    "                    (default: results/lps_bulk_verification)\n"
    "  --quick           m in [1, 2], step 0.25, and check the exact-weight\n"
    "                    errors (smoke test; exit code 1 on failure)\n"
    "  --help            this text\n";

  [[noreturn]] void
  fail(const std::string &message)
  {
    std::cerr << "perideal-lps-bulk-verification: error: " << message << "\n\n"
              << usage;
    std::exit(1);
  }

  struct Options
  {
    std::string output_dir = "results/lps_bulk_verification";
    bool        quick      = false;
  };

  Options
  parse_command_line(int argc, char **argv)
  {
    Options o;
    for (int i = 1; i < argc; ++i)
      {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h")
          {
            std::cout << usage;
            std::exit(0);
          }
        else if (arg == "--output-dir")
          {
            if (i + 1 >= argc)
              fail("option --output-dir needs a value");
            o.output_dir = argv[++i];
          }
        else if (arg == "--quick")
          o.quick = true;
        else
          fail("unknown option '" + arg + "'");
      }
    return o;
  }

  /**
   * The --quick check. With exact weights, err_volume must be round-off
   * (<= 1e-13) at every m. At m = 2 the C and b errors must lie within
   * +-10 % of the values of the full sweep (exact weights, m = 2), given
   * below. In the bulk all five errors are |eta| times constants fixed by
   * the material and the field (11.25, 22.5, 7.45, 1.52, 15.1), where eta =
   * 5.0e-4 at m = 2 is the cubic anisotropy of the lattice fourth moment
   * (doc/verification-bulk.md), so they are deterministic to round-off
   * (~1e-9 relative): the window leaves room for compilers, and catches a
   * wrong model constant (3K - 5 mu, 15 mu, the 3/m of the dilatation), a
   * wrong b_an (the factor 1/2 of one extraction of Eq. 46 gives err_b1 =
   * 4.5e-2) or a changed force formula, and also a comparison that has
   * become trivial (an error that vanishes).
   */
  struct QuickBounds
  {
    static constexpr double volume      = 1e-13;
    static constexpr double check_m     = 2.;
    static constexpr double tolerance   = 0.1;
    static constexpr double C1111       = 5.5765685995827763e-3;
    static constexpr double C1122       = 1.1153137199167773e-2;
    static constexpr double b1          = 3.6930917878039704e-3;
    static constexpr double b2          = 7.5295441007083852e-4;
    static constexpr double b3          = 7.4935140556908753e-3;
    static constexpr double cross_check = 1e-12;
  };

  /// The material of Sect. 4.2: E = 1 GPa, nu = 0.2.
  constexpr double youngs_modulus = 1e9;
  constexpr double poissons_ratio = 0.2;
  constexpr double bulk_modulus =
    youngs_modulus / (3 * (1 - 2 * poissons_ratio));
  constexpr double shear_modulus = youngs_modulus / (2 * (1 + poissons_ratio));

  std::unique_ptr<Models::Model<3>>
  make_model()
  {
    const std::string name = "linear peridynamic solid";
    ParameterHandler  prm;
    Models::ModelRegistry<3>::declare_parameters(prm);
    prm.enter_subsection(name);
    prm.set("Elastic constants", "Young's modulus and Poisson's ratio");
    prm.set("Young's modulus", youngs_modulus);
    prm.set("Poisson's ratio", poissons_ratio);
    prm.set("Influence function", "gaussian");
    prm.leave_subsection();
    return Models::ModelRegistry<3>::create(name, prm);
  }

  /// One algorithm with its parameters, created through the registry.
  struct Variant
  {
    std::string                       name;
    std::unique_ptr<PartialVolume<3>> algorithm;
  };

  Variant
  make_variant(const std::string &name, const int taylor_order)
  {
    ParameterHandler prm;
    PartialVolumeRegistry<3>::declare_parameters(prm);
    if (taylor_order > 0)
      {
        prm.enter_subsection(name);
        prm.set("Taylor order", std::to_string(taylor_order));
        prm.leave_subsection();
      }
    return {name, PartialVolumeRegistry<3>::create(name, prm)};
  }

  /**
   * The quadratic field of Eq. (45): component k is
   * c[k][0] x^2 + c[k][1] y^2 + c[k][2] z^2 + c[k][3] xy + c[k][4] yz
   * + c[k][5] xz, with the coefficients of Sect. 4.3 (c_u5 = c_v6 = c_w4
   * = 0), in 1/h.
   */
  struct QuadraticField
  {
    std::array<std::array<double, 6>, 3> c = {
      {{{0.6, 1.3, 0.8, 0.5, 0., 1.8}},
       {{1.1, 1.6, 0.7, 1., 1.2, 0.}},
       {{0.3, 1.2, 0.1, 0., 1.7, 0.6}}}};

    Tensor<1, 3>
    value(const Tensor<1, 3> &x) const
    {
      Tensor<1, 3> u;
      for (unsigned int k = 0; k < 3; ++k)
        u[k] = c[k][0] * x[0] * x[0] + c[k][1] * x[1] * x[1] +
               c[k][2] * x[2] * x[2] + c[k][3] * x[0] * x[1] +
               c[k][4] * x[1] * x[2] + c[k][5] * x[0] * x[2];
      return u;
    }

    /// The (constant) Hessian of component @p k.
    Tensor<2, 3>
    hessian(const unsigned int k) const
    {
      Tensor<2, 3> H;
      H[0][0] = 2 * c[k][0];
      H[1][1] = 2 * c[k][1];
      H[2][2] = 2 * c[k][2];
      H[0][1] = H[1][0] = c[k][3];
      H[1][2] = H[2][1] = c[k][4];
      H[0][2] = H[2][0] = c[k][5];
      return H;
    }

    /**
     * The analytical force density in the bulk,
     * \f$b^{an} = -[(K + \mu/3)\nabla(\nabla\cdot u) + \mu \Delta u]\f$:
     * the continuum LPS force of a quadratic field is the Navier operator,
     * for any spherical influence function and horizon
     * (doc/verification-bulk.md).
     */
    Tensor<1, 3>
    analytical_force_density(const double K, const double mu) const
    {
      Tensor<1, 3> b;
      for (unsigned int p = 0; p < 3; ++p)
        {
          double grad_div = 0, laplace = 0;
          for (unsigned int k = 0; k < 3; ++k)
            {
              grad_div += hessian(k)[k][p];
              laplace += hessian(p)[k][k];
            }
          b[p] = -((K + mu / 3) * grad_div + mu * laplace);
        }
      return b;
    }
  };

  /// A bond of the node at the origin to the neighbour at an integer offset.
  struct Bond
  {
    std::array<int, 3> offset;
    Tensor<1, 3>       xi;
    Tensor<1, 3>       n;
    double             r;
    double             beta;
  };

  struct Row
  {
    double m;
    double err_volume, err_weighted_volume, err_C1111, err_C1122;
    double err_b[3];
    double seconds;
  };

  /**
   * The quantities of one row. The discrete LPS force of Eq. (20) is the
   * test oracle's bond sum (Testing::reference_force_density()),
   * \f$f_i = \sum_j [a_i(r)\theta_i + a_j(r)\theta_j + (b_i(r) + b_j(r))
   * e_{ij}]\, n_{ij}\, \beta_{ij} V\f$, with each dilatation
   * \f$\theta_k = (3/m_k)\sum_l \omega r e_{kl} \beta_{kl} V\f$ summed over
   * node k's own lattice neighbourhood (Testing::reference_dilatation()); on
   * the infinite grid every node has the same beta table and
   * \f$m_j = m_i\f$, so one list of bonds serves every node.
   */
  struct BulkNode
  {
    double            m_ratio;
    std::vector<Bond> bonds;
    double            volume;
    double            weighted_volume;

    BulkNode(const UniformGridWeights<3> &table)
      : m_ratio(table.m_ratio())
      , volume(table.neighbourhood_measure())
      , weighted_volume(0)
    {
      for (const auto &w : table.neighbours())
        {
          Bond b;
          b.offset = w.offset;
          for (unsigned int d = 0; d < 3; ++d)
            b.xi[d] = w.offset[d];
          b.r    = b.xi.norm();
          b.n    = b.xi / b.r;
          b.beta = w.beta;
          bonds.push_back(b);
        }
    }

    void
    compute_weighted_volume(const Models::Model<3> &model)
    {
      weighted_volume = 0;
      for (const Bond &b : bonds)
        weighted_volume += model.influence(b.r, m_ratio) * b.r * b.r * b.beta;
    }

    /**
     * Eq. (43) with the model's coefficients: the linearised force state
     * \f$t = a\theta + b e\f$ under a homogeneous strain \f$\varepsilon\f$
     * has stress \f$\sigma_{pq} = \sum_j t_j \xi_p\xi_q/r\, \beta_j\f$ and
     * \f$\theta = (3/m)\sum_k \omega_k \zeta_r\zeta_s \varepsilon_{rs}
     * \beta_k\f$, so \f$C_{pqrs} = (\sum_j a_j \xi_p\xi_q/r\,\beta_j)
     * (3/m)(\sum_k\omega_k\zeta_r\zeta_s\beta_k) + \sum_j b_j
     * \xi_p\xi_q\xi_r\xi_s/r^2\,\beta_j\f$; for the LPS
     * (\f$a = (3K-5\mu)\omega r/m\f$, \f$b = 15\mu\omega/m\f$) this is
     * Eq. (43). Returns {C1111, C1122}.
     */
    std::array<double, 2>
    elasticity_coefficients(const Models::Model<3> &model) const
    {
      const double mi  = weighted_volume;
      double       A11 = 0, D11 = 0, D22 = 0, B1111 = 0, B1122 = 0;
      for (const Bond &b : bonds)
        {
          const double omega = model.influence(b.r, m_ratio);
          const double a     = model.dilatation_coefficient(mi, b.r, m_ratio);
          const double e     = model.extension_coefficient(mi, b.r, m_ratio);
          const double x2 = b.xi[0] * b.xi[0], y2 = b.xi[1] * b.xi[1];
          A11 += a / b.r * x2 * b.beta;
          D11 += 3. / mi * omega * x2 * b.beta;
          D22 += 3. / mi * omega * y2 * b.beta;
          B1111 += e * x2 * x2 / (b.r * b.r) * b.beta;
          B1122 += e * x2 * y2 / (b.r * b.r) * b.beta;
        }
      return {{A11 * D11 + B1111, A11 * D22 + B1122}};
    }

    /// The internal force density f at the origin for @p field.
    Tensor<1, 3>
    force_density(const Models::Model<3> &model,
                  const QuadraticField   &field) const
    {
      const double mi = weighted_volume;
      const double mj = weighted_volume; // the same table at every node

      // Nodal displacements on the lattice cube that holds every node within
      // two horizons of the origin, looked up like the library's nodal
      // vector.
      int bound = 0;
      for (const Bond &b : bonds)
        for (const int o : b.offset)
          bound = std::max(bound, std::abs(o));
      const int                 reach = 2 * bound, side = 2 * reach + 1;
      std::vector<Tensor<1, 3>> u(std::size_t(side) * side * side);
      auto index = [&](const int x, const int y, const int z) {
        return (std::size_t(z + reach) * side + (y + reach)) * side +
               (x + reach);
      };
      for (int z = -reach; z <= reach; ++z)
        for (int y = -reach; y <= reach; ++y)
          for (int x = -reach; x <= reach; ++x)
            u[index(x, y, z)] =
              field.value(Tensor<1, 3>({double(x), double(y), double(z)}));

      // One oracle bond per table entry; its handle is the entry's number,
      // which the look-ups below turn into a stride in u.
      std::vector<Testing::ReferenceBond<3>> reference_bonds;
      std::vector<long long>                 stride(bonds.size());
      for (std::size_t k = 0; k < bonds.size(); ++k)
        {
          const Bond &b = bonds[k];
          reference_bonds.push_back(Testing::make_reference_bond<3>(model,
                                                                    m_ratio,
                                                                    k,
                                                                    b.xi,
                                                                    b.beta,
                                                                    mi,
                                                                    true,
                                                                    mj));
          stride[k] =
            (long long)(index(b.offset[0], b.offset[1], b.offset[2])) -
            (long long)(index(0, 0, 0));
        }
      auto dilatation = [&](const std::size_t node) {
        return Testing::reference_dilatation<3>(
          reference_bonds,
          u[node],
          [&](const Testing::ReferenceBond<3> &b) {
            return u[node + stride[b.neighbor]];
          });
      };

      const std::size_t  origin = index(0, 0, 0);
      const Tensor<1, 3> f      = Testing::reference_force_density<3>(
        reference_bonds,
        u[origin],
        dilatation(origin),
        [&](const Testing::ReferenceBond<3> &b) {
          return u[origin + stride[b.neighbor]];
        },
        [&](const Testing::ReferenceBond<3> &b) {
          return dilatation(origin + stride[b.neighbor]);
        });
      return f;
    }
  };

  /**
   * The library's BondOperator on a finite grid of unit cubes
   * (exact weights, horizon @p m_ratio): the nodal force (V = 1, so the
   * force density) at the centre node, for @p field centred there. The grid
   * is wide enough that the centre node and all its neighbours' neighbours
   * are interior nodes.
   */
  Tensor<1, 3>
  library_operator_force(const Models::Model<3> &model,
                         const QuadraticField   &field,
                         const double            m_ratio)
  {
    const MPI_Comm     comm  = MPI_COMM_SELF;
    const unsigned int half  = 2 * (std::ceil(m_ratio + 0.5) + 1);
    const unsigned int cells = 2 * half + 1;
    parallel::distributed::Triangulation<3> tria(comm);
    GridGenerator::subdivided_hyper_rectangle(tria,
                                              {cells, cells, cells},
                                              Point<3>(),
                                              Point<3>(cells, cells, cells));
    DoFHandler<3> dof_handler(tria);
    FESystem<3>   fe(FE_DGQ<3>(0), 3);
    dof_handler.distribute_dofs(fe);

    Discretization::NodeSet<3> nodes;
    nodes.reinit(dof_handler, 2 * (m_ratio + std::sqrt(3.)));
    Discretization::NeighborList<3> lists;
    const auto exact = PartialVolumeRegistry<3>::create("exact");
    lists.reinit(nodes, m_ratio, *exact, model.is_state_based());
    Operators::BondOperator<3> op;
    op.reinit(nodes, lists, model, m_ratio);

    const Point<3> centre(half + 0.5, half + 0.5, half + 0.5);
    Operators::BondOperator<3>::VectorType u, force;
    op.initialize_dof_vector(u);
    op.initialize_dof_vector(force);
    unsigned int centre_node = numbers::invalid_unsigned_int;
    for (unsigned int i = 0; i < nodes.n_owned(); ++i)
      {
        const Tensor<1, 3> value = field.value(nodes[i].location - centre);
        for (unsigned int c = 0; c < 3; ++c)
          u(nodes[i].dofs[c]) = value[c];
        if (nodes[i].location.distance(centre) < 1e-9)
          centre_node = i;
      }
    u.update_ghost_values();
    AssertThrow(centre_node != numbers::invalid_unsigned_int,
                ExcMessage("no node at the centre of the grid"));
    op.apply(u, force);
    Tensor<1, 3> f;
    for (unsigned int c = 0; c < 3; ++c)
      f[c] = force(nodes[centre_node].dofs[c]) / nodes[centre_node].volume();
    return f;
  }

  /// Eq. (36) in scaled units, omega = exp(-r^2/m^2).
  double
  analytical_weighted_volume(const double m)
  {
    return (1.5 * std::sqrt(M_PI) * std::erf(1.) - 5. / M_E) * M_PI *
           std::pow(m, 5);
  }

  double
  relative_error(const double x, const double x_an)
  {
    return std::abs(x / x_an - 1);
  }

  Row
  compute_row(const Variant          &variant,
              const Models::Model<3> &model,
              const QuadraticField   &field,
              const double            m)
  {
    const auto                  start = std::chrono::steady_clock::now();
    const UniformGridWeights<3> table(*variant.algorithm, m);
    BulkNode                    node(table);
    node.compute_weighted_volume(model);
    const auto                          C = node.elasticity_coefficients(model);
    const Tensor<1, 3>                  f = node.force_density(model, field);
    const std::chrono::duration<double> elapsed =
      std::chrono::steady_clock::now() - start;

    const double       K = bulk_modulus, mu = shear_modulus;
    const Tensor<1, 3> b_an = field.analytical_force_density(K, mu);
    Row                row;
    row.m          = m;
    row.err_volume = relative_error(node.volume, 4. / 3. * M_PI * m * m * m);
    row.err_weighted_volume =
      relative_error(node.weighted_volume, analytical_weighted_volume(m));
    row.err_C1111 = relative_error(C[0], K + 4. / 3. * mu);
    row.err_C1122 = relative_error(C[1], K - 2. / 3. * mu);
    for (unsigned int p = 0; p < 3; ++p)
      row.err_b[p] = relative_error(-f[p], b_an[p]);
    row.seconds = elapsed.count();
    return row;
  }

  std::string
  format(const double x)
  {
    char s[32];
    std::snprintf(s, sizeof s, "%.17g", x);
    return s;
  }

  /// Max and median of @p values; NaN if any value is not finite.
  std::array<double, 2>
  max_and_median(std::vector<double> values)
  {
    for (const double v : values)
      if (!std::isfinite(v))
        return {{std::numeric_limits<double>::quiet_NaN(),
                 std::numeric_limits<double>::quiet_NaN()}};
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    const double      median =
      n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
    return {{values.back(), median}};
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const Options                    o = parse_command_line(argc, argv);
  try
    {
      const auto           model = make_model();
      const QuadraticField field;
      bool                 passed = true;

      std::printf("LPS bulk verification: E = %g Pa, nu = %g, K = %.6g Pa, "
                  "mu = %.6g Pa, Gaussian influence\n",
                  youngs_modulus,
                  poissons_ratio,
                  bulk_modulus,
                  shear_modulus);
      const Tensor<1, 3> b_an =
        field.analytical_force_density(bulk_modulus, shear_modulus);
      std::printf("b_an = (%.6g, %.6g, %.6g) Pa/h\n",
                  b_an[0],
                  b_an[1],
                  b_an[2]);

      {
        const double          m     = QuickBounds::check_m;
        const Variant         exact = make_variant("exact", 0);
        UniformGridWeights<3> table(*exact.algorithm, m);
        BulkNode              node(table);
        node.compute_weighted_volume(*model);
        const Tensor<1, 3> f_here    = node.force_density(*model, field);
        const Tensor<1, 3> f_library = library_operator_force(*model, field, m);
        const double       difference =
          (f_here - f_library).norm() / f_library.norm();
        std::printf("BondOperator at m = %g (exact weights, "
                    "finite grid): |f - f_library| / |f_library| = %.2e\n",
                    m,
                    difference);
        if (!(difference <= QuickBounds::cross_check))
          {
            std::printf("FAILED: the sum here is not the library's force\n");
            passed = false;
          }
      }

      std::vector<Variant> variants;
      variants.push_back(make_variant("approximate", 0));
      variants.push_back(make_variant("quasi-analytical", 4));
      variants.push_back(make_variant("exact", 0));

      // m = (k0 + k)/k0, each rounded once (no repeated addition).
      const int k0 = o.quick ? 4 : 20, k_max = o.quick ? 4 : 180;

      std::filesystem::create_directories(o.output_dir);
      const std::string file_name = o.output_dir + "/lps_bulk_verification.csv";
      std::ofstream     csv(file_name);
      if (!csv)
        fail("cannot write " + file_name);
      csv << "m,algorithm,err_volume,err_weighted_volume,err_C1111,"
             "err_C1122,err_b1,err_b2,err_b3,seconds\n";

      const char *columns[] = {"err_volume",
                               "err_weighted_volume",
                               "err_C1111",
                               "err_C1122",
                               "err_b1",
                               "err_b2",
                               "err_b3"};
      std::printf("\nRelative errors over m = 1 to %g (step %g): max / median\n"
                  "%-18s",
                  double(k0 + k_max) / k0,
                  1. / k0,
                  "algorithm");
      for (const char *c : columns)
        std::printf(" %19s", c);
      std::printf(" %9s\n", "seconds");

      for (const Variant &v : variants)
        {
          std::vector<std::vector<double>> errors(7);
          double                           total_seconds = 0;
          for (int k = 0; k <= k_max; ++k)
            {
              const double m   = double(k0 + k) / k0;
              const Row    row = compute_row(v, *model, field, m);
              csv << format(m) << ',' << v.name << ',' << format(row.err_volume)
                  << ',' << format(row.err_weighted_volume) << ','
                  << format(row.err_C1111) << ',' << format(row.err_C1122)
                  << ',' << format(row.err_b[0]) << ',' << format(row.err_b[1])
                  << ',' << format(row.err_b[2]) << ',' << row.seconds << '\n';
              const double values[] = {row.err_volume,
                                       row.err_weighted_volume,
                                       row.err_C1111,
                                       row.err_C1122,
                                       row.err_b[0],
                                       row.err_b[1],
                                       row.err_b[2]};
              for (unsigned int c = 0; c < 7; ++c)
                errors[c].push_back(values[c]);
              total_seconds += row.seconds;

              if (o.quick && v.name == "exact")
                {
                  auto check = [&](const char  *what,
                                   const double error,
                                   const double lower,
                                   const double upper) {
                    if (!(error >= lower && error <= upper))
                      {
                        std::printf("FAILED: exact weights, m = %g: %s = "
                                    "%.4e is not in [%.4e, %.4e]\n",
                                    m,
                                    what,
                                    error,
                                    lower,
                                    upper);
                        passed = false;
                      }
                  };
                  auto near = [&](const char  *what,
                                  const double error,
                                  const double reference) {
                    check(what,
                          error,
                          (1 - QuickBounds::tolerance) * reference,
                          (1 + QuickBounds::tolerance) * reference);
                  };
                  check("err_volume", row.err_volume, 0., QuickBounds::volume);
                  if (m == QuickBounds::check_m)
                    {
                      near("err_C1111", row.err_C1111, QuickBounds::C1111);
                      near("err_C1122", row.err_C1122, QuickBounds::C1122);
                      near("err_b1", row.err_b[0], QuickBounds::b1);
                      near("err_b2", row.err_b[1], QuickBounds::b2);
                      near("err_b3", row.err_b[2], QuickBounds::b3);
                    }
                }
            }
          const std::string label =
            v.name == "quasi-analytical" ? "quasi-anal. N=4" : v.name;
          std::printf("%-18s", label.c_str());
          for (const auto &e : errors)
            {
              const auto s = max_and_median(e);
              std::printf(" %9.2e/%9.2e", s[0], s[1]);
            }
          std::printf(" %9.2f\n", total_seconds);
        }
      std::printf("Written: %s\n", file_name.c_str());
      if (o.quick)
        std::printf("Quick check of the exact-weight errors: %s\n",
                    passed ? "passed" : "FAILED");
      return passed ? 0 : 1;
    }
  catch (const std::exception &e)
    {
      std::cerr << "perideal-lps-bulk-verification: error: " << e.what()
                << '\n';
      return 1;
    }
}
