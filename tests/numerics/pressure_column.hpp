// The column of the pressure-system tests: a 4 x 3 grid of 0.5 m cells filled with material
// points, a van Genuchten soil, and the Jacobian's check against finite differences
// (tests/numerics/test_pressure_system.cpp, test_pressure_surface.cpp, test_surface_penalty.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

inline physics::HydraulicModel van_genuchten_soil() {
  return {physics::CompressibleFluid::create(1000.0, 0.0, 1e8),
          physics::IdealGas::create(1.2),
          physics::VanGenuchten::create(2e4, 0.4, 0.05, 1.0),
          physics::MualemVanGenuchten::create(0.4),
          physics::GasPowerRelPerm::create(2.0),
          2700.0,
          1e-11,
          1e-3,
          1.8e-5};
}

/// A 4 x 3 grid of 0.5 m cells filled with 2 x 2 points per cell, two materials (left and right
/// halves), each point with its own porosity and solid volumetric rate.
struct Column {
  Grid<2> grid{Vec<2>(0.0, 0.0), Vec<2>(0.5, 0.5), {4, 3}};
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  std::vector<std::int64_t> ranges;
  std::vector<double> div_vs;

  explicit Column(unsigned seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Vec<2>> xs;
    for (int half = 0; half < 2; ++half) {
      ranges.push_back(static_cast<std::int64_t>(xs.size()));
      for (int cx = 2 * half; cx < 2 * half + 2; ++cx)
        for (int cy = 0; cy < 3; ++cy)
          for (int k = 0; k < 4; ++k)
            xs.emplace_back(0.5 * cx + 0.125 + 0.25 * (k % 2) + 0.03 * u(gen),
                            0.5 * cy + 0.125 + 0.25 * (k / 2) + 0.03 * u(gen));
    }
    ranges.push_back(static_cast<std::int64_t>(xs.size()));
    const auto n = xs.size();
    for (std::size_t p = 0; p < n; ++p) {
      const int material = p < static_cast<std::size_t>(ranges[1]) ? 0 : 1;
      mp.push_back(material, xs[p], Vec<2>(0.125, 0.125), 100.0, 0.0625);
    }
    fp.resize(n);
    div_vs.resize(n);
    for (std::size_t p = 0; p < n; ++p) {
      fp.porosity[p] = 0.35 + 0.05 * u(gen);
      div_vs[p] = 1e-3 * u(gen);
    }
  }
};

/// Prepares `sys` at the column's configuration with its solid rates.
template <class S>
bool prepare(S& sys, const Column& c) {
  sys.set_solid_rate(c.div_vs);
  return sys.prepare(c.mp, c.fp, c.ranges);
}

/// Worst |J_fd - J| over each row's largest |J| entry, by central differences of the rhs with a
/// 1 Pa step (tests/numerics/test_pressure_system.cpp states their error); entries outside the
/// pattern count too.
template <class S>
double jacobian_error(S& sys, std::vector<double> y, double t) {
  const auto& pat = sys.pattern();
  const auto n = sys.n_unknowns();
  std::vector<double> values(pat.col.size());
  EXPECT_EQ(sys.jacobian(t, y, values), 0);
  std::vector<std::vector<double>> dense(n, std::vector<double>(n, 0.0));
  for (std::int64_t r = 0; r < n; ++r)
    for (auto q = pat.row_ptr[r]; q < pat.row_ptr[r + 1]; ++q) dense[r][pat.col[q]] = values[q];
  const double h = 1.0;  // [Pa]: pressures ~1e4-1e5 Pa, nonlinearity scale ~2e4 Pa
  std::vector<double> fp(n), fm(n);
  std::vector<double> row_scale(n, 0.0);
  for (std::int64_t r = 0; r < n; ++r)
    for (const double v : dense[r]) row_scale[r] = std::max(row_scale[r], std::abs(v));
  double worst = 0.0;
  for (std::int64_t k = 0; k < n; ++k) {
    const double y0 = y[k];
    y[k] = y0 + h;
    EXPECT_EQ(sys.rhs(t, y, fp), 0);
    y[k] = y0 - h;
    EXPECT_EQ(sys.rhs(t, y, fm), 0);
    y[k] = y0;
    for (std::int64_t r = 0; r < n; ++r) {
      const double fd = (fp[r] - fm[r]) / (2.0 * h);
      worst = std::max(worst, std::abs(fd - dense[r][k]) / row_scale[r]);
    }
  }
  return worst;
}

}  // namespace unsatmpm::numerics
