// Checkpoint restore checks shared by the cycles' tests (docs/output.md, "Checkpoints and
// resume"): a solver steps a while, saves, and a second solver set up from the same case restores
// the state; both then take the same steps, and `check` compares them. The explicit cycles and the
// main cycle with a deformable skeleton must agree bit for bit (same_bits); the main cycle with a
// rigid skeleton restarts CVODE where the first ran on.
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "cycles/setup.hpp"
#include "input/case_parser.hpp"

namespace unsatmpm::restore_check {

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

/// Steps `s` n times from t as the run loop does (the explicit step, or the main cycle's
/// interval; no output times); returns the time reached.
template <class Solver>
double advance(const Case& c, Solver& s, double t, int n) {
  for (int i = 0; i < n; ++i) {
    double dt = 0.0;
    if constexpr (requires { s.interval(); })
      dt = s.interval();
    else
      dt = explicit_time_step(c.solver.time_step, s.grid().min_spacing(), s.max_wave_speed());
    s.step(t, dt);
    t += dt;
  }
  return t;
}

/// Runs `before` steps of a solver of case `text`, saves it, restores a second one from the same
/// case, runs both `after` steps on, and hands them to `check`.
template <int D, class Solver, class Check>
void restore_and_compare(const std::string& text, int before, int after, Check&& check) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("unsatmpm_restore_" +
       std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + ".bin");
  const Case c = parse_case_text(text, "<test>");
  const auto grid = make_grid<D>(c);
  Solver first(c, grid, fill_bodies<D>(c, grid), 1);
  const double t = advance(c, first, 0.0, before);
  {
    CheckpointWriter w(file, "test checkpoint");
    w.value("time", t);
    first.save(w);
    w.finish();
  }
  Solver second(c, grid, fill_bodies<D>(c, grid), 1);
  CheckpointReader r(file);
  const double t_saved = r.value<double>("time");
  second.restore(r);
  r.finish();
  std::filesystem::remove(file);
  advance(c, first, t, after);
  advance(c, second, t_saved, after);
  check(first, second);
}

/// A saturated column loaded at its drained top (V9's), in the `cycle` given.
inline std::string loaded_column(const std::string& cycle) {
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

}  // namespace unsatmpm::restore_check
