// The relaxation of each fluid's pressure offsets between the points of a cell
// (relax_pressure_offsets), applied to a step's increments before the masses are assigned: by the
// explicit cycle every step, by the main cycle ten times a coupling interval
// (cycles/undrained.hpp).
//
// The explicit cycle keeps the pressures on the points. The grid sees a point's pressure only
// through sums over the points of its cells (the nodal forces, the nodal mass balances), so a
// pattern of offsets between the points of a cell that these sums do not see is never evened
// out: the null space of the points-to-grid map (Hammerquist & Nairn, Comput. Part. Mech. 2017,
// "Improving accuracy in the MPM method using a null space filter"). The increments themselves
// are smooth (nodal update), but points that move past each other carry the increments of
// different paths into one cell. On the explicit embankment, resumed at 100 s, the gas pressure's
// offsets from its cell's mean were all in the accumulated increments, none in the inversion
// (rms 1.1 kPa at 101 s, 1.5 kPa at 104 s, single points 15-20 kPa below their cells; the
// liquid's 10.9 kPa rms at 100 s against the main cycle's 7.6); by 121 s the gas's reached
// -60 kPa, where the gas law rho = exp(P / K) leaves 0.3 % of the gas and its own wave (1.8 km/s)
// collapsed the explicit step (verification/embankment/README.md).
//
// In the soil a fluid diffuses: across one cell of size h in about h^2 / D_a, with its
// diffusivity D_a = rho_a kappa k_ra / (mu_a s_a) (s_a its storage at the other fluid's content
// fixed, below). So each fluid's offsets are relaxed here at that rate. With S_1 the
// volume-weighted least-squares linear fit of the points' values at each node, evaluated at the
// points and blended with the shape functions (it reproduces a linear field, also at the body's
// edge), and S_0 the weighted mean at each node interpolated back (it keeps sum_p w_p Q_p, w the
// weights below), each step moves the points' new pressures Q by
//   f = -(I - S_0) [beta (I - S_1) Q],   beta_p = min(1, dt D_a,p / h^2),
// so that a pattern the nodes do not see ((I - S) Q = Q) decays at the rate D_a / h^2, a linear
// field is left alone, and the fluid moved between the points sums to zero (the outer S_0),
// which exchange is limited so that no point leaves the range of the pressures around it
// (numerics/offset_bounds.hpp; away from the extremes it is (I - S_0) itself). A
// resolved field of wavenumber k is left alone but for the interpolation's offset between the
// points of a cell, of order (k h)^3: it changes by about beta (k h)^3 / 34 a step (measured),
// where the fluid's own diffusion changes it by beta (k h)^2, 2 % of that at 10 cells a
// wavelength (tests/numerics/test_pressure_offsets.cpp). Where a fluid hardly moves (dry soil's
// water) its offsets relax as slowly as it flows. The mass moved between the points is w_p f_p
// with w_p = V_p s_a,p, at a fixed content of the other fluid at each point (dP_g = -A_gl f / A_gg
// for the liquid, dP_l = -A_lg f / A_ll for the gas), so s_l = A_ll - A_lg A_gl / A_gg and
// s_g = A_gg - A_gl A_lg / A_ll; where the point holds P_g (no gas phase, or no gas storage) the
// gas takes no part and the liquid's storage is A_ll. (A lumped mean in all three passes moved
// the hydrostatic column's edge points, whose one-sided mean is off by a fraction of the field's
// change over a cell: 44 Pa in 0.1 s in tests/cycles/test_three_phase_cycle.cpp. A nodal value
// from the linear fit, interpolated, extrapolated the fit to nodes the points barely reach and
// drove a rain-wetted block's gas to vacuum.)
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Cholesky>

#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"
#include "numerics/offset_bounds.hpp"
#include "numerics/parallel.hpp"
#include "numerics/shape_functions.hpp"
#include "physics/unsaturated_state.hpp"

namespace unsatmpm::numerics {

/// Fluid a's storage at the other fluid's content fixed [kg/m^3/Pa] at a point of storage matrix
/// `a` and saturation s_l: 0 for the gas where the point holds P_g (no gas phase, or no gas
/// storage), A_ll for the liquid there.
inline double storage_at_fixed_other(const physics::StorageMatrix& a, double s_l,
                                     physics::Fluid fluid) {
  const bool gas_held = 1.0 - s_l <= physics::gas_free_saturation || !(a.gg > 0.0);
  if (!(a.ll > 0.0)) return 0.0;
  if (fluid == physics::gas_phase) return gas_held ? 0.0 : std::max(a.gg - a.gl * a.lg / a.ll, 0.0);
  return gas_held ? a.ll : std::max(a.ll - a.lg * a.gl / a.gg, 0.0);
}

/// A node's fit from the sums of subtract_projection below, left in place of the sums of y: the
/// weighted least-squares linear fit a + b.d to the points the node reaches (exact for a linear
/// field; b's components 0 along directions the points do not span). `r`: M0 = sum N w,
/// sum N w d, the upper triangle of sum N w d d^T, then sum N w y and sum N w y d, with
/// d = (x_p - x_i) / h per direction.
template <int D>
void fit_node(double* r) {
  constexpr int n_moments = 1 + D + D * (D + 1) / 2;
  const double m0 = r[0], y0 = r[n_moments];
  using MatD = Eigen::Matrix<double, D, D>;
  MatD c;
  Vec<D> m1, rhs;
  for (int a = 0, k = 1 + D; a < D; ++a) {
    m1[a] = r[1 + a];
    for (int b = a; b < D; ++b, ++k) c(a, b) = c(b, a) = r[k];
  }
  for (int a = 0; a < D; ++a) rhs[a] = r[n_moments + 1 + a];
  // The slope from the weighted covariance of the offsets d.
  c -= m1 * m1.transpose() / m0;
  rhs -= m1 * (y0 / m0);
  const Eigen::LDLT<MatD> ldlt(c);
  // The points reach a node from a quarter cell around it at least (GIMP, 2 a cell): a pivot of
  // 1e-6 of the weight means they lie on a line or a point, and the slope is not fitted.
  Vec<D> slope = Vec<D>::Zero();
  if (ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 1e-6 * m0)
    slope = ldlt.solve(rhs);
  r[n_moments] = (y0 - m1.dot(slope)) / m0;
  for (int a = 0; a < D; ++a) r[n_moments + 1 + a] = slope[a];
}

/// The position of a stencil's slot relative to its slot 0, in cells (the stencil's tensor order,
/// x fastest: numerics/shape_functions.hpp).
template <int D, class K>
Vec<D> stencil_offset(int slot) {
  Vec<D> o;
  for (int a = 0; a < D; ++a, slot /= K::n_support) o[a] = slot % K::n_support;
  return o;
}

/// Fluid a's diffusivity D_a = rho_a kappa k_ra / (mu_a s_a) [m^2/s] at point p of volume v and
/// weight w = v s_a > 0 (s_a: storage_at_fixed_other), with kappa k_ra / mu_a = n S_a / drag_a.
template <int D>
double fluid_diffusivity(const FluidPoints<D>& fp, std::int64_t p, physics::Fluid fluid, double v,
                         double w) {
  const bool gas = fluid == physics::gas_phase;
  const double s_a = gas ? 1.0 - fp.saturation[p] : fp.saturation[p];
  const double mobility = fp.porosity[p] * s_a / (gas ? fp.gas_drag[p] : fp.liquid_drag[p]);
  return (gas ? fp.gas_density[p] : fp.liquid_density[p]) * mobility * v / w;
}

/// Y <- Y - S_1 Y over the points of weight w > 0 (`weight`): S_1 fits the point values Y at each
/// node (fit_node) and evaluates the nodes' fits at each point, blended with the shape functions.
/// It reproduces a linear field, also at the body's edge, where the mean of one-sided points is
/// off by a fraction of the field's change over a cell. It weights the points that take part by
/// their volume alone: its fit is the target the offsets relax to, not a balance (the exchange
/// after it keeps the fluid, numerics/offset_bounds.hpp), and weighted by the storages, which
/// differ by orders of magnitude between a saturated point or one at a retention law's flat S_max
/// and an unsaturated neighbour, it ignored the light points' own values and extrapolated their
/// heavier neighbours' field to them: on the embankment's crest corner (main cycle, 2026-11-28)
/// two points at S_max went to +105 and +138 kPa beside neighbours below -15 kPa and the surface
/// held at 0, and were thrown out. And the fit at a point is held within the values of the points
/// its nodes reach: the least-squares line of a concave field lies above its ends, and at a
/// wetted corner (the surface at zero suction, the soil drier inwards) the volume-weighted fit
/// still raised the corner point's liquid pressure above its gas's (+9 kPa at 13.5 s on 0.4 m
/// cells, main cycle), where the net stress reached the tension cut-off and the point was torn
/// loose (kinetic energy 15.8 J/m at 14 s; 4e-5 J/m bounded). A smooth field is within the bounds
/// there: a resolved sine's change stays third order (tests/numerics/test_pressure_offsets.cpp).
/// Those bounds, max Y and max -Y over the points each node reaches, are left in scratch.bounds.
/// The points' stencils are read from scratch.stencils, which fill_stencils must have filled for
/// the points' positions (numerics/offset_stencils.hpp).
template <int D, class K>
void subtract_projection(const Grid<D>& grid, const MaterialPoints<D>& mp,
                         const std::vector<double>& weight, OffsetScratch& scratch,
                         std::vector<double>& y) {
  constexpr int n_moments = 1 + D + D * (D + 1) / 2, n_fit = 1 + D;
  // The sums, the fit in place of the sums of y, and the bounds max y and max -y.
  constexpr int n_summed = n_moments + n_fit, stride = n_summed + 2;
  constexpr double none = -std::numeric_limits<double>::infinity();
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size()), n_nodes = grid.n_nodes();
  const int n_threads = static_cast<int>(scratch.threads.size());
  for (auto& b : scratch.threads) b.resize(static_cast<std::size_t>(stride * n_nodes));
  scratch.bounds.resize(static_cast<std::size_t>(2 * n_nodes));
  const StencilCache& stencils = scratch.stencils;
  stencils.require(mp.size());
  parallel_region(n_threads, [&] {
    double* buf = cleared_thread_buffer(scratch.threads);
    for (std::int64_t i = 0; i < n_nodes; ++i)
      buf[stride * i + n_summed] = buf[stride * i + n_summed + 1] = none;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (weight[p] <= 0.0) continue;
      const CachedStencil st = stencils[p];
      Vec<D> base;
      for (int a = 0; a < D; ++a) base[a] = stencils.offset_of(p, a);
      for (int k = 0; k < st.n; ++k) {
        double* r = buf + stride * st.node(k);
        const double wn = st.w[k] * mp.volume[p];
        r[0] += wn, r[n_moments] += wn * y[p];
        const Vec<D> d = base - stencil_offset<D, K>(st.slot(k));
        for (int a = 0, j = 1 + D; a < D; ++a) {
          r[1 + a] += wn * d[a], r[n_moments + 1 + a] += wn * y[p] * d[a];
          for (int b = a; b < D; ++b, ++j) r[j] += wn * d[a] * d[b];
        }
        if (st.w[k] > 0.0) {
          r[n_summed] = std::max(r[n_summed], y[p]);
          r[n_summed + 1] = std::max(r[n_summed + 1], -y[p]);
        }
      }
    }
    // The threads' buffers into the first: the sums added, the bounds by their largest.
    double* sums = scratch.threads[0].data();
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n_nodes; ++i) {
      double* r = sums + stride * i;
      for (int t = 1; t < n_threads; ++t) {
        const double* o = scratch.threads[t].data() + stride * i;
        for (int j = 0; j < n_summed; ++j) r[j] += o[j];
        for (int j = n_summed; j < stride; ++j) r[j] = std::max(r[j], o[j]);
      }
      scratch.bounds[2 * i] = r[n_summed], scratch.bounds[2 * i + 1] = r[n_summed + 1];
      if (r[0] > 0.0)
        fit_node<D>(r);
      else
        std::fill(r + n_moments, r + n_summed, 0.0);
    }
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (weight[p] <= 0.0) continue;
      const CachedStencil st = stencils[p];
      Vec<D> base;
      for (int a = 0; a < D; ++a) base[a] = stencils.offset_of(p, a);
      double s = 0.0, hi = none, minus_lo = none;
      for (int k = 0; k < st.n; ++k) {
        const double* fit = sums + stride * st.node(k) + n_moments;
        double value = fit[0];
        const Vec<D> d = base - stencil_offset<D, K>(st.slot(k));
        for (int a = 0; a < D; ++a) value += fit[1 + a] * d[a];
        if (st.w[k] > 0.0)
          hi = std::max(hi, fit[n_fit]), minus_lo = std::max(minus_lo, fit[n_fit + 1]);
        s += st.w[k] * value;
      }
      y[p] -= std::clamp(s, -minus_lo, hi);
    }
  });
}

/// Moves the step's increments of fluid a's pressure (and of the other's, at its content fixed)
/// by the relaxation of fluid a's offsets above, with the storage and drag of the step's start
/// (FluidPoints::storage, liquid_drag, gas_drag). The rate columns of `fp` (no longer needed once
/// the increments are solved) serve as the weights and the filtered values. scratch.stencils must
/// hold the points' stencils (fill_stencils).
template <int D, class K>
void relax_offsets(const Grid<D>& grid, const MaterialPoints<D>& mp, double dt,
                   physics::Fluid fluid, OffsetScratch& scratch, FluidPoints<D>& fp) {
  const bool gas = fluid == physics::gas_phase;
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const int n_threads = static_cast<int>(scratch.threads.size());
  std::vector<double>& w = fp.liquid_rate;
  std::vector<double>& y = fp.gas_rate;
  std::vector<double>& own = gas ? fp.gas_increment : fp.liquid_increment;
  std::vector<double>& other = gas ? fp.liquid_increment : fp.gas_increment;
  const std::vector<double>& pressure = gas ? fp.gas_pressure : fp.liquid_pressure;
  const double h2 = grid.min_spacing() * grid.min_spacing();
  parallel_region(n_threads, [&] {
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      w[p] = mp.volume[p] * storage_at_fixed_other(fp.storage[p], fp.saturation[p], fluid);
      y[p] = w[p] > 0.0 ? pressure[p] + own[p] : 0.0;
    }
  });
  subtract_projection<D, K>(grid, mp, w, scratch, y);
  parallel_region(n_threads, [&] {
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (!(w[p] > 0.0)) continue;
      y[p] *= std::min(1.0, dt * fluid_diffusivity(fp, p, fluid, mp.volume[p], w[p]) / h2);
    }
  });
  exchange_within_bounds<D, K>(grid, mp, pressure, own, w, scratch, y);
  parallel_region(n_threads, [&] {
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (!(w[p] > 0.0)) continue;
      const physics::StorageMatrix& a = fp.storage[p];
      own[p] -= y[p];
      if (gas)
        other[p] += a.lg * y[p] / a.ll;
      else if (storage_at_fixed_other(a, fp.saturation[p], physics::gas_phase) > 0.0)
        other[p] += a.gl * y[p] / a.gg;
    }
  });
}

/// Both fluids' offsets relaxed, the liquid's first, over the points' stencils evaluated once.
template <int D, class K>
void relax_pressure_offsets(const Grid<D>& grid, const MaterialPoints<D>& mp, double dt,
                            OffsetScratch& scratch, FluidPoints<D>& fp) {
  fill_stencils<D, K>(grid, mp, static_cast<int>(scratch.threads.size()), scratch.stencils);
  relax_offsets<D, K>(grid, mp, dt, physics::liquid_phase, scratch, fp);
  relax_offsets<D, K>(grid, mp, dt, physics::gas_phase, scratch, fp);
}

}  // namespace unsatmpm::numerics
