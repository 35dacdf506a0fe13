// The relaxation of each fluid's pressure offsets between the points of a cell
// (numerics/pressure_offsets.hpp), on a block of 2 x 2 GIMP points per cell: each fluid's pass
// keeps that fluid and the other's content at each point, removes a pattern the grid does not see
// at the rate D_a / h^2, and leaves a resolved field nearly alone.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "numerics/pressure_offsets.hpp"
#include "numerics/three_phase_transfers.hpp"
#include "tests/numerics/mobile_gas_soil.hpp"

namespace unsatmpm::numerics {
namespace test_pressure_offsets {

constexpr double h = 0.2;  // cell size [m]

// cells x cells of soil at porosity 0.4, 2 x 2 points a cell, in the middle of a grid with a
// margin of 2 cells; P_l = -5 kPa, gas pressures from `gas(x, y, corner)`, corner 0..3 the
// point's place in its cell.
struct Block {
  Grid<2> grid;
  MaterialPoints<2> mp;
  FluidPoints<2> fp;
  OffsetScratch scratch;
  physics::HydraulicModel hm = mobile_gas_soil(0.1);
  template <class F>
  Block(int cells, F gas) : grid(Vec<2>(0.0, 0.0), Vec<2>(h, h), {cells + 4, cells + 4}) {
    const double v = h * h / 4.0;
    for (int i = 0; i < 2 * cells; ++i)
      for (int j = 0; j < 2 * cells; ++j) {
        const Vec<2> x(2 * h + (i + 0.5) * h / 2, 2 * h + (j + 0.5) * h / 2);
        mp.push_back(0, x, Vec<2>(h / 4, h / 4), 0.6 * hm.solid_density * v, v);
      }
    fp.resize(mp.size());
    for (std::size_t p = 0; p < mp.size(); ++p) {
      const int corner = static_cast<int>(p / (2 * cells)) % 2 * 2 + static_cast<int>(p % 2);
      const double p_g = gas(mp.position[p][0], mp.position[p][1], corner);
      fp.porosity[p] = 0.4, fp.liquid_pressure[p] = -5e3 + p_g, fp.gas_pressure[p] = p_g;
      refresh_point_laws<2>(hm, static_cast<std::int64_t>(p), hm.state(-5e3 + p_g, p_g), fp);
    }
  }
  // Fluid a's diffusivity D_a at point p [m^2/s].
  double diffusivity(std::size_t p, physics::Fluid a = physics::gas_phase) const {
    const double v = mp.volume[p];
    return fluid_diffusivity(fp, static_cast<std::int64_t>(p), a, v,
                             v * storage_at_fixed_other(fp.storage[p], fp.saturation[p], a));
  }
  void relax(double dt, physics::Fluid a = physics::gas_phase) {
    fill_stencils<2, GimpKernel>(grid, mp, 1, scratch.stencils);
    relax_offsets<2, GimpKernel>(grid, mp, dt, a, scratch, fp);
  }
};

// Each fluid's pass moves that fluid between the points, its sum kept, and no point's content of
// the other fluid changes, for offsets of any pattern; both passes together keep both fluids.
TEST(PressureOffsets, KeepEachFluidAndThePointsContentOfTheOther) {
  const auto field = [](double x, double y, int corner) {
    return 2e3 * std::sin(7.0 * x) * std::cos(5.0 * y) + 500.0 * corner;
  };
  for (const physics::Fluid a : {physics::liquid_phase, physics::gas_phase}) {
    Block b(6, field);
    b.relax(1.0, a);  // beta = 1 at every point
    double moved = 0.0, size = 0.0;
    for (std::size_t p = 0; p < b.mp.size(); ++p) {
      const physics::StorageMatrix& s = b.fp.storage[p];
      const double dl = b.fp.liquid_increment[p], dg = b.fp.gas_increment[p];
      const double liquid = s.ll * dl + s.lg * dg, gas = s.gl * dl + s.gg * dg;
      const double own = a == physics::gas_phase ? gas : liquid;
      const double other = a == physics::gas_phase ? liquid : gas;
      EXPECT_NEAR(other, 0.0, 1e-12 * (std::abs(s.ll * dl) + std::abs(s.gg * dg))) << p;
      moved += b.mp.volume[p] * own, size += std::abs(b.mp.volume[p] * own);
    }
    ASSERT_GT(size, 0.0);
    EXPECT_LT(std::abs(moved), 1e-12 * size) << a;
  }
  Block b(6, field);
  relax_pressure_offsets<2, GimpKernel>(b.grid, b.mp, 1.0, b.scratch, b.fp);
  double sums[2] = {0.0, 0.0}, sizes[2] = {0.0, 0.0};
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    const physics::StorageMatrix& s = b.fp.storage[p];
    const double dl = b.fp.liquid_increment[p], dg = b.fp.gas_increment[p];
    const double m[2] = {s.ll * dl + s.lg * dg, s.gl * dl + s.gg * dg};
    for (int i = 0; i < 2; ++i) sums[i] += m[i], sizes[i] += std::abs(m[i]);
  }
  for (int i = 0; i < 2; ++i) EXPECT_LT(std::abs(sums[i]), 1e-12 * sizes[i]) << i;
}

// Offsets of +-100 Pa between the points of every cell in both pressures (a pattern the nodes do
// not see: each cell's points sum to zero with equal weights, which the storages are to 1e-3): one
// step of dt removes the fraction beta = dt D_a / h^2 of fluid a's, all of them where beta
// reaches 1.
TEST(PressureOffsets, RemoveAPatternTheGridDoesNotSee) {
  const auto pattern = [](double, double, int corner) {
    return corner == 0 || corner == 3 ? 100.0 : -100.0;
  };
  for (const physics::Fluid a : {physics::liquid_phase, physics::gas_phase})
    for (const double fraction : {0.01, 1.0}) {
      Block b(6, pattern);
      const double dt = fraction * h * h / b.diffusivity(0, a);
      b.relax(dt, a);
      const auto& increment = a == physics::gas_phase ? b.fp.gas_increment : b.fp.liquid_increment;
      for (std::size_t p = 0; p < b.mp.size(); ++p) {
        const double offset = b.fp.gas_pressure[p];  // the same in P_l = P_g - 5 kPa
        const double beta = std::min(1.0, dt * b.diffusivity(p, a) / (h * h));
        // Away from the block's edge, where the pattern is seen by no node.
        const Vec<2> x = b.mp.position[p];
        if (x.minCoeff() < 3 * h || x.maxCoeff() > 7 * h) continue;
        EXPECT_NEAR(increment[p], -beta * offset, 0.02 * beta * std::abs(offset)) << a << " " << p;
      }
    }
}

// A resolved field, a sine of 10 or 20 cells' wavelength: the linear fits reproduce it at the
// points up to its curvature, (k h)^2, and the interpolation adds an offset of order (k h)^3
// between the two points of a cell; that offset is what remains of the filtered value. So one
// step at beta = 1 changes the field by a third-order amount (8 times less at twice the
// wavelength) that stays below 5 % of what the gas's own diffusion does in the same step,
// beta (k h)^2 of the amplitude (measured: (k h)^3 / 34, 1.9 % at 10 cells). Away from the edge.
double largest_change(double wavelength_cells) {
  const double k = 2.0 * std::numbers::pi / (wavelength_cells * h), amplitude = 1e3;
  Block b(4 * static_cast<int>(wavelength_cells),
          [&](double x, double, int) { return amplitude * std::sin(k * x); });
  double dt = 0.0;
  for (std::size_t p = 0; p < b.mp.size(); ++p) dt = std::max(dt, h * h / b.diffusivity(p));
  b.relax(dt);  // beta = 1 everywhere
  double largest = 0.0;
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    const Vec<2> x = b.mp.position[p];
    const double inner = 2 * h + wavelength_cells * h;
    if (x.minCoeff() < inner || x.maxCoeff() > inner + 2 * wavelength_cells * h) continue;
    largest = std::max(largest, std::abs(b.fp.gas_increment[p]));
  }
  return largest / amplitude;
}

TEST(PressureOffsets, LeaveAResolvedFieldNearlyAlone) {
  const double kh = 2.0 * std::numbers::pi / 10.0;
  const double ten = largest_change(10.0), twenty = largest_change(20.0);
  EXPECT_LT(ten, 0.05 * kh * kh);
  EXPECT_GT(ten / twenty, 6.0);
  EXPECT_LT(ten / twenty, 10.0);
}

// A wetted face over drier soil (the embankment's, verification/embankment/investigations.md, "What
// stopped them"): pressures rising by 200 Pa a column of points to the block's last column, whose
// points hold 1,000 times less (wetted), with the column before it 150 Pa above the ramp. The last
// column sits at its fit, the highest of all; the column before gives to its nodes, whose mean
// each point takes. After fluid a's pass at beta = 1 no point's pressure of that fluid lies
// outside the range of the pressures around it before the pass (the points within 2.5 cells along
// each axis, which hold every point its nodes reach): the last column does not rise (without the
// limit, 8 points in the liquid's pass and 15 in the gas's left their range), and the pass's fluid
// is kept where the limit acts.
TEST(PressureOffsets, EachPassMakesNoNewExtremeInItsFluidsPressure) {
  constexpr int cells = 4;
  const double first = 2 * h + h / 4, last = first + (2 * cells - 1) * h / 2;
  const auto column = [&](double x) { return std::round((x - first) / (h / 2)); };
  const auto field = [&](double x, double, int) {
    return 200.0 * column(x) + (column(x) == 2 * cells - 2 ? 150.0 : 0.0);
  };
  for (const physics::Fluid a : {physics::liquid_phase, physics::gas_phase}) {
    Block b(cells, field);
    const std::size_t n = b.mp.size();
    for (std::size_t p = 0; p < n; ++p)
      if (b.mp.position[p][0] > last - h / 4) {
        physics::StorageMatrix& s = b.fp.storage[p];
        s.ll *= 1e-3, s.lg *= 1e-3, s.gl *= 1e-3, s.gg *= 1e-3;
      }
    b.relax(1.0, a);
    const bool gas = a == physics::gas_phase;
    const auto& q = gas ? b.fp.gas_pressure : b.fp.liquid_pressure;
    const auto& d = gas ? b.fp.gas_increment : b.fp.liquid_increment;
    double moved = 0.0, sum = 0.0, size = 0.0;
    int outside = 0;
    for (std::size_t p = 0; p < n; ++p) {
      const physics::StorageMatrix& s = b.fp.storage[p];
      const double dl = b.fp.liquid_increment[p], dg = b.fp.gas_increment[p];
      const double own = gas ? s.gl * dl + s.gg * dg : s.ll * dl + s.lg * dg;
      sum += own, size += std::abs(own);
      double lo = q[p], hi = q[p];
      for (std::size_t o = 0; o < n; ++o)
        if ((b.mp.position[o] - b.mp.position[p]).cwiseAbs().maxCoeff() <= 2.5 * h)
          lo = std::min(lo, q[o]), hi = std::max(hi, q[o]);
      const double after = q[p] + d[p];
      if (after > hi + 1e-9 * std::abs(hi) || after < lo - 1e-9 * std::abs(lo)) ++outside;
      moved = std::max(moved, std::abs(d[p]));
    }
    // The offsets relaxed beside the extreme (26 and 36 Pa; a single factor per node, the
    // smallest of its points', moved 4.5 and 6.2 Pa).
    EXPECT_GT(moved, 10.0) << a;
    EXPECT_EQ(outside, 0) << a;
    EXPECT_LT(std::abs(sum), 1e-12 * size) << a;
  }
}

// With two threads (each its own node buffer, summed) the relaxation gives one thread's result to
// round-off.
TEST(PressureOffsets, TwoThreadsGiveOnesResult) {
  const auto field = [](double x, double y, int corner) {
    return 2e3 * std::sin(7.0 * x) * std::cos(5.0 * y) + 500.0 * corner;
  };
  Block one(6, field), two(6, field);
  two.scratch.resize(2);
  relax_pressure_offsets<2, GimpKernel>(one.grid, one.mp, 1e-3, one.scratch, one.fp);
  relax_pressure_offsets<2, GimpKernel>(two.grid, two.mp, 1e-3, two.scratch, two.fp);
  double largest = 0.0;
  for (std::size_t p = 0; p < one.mp.size(); ++p)
    largest = std::max(largest, std::abs(one.fp.gas_increment[p]));
  ASSERT_GT(largest, 0.0);
  for (std::size_t p = 0; p < one.mp.size(); ++p) {
    EXPECT_NEAR(two.fp.gas_increment[p], one.fp.gas_increment[p], 1e-9 * largest) << p;
    EXPECT_NEAR(two.fp.liquid_increment[p], one.fp.liquid_increment[p],
                1e-9 * std::abs(one.fp.liquid_increment[p]) + 1e-9 * largest)
        << p;
  }
}

// The linear fit S_1 on its own (subtract_projection, weights w): it reproduces a linear field at
// every point, the block's edges too, and the points count in it by their volume whatever their
// storage (w), only w > 0 saying which take part. Where the points of the block's last column
// hold almost nothing (w = 1e-9, as a saturated point beside unsaturated ones) and sit below a
// steep ramp of their heavier neighbours, a fit weighted by w would extrapolate the ramp to them
// (37.5 kPa there, the ramp ending at 32.5 kPa, the column at 0): their own values count.
TEST(PressureOffsets, TheLinearFitReproducesALinearFieldCountsEveryPointAndMakesNoNewExtreme) {
  Block b(4, [](double, double, int) { return 0.0; });
  const std::size_t n = b.mp.size();
  fill_stencils<2, GimpKernel>(b.grid, b.mp, 1, b.scratch.stencils);
  std::vector<double> w(n), y(n);
  for (std::size_t p = 0; p < n; ++p) {
    const Vec<2> x = b.mp.position[p];
    w[p] = 1.0 + 0.5 * std::sin(37.0 * static_cast<double>(p));
    y[p] = 1e3 + 5e3 * x[0] / h - 2e3 * x[1] / h;
  }
  std::vector<double> linear = y;
  subtract_projection<2, GimpKernel>(b.grid, b.mp, w, b.scratch, linear);
  for (std::size_t p = 0; p < n; ++p) EXPECT_NEAR(linear[p], 0.0, 1e-9 * std::abs(y[p])) << p;

  const double last = b.mp.position[0][0] + 7 * h / 2;  // the block's last column of points
  double highest = -1e300;
  for (std::size_t p = 0; p < n; ++p) {
    const Vec<2> x = b.mp.position[p];
    const bool light = x[0] > last - h / 4;
    w[p] = light ? 1e-9 : 1.0;
    y[p] = light ? 0.0 : 5e3 * (x[0] - 2 * h) / (h / 2);
    highest = std::max(highest, y[p]);
  }
  std::vector<double> residual = y, even = y;
  subtract_projection<2, GimpKernel>(b.grid, b.mp, w, b.scratch, residual);
  subtract_projection<2, GimpKernel>(b.grid, b.mp, std::vector<double>(n, 1.0), b.scratch, even);
  double above = -1e300;
  for (std::size_t p = 0; p < n; ++p) {
    EXPECT_NEAR(residual[p], even[p], 1e-12 * highest) << p;
    above = std::max(above, y[p] - residual[p] - highest);
  }
  EXPECT_LT(above, 0.0);

  // A field steepening towards the block's edge, y = -5 kPa (7 - i)^2 in column i of points (the
  // wetted crest's corner, its surface at zero suction, the soil drier inwards): a node's linear
  // fit to the columns it reaches passes above the edge column's values (the least-squares line
  // of a concave field lies above its ends), and the fit at a point is held within the values of
  // the points its nodes reach, so the relaxation makes no new extreme.
  for (std::size_t p = 0; p < n; ++p) {
    const double i = (b.mp.position[p][0] - b.mp.position[0][0]) / (h / 2);
    w[p] = 1.0, y[p] = -5e3 * (7.0 - i) * (7.0 - i);
  }
  std::vector<double> concave = y;
  subtract_projection<2, GimpKernel>(b.grid, b.mp, w, b.scratch, concave);
  double highest_fit = -1e300;
  for (std::size_t p = 0; p < n; ++p) highest_fit = std::max(highest_fit, y[p] - concave[p]);
  EXPECT_LE(highest_fit, 1e-9 * 5e3);
}

// Points that hold P_g (no gas phase) take no part in the gas's pass, and in the liquid's their
// gas pressure stays: the liquid's storage there is A_ll.
TEST(PressureOffsets, PointsThatHoldTheGasPressureKeepIt) {
  Block b(4, [](double, double, int corner) { return 300.0 * corner; });
  for (std::size_t p = 0; p < b.mp.size(); ++p) b.fp.saturation[p] = 1.0;
  b.relax(1.0, physics::gas_phase);
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    EXPECT_EQ(b.fp.gas_increment[p], 0.0);
    EXPECT_EQ(b.fp.liquid_increment[p], 0.0);
  }
  b.relax(1.0, physics::liquid_phase);
  double moved = 0.0;
  for (std::size_t p = 0; p < b.mp.size(); ++p) {
    EXPECT_EQ(b.fp.gas_increment[p], 0.0);
    moved += std::abs(b.fp.liquid_increment[p]);
  }
  EXPECT_GT(moved, 0.0);
}

}  // namespace test_pressure_offsets
}  // namespace unsatmpm::numerics
