// Rainfall on the free surface: the time function's exact mean, where the rain lands and how much
// (RainfallSurface::supply), the switches between flux and held (zero-suction) nodes
// (RainfallSurface::update_modes), and three runs of the implicit cycle on a rigid column:
//   - rain below the saturated conductivity: every drop enters, no node ponds;
//   - rain far above it: the top ponds, and less enters than falls;
//   - no rain, the base held at a water table above the top: the top becomes a seepage face and
//     carries the steady upward flow out.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "cycles/implicit_solver.hpp"
#include "cycles/rainfall.hpp"

namespace unsatmpm {
namespace test_rainfall {

TEST(TimeFunction, MeanIsExactForPiecewiseLinear) {
  const TimeFunction f{{{1.0, 2.0}, {3.0, 6.0}, {4.0, 0.0}}};
  // Constant before the first point and after the last; trapezoids between.
  EXPECT_DOUBLE_EQ(f.mean(-2.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(f.mean(5.0, 9.0), 0.0);
  EXPECT_DOUBLE_EQ(f.mean(1.0, 3.0), 4.0);
  // [0, 5]: 2 * 1 + (2 + 6) / 2 * 2 + (6 + 0) / 2 * 1 + 0 = 13, mean 13 / 5.
  EXPECT_DOUBLE_EQ(f.mean(0.0, 5.0), 13.0 / 5.0);
  // Additive over a split inside a segment and across a breakpoint.
  for (const double split : {1.5, 3.0, 3.7})
    EXPECT_NEAR(f.mean(0.5, split) * (split - 0.5) + f.mean(split, 4.5) * (4.5 - split),
                f.mean(0.5, 4.5) * 4.0, 1e-12);
  EXPECT_DOUBLE_EQ(f.mean(2.0, 2.0), f(2.0));
}

// A 4 x 3 grid of 1 m cells; gravity along -y. Node columns i = 0..4, each with a strip of rain
// [i - 0.5, i + 0.5) m (half of it inside the grid at i = 0 and 4).
struct RainGrid {
  numerics::Grid<2> grid{numerics::Vec<2>(0.0, 0.0), numerics::Vec<2>(1.0, 1.0), {4, 3}};
  std::int64_t node(int i, int j) const { return j * grid.stride[1] + i; }
};

using Rain = RainfallSurface<2, numerics::LinearKernel>;

// Points in strips 0 (two, the upper one takes the rain), 1 and 3; none in 2 and 4.
numerics::MaterialPoints<2> rain_points() {
  numerics::MaterialPoints<2> mp;
  const numerics::Vec<2> half(0.25, 0.25);
  for (const auto& x : {numerics::Vec<2>(0.3, 1.5), numerics::Vec<2>(0.3, 2.5),
                        numerics::Vec<2>(1.2, 1.8), numerics::Vec<2>(2.6, 0.4)})
    mp.push_back(0, x, half, 1.0, 0.25);
  return mp;
}

TEST(RainfallSurface, RainLandsOnTheTopRowOfEachColumn) {
  const RainGrid g;
  const auto mp = rain_points();
  const double rate = 1e-2;  // 36 mm/h of water at 1000 kg/m^3 [kg/(m^2 s)]
  Rain rain(g.grid, TimeFunction{{{0.0, 36.0}}}, 1000.0, 1, -1);
  // Every node a surface node: each top point passes its strip's rain by its weights.
  const std::vector<std::uint8_t> all(g.grid.n_nodes(), 1);
  const auto q = rain.supply(0.0, 1.0, mp, all);
  // The supply when points `tops` take the rain of strips 0, 1 and 3 (widths 0.5, 1, 1).
  const auto by_weights = [&](std::array<int, 3> tops) {
    std::vector<double> e(g.grid.n_nodes(), 0.0);
    numerics::PointStencil<2, numerics::LinearKernel> st;
    const std::array<double, 3> width{0.5, 1.0, 1.0};
    for (int k = 0; k < 3; ++k) {
      st.evaluate(g.grid, mp.position[tops[k]], mp.half_size[tops[k]]);
      for (int a = 0; a < st.n; ++a) e[st.node[a]] += rate * width[k] * st.w[a];
    }
    return e;
  };
  const auto expected = by_weights({1, 2, 3});
  for (std::int64_t i = 0; i < g.grid.n_nodes(); ++i) EXPECT_NEAR(q[i], expected[i], 1e-15) << i;
  EXPECT_NEAR(std::accumulate(q.begin(), q.end(), 0.0), rate * 2.5, 1e-15);
  // Only the upper nodes of the point at (0.3, 2.5) on the surface: its strip's rain goes to
  // them alone, in proportion 0.7 : 0.3.
  std::vector<std::uint8_t> surface(g.grid.n_nodes(), 0);
  surface[g.node(0, 3)] = surface[g.node(1, 3)] = 1;
  const auto r = rain.supply(0.0, 1.0, mp, surface);
  EXPECT_NEAR(r[g.node(0, 3)], rate * 0.5 * 0.7, 1e-15);
  EXPECT_NEAR(r[g.node(1, 3)], rate * 0.5 * 0.3, 1e-15);
  EXPECT_EQ(r[g.node(0, 2)], 0.0);
  // The other strips' points touch no surface node: they pass their rain to all their nodes.
  EXPECT_NEAR(std::accumulate(r.begin(), r.end(), 0.0), rate * 2.5, 1e-15);
  // Gravity along +y: the lowest point of strip 0 takes its rain.
  Rain upside_down(g.grid, TimeFunction{{{0.0, 36.0}}}, 1000.0, 1, +1);
  const auto u = upside_down.supply(0.0, 1.0, mp, all);
  const auto expected_up = by_weights({0, 2, 3});
  for (std::int64_t i = 0; i < g.grid.n_nodes(); ++i) EXPECT_NEAR(u[i], expected_up[i], 1e-15) << i;
  EXPECT_EQ(u[g.node(0, 3)], 0.0);
}

// A flat top, 2 x 2 points per cell over the grid's lower two rows: every point of the top row
// takes the rain over its own width, so that each top node gets the same rain per unit of its
// measure. Taking it all at one point of each column (where two tie) gave node 1 1.125 times it.
TEST(RainfallSurface, AFlatTopRowSharesTheRainByWidth) {
  const RainGrid g;
  numerics::MaterialPoints<2> mp;
  const numerics::Vec<2> half(0.25, 0.25);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i)
      mp.push_back(0, numerics::Vec<2>(0.25 + 0.5 * i, 0.25 + 0.5 * j), half, 1.0, 0.25);
  const double rate = 1e-2;  // [kg/(m^2 s)]
  Rain rain(g.grid, TimeFunction{{{0.0, 36.0}}}, 1000.0, 1, -1);
  std::vector<std::uint8_t> surface(g.grid.n_nodes(), 0);
  for (int i = 0; i <= 4; ++i) surface[g.node(i, 2)] = 1;
  const auto check = [&](const char* what) {
    const auto q = rain.supply(0.0, 1.0, mp, surface);
    for (int i = 0; i <= 4; ++i)
      EXPECT_NEAR(q[g.node(i, 2)], rate * (i == 0 || i == 4 ? 0.5 : 1.0), 1e-15) << what << i;
    EXPECT_NEAR(std::accumulate(q.begin(), q.end(), 0.0), rate * 4.0, 1e-15) << what;
  };
  check("flat: ");
  // A point of the top row a little lower (less than half a point) still takes its width's rain.
  mp.position[30][1] -= 0.1;  // x = 3.25, beside x = 2.75 in column 3
  const auto shares = rain.point_supply(0.0, 1.0, mp, surface);
  ASSERT_EQ(shares.size(), 8u);
  for (const auto& [p, r] : shares) {
    EXPECT_GE(p, 24);  // the top row's points, not the row below
    EXPECT_NEAR(r, rate * 0.5, 1e-15) << p;
  }
  // Lowered by more than half a point, it leaves the rain of its column to its neighbour.
  mp.position[30][1] -= 0.2;
  const auto lower = rain.point_supply(0.0, 1.0, mp, surface);
  double total = 0.0;
  for (const auto& [p, r] : lower) {
    EXPECT_NE(p, 30);
    total += r;
  }
  EXPECT_NEAR(total, rate * 4.0, 1e-15);
}

TEST(RainfallSurface, NodesSwitchBetweenFluxAndHeld) {
  const RainGrid g;
  Rain rain(g.grid, TimeFunction{{{0.0, 36.0}}}, 1000.0, 1, -1);
  const auto n = g.grid.n_nodes();
  // Points just below the top row, one per strip 0..3: rain reaches rows 3 and 2 (all flagged).
  numerics::MaterialPoints<2> mp;
  for (int i = 0; i < 4; ++i)
    mp.push_back(0, numerics::Vec<2>(i + 0.25, 2.9), numerics::Vec<2>(0.25, 0.25), 1.0, 0.25);
  const auto supply = rain.supply(0.0, 1.0, mp, std::vector<std::uint8_t>(n, 1));
  ASSERT_GT(supply[g.node(1, 3)], 0.0);
  ASSERT_GT(supply[g.node(3, 2)], 0.0);
  const std::int64_t wet = g.node(1, 3), dry = g.node(2, 3), seep = g.node(3, 2),
                     inner = g.node(1, 1);
  std::vector<std::uint8_t> surface(n, 0);
  surface[wet] = surface[dry] = surface[seep] = 1;
  std::array<std::vector<double>, 2> p{std::vector<double>(n, -5e3), std::vector<double>(n, 0.0)};
  p[0][wet] = 0.0;     // suction reached zero: ponds
  p[0][seep] = 10.0;   // liquid above the gas pressure: seeps
  p[0][inner] = 50.0;  // not on the surface: stays flux, whatever its pressure
  std::vector<double> inflow(n, 0.0);
  auto flux = rain.update_modes(surface, p, inflow);
  EXPECT_EQ(flux[wet], 0);
  EXPECT_EQ(flux[seep], 0);
  EXPECT_EQ(flux[dry], 1);
  EXPECT_EQ(flux[inner], 1);
  EXPECT_EQ(rain.held_nodes(), 2);
  // Held nodes stay held while they take no more than the rain brings (the seepage node gives
  // water out) ...
  inflow[wet] = 0.9 * supply[wet], inflow[seep] = -1e-3;
  flux = rain.update_modes(surface, p, inflow);
  EXPECT_EQ(flux[wet], 0);
  EXPECT_EQ(flux[seep], 0);
  // ... and return to flux when they would take more: the rain can no longer keep them wet.
  inflow[wet] = 1.1 * supply[wet], inflow[seep] = 1.1 * supply[seep];
  flux = rain.update_modes(surface, p, inflow);
  EXPECT_EQ(flux[wet], 1);
  EXPECT_EQ(flux[seep], 1);
  EXPECT_EQ(rain.held_nodes(), 0);
  // A node that leaves the surface returns to flux mode.
  p[0][dry] = 0.0;
  flux = rain.update_modes(surface, p, inflow);
  EXPECT_EQ(flux[dry], 0);
  surface[dry] = 0;
  flux = rain.update_modes(surface, p, inflow);
  EXPECT_EQ(flux[dry], 1);
}

// A rigid column of 1 m in a 1.5 m grid (0.05 m cells, 2 points per cell), gravity along -x;
// van Genuchten soil with kappa = 1e-11 m^2: K_s = kappa rho g / mu = 9.81e-5 m/s (353 mm/h).
// Gas held at 0 on the free surface; the base impervious.
constexpr double rho_w = 1000.0, g = 9.81, kappa = 1e-11, mu = 1e-3;

Case rain_column(double intensity_mm_h, double initial_suction, double end_time) {
  Case c;
  c.file = "<test>";
  c.name = "rain_column";
  c.dimension = 1;
  c.shape_function = ShapeFunctionKind::linear;
  c.grid = {{0.0}, {1.5}, {30}};
  c.gravity = {-g};
  c.phases = Phases::solid_liquid_gas;
  c.fluids = FluidsSpec{physics::CompressibleFluid::create(rho_w, 0.0, 2e9), mu,
                        physics::CompressibleFluid::create(1.2, 0.0, 1e5), 1.8e-5};
  c.mass_balance = physics::MassBalance::full;
  c.skeleton = physics::Skeleton::rigid;
  HydraulicSpec h{2700.0,
                  0.4,
                  kappa,
                  physics::VanGenuchten::create(2e4, 0.5, 0.0, 1.0),
                  physics::PowerRelPerm::create(3.0),
                  physics::ConstantRelPerm{}};
  c.materials.push_back({"soil", 0.6 * 2700.0, physics::LinearElastic::create(1e7, 0.3), h});
  c.bodies.push_back({"column", 0, 2, BoxGeometry{{0.0}, {1.0}}, std::vector<double>{0.0},
                      InitialPressures{-initial_suction, 0.0}});
  c.free_surface = SurfaceSpec{};
  c.free_surface->rainfall = TimeFunction{{{0.0, intensity_mm_h}}};
  c.free_surface->gas_pressure = TimeFunction{{{0.0, 0.0}}};
  c.solver.cycle = Cycle::implicit_pressure;
  c.solver.implicit.coupling_interval = 1.0;
  c.solver.end_time = end_time;
  return c;
}

struct RainRun {
  numerics::FluidBalance start, end;
  std::int64_t held = 0;
  double top_suction = 0.0;              // of the topmost point [Pa]
  double top_liquid = 0.0, top_x = 0.0;  // its liquid pressure [Pa] and position [m]
};

template <class K = numerics::LinearKernel>
RainRun run_rain(const Case& c) {
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, K> solver(c, grid, fill_bodies<1>(c, grid), 1);
  RainRun r;
  r.start = solver.balance();
  for (double t = 0.0; t < c.solver.end_time - 1e-9; t += solver.interval())
    solver.step(t, solver.interval());
  r.end = solver.balance();
  r.held = solver.rain_held_nodes();
  const auto& fp = solver.fluids();
  r.top_suction = fp.gas_pressure.back() - fp.liquid_pressure.back();
  r.top_liquid = fp.liquid_pressure.back();
  r.top_x = solver.points().position.back()[0];
  return r;
}

double mismatch(const RainRun& r) {
  return (r.end.liquid_mass - r.start.liquid_mass - r.end.liquid_inflow) / r.start.liquid_mass;
}

// 36 mm/h (about K_s / 10) on a dry column for 100 s: the rain all enters. The supply is a
// constant rate in the inflow integral, which BDF integrates exactly: the inflow equals
// r rho t to round-off (1e-9 relative). The mass balance closes to 1e-3 as in V1.
TEST(Rainfall, LightRainAllEntersAndNothingPonds) {
  const Case c = rain_column(36.0, 5e4, 100.0);
  const RainRun r = run_rain(c);
  const double fallen = 36.0 * 1e-3 / 3600.0 * rho_w * 100.0;  // kg/m^2
  EXPECT_NEAR(r.end.liquid_inflow, fallen, 1e-9 * fallen);
  EXPECT_EQ(r.held, 0);
  EXPECT_GT(r.top_suction, 0.0);
  EXPECT_LT(std::abs(mismatch(r)), 1e-3);
}

// 3600 mm/h (about 10 K_s) on a nearly saturated column (suction 2 kPa, a deficit of about
// 2 kg/m^2): the top node ponds within the first second (CVODE stops where its liquid pressure
// reaches the gas pressure), the column fills in about 12 s, and at 30 s it is saturated and
// hydrostatic below the ponded top: the top point's P_l = rho g (1 m - x) within 1 %. Far less
// enters than falls (30 kg/m^2).
TEST(Rainfall, HeavyRainPondsAndRunsOff) {
  const Case c = rain_column(3600.0, 2e3, 30.0);
  const RainRun r = run_rain(c);
  const double fallen = 3600.0 * 1e-3 / 3600.0 * rho_w * 30.0;
  EXPECT_GE(r.held, 1);
  EXPECT_LT(r.end.liquid_inflow, 0.1 * fallen);
  EXPECT_GT(r.end.liquid_inflow, 0.0);
  const double hydrostatic = rho_w * g * (1.0 - r.top_x);
  EXPECT_NEAR(r.top_liquid, hydrostatic, 0.01 * hydrostatic);
  EXPECT_LT(std::abs(mismatch(r)), 1e-3);
}

// Heavy rain (10,000 mm/h, 28 K_s) on the dry column (50 kPa) for 10 s, its top on a node line
// (1 m) and half a cell past one (1.025 m; the node beyond, 1.05 m, holds an eighth of a full
// node's volume): both pond (less enters than falls) and take in about as much, within 20 % (set
// beforehand as a first-order effect of the 0.05 m cells; measured 2.3 %, 25.48 and 24.89
// kg/m^2). (First tried for 3 s, in which neither column ponds.) When the surface nodes took all
// the rain of their top points and ponded by their own pressure, the light node beyond ponded at
// once over dry points and the half-cell column took in 36 % of the other's (8.8 against 24.5
// kg/m^2, the same column as a case file; cycles/top_row_pressures.hpp).
TEST(Rainfall, ATopHalfACellPastANodeLineTakesInTheRain) {
  const Case on_line = rain_column(10000.0, 5e4, 10.0);
  Case past = on_line;
  std::get<BoxGeometry>(past.bodies[0].geometry).max[0] = 1.025;
  const RainRun a = run_rain(on_line), b = run_rain(past);
  const double fallen = 10000.0 * 1e-3 / 3600.0 * rho_w * 10.0;  // kg/m^2
  EXPECT_LT(a.end.liquid_inflow, 0.99 * fallen);
  EXPECT_LT(b.end.liquid_inflow, 0.99 * fallen);
  EXPECT_NEAR(b.end.liquid_inflow, a.end.liquid_inflow, 0.2 * a.end.liquid_inflow);
  EXPECT_LT(std::abs(mismatch(b)), 1e-3);
}

// The same heavy rain on GIMP points (6 per cell) whose top lies a sixth of a cell past a node
// line (the box to 1.005 m takes one more point, at 1.0042 m, whose domain reaches 1.0083 m):
// holding the surface node layer, the main cycle holds the ponded face at the node
// beyond, which the points barely reach, and takes in too little (docs/known_failures.md); with
// the face's penalty (solver.implicit.surface_penalty, acting on the ponded part of the face) it
// takes in what the column with its top on the node line takes in, within 10 % (set beforehand as
// a first-order effect of the 0.05 m cells), and keeps its balance.
TEST(Rainfall, ThePenaltyTakesInTheRainOfATopBetweenNodeLines) {
  Case on_line = rain_column(10000.0, 5e4, 10.0);
  on_line.shape_function = ShapeFunctionKind::gimp;
  on_line.bodies[0].points_per_cell = 6;
  Case past = on_line;
  std::get<BoxGeometry>(past.bodies[0].geometry).max[0] = 1.005;
  past.solver.implicit.surface_penalty = 16.0;
  const RainRun a = run_rain<numerics::GimpKernel>(on_line);
  const RainRun b = run_rain<numerics::GimpKernel>(past);
  const double fallen = 10000.0 * 1e-3 / 3600.0 * rho_w * 10.0;  // kg/m^2
  EXPECT_LT(b.end.liquid_inflow, 0.99 * fallen);
  EXPECT_NEAR(b.end.liquid_inflow, a.end.liquid_inflow, 0.1 * a.end.liquid_inflow);
  EXPECT_LT(std::abs(mismatch(b)), 1e-3);
}

// Upward seepage: the base held at the pressure of a water table 0.5 m above the top
// (rho g 1.5 m), no rain, the column saturated and hydrostatic at t = 0 (top point at +4.8 kPa).
// The top node's liquid pressure is above the gas pressure, so it becomes a seepage face at the
// first interval's end, and the column settles to steady upward flow with P_l = 0 at the top:
// the pressure falls linearly from the base, which linear shape functions represent exactly. The
// top point's pressure then lies within 1 % of rho g 1.5 m (1 - x) (the steady state is reached in
// far less than the 10 s run: rigid, saturated, stiff water), and water has left.
TEST(Rainfall, SeepageFaceLetsWaterOut) {
  Case c = rain_column(0.0, 0.0, 10.0);
  const double base = rho_w * g * 1.5;
  BoundarySpec bottom{"base", {0, 0.0}, std::nullopt, std::nullopt, std::nullopt};
  bottom.liquid = LiquidCondition{LiquidCondition::Kind::pressure, TimeFunction{{{0.0, base}}}};
  c.boundaries = {bottom};
  const auto grid = make_grid<1>(c);
  ImplicitSolver<1, numerics::LinearKernel> solver(c, grid, fill_bodies<1>(c, grid), 1);
  auto& fp = solver.fluids();
  const auto& mp = solver.points();
  for (std::size_t p = 0; p < fp.size(); ++p) {
    fp.liquid_pressure[p] = rho_w * g * (1.5 - mp.position[p][0]);
    fp.gas_pressure[p] = 0.0;
    fp.saturation[p] = 1.0;
    fp.liquid_density[p] = c.fluids->liquid.density(fp.liquid_pressure[p]);
  }
  for (double t = 0.0; t < c.solver.end_time - 1e-9; t += solver.interval())
    solver.step(t, solver.interval());
  EXPECT_GE(solver.rain_held_nodes(), 1);
  const double x_top = mp.position.back()[0];
  EXPECT_NEAR(fp.liquid_pressure.back(), base * (1.0 - x_top), 0.01 * base * (1.0 - x_top));
  // Steady upward flow leaves through the top node (x = 1 m) at K_s (0.5 m / 1 m) rho_w: inflow
  // there -4.9e-2 kg/(m^2 s), within 1 %.
  const double q = kappa * rho_w * g / mu * 0.5 * rho_w;
  EXPECT_NEAR(solver.surface_liquid_inflow()[20], -q, 0.01 * q);
}

}  // namespace test_rainfall
}  // namespace unsatmpm
