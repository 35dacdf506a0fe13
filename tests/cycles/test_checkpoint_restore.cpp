// A solver restored from a checkpoint goes on as the one that wrote it (issue: checkpoint and
// resume; docs/output.md, "Checkpoints and resume"): each cycle steps a while, saves, and a second
// solver set up from the same case restores the state; both then take the same steps. The explicit
// cycles and the main cycle with a deformable skeleton must agree bit for bit; the main cycle with
// a rigid skeleton restarts CVODE where the first ran on, so there the two agree within ten times
// CVODE's error weight, 10 (rtol max|P| + atol), set before the run.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cycle_adapters.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm {
namespace {

namespace fs = std::filesystem;

const char* const one_phase_2d = R"(
name: block
dimension: 2
grid: {origin: [0, 0], size: [1, 2], cells: [8, 16]}
shape_function: gimp
gravity: [0, -9.81]
materials:
  - {name: soil, density: 1800, model: mohr_coulomb, young_modulus: 1.0e+6, poisson_ratio: 0.3,
     friction_angle: 30, dilatancy_angle: 0, cohesion: 1000}
bodies:
  - {name: block, material: soil, points_per_cell: 2, box: {min: [0, 0], max: [1, 1.5]}}
boundaries:
  - {name: base, plane: {axis: y, at: 0}, mechanical: fixed}
  - {name: left, plane: {axis: x, at: 0}, mechanical: roller}
  - {name: right, plane: {axis: x, at: 1}, mechanical: roller}
  - name: top
    plane: {axis: y, at: 1.5}
    traction: {normal: {ramp: {from: 0, to: 2.0e+4, start: 0, end: 0.05}}}
solver: {end_time: 1, damping: 0.02}
output: {times: [1]}
)";

/// A saturated column loaded at its drained top (V9's), in the `cycle` given.
std::string loaded_column(const std::string& cycle) {
  return R"(
name: column
dimension: 1
grid: {origin: [0], size: [1], cells: [20]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 2.0e+8, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.4, intrinsic_permeability: 1.0e-10,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: power, exponent: 3}}
bodies:
  - {name: column, material: soil, points_per_cell: 2, box: {min: [0], max: [1]},
     initial_state: {liquid_pressure: 0, gas_pressure: 0}}
boundaries:
  - {name: base, plane: {axis: x, at: 0}, mechanical: fixed}
  - name: top
    plane: {axis: x, at: 1}
    liquid: {pressure: 0}
    gas: {pressure: 0}
    traction: {normal: {ramp: {from: 0, to: 1.0e+4, start: 0, end: 0.008}}}
solver: {end_time: 1, damping: 0, cycle: )" +
         cycle + "}\noutput: {times: [1]}\n";
}

/// V1's infiltration into a rigid unsaturated column, in the main cycle.
const char* const rigid_infiltration = R"(
name: infiltration
dimension: 1
grid: {origin: [0], size: [1], cells: [40]}
shape_function: linear
gravity: [0]
phases: solid_liquid_gas
fluids:
  liquid: {density: 1000, bulk_modulus: 8.0e+7, viscosity: 1.0e-3}
  gas: {model: ideal, density: 1.2, viscosity: 1.8e-5}
mass_balance: full
skeleton: rigid
materials:
  - {name: soil, model: linear_elastic, young_modulus: 1.0e+7, poisson_ratio: 0.3,
     solid_density: 2700, porosity: 0.3, intrinsic_permeability: 5.0e-11,
     retention: {model: linear, a_s: 1.0e-6}, liquid_relative_permeability: {model: constant},
     gas_relative_permeability: {model: constant}}
bodies:
  - {name: column, material: soil, points_per_cell: 4, box: {min: [0], max: [1]},
     initial_state: {suction: 5.0e+5, gas_pressure: 0}}
boundaries:
  - {name: top, plane: {axis: x, at: 1}, liquid: {suction: 0}, gas: {pressure: 0}}
  - {name: bottom, plane: {axis: x, at: 0}, gas: {pressure: 0}}
solver: {end_time: 6, damping: 0, cycle: implicit, implicit: {coupling_interval: 0.03}}
output: {times: [6]}
)";

class CheckpointRestoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    file_ = fs::temp_directory_path() /
            ("unsatmpm_restore_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".bin");
  }
  void TearDown() override { fs::remove(file_); }

  /// Steps `a` n times from t, as the run loop does (without output times); returns the time.
  template <class Solver>
  static double advance(const Case& c, Solver& s, double t, int n) {
    for (int i = 0; i < n; ++i) {
      const double dt = next_step(c, s);
      s.step(t, dt);
      t += dt;
    }
    return t;
  }

  /// Runs `before` steps, saves, restores into a second solver, and runs both `after` steps on;
  /// returns the two solvers' final states through `check`.
  template <int D, class Solver, class Check>
  void restore_and_compare(const std::string& text, int before, int after, Check&& check) {
    const Case c = parse_case_text(text, "<test>");
    const auto grid = make_grid<D>(c);
    Solver first(c, grid, fill_bodies<D>(c, grid), 1);
    double t = advance(c, first, 0.0, before);
    {
      CheckpointWriter w(file_, "test checkpoint");
      w.value("time", t);
      first.save(w);
      w.finish();
    }
    Solver second(c, grid, fill_bodies<D>(c, grid), 1);
    CheckpointReader r(file_);
    const double t_saved = r.value<double>("time");
    second.restore(r);
    r.finish();
    advance(c, first, t, after);
    advance(c, second, t_saved, after);
    check(first, second);
  }

  fs::path file_;
};

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

template <int D>
void expect_same_points(const numerics::MaterialPoints<D>& a,
                        const numerics::MaterialPoints<D>& b) {
  EXPECT_TRUE(same_bits(a.position, b.position));
  EXPECT_TRUE(same_bits(a.velocity, b.velocity));
  EXPECT_TRUE(same_bits(a.stress, b.stress));
  EXPECT_TRUE(same_bits(a.volume, b.volume));
  EXPECT_TRUE(same_bits(a.plastic_strain, b.plastic_strain));
}

template <int D>
void expect_same_fluids(const numerics::FluidPoints<D>& a, const numerics::FluidPoints<D>& b) {
  EXPECT_TRUE(same_bits(a.liquid_pressure, b.liquid_pressure));
  EXPECT_TRUE(same_bits(a.gas_pressure, b.gas_pressure));
  EXPECT_TRUE(same_bits(a.porosity, b.porosity));
  EXPECT_TRUE(same_bits(a.liquid_velocity, b.liquid_velocity));
}

TEST_F(CheckpointRestoreTest, OnePhaseCycleGoesOnBitForBit) {
  using S = ExplicitSolver<2, numerics::GimpKernel>;
  restore_and_compare<2, S>(one_phase_2d, 150, 150, [](const S& a, const S& b) {
    EXPECT_GT(a.points().plastic_strain[0] + a.points().displacement[0].norm(), 0.0);
    expect_same_points<2>(a.points(), b.points());
  });
}

TEST_F(CheckpointRestoreTest, ThreePhaseCycleGoesOnBitForBit) {
  using S = ThreePhaseSolver<1, numerics::LinearKernel>;
  restore_and_compare<1, S>(loaded_column("explicit"), 300, 300, [](const S& a, const S& b) {
    expect_same_points<1>(a.points(), b.points());
    expect_same_fluids<1>(a.fluids(), b.fluids());
    EXPECT_EQ(a.balance().liquid_inflow, b.balance().liquid_inflow);
  });
}

TEST_F(CheckpointRestoreTest, MainCycleWithADeformableSkeletonGoesOnBitForBit) {
  using S = ImplicitSolver<1, numerics::LinearKernel>;
  restore_and_compare<1, S>(loaded_column("implicit"), 300, 100, [](const S& a, const S& b) {
    EXPECT_GT(a.fluids().liquid_pressure[20], 1e3);  // the load made pore pressure
    expect_same_points<1>(a.points(), b.points());
    expect_same_fluids<1>(a.fluids(), b.fluids());
    EXPECT_TRUE(same_bits(a.nodal_pressures()[0], b.nodal_pressures()[0]));
    EXPECT_EQ(a.balance().liquid_inflow, b.balance().liquid_inflow);
    EXPECT_EQ(a.interval(), b.interval());
  });
}

TEST_F(CheckpointRestoreTest, MainCycleWithARigidSkeletonAgreesWithinCvodesTolerance) {
  using S = ImplicitSolver<1, numerics::LinearKernel>;
  restore_and_compare<1, S>(rigid_infiltration, 10, 30, [](const S& a, const S& b) {
    const double rtol = 1e-6, atol = 1.0;  // the case's CVODE tolerances (the defaults)
    for (const auto field :
         {&numerics::FluidPoints<1>::liquid_pressure, &numerics::FluidPoints<1>::gas_pressure}) {
      const auto& pa = a.fluids().*field;
      const auto& pb = b.fluids().*field;
      double scale = 0.0, worst = 0.0;
      for (std::size_t p = 0; p < pa.size(); ++p) {
        scale = std::max(scale, std::abs(pa[p]));
        worst = std::max(worst, std::abs(pa[p] - pb[p]));
      }
      EXPECT_LE(worst, 10.0 * (rtol * scale + atol));
    }
    // The infiltration moved the pressures: the comparison is not of two states at rest.
    EXPECT_LT(a.fluids().liquid_pressure.back(), 4.5e5);
  });
}

}  // namespace
}  // namespace unsatmpm
