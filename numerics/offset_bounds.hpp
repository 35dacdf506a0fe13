// The fluid the offsets' relaxation moves between the points (numerics/pressure_offsets.hpp),
// kept and held within the range of the pressures around each point, so that a pass makes no new
// extreme in its fluid's pressure.
//
// The relaxation moves the mass w_p y_p of each point (y_p = beta_p (I - S_1) Q, w_p its storage
// times its volume) through its nodes: point p hands N_ip w_p y_p to node i and takes back
// N_ip w_p Ybar_i, Ybar_i = sum_q N_iq w_q y_q / sum_q N_iq w_q, so its mass changes by
// F_ip = N_ip w_p (Ybar_i - y_p) from node i, and the F_ip of a node sum to zero. That exchange
// keeps the fluid but is not monotone: a point at or below its fit takes its node's mean, in
// pressure at its own storage. On the embankment's wetted face (P0 = 50 kPa, an occluded gas
// giving way, main cycle, 2026-11-29) the face's highest point, at its fit, rose by 150-260 Pa at
// each relaxation beside heavier points above theirs, to +6.5 kPa where the face is held at 0,
// and its neighbours' fits, which reach it, rose with it, until one of them loosened, filled with
// water and was thrown out at 480 kPa (verification/embankment/investigations.md, "What stopped
// them").
//
// So the exchange is limited as in flux-corrected transport (Zalesak, J. Comput. Phys. 31, 1979;
// Kuzmin, Löhner & Turek, "Flux-Corrected Transport", 2012), the nodes taking the place of the
// edges. A point may change in the pass's fluid's pressure by what keeps it within the extremes
// of that pressure over the points its nodes reach, taken at the pass's start: between lo_p <= 0
// and hi_p >= 0. With P_p+ and P_p- the sums of its positive and negative F_ip, it takes the
// fraction R_p+ = min(1, w_p hi_p / P_p+) of each inflow and gives R_p- = min(1, w_p lo_p / P_p-)
// of each outflow at most. At node i the inflows so allowed, A_i = sum R_p+ F_ip+, and the
// outflows, G_i = sum R_p- |F_ip-|, are both scaled to the smaller, T_i = min(A_i, G_i), so the
// node's exchange still sums to zero, and each point changes by
// sum_i (R_p+ F_ip+ T_i / A_i + R_p- F_ip- T_i / G_i) / w_p, between lo_p and hi_p. Away from
// the extremes R = 1 and the exchange is as before; a point at its range's top takes nothing, and
// what its neighbours give goes to the node's other points in proportion to what they may take
// (a single factor per node, the smallest R of its points, stops nearly every exchange beside an
// extreme: in tests/numerics/test_pressure_offsets.cpp's wetted face it moved no point by more
// than 6.2 Pa, this form by up to 36 Pa). Only the pass's own fluid is bounded:
// the other's pressure moves with it at its content fixed (pressure_offsets.hpp), and bounded by
// its own range, a single value where that fluid is uniform, it would stop the pass altogether (a
// liquid offset at uniform gas pressure, tests/cycles/test_undrained.cpp); the other fluid's pass
// bounds that one.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "numerics/explicit_transfers.hpp"
#include "numerics/material_points.hpp"
#include "numerics/offset_stencils.hpp"
#include "numerics/parallel.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {

/// The relaxation's scratch: the points' stencils, per thread a node buffer, per node the extremes
/// of the pass's fluid's pressure around it at the pass's start, and per point its limits.
struct OffsetScratch {
  StencilCache stencils;
  std::vector<std::vector<double>> threads{std::vector<double>{}};
  // Per node: max Q and max -Q over the points it reaches that take part in the pass (-inf where
  // none does), Q the pass's fluid's pressure after the step's increments (subtract_projection).
  std::vector<double> bounds;
  std::vector<double> limits;  // per point: R+ and R- (exchange_within_bounds)
  void resize(int n_threads) { threads.resize(static_cast<std::size_t>(n_threads)); }
};

/// Point p's limits on its inflows and outflows (R_p+, R_p-, above), with its stencil `st`
/// evaluated, the nodes' means Ybar at stride 4 in `sums` and the nodes' bounds in `bounds`; its
/// exchanges F_ip with each node are left in `f` (0 where N_ip = 0).
inline std::pair<double, double> inflow_outflow_limits(const CachedStencil& st, const double* sums,
                                                       const double* bounds, double w, double y,
                                                       double q, double* f) {
  constexpr double none = -std::numeric_limits<double>::infinity();
  double hi = none, minus_lo = none, gain = 0.0, loss = 0.0;
  for (int k = 0; k < st.n; ++k) {
    f[k] = 0.0;
    if (!(st.w[k] > 0.0)) continue;
    const std::int64_t i = st.node(k);
    const double* b = bounds + 2 * i;
    hi = std::max(hi, b[0]), minus_lo = std::max(minus_lo, b[1]);
    f[k] = st.w[k] * w * (sums[4 * i + 1] - y);
    (f[k] > 0.0 ? gain : loss) += f[k];
  }
  const double up = std::max(hi - q, 0.0), down = std::min(-minus_lo - q, 0.0);
  return {gain > w * up ? w * up / gain : 1.0, loss < w * down ? w * down / loss : 1.0};
}

/// Replaces the relaxation's moved values y (fluid a's pass, weights w) by minus the limited
/// exchange's change of each point's pressure (above): the fluid moved between the points sums to
/// zero, and no point's pressure, `pressure` plus the step's increment `increment`, leaves the
/// range of the pressures around it (scratch.bounds, left by subtract_projection,
/// numerics/pressure_offsets.hpp). The points' stencils are read from scratch.stencils.
template <int D, class K>
void exchange_within_bounds(const Grid<D>& grid, const MaterialPoints<D>& mp,
                            const std::vector<double>& pressure,
                            const std::vector<double>& increment, const std::vector<double>& w,
                            OffsetScratch& scratch, std::vector<double>& y) {
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size()), n_nodes = grid.n_nodes();
  // Per node: sum N w, then the mean Ybar; the allowed inflows A, then outflows G, replaced by
  // T / A and T / G.
  for (auto& b : scratch.threads) b.resize(static_cast<std::size_t>(4 * n_nodes));
  const double* bounds = scratch.bounds.data();
  scratch.limits.resize(static_cast<std::size_t>(2 * n_mp));
  double* limits = scratch.limits.data();
  const StencilCache& stencils = scratch.stencils;
  stencils.require(mp.size());
  parallel_region(static_cast<int>(scratch.threads.size()), [&] {
    double* buf = cleared_thread_buffer(scratch.threads);
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (!(w[p] > 0.0)) continue;
      const CachedStencil st = stencils[p];
      for (int k = 0; k < st.n; ++k) {
        double* r = buf + 4 * st.node(k);
        r[0] += st.w[k] * w[p], r[1] += st.w[k] * w[p] * y[p];
      }
    }
    reduce_thread_buffers(scratch.threads);
    double* sums = scratch.threads[0].data();
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n_nodes; ++i)
      sums[4 * i + 1] = sums[4 * i] > 0.0 ? sums[4 * i + 1] / sums[4 * i] : 0.0;
    // Only the threads' own buffers' last two places are written below (thread 0's is `sums`).
    for (std::int64_t i = 0; i < n_nodes; ++i) buf[4 * i + 2] = buf[4 * i + 3] = 0.0;
#pragma omp barrier
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (!(w[p] > 0.0)) continue;
      const CachedStencil st = stencils[p];
      double f[stencil_capacity<D, K>];
      const auto [r_in, r_out] =
          inflow_outflow_limits(st, sums, bounds, w[p], y[p], pressure[p] + increment[p], f);
      limits[2 * p] = r_in, limits[2 * p + 1] = r_out;
      for (int k = 0; k < st.n; ++k) {
        if (f[k] > 0.0)
          buf[4 * st.node(k) + 2] += r_in * f[k];
        else
          buf[4 * st.node(k) + 3] -= r_out * f[k];
      }
    }
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n_nodes; ++i) {
      double* r = sums + 4 * i;
      for (std::size_t t = 1; t < scratch.threads.size(); ++t)
        r[2] += scratch.threads[t][4 * i + 2], r[3] += scratch.threads[t][4 * i + 3];
      const double both = std::min(r[2], r[3]);
      r[2] = r[2] > 0.0 ? both / r[2] : 0.0, r[3] = r[3] > 0.0 ? both / r[3] : 0.0;
    }
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      if (!(w[p] > 0.0)) continue;
      const CachedStencil st = stencils[p];
      const double r_in = limits[2 * p], r_out = limits[2 * p + 1];
      double change = 0.0;  // of the point's pressure
      for (int k = 0; k < st.n; ++k) {
        const double* r = sums + 4 * st.node(k);
        const double f = st.w[k] * (r[1] - y[p]);
        change += f > 0.0 ? r_in * r[2] * f : r_out * r[3] * f;
      }
      y[p] = -change;
    }
  });
}

}  // namespace unsatmpm::numerics
