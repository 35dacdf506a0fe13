// The nodal pressure system of the implicit cycle: its analytic Jacobian against central finite
// differences of its right-hand side (saturated, unsaturated and mixed states, gravity, a solid
// volumetric rate, prescribed nodes with non-zero rates, both forms), the completeness of its
// sparsity pattern, hydrostatic rest, and the balance of storage change and boundary inflow.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>

#include "numerics/pressure/pressure_system.hpp"
#include "tests/numerics/linear_soil.hpp"
#include "tests/numerics/pressure_column.hpp"

namespace unsatmpm::numerics {
namespace test_pressure_system {

using System = PressureSystem<2, LinearKernel>;

/// van_genuchten_soil's curves given as measured points (physics/monotone_table.hpp).
physics::HydraulicModel tabulated_soil() {
  const auto vg = physics::VanGenuchten::create(2e4, 0.4, 0.05, 1.0);
  const auto mualem = physics::MualemVanGenuchten::create(0.4);
  std::vector<std::array<double, 2>> retention, liquid, gas;
  for (const double s : {0.0, 2e3, 6e3, 1.5e4, 3e4, 7e4, 1.5e5, 4e5, 1e6})
    retention.push_back({s, vg.saturation(s)});
  for (const double se : {0.0, 0.2, 0.45, 0.7, 0.85, 0.95, 1.0}) {
    liquid.push_back({se, mualem.value(se)});
    gas.push_back({se, (1 - se) * (1 - se)});
  }
  return {physics::CompressibleFluid::create(1000.0, 0.0, 1e8),
          physics::IdealGas::create(1.2),
          physics::TabulatedRetention::create(retention),
          physics::TabulatedRelPerm::create(liquid, false),
          physics::TabulatedRelPerm::create(gas, true),
          2700.0,
          1e-11,
          1e-3,
          1.8e-5};
}

/// Unknowns from a nodal field: P_g = 1e4 + noise, P_l = P_g - s with the suction s a ramp in x
/// from s_left to s_right [Pa].
template <class S>
std::vector<double> state(const S& sys, const Grid<2>& grid, double s_left, double s_right,
                          unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(sys.n_unknowns(), 0.0);  // inflow integrals 0
  for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k) {
    const auto [node, fluid] = sys.unknown_location(k);
    const double x = grid.node_position(node)[0] / 2.0;
    const double pg = 1e4 + 2e3 * u(gen);
    y[k] = fluid == gas_phase ? pg : pg - (s_left + (s_right - s_left) * x) + 1e3 * u(gen);
  }
  return y;
}

/// Every point's suction stays clear of the kink at s = 0 by more than the FD step's reach.
bool clear_of_kink(System& sys, const Column& c, std::span<const double> y) {
  std::array<std::vector<double>, 2> p;
  sys.nodal_pressures(0.0, y, p);
  for (std::size_t q = 0; q < c.mp.position.size(); ++q) {
    PointStencil<2, LinearKernel> st;
    st.evaluate(c.grid, c.mp.position[q], c.mp.half_size[q]);
    double s = 0.0;
    for (int a = 0; a < st.n; ++a) s += st.w[a] * (p[1][st.node[a]] - p[0][st.node[a]]);
    if (std::abs(s) < 100.0) return false;
  }
  return true;
}

/// The column's prescribed nodes: the top row's liquid and gas, and one more node's gas.
template <class S>
void configure(S& sys, const Column& c) {
  // Top row: liquid and gas prescribed; one more node, gas only.
  std::vector<std::uint8_t> top(c.grid.n_nodes(), 0), gas(c.grid.n_nodes(), 0);
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i)
    if (c.grid.node_ijk(i)[1] == 3) top[i] = gas[i] = 1;
  gas[2] = 1;
  sys.set_prescribed(liquid_phase, top);
  sys.set_prescribed(gas_phase, gas);
  sys.set_prescription([](double t, NodalPrescription& np) {
    for (std::size_t i = 0; i < np.prescribed[0].size(); ++i) {
      np.value[0][i] = -3e4 + 100.0 * t, np.rate[0][i] = 100.0;
      np.value[1][i] = 5e3 - 20.0 * t, np.rate[1][i] = -20.0;
    }
  });
}

// Central differences with h = 1 Pa: truncation ~ (h / 2e4 Pa)^2 ~ 3e-9, round-off
// ~ 1e-16 * 1e5 Pa / h ~ 1e-11, relative to each row's largest entry (measured: 2e-11
// unsaturated, up to 1e-7 saturated and mixed). A missing term errs O(1e-3..1): removing the
// storage-derivative term, the simplified form's d T/dP or the gravity term's d rho/dP each
// failed these tests.
constexpr double fd_tolerance = 1e-6;

struct Regime {
  const char* name;
  double s_left, s_right;  // suction ramp across x [Pa]
};

class PressureSystemJacobian : public ::testing::TestWithParam<std::tuple<MassBalance, Regime>> {};

TEST_P(PressureSystemJacobian, MatchesFiniteDifferences) {
  const auto [form, regime] = GetParam();
  int tested = 0;
  for (unsigned seed = 1; seed <= 12 && tested < 3; ++seed) {
    Column c(seed);
    System sys(c.grid, {van_genuchten_soil(), linear_soil()}, form, Vec<2>(0.0, -9.81));
    configure(sys, c);
    prepare(sys, c);
    const auto y = state(sys, c.grid, regime.s_left, regime.s_right, seed);
    if (!clear_of_kink(sys, c, y)) continue;
    ++tested;
    EXPECT_LT(jacobian_error(sys, y, 0.7), fd_tolerance) << regime.name << " seed " << seed;
  }
  EXPECT_GE(tested, 2) << "too few states clear of the kink s = 0";
}

// The sums over the points split among threads (numerics/pressure/thread_sums.hpp): the rhs and
// the Jacobian on 2 and 3 threads equal the serial ones within rounding (each entry a sum of a
// few tens of terms, re-associated: relative differences of order 1e-15 of the row's largest
// term; 1e-12 leaves room and still fails for a lost or doubled point), the same threads give the
// same bits, and the threaded Jacobian still matches finite differences.
TEST(PressureSystem, ThreadedSumsMatchTheSerialOnes) {
  const Column c(3);
  auto make = [&](int threads) {
    auto sys = std::make_unique<System>(c.grid, std::vector{van_genuchten_soil(), linear_soil()},
                                        MassBalance::full, Vec<2>(0.0, -9.81));
    sys->set_threads(threads);
    configure(*sys, c);
    prepare(*sys, c);
    return sys;
  };
  const auto serial_system = make(1);
  System& serial = *serial_system;
  const auto y = state(serial, c.grid, 3e4, 8e4, 3);
  std::vector<double> f1(serial.n_unknowns()), j1(serial.pattern().col.size());
  ASSERT_EQ(serial.rhs(0.7, y, f1), 0);
  ASSERT_EQ(serial.jacobian(0.7, y, j1), 0);
  for (const int threads : {2, 3}) {
    const auto threaded = make(threads);
    System& sys = *threaded;
    ASSERT_EQ(sys.pattern(), serial.pattern());
    std::vector<double> f(f1.size()), j(j1.size()), f_again(f1.size());
    ASSERT_EQ(sys.rhs(0.7, y, f), 0);
    ASSERT_EQ(sys.rhs(0.7, y, f_again), 0);
    ASSERT_EQ(sys.jacobian(0.7, y, j), 0);
    EXPECT_EQ(f, f_again) << threads << " threads";
    const double f_scale = std::abs(*std::max_element(
        f1.begin(), f1.end(), [](double a, double b) { return std::abs(a) < std::abs(b); }));
    for (std::size_t k = 0; k < f.size(); ++k)
      EXPECT_NEAR(f[k], f1[k], 1e-12 * f_scale) << threads << " threads, unknown " << k;
    const auto& pat = serial.pattern();
    for (std::int64_t r = 0; r < pat.n; ++r) {
      double row_scale = 0.0;
      for (auto q = pat.row_ptr[r]; q < pat.row_ptr[r + 1]; ++q)
        row_scale = std::max(row_scale, std::abs(j1[q]));
      for (auto q = pat.row_ptr[r]; q < pat.row_ptr[r + 1]; ++q)
        EXPECT_NEAR(j[q], j1[q], 1e-12 * row_scale) << threads << " threads, row " << r;
    }
    EXPECT_LT(jacobian_error(sys, y, 0.7), fd_tolerance) << threads << " threads";
  }
}

// The same with measured curves: their slopes and curvatures are the interpolant's exact
// derivatives, so the Jacobian stays consistent.
TEST(PressureSystem, JacobianWithTabulatedCurvesMatchesFiniteDifferences) {
  for (const MassBalance form : {MassBalance::full, MassBalance::simplified})
    for (const Regime regime : {Regime{"unsaturated", 3e4, 1.5e5}, Regime{"mixed", -6e4, 9e4}}) {
      int tested = 0;
      for (unsigned seed = 1; seed <= 12 && tested < 2; ++seed) {
        Column c(seed);
        System sys(c.grid, {tabulated_soil(), linear_soil()}, form, Vec<2>(0.0, -9.81));
        configure(sys, c);
        prepare(sys, c);
        const auto y = state(sys, c.grid, regime.s_left, regime.s_right, seed);
        if (!clear_of_kink(sys, c, y)) continue;
        ++tested;
        EXPECT_LT(jacobian_error(sys, y, 0.7), fd_tolerance) << regime.name << " seed " << seed;
      }
      EXPECT_GE(tested, 1) << regime.name;
    }
}

INSTANTIATE_TEST_SUITE_P(FormsAndStates, PressureSystemJacobian,
                         ::testing::Combine(::testing::Values(MassBalance::full,
                                                              MassBalance::simplified),
                                            ::testing::Values(Regime{"unsaturated", 3e4, 1.5e5},
                                                              Regime{"saturated", -4e4, -1e4},
                                                              Regime{"mixed", -6e4, 9e4})));

TEST(PressureSystem, PatternHasEveryUnknownAndItsNeighbours) {
  Column c(3);
  System sys(c.grid, {van_genuchten_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  configure(sys, c);
  EXPECT_TRUE(prepare(sys, c));
  // 20 nodes, 5 on the top row prescribed for both fluids, node 2 for the gas: 15 + 14 pressure
  // unknowns, and the two inflow integrals.
  EXPECT_EQ(sys.n_pressure_unknowns(), 29);
  EXPECT_EQ(sys.n_unknowns(), 31);
  EXPECT_FALSE(prepare(sys, c));  // same configuration, same pattern
  const auto& pat = sys.pattern();
  for (std::int64_t r = 0; r < pat.n; ++r) {
    const auto first = pat.col.begin() + pat.row_ptr[r],
               last = pat.col.begin() + pat.row_ptr[r + 1];
    EXPECT_TRUE(std::binary_search(first, last, r)) << "diagonal of row " << r;
    EXPECT_TRUE(std::is_sorted(first, last));
  }
}

// A saturated column at hydrostatic liquid pressure, no solid rate: the rates vanish to the
// profile's curvature (the liquid is compressible: the secant slope over a cell and rho(P_p) g at
// a point differ by ~ rho g h / K = 6e-5 of rho g), far below the rate a wrong gravity term gives.
TEST(PressureSystem, HydrostaticStateIsAtRest) {
  Column c(5);
  std::fill(c.div_vs.begin(), c.div_vs.end(), 0.0);
  const double k_l = 8e7, rho = 1000.0, g = 9.81, kappa = 5e-11, mu = 1e-3;
  System sys(c.grid, {linear_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -g));
  std::vector<std::uint8_t> top(c.grid.n_nodes(), 0);
  for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i) top[i] = c.grid.node_ijk(i)[1] == 3;
  sys.set_prescribed(liquid_phase, top);
  sys.set_prescribed(gas_phase, top);
  sys.set_prescription([](double, NodalPrescription& np) {
    for (std::size_t i = 0; i < np.value[0].size(); ++i)
      np.value[0][i] = 0.0, np.value[1][i] = -5e3;
  });
  prepare(sys, c);
  std::vector<double> y(sys.n_unknowns(), 0.0), ydot(sys.n_unknowns());
  for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k) {
    const auto [node, fluid] = sys.unknown_location(k);
    const double depth = 1.5 - c.grid.node_position(node)[1];
    // Exact hydrostatics of the compressible liquid: dP/dz = -rho(P) g.
    y[k] = fluid == gas_phase ? -5e3 : -k_l * std::log1p(-rho * g * depth / k_l);
  }
  ASSERT_EQ(sys.rhs(0.0, y, ydot), 0);
  // Rate that an unbalanced gravity flux would give at a node: (2/h) c rho g / A_ll.
  const double c_l = rho * kappa / mu, a_ll = 0.3 * rho / k_l;
  const double rate_scale = (2.0 / 0.5) * c_l * rho * g / a_ll;
  for (std::int64_t k = 0; k < sys.n_pressure_unknowns(); ++k)
    EXPECT_LT(std::abs(ydot[k]), 1e-3 * rate_scale) << "unknown " << k;
  const auto q = sys.boundary_inflow(0.0, y);
  EXPECT_LT(std::abs(q[0]), 1e-3 * c_l * rho * g * 2.0);  // width 2 m
}

/// What expect_storage_change_equals_inflow evaluated: the state y, its rates y' and the inflow.
struct Balance {
  std::vector<double> y, ydot;
  std::array<double, 2> inflow;
};
/// The column (no solid rate) configured and prepared in `sys`, at seed 7's ramp state y: checks
/// that the total mass rate of each fluid, sum over all active nodes of M P' (prescribed rates
/// included), equals sum of F (zero by the partition of unity) plus the inflow.
template <class S>
Balance expect_storage_change_equals_inflow(S& sys, Column& c) {
  std::fill(c.div_vs.begin(), c.div_vs.end(), 0.0);
  configure(sys, c);
  prepare(sys, c);
  Balance b{state(sys, c.grid, 3e4, 1.5e5, 7), {}, {}};
  b.ydot.resize(b.y.size());
  EXPECT_EQ(sys.rhs(0.0, b.y, b.ydot), 0);
  const auto total = sys.storage_rate(0.0, b.y);
  b.inflow = sys.boundary_inflow(0.0, b.y);
  for (int a = 0; a < 2; ++a)
    EXPECT_NEAR(total[a], b.inflow[a], 1e-10 * std::abs(b.inflow[a]) + 1e-18) << a;
  EXPECT_GT(std::abs(b.inflow[0]), 0.0);
  return b;
}

// With no solid rate, what the nodes store equals what enters through the prescribed nodes:
// sum_i (M_i P'_i) over the unknown nodes = the boundary inflow, fluid by fluid.
TEST(PressureSystem, StorageChangeEqualsBoundaryInflow) {
  Column c(7);
  System sys(c.grid, {van_genuchten_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  const Balance b = expect_storage_change_equals_inflow(sys, c);
  EXPECT_TRUE(clear_of_kink(sys, c, b.y));
  // The inflow integrals' rates are the inflow over their scales.
  for (int a = 0; a < 2; ++a)
    EXPECT_NEAR(b.ydot[sys.inflow_unknown(a)] * sys.inflow_scale(a), b.inflow[a],
                1e-12 * std::abs(b.inflow[a]));
}

// The same with GIMP, whose supports (half-size 0.125 m, points jittered by up to 0.03 m) poke out
// of the grid at its edges: the nodes beyond the edges take part through the edge nodes
// (numerics/shape_functions.hpp), so each point's flux still reaches the nodes with gradients that
// sum to zero. Dropping those nodes put the stored mass rate 1.0 % (liquid) and 1.7 % (gas) off
// the inflow here.
TEST(PressureSystem, StorageChangeEqualsBoundaryInflowWithGimpAtTheGridsEdges) {
  Column c(7);
  PressureSystem<2, GimpKernel> sys(c.grid, {van_genuchten_soil(), linear_soil()},
                                    MassBalance::full, Vec<2>(0.0, -9.81));
  expect_storage_change_equals_inflow(sys, c);
}

// The Jacobian drop tolerance with GIMP (half-size 0.125 m in 0.5 m cells, points jittered by up
// to 0.03 m, so some reach into a third node per direction). With tau = 0.05: the pattern loses
// entries, the rhs is unchanged bit for bit, and the Jacobian changes by less than tau of its
// size, ||J_pruned - J|| < tau ||J|| (Frobenius): every dropped term is below tau of a full one,
// and each node's rows are scaled by the same M^-1 in both. (Entry by entry the change reached
// 0.057 of a row's largest entry, measured: M^-1 mixes a node's liquid and gas rows, so an entry
// can collect the dropped terms of both.)
TEST(PressureSystem, JacobianDropLeavesOutOnlyWeakCouplings) {
  using Gimp = PressureSystem<2, GimpKernel>;
  const double tau = 0.05;
  Column c(5);
  Gimp exact(c.grid, {van_genuchten_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  Gimp pruned(c.grid, {van_genuchten_soil(), linear_soil()}, MassBalance::full, Vec<2>(0.0, -9.81));
  pruned.set_jacobian_drop_tolerance(tau);
  for (Gimp* sys : {&exact, &pruned}) prepare(*sys, c);
  ASSERT_EQ(exact.n_unknowns(), pruned.n_unknowns());
  EXPECT_LT(pruned.pattern().n_nonzeros(), exact.pattern().n_nonzeros());
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(exact.n_unknowns(), 0.0);
  for (std::int64_t k = 0; k < exact.n_pressure_unknowns(); ++k)
    y[k] = exact.unknown_location(k).second == gas_phase ? 1e4 + 1e3 * u(gen) : -5e4 + 2e4 * u(gen);
  std::vector<double> f_exact(y.size()), f_pruned(y.size());
  ASSERT_EQ(exact.rhs(0.0, y, f_exact), 0);
  ASSERT_EQ(pruned.rhs(0.0, y, f_pruned), 0);
  EXPECT_EQ(f_exact, f_pruned);
  const auto& pe = exact.pattern();
  const auto& pp = pruned.pattern();
  std::vector<double> je(pe.col.size()), jp(pp.col.size());
  ASSERT_EQ(exact.jacobian(0.0, y, je), 0);
  ASSERT_EQ(pruned.jacobian(0.0, y, jp), 0);
  // Pruned values into the exact pattern (a pruned entry outside it would be an error).
  std::vector<double> jp_in_exact(je.size(), 0.0);
  for (std::int64_t r = 0; r < pe.n; ++r)
    for (auto q = pp.row_ptr[r]; q < pp.row_ptr[r + 1]; ++q) {
      const auto first = pe.col.begin() + pe.row_ptr[r], last = pe.col.begin() + pe.row_ptr[r + 1];
      const auto at = std::lower_bound(first, last, pp.col[q]);
      ASSERT_TRUE(at != last && *at == pp.col[q]) << "pruned entry outside the exact pattern";
      jp_in_exact[at - pe.col.begin()] = jp[q];
    }
  double diff = 0.0, norm = 0.0;
  for (std::size_t q = 0; q < je.size(); ++q) {
    diff += (jp_in_exact[q] - je[q]) * (jp_in_exact[q] - je[q]);
    norm += je[q] * je[q];
  }
  EXPECT_LT(std::sqrt(diff / norm), tau);
  EXPECT_GT(diff, 0.0);  // something was dropped
  EXPECT_THROW(pruned.set_jacobian_drop_tolerance(1.0), std::invalid_argument);
  EXPECT_THROW(pruned.set_jacobian_drop_tolerance(-0.1), std::invalid_argument);
}

}  // namespace test_pressure_system
}  // namespace unsatmpm::numerics
