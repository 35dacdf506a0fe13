// The main cycle's flow correction (cycles/flow_correction.hpp) on an unsaturated 1D column whose
// points depart from the flow's prediction: no correction where they follow it; the masses it
// hands the nodal solve sum to what entered at the prescribed node (zero without one); a departure
// decays without overshoot however long the sub-step, moving water from high to low pressure; a
// departure within the flow's tolerance is left alone; the factorisation is renewed when the
// storage stiffens; a departure drains through a face whose condition is a penalty. Its masses
// are taken as the main cycle takes them, through the nodal solve.
#include "cycles/flow_correction.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cycles/fixed_stress.hpp"
#include "numerics/three_phase_g2p.hpp"
#include "tests/numerics/linear_soil.hpp"

namespace unsatmpm {
namespace test_flow_correction {

using K = numerics::LinearKernel;

/// 10 cells of 0.1 m, 2 points each, at 20 kPa suction (S_l = 0.98), gas at 0, on a grid of
/// `cells` >= 10 cells (beyond the tenth, empty: the column's top a free face).
struct Column {
  numerics::Grid<1> grid;
  std::vector<physics::HydraulicModel> models{numerics::linear_soil()};
  numerics::MaterialPoints<1> mp;
  numerics::FluidPoints<1> fp;
  std::vector<std::int64_t> ranges{0};
  numerics::PressureSystem<1, K> system{grid, models, physics::MassBalance::full,
                                        numerics::Vec<1>(0.0)};
  std::array<std::vector<double>, 2> start, predicted;
  std::array<std::vector<std::uint8_t>, 2> held;  // the prescribed nodes, per fluid

  /// `drained_top`: the liquid prescribed at the top node; `penalty` > 0: the top node's liquid
  /// free, its face penalised with that factor (numerics/pressure/surface_penalty.hpp).
  explicit Column(bool drained_top, int cells = 10, double penalty = 0.0)
      : grid(numerics::Vec<1>(0.0), numerics::Vec<1>(0.1), {cells}) {
    for (int c = 0; c < 10; ++c)
      for (int k = 0; k < 2; ++k)
        mp.push_back(0, numerics::Vec<1>(0.1 * c + 0.025 + 0.05 * k), numerics::Vec<1>(0.025), 1.0,
                     0.05);
    ranges.push_back(static_cast<std::int64_t>(mp.size()));
    fp.resize(mp.size());
    for (std::size_t p = 0; p < mp.size(); ++p) {
      fp.porosity[p] = 0.3, fp.liquid_pressure[p] = -2e4, fp.gas_pressure[p] = 0.0;
    }
    refresh();
    held = {std::vector<std::uint8_t>(grid.n_nodes(), 0),
            std::vector<std::uint8_t>(grid.n_nodes(), 0)};
    held[0][10] = drained_top;
    for (int a = 0; a < 2; ++a) system.set_prescribed(a, held[a]);
    if (penalty > 0.0) {
      system.set_surface_prescribed(numerics::liquid_phase, true);
      system.set_surface_penalty(numerics::liquid_phase, penalty);
      system.set_prescription([](double, numerics::NodalPrescription& np) {
        np.surface_value = {-2e4, 0.0};
      });
    }
    system.prepare(mp, fp, ranges);
    balance.assign(1, std::vector<double>(6 * grid.n_nodes()));
    start = {fp.liquid_pressure, fp.gas_pressure};
    predicted = {std::vector<double>(mp.size(), 0.0), std::vector<double>(mp.size(), 0.0)};
  }
  /// Saturation, densities and storage from the pressures.
  void refresh() {
    update_fluid_state<1>(models, ranges, fp);
    for (std::size_t p = 0; p < mp.size(); ++p)
      fp.storage[p] = models[0].storage(fp.porosity[p], fp.liquid_pressure[p], fp.gas_pressure[p]);
  }
  /// The flow's end pressures at the nodes, for the correction's tolerance: the start's 20 kPa
  /// suction (the gas at 0).
  std::array<std::vector<double>, 2> nodal() const {
    return {std::vector<double>(grid.n_nodes(), -2e4), std::vector<double>(grid.n_nodes(), 0.0)};
  }
  double liquid_mass() const {
    double m = 0.0;
    for (std::size_t p = 0; p < mp.size(); ++p)
      m += fp.porosity[p] * mp.volume[p] * fp.saturation[p] * fp.liquid_density[p];
    return m;
  }
  /// The correction's masses at the sub-step [tau, tau + h] into `mass`, through the nodal solve
  /// it rides on, which holds the prescribed nodes as the main cycle's does (its increments are
  /// left in fp's increment columns, what entered at the held nodes in through_held): returns what
  /// entered with the correction.
  std::array<double, 2> correct(FlowCorrection<1, K>& fc, double tau, double h,
                                std::array<std::vector<double>, 2>& mass) {
    std::fill(fp.liquid_rate.begin(), fp.liquid_rate.end(), 0.0);
    std::fill(fp.gas_rate.begin(), fp.gas_rate.end(), 0.0);
    std::array<double, 2> entered{0.0, 0.0};
    double seconds = 0.0;
    through_held = numerics::nodal_pressure_increments<1, K, false>(
        grid, mp, 1.0, balance, {&held[0], &held[1]}, fp,
        fc.source(grid, mp, fp, tau, h, mass, entered, seconds));
    return entered;
  }
  /// The same, applied linearly (P += dP); the masses are left in `applied`.
  std::array<double, 2> apply(FlowCorrection<1, K>& fc, double tau, double h) {
    const auto entered = correct(fc, tau, h, applied);
    for (std::size_t p = 0; p < mp.size(); ++p) {
      fp.liquid_pressure[p] += fp.liquid_increment[p];
      fp.gas_pressure[p] += fp.gas_increment[p];
    }
    return entered;
  }
  /// Largest |P - P_start - (tau / dt) predicted| of the liquid over the points [Pa].
  double departure(double along) const {
    double d = 0.0;
    for (std::size_t p = 0; p < mp.size(); ++p)
      d = std::max(d, std::abs(fp.liquid_pressure[p] - start[0][p] - along * predicted[0][p]));
    return d;
  }
  std::vector<std::vector<double>> balance;
  std::array<std::vector<double>, 2> applied;
  std::array<double, 2> through_held{0.0, 0.0};
};

/// A departure of the liquid that alternates from node to node, +-`amplitude` at the nodes but
/// the top one (which a drained column holds): the mode the skeleton cannot answer (with linear
/// shape functions it leaves every cell's mean).
void depart(Column& c, double amplitude) {
  numerics::PointStencil<1, K> st;
  for (std::size_t p = 0; p < c.mp.size(); ++p) {
    st.evaluate(c.grid, c.mp.position[p], c.mp.half_size[p]);
    for (int a = 0; a < st.n; ++a)
      if (st.node[a] + 1 < c.grid.n_nodes())
        c.fp.liquid_pressure[p] += st.w[a] * (st.node[a] % 2 ? -amplitude : amplitude);
  }
  c.refresh();
}

TEST(FlowCorrection, PointsThatFollowThePredictionAreLeftAlone) {
  Column c(true);
  for (std::size_t p = 0; p < c.mp.size(); ++p) c.predicted[0][p] = 300.0 * std::sin(3.0 * p);
  FlowCorrection<1, K> fc;
  fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 0.5, c.nodal(), 1e-6, 1.0);
  // Half-way through the interval, the points have changed by half the prediction.
  for (std::size_t p = 0; p < c.mp.size(); ++p) c.fp.liquid_pressure[p] += 0.5 * c.predicted[0][p];
  c.refresh();
  std::array<std::vector<double>, 2> mass;
  const auto entered = c.correct(fc, 0.25, 1e-3, mass);
  for (const auto& m : mass)
    for (const double v : m) EXPECT_NEAR(v, 0.0, 1e-18);
  EXPECT_NEAR(entered[0], 0.0, 1e-18);
}

TEST(FlowCorrection, MovesWaterDownTheDepartureAndKeepsTheMass) {
  for (const bool drained : {false, true}) {
    Column c(drained);
    FlowCorrection<1, K> fc;
    fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1.0, c.nodal(), 1e-6, 1.0);
    depart(c, 500.0);
    const double before = c.liquid_mass();
    const auto entered = c.apply(fc, 0.0, 1e-3);
    double total = 0.0, moved = 0.0;
    for (std::int64_t i = 0; i < c.grid.n_nodes(); ++i)
      total += c.applied[0][i], moved += std::abs(c.applied[0][i]);
    ASSERT_GT(moved, 0.0);
    EXPECT_NEAR(total, entered[0], 1e-12 * moved);
    if (!drained) {
      EXPECT_NEAR(entered[0], 0.0, 1e-12 * moved);
    }
    // Water leaves the high (even) nodes for the low (odd) ones.
    for (std::int64_t i = 1; i + 1 < c.grid.n_nodes(); ++i)
      EXPECT_LT(c.applied[0][i] * (i % 2 ? -1.0 : 1.0), 0.0) << "node " << i;
    c.refresh();
    // The points hold what the nodal solve gave them: their mass changed by what entered, to
    // first order in the pressure change (the solve is linear).
    EXPECT_NEAR(c.liquid_mass() - before, entered[0] + c.through_held[0], 1e-3 * moved + 1e-15);
  }
}

TEST(FlowCorrection, ADepartureDecaysWithoutOvershootForAnyStep) {
  for (const double h : {1e-4, 1e-2, 1.0, 1e3}) {
    Column c(true);
    FlowCorrection<1, K> fc;
    fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1e4, c.nodal(), 1e-6, 1.0);
    depart(c, 500.0);
    double last = c.departure(0.0);
    for (int k = 0; k < 20; ++k) {
      c.apply(fc, 0.0, h);
      c.refresh();
      const double now = c.departure(0.0);

      EXPECT_LE(now, last * (1.0 + 1e-9)) << "h = " << h << ", step " << k;
      last = now;
    }
    // A step long against the departure's diffusion time removes most of it at once.
    if (h >= 1.0) {
      EXPECT_LT(last, 0.5 * 500.0) << "h = " << h;
    }
  }
}

TEST(FlowCorrection, LeavesADepartureWithinTheFlowsToleranceAlone) {
  // A departure of 0.4 Pa on a field at 20 kPa: below rtol |P| + atol = 1.02 Pa.
  Column c(true);
  FlowCorrection<1, K> fc;
  fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1.0, c.nodal(), 1e-6, 1.0);
  depart(c, 0.4);
  std::array<std::vector<double>, 2> mass;
  const auto entered = c.correct(fc, 0.0, 1e-3, mass);
  for (const auto& m : mass)
    for (const double v : m) EXPECT_EQ(v, 0.0);
  EXPECT_EQ(entered[0], 0.0);
  EXPECT_EQ(fc.n_renewals(), 0);
  depart(c, 2.0);  // now beyond it
  c.correct(fc, 0.0, 1e-3, mass);
  EXPECT_EQ(fc.n_renewals(), 1);
}

TEST(FlowCorrection, RenewsItsMatrixWhenTheStorageStiffens) {
  Column c(true);
  FlowCorrection<1, K> fc;
  fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1.0, c.nodal(), 1e-6, 1.0);
  depart(c, 500.0);
  std::array<std::vector<double>, 2> mass;
  c.correct(fc, 0.0, 1e-3, mass);
  c.correct(fc, 1e-3, 1e-3, mass);
  EXPECT_EQ(fc.n_renewals(), 1);
  // The liquid saturates: its storage falls from the retention's slope to its compressibility.
  for (std::size_t p = 0; p < c.mp.size(); ++p) c.fp.liquid_pressure[p] += 2.1e4;
  c.refresh();
  c.correct(fc, 2e-3, 1e-3, mass);
  EXPECT_EQ(fc.n_renewals(), 2);
  // A step twice as long is renewed too.
  c.correct(fc, 3e-3, 2e-3, mass);
  EXPECT_EQ(fc.n_renewals(), 3);
}

TEST(FlowCorrection, DrainsADepartureThroughAPenalisedFace) {
  // A departure of +500 Pa of the liquid everywhere: in a closed column no Darcy flux answers
  // it, so nothing moves; with the column's top a penalised face (the flow's own condition
  // there drains it) water leaves through the face, counted as what entered, the departure
  // decays without overshoot, and a long step removes most of it.
  for (const double penalty : {0.0, 16.0}) {
    Column c(false, 12, penalty);
    ASSERT_EQ(c.system.surface_penalty_couplings()[0].value.empty(), penalty == 0.0);
    FlowCorrection<1, K> fc;
    fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1e4, c.nodal(), 1e-6, 1.0);
    for (auto& p : c.fp.liquid_pressure) p += 500.0;
    c.refresh();
    const double before = c.liquid_mass();
    const auto entered = c.apply(fc, 0.0, 1e-3);
    double total = 0.0, moved = 0.0;
    for (const double m : c.applied[0]) total += m, moved += std::abs(m);
    if (penalty == 0.0) {
      EXPECT_LT(moved, 1e-12 * before) << "a uniform departure in a closed column";
      continue;
    }
    ASSERT_LT(entered[0], 0.0);
    EXPECT_NEAR(total, entered[0], 1e-12 * moved);
    c.refresh();
    EXPECT_NEAR(c.liquid_mass() - before, entered[0], 1e-3 * moved);
    double last = c.departure(0.0);
    EXPECT_LT(last, 500.0);
    for (int k = 0; k < 20; ++k) {
      c.apply(fc, 0.0, 1.0);
      c.refresh();
      const double now = c.departure(0.0);
      EXPECT_LE(now, last * (1.0 + 1e-9)) << "step " << k;
      last = now;
    }
    EXPECT_LT(last, 0.5 * 500.0);
  }
}

TEST(FlowCorrection, GmresAndKluGiveTheSameMasses) {
  // The correction's masses with its first choice (GMRES to solve_fraction of the flow's
  // tolerance, here 1.02 Pa, on a 500 Pa departure), with KLU only, and with GMRES cut short so
  // that KLU takes over: the same to the solve's accuracy, and the fallback to the bit. The
  // accuracy scales with solve_fraction: a tenth of it, relative to the largest mass (1e-4 when
  // the solve went to a thousandth of the tolerance).
  std::array<std::array<std::vector<double>, 2>, 3> masses;
  std::array<long, 3> iterations{}, direct{};
  for (int mode = 0; mode < 3; ++mode) {
    Column c(true);
    FlowCorrection<1, K> fc(mode == 2 ? 1 : 30);
    fc.set_direct(mode == 1);
    fc.begin(c.system, c.models, c.fp, c.start, c.predicted, 1.0, c.nodal(), 1e-6, 1.0);
    depart(c, 500.0);
    c.correct(fc, 0.0, 1e-2, masses[mode]);
    iterations[mode] = fc.n_iterations(), direct[mode] = fc.n_direct_solves();
  }
  EXPECT_GT(iterations[0], 0);
  EXPECT_EQ(direct[0], 0);
  EXPECT_EQ(iterations[1], 0);
  EXPECT_EQ(direct[1], 1);
  EXPECT_EQ(direct[2], 1);
  double scale = 0.0;
  for (const double m : masses[1][0]) scale = std::max(scale, std::abs(m));
  ASSERT_GT(scale, 0.0);
  for (std::size_t i = 0; i < masses[1][0].size(); ++i) {
    EXPECT_NEAR(masses[0][0][i], masses[1][0][i], 0.1 * solve_fraction * scale) << "node " << i;
    EXPECT_EQ(masses[2][0][i], masses[1][0][i]) << "node " << i;
  }
}

}  // namespace test_flow_correction
}  // namespace unsatmpm
