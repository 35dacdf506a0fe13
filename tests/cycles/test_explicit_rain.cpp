// The explicit cycle's rain (cycles/explicit_rain.hpp) driven by hand, without the cycle: a 1D
// column whose top node alternates between held and flux, as the top node of a coarse column does
// once its top point has filled (verification/rain/README.md). What the node takes in, counted as
// the cycle counts it (a held step's inflow, a flux step's rain delivered), never exceeds the
// rain fallen on it by more than one held step's excess.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "cycles/explicit_rain.hpp"
#include "cycles/setup.hpp"
#include "input/case_parser.hpp"
#include "tests/cycles/rigid_soil.hpp"

namespace unsatmpm {
namespace test_explicit_rain {

using Rain = ExplicitRain<1, numerics::LinearKernel>;

// 3,600 mm/h: 1 kg/(m^2 s) of water.
const Case& column_case() {
  static const Case c = parse_case_text(R"(
name: rain
dimension: 1
grid: {origin: [0], size: [1], cells: [4]}
shape_function: linear
gravity: [-9.81]
)" + test_soils::rigid_soil_yaml() + R"(bodies:
  - {name: col, material: soil, points_per_cell: 2, box: {min: [0], max: [0.5]},
     initial_state: {suction: 5000, gas_pressure: 0}}
free_surface: {liquid: {rainfall: 3600}, gas: {pressure: 0}}
solver: {end_time: 1, damping: 0, cycle: explicit}
output: {}
)",
                                        "<test>");
  return c;
}

// The column of the case by hand: four points of 0.125 m in [0, 0.5], its top node x = 0.5 (node
// 2) the only free-surface node; every point's liquid at its gas pressure, so that a flux top
// node becomes held.
struct Column {
  numerics::Grid<1> grid = make_grid<1>(column_case());
  numerics::MaterialPoints<1> mp;
  numerics::FluidPoints<1> fp;
  std::vector<std::uint8_t> surface = std::vector<std::uint8_t>(5, 0);
  static constexpr std::int64_t top = 2;
  static constexpr double rate = 1.0;  // the rain [kg/(m^2 s)]
  Column() {
    for (int p = 0; p < 4; ++p)
      mp.push_back(0, numerics::Vec<1>(0.0625 + 0.125 * p), numerics::Vec<1>(0.0625), 1.0, 0.125);
    fp.resize(mp.size());
    std::fill(fp.liquid_pressure.begin(), fp.liquid_pressure.end(), 0.0);
    std::fill(fp.gas_pressure.begin(), fp.gas_pressure.end(), 0.0);
    surface[top] = 1;
  }
  /// One step of length dt from t: the modes, then (held) the soil taking `held_take` times the
  /// rain through the node, or (flux) the rain delivered to the points. Returns what was taken in
  /// [kg/m^2].
  double step(Rain& rain, double t, double dt, double held_take) {
    const bool flux = rain.modes(t, t + dt, mp, fp, surface)[top] != 0;
    std::fill(rain.inflow().begin(), rain.inflow().end(), 0.0);
    std::fill(fp.liquid_rate.begin(), fp.liquid_rate.end(), 0.0);
    if (!flux) {
      rain.inflow()[top] = held_take * rate;
      return held_take * rate * dt;
    }
    return rain.add_to_rates(t, t + dt, mp, surface, fp) * dt;
  }
};

// Held steps that take 1.25 times the rain, each followed by a flux step (the held node took more
// than falls): the flux step pays the excess out of its rain. Without the debt the node took in
// 1.125 times what fell.
TEST(ExplicitRain, AHeldStepsExcessIsPaidOutOfTheNextRain) {
  Column col;
  Rain rain(column_case(), col.grid);
  const double dt = 1e-3;
  double taken = 0.0, t = 0.0;
  for (int k = 0; k < 40; ++k, t += dt) {
    taken += col.step(rain, t, dt, 1.25);
    const double fallen = Column::rate * (t + dt);
    EXPECT_LE(taken, fallen + 0.25 * Column::rate * dt * (1.0 + 1e-12)) << k;
    if (k % 2 == 1) {  // after each flux step
      EXPECT_NEAR(taken, fallen, 1e-14) << k;
    }
  }
  EXPECT_EQ(rain.held_nodes(), 0);  // the last step was a flux one
}

// A held node that takes less than the rain lets the rest run off, and that is no credit for
// later: after a held step at half the rain and one at 1.25 times it, the flux step pays only the
// second's excess.
TEST(ExplicitRain, RainThatRunsOffIsNotCredited) {
  Column col;
  Rain rain(column_case(), col.grid);
  const double dt = 1e-3, falls = Column::rate * dt;
  EXPECT_NEAR(col.step(rain, 0.0, dt, 0.5), 0.5 * falls, 1e-15);      // held
  EXPECT_NEAR(col.step(rain, dt, dt, 1.25), 1.25 * falls, 1e-15);     // still held
  EXPECT_NEAR(col.step(rain, 2 * dt, dt, 0.0), 0.75 * falls, 1e-15);  // flux, pays 0.25
  col.fp.liquid_pressure.assign(4, -1e3);                             // drained: stays flux
  EXPECT_NEAR(col.step(rain, 3 * dt, dt, 0.0), falls, 1e-15);
}

// The debt goes with a checkpoint: a rain restored between a held step and the flux step after
// it delivers what the original does; and a node that leaves the surface drops its debt.
TEST(ExplicitRain, TheDebtSurvivesACheckpointAndLeavesWithTheSurface) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "unsatmpm_test_explicit_rain.bin";
  Column col;
  Rain rain(column_case(), col.grid);
  const double dt = 1e-3;
  col.step(rain, 0.0, dt, 1.25);  // held, 0.25 rate dt beyond the rain
  {
    CheckpointWriter w(file, "rain");
    rain.save(w);
    w.finish();
  }
  Rain restored(column_case(), col.grid);
  CheckpointReader r(file);
  restored.restore(r);
  r.finish();
  std::filesystem::remove(file);
  Column other;
  const double original = col.step(rain, dt, dt, 0.0);
  EXPECT_NEAR(original, 0.75 * Column::rate * dt, 1e-15);
  EXPECT_EQ(other.step(restored, dt, dt, 0.0), original);
  // Held again with the same excess, then the node off the surface: the debt is dropped, and
  // back on the surface it takes all its rain.
  col.step(rain, 2 * dt, dt, 1.25);
  col.surface[Column::top] = 0;
  col.surface[Column::top + 1] = 1;
  col.step(rain, 3 * dt, dt, 0.0);
  col.surface[Column::top] = 1;
  col.surface[Column::top + 1] = 0;
  col.fp.liquid_pressure.assign(4, -1e3);
  EXPECT_NEAR(col.step(rain, 4 * dt, dt, 0.0), Column::rate * dt, 1e-15);
}

// A node ponds when its points' liquid pressure reaches the air's above the face (the surface's
// gas pressure, 0 here), not its points' own gas pressure: a top point whose gas the rain has
// compressed along with its water (P_l 10 kPa, P_g 10.4 kPa) is ponded, one whose water is below
// the air's pressure is not, though its own gas is lower still. (Compared with the points' gas,
// V16's column with its top half a cell past a node line never ponded and its top point's gas went
// to a vacuum: cycles/explicit_rain.hpp.)
TEST(ExplicitRain, ANodePondsWhenItsWaterReachesTheAirsPressure) {
  Column col;
  Rain rain(column_case(), col.grid);
  col.fp.liquid_pressure.assign(4, 1.0e4);
  col.fp.gas_pressure.assign(4, 1.04e4);
  EXPECT_EQ(rain.modes(0.0, 1e-3, col.mp, col.fp, col.surface)[Column::top], 0);
  Rain other(column_case(), col.grid);
  col.fp.liquid_pressure.assign(4, -100.0);
  col.fp.gas_pressure.assign(4, -500.0);
  EXPECT_EQ(other.modes(0.0, 1e-3, col.mp, col.fp, col.surface)[Column::top], 1);
}

}  // namespace test_explicit_rain
}  // namespace unsatmpm
