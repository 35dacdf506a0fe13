// The phases of the explicit one-phase MPM step, each a plain loop over contiguous arrays:
//   p2g          MP mass, momentum, internal and gravity forces to the nodes (per-thread buffers)
//   reduce       sum the per-thread buffers node by node
//   solve_grid   nodal accelerations with local damping, boundary conditions, Euler-Cromer velocity
//   g2p          MP velocity (FLIP/PIC blend), position, velocity gradient, strain, volume, and the
//                stress update (Jaumann-rotated, then the constitutive increment) — update stress
//                last; in the one-phase cycle with linear shape functions the velocity gradient is
//                taken from the points' updated momenta mapped back to the nodes (MUSL,
//                numerics/velocity_remap.hpp)
// Internal force f_a = -sum_p V_p sigma_p . grad N_a(x_p); gravity f_a = sum_p m_p N_a(x_p) g.
// Local damping (docs/balance_laws.md): f_damp = -alpha |f| sign(v), component by component.
#pragma once

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <type_traits>

#include "numerics/material_points.hpp"
#include "numerics/nodal_state.hpp"
#include "numerics/parallel.hpp"
#include "numerics/point_models.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm::numerics {

/// sigma . grad N for the first D rows of the Voigt stress (force per unit volume, per node
/// weight).
template <int D>
inline Vec<D> stress_dot_gradient(const physics::Vec6& s, const Vec<D>& g) {
  Vec<D> f;
  if constexpr (D == 1) {
    f[0] = s[0] * g[0];
  } else if constexpr (D == 2) {
    f[0] = s[0] * g[0] + s[3] * g[1];
    f[1] = s[3] * g[0] + s[1] * g[1];
  } else {
    f[0] = s[0] * g[0] + s[3] * g[1] + s[5] * g[2];
    f[1] = s[3] * g[0] + s[1] * g[1] + s[4] * g[2];
    f[2] = s[5] * g[0] + s[4] * g[1] + s[2] * g[2];
  }
  return f;
}

/// Inside a parallel region: this thread's scatter buffer, zeroed.
inline double* cleared_thread_buffer(std::vector<std::vector<double>>& scatter) {
  std::vector<double>& buf = scatter[omp_get_thread_num()];
  std::fill(buf.begin(), buf.end(), 0.0);
  return buf.data();
}

/// Inside a parallel region, after the scatter loop: sums the other threads' buffers into
/// buffer 0, value range by value range (each thread a range: no races, no locks).
inline void reduce_thread_buffers(std::vector<std::vector<double>>& scatter) {
  const int n_threads = static_cast<int>(scatter.size());
  if (n_threads == 1) return;
  const std::int64_t n_values = static_cast<std::int64_t>(scatter[0].size());
#pragma omp for schedule(static)
  for (std::int64_t i = 0; i < n_values; ++i) {
    double s = 0.0;
    for (int t = 1; t < n_threads; ++t) s += scatter[t][i];
    scatter[0][i] += s;
  }
}

/// What the pore fluids add to a point of the mixture when they move with the solid (the implicit
/// cycle's mechanics, docs/cycles.md): their mass n S_a rho_a V [kg] and the pore pressure
/// max(P_l, P_g) [Pa] that turns the net stress into the total stress.
struct PoreLoads {
  std::span<const double> added_mass;
  std::span<const double> pore_pressure;
  std::span<const double> suction;     // [Pa], per point, for a suction-dependent strength
  std::span<StrengthMemo> strength;    // per point, the strength prepared at that suction
  std::span<const double> max_volume;  // [m^3], per point (HydraulicModel::max_volume)
};

/// No pore fluids: a one-phase solid (the default of p2g and g2p).
struct NoPoreLoads {};

/// MUSL's remap (numerics/velocity_remap.hpp) in the step of kernel K and pore loads Pore: the
/// one-phase cycle with linear shape functions. The main cycle's mixture keeps the nodes' own
/// velocities (USL): with the remap its saturated columns at the saturation kink went unstable
/// at a lower liquid stiffness (velocity_remap.hpp says what was measured).
template <class K, class Pore>
inline constexpr bool remaps_velocity = (K::remap_velocity) && (std::is_same_v<Pore, NoPoreLoads>);

/// Scatters MP mass, momentum and forces into the per-thread buffers, then sums them into
/// buffer 0. `gravity` [m/s^2]. With PoreLoads, the mass is the mixture's and the stress the
/// total stress sigma = sigma_bar - p_pore I (mp.stress being the net stress); the choice is made
/// at compile time, not per point.
template <int D, class K, class Pore = NoPoreLoads>
void p2g(const Grid<D>& grid, const MaterialPoints<D>& mp, const Vec<D>& gravity,
         NodalState<D>& nodes, const Pore& pore = {}) {
  constexpr bool with_pore = std::is_same_v<Pore, PoreLoads>;
  static_assert(with_pore || std::is_same_v<Pore, NoPoreLoads>, "PoreLoads or NoPoreLoads");
  constexpr int R = NodalState<D>::record;
  const std::int64_t n_mp = static_cast<std::int64_t>(mp.size());
  const int n_threads = static_cast<int>(nodes.scatter.size());
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(n_threads, [&] {
    double* buf = cleared_thread_buffer(nodes.scatter);
    TransferStencil<D, K> st;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n_mp; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      double m = mp.mass[p];
      if constexpr (with_pore) m += pore.added_mass[p];
      const double vol = mp.volume[p];
      double mom[D], fg[D];
      for (int d = 0; d < D; ++d) mom[d] = m * mp.velocity[p][d], fg[d] = m * gravity[d];
      physics::Vec6 vs = vol * mp.stress[p];
      if constexpr (with_pore)
        for (int d = 0; d < 3; ++d) vs[d] -= vol * pore.pore_pressure[p];
      for (int a = 0; a < st.n; ++a) {
        double* rec = buf + st.node[a] * R;
        const double w = st.w[a];
        rec[0] += w * m;
        const Vec<D> fi = stress_dot_gradient<D>(vs, st.grad[a]);
        for (int d = 0; d < D; ++d) {
          rec[1 + d] += w * mom[d];
          rec[1 + D + d] += w * fg[d] - fi[d];
        }
      }
    }
    reduce_thread_buffers(nodes.scatter);
  });
}

/// Nodal accelerations and Euler-Cromer velocities. Nodes lighter than `mass_floor` [kg] are
/// treated as empty (zero velocity) so that a sliver of mass cannot produce a huge acceleration.
/// Fixed components, then rigid plates (numerics/rigid_plates.hpp).
template <int D>
void solve_grid(double dt, double damping, double mass_floor, NodalState<D>& nodes) {
  const std::int64_t n = nodes.n_nodes();
  parallel_region(static_cast<int>(nodes.scatter.size()), [&] {
#pragma omp for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      const double m = nodes.mass(i);
      if (m <= mass_floor) {
        nodes.velocity[i].setZero();
        nodes.acceleration[i].setZero();
        continue;
      }
      const Vec<D> v_old = nodes.momentum(i) / m;
      const Vec<D> f = nodes.force(i);
      Vec<D> a;
      for (int d = 0; d < D; ++d) {
        const double sign = v_old[d] > 0.0 ? 1.0 : (v_old[d] < 0.0 ? -1.0 : 0.0);
        a[d] = (f[d] - damping * std::abs(f[d]) * sign) / m;
      }
      Vec<D> v = v_old + dt * a;
      const std::uint8_t mask = nodes.fixed[i];
      for (int d = 0; d < D; ++d)
        if (mask & (1u << d)) {
          // A held component has zero velocity after the step; its acceleration is what brings it
          // there, so FLIP's increment and PIC's value agree.
          a[d] = -v_old[d] / dt;
          v[d] = 0.0;
        }
      nodes.acceleration[i] = a;
      nodes.velocity[i] = v;
    }
  });
  apply_rigid_plates(nodes.plates, dt, damping, mass_floor, nodes);
}

/// Objective (Jaumann) rotation of the stress by the spin increment W dt: sigma += W s - s W.
template <int D>
inline void rotate_stress(const Eigen::Matrix<double, D, D>& spin_dt, physics::Vec6& s) {
  if constexpr (D == 2) {
    const double w = spin_dt(0, 1);
    const double sxy = s[3], sxx = s[0], syy = s[1];
    s[0] += 2.0 * w * sxy;
    s[1] -= 2.0 * w * sxy;
    s[3] += w * (syy - sxx);
  } else if constexpr (D == 3) {
    // W s - s W for skew W (w1 = W_xy, w2 = W_yz, w3 = W_xz), written out component by component.
    const double w1 = spin_dt(0, 1), w2 = spin_dt(1, 2), w3 = spin_dt(0, 2);
    const double xx = s[0], yy = s[1], zz = s[2], xy = s[3], yz = s[4], zx = s[5];
    s[0] += 2.0 * (w1 * xy + w3 * zx);
    s[1] += 2.0 * (-w1 * xy + w2 * yz);
    s[2] += 2.0 * (-w3 * zx - w2 * yz);
    s[3] += w1 * (yy - xx) + w3 * yz + w2 * zx;
    s[4] += -w1 * zx + w2 * (zz - yy) - w3 * xy;
    s[5] += w1 * yz - w2 * xy + w3 * (zz - xx);
  }
}

/// det(I + A) written out for the small fixed sizes (the volume ratio of a step).
template <int D>
inline double det_identity_plus(const Eigen::Matrix<double, D, D>& a) {
  if constexpr (D == 1) {
    return 1.0 + a(0, 0);
  } else if constexpr (D == 2) {
    return (1.0 + a(0, 0)) * (1.0 + a(1, 1)) - a(0, 1) * a(1, 0);
  } else {
    const Eigen::Matrix3d f = Eigen::Matrix3d::Identity() + a;
    return f(0, 0) * (f(1, 1) * f(2, 2) - f(1, 2) * f(2, 1)) -
           f(0, 1) * (f(1, 0) * f(2, 2) - f(1, 2) * f(2, 0)) +
           f(0, 2) * (f(1, 0) * f(2, 1) - f(1, 1) * f(2, 0));
  }
}

/// The solid's part of g2p at one point, from the velocity gradient times dt: strain increment,
/// volume, and the stress (Jaumann-rotated, then the constitutive increment at the point's
/// suction [Pa], a number or a HeldSuction).
template <int D, class Model, class Suction>
inline void update_solid(const Model& model, const Eigen::Matrix<double, D, D>& l_dt,
                         const Suction& suction, std::int64_t p, MaterialPoints<D>& mp) {
  physics::Vec6 d_eps = physics::Vec6::Zero();
  for (int d = 0; d < D; ++d) d_eps[d] = l_dt(d, d);
  if constexpr (D >= 2) d_eps[3] = l_dt(0, 1) + l_dt(1, 0);
  if constexpr (D == 3) {
    d_eps[4] = l_dt(1, 2) + l_dt(2, 1);
    d_eps[5] = l_dt(0, 2) + l_dt(2, 0);
  }
  mp.volume[p] *= det_identity_plus<D>(l_dt);
  mp.strain[p] += d_eps;
  rotate_stress<D>(0.5 * (l_dt - l_dt.transpose()), mp.stress[p]);
  stress_update(model, d_eps, suction, mp.stress[p], mp.plastic_strain[p]);
}

/// What g2p reports back for the step-size control and the blow-up check.
struct G2pReport {
  double max_wave_speed = 0.0;  // max_p c_p + max_p |v_p| >= max_p (c_p + |v_p|) [m/s]
  std::int64_t first_bad = -1;  // an MP with a non-finite state or outside the grid, or -1
};

/// Grid to points and stress update for the MPs [begin, end) that share one model. With
/// PoreLoads, the strength follows each point's suction [Pa] and its volume is bounded by its
/// max_volume [m^3]; without (a one-phase case), suction 0 and no bound. With MUSL
/// (remaps_velocity, numerics/velocity_remap.hpp) the velocities are updated already and the
/// gradient is taken from nodes.remapped; the position moves with the grid's velocities.
template <int D, class K, class Model, class Pore = NoPoreLoads>
G2pReport g2p(const Grid<D>& grid, const NodalState<D>& nodes, const Model& model, double dt,
              double flip_fraction, std::int64_t begin, std::int64_t end, MaterialPoints<D>& mp,
              const Pore& pore = {}) {
  constexpr bool with_pore = std::is_same_v<Pore, PoreLoads>;
  static_assert(with_pore || std::is_same_v<Pore, NoPoreLoads>, "PoreLoads or NoPoreLoads");
  using MatD = Eigen::Matrix<double, D, D>;
  const double modulus = wave_modulus(model);
  double max_compliance = 0.0, max_v2 = 0.0;  // max V/m [m^3/kg], max |v|^2: no sqrt per point
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  mp.kernel_memo.prepare(grid, mp.size());
  parallel_region(static_cast<int>(nodes.scatter.size()), [&] {
    TransferStencil<D, K> st;
#pragma omp for schedule(static) reduction(max : max_compliance, max_v2) reduction(min : bad)
    for (std::int64_t p = begin; p < end; ++p) {
      evaluate_stencil<D, K>(st, grid, mp, p);
      // Plain scalar accumulators: Eigen's 3-vector temporaries here went through the stack with
      // store-forwarding stalls (measured: a third of the 3D step).
      Vec<D> v_pic = Vec<D>::Zero(), a_sum = Vec<D>::Zero();
      MatD grad_v = MatD::Zero();
      for (int a = 0; a < st.n; ++a) {
        const double* vn = nodes.velocity[st.node[a]].data();
        const double* an = nodes.acceleration[st.node[a]].data();
        // With MUSL the gradient's velocities are the remapped ones, the velocity is updated.
        const double* vg = remaps_velocity<K, Pore> ? nodes.remapped[st.node[a]].data() : vn;
        const double w = st.w[a];
        for (int i = 0; i < D; ++i) {
          v_pic[i] += w * vn[i];
          if constexpr (!remaps_velocity<K, Pore>) a_sum[i] += w * an[i];
          for (int j = 0; j < D; ++j) grad_v(i, j) += vg[i] * st.grad[a][j];
        }
      }
      if constexpr (!remaps_velocity<K, Pore>) {
        const Vec<D> v_flip = mp.velocity[p] + dt * a_sum;
        mp.velocity[p] = flip_fraction * v_flip + (1.0 - flip_fraction) * v_pic;
      }
      const Vec<D> dx = dt * v_pic;
      mp.position[p] += dx;
      mp.displacement[p] += dx;

      if constexpr (with_pore) {
        update_solid<D>(model, MatD(dt * grad_v), HeldSuction{pore.suction[p], pore.strength[p]}, p,
                        mp);
        mp.volume[p] = std::min(mp.volume[p], pore.max_volume[p]);
      } else {
        update_solid<D>(model, MatD(dt * grad_v), 0.0, p, mp);
      }

      const double compliance = mp.volume[p] / mp.mass[p], v2 = mp.velocity[p].squaredNorm();
      max_compliance = std::max(max_compliance, compliance);
      max_v2 = std::max(max_v2, v2);
      if (!(std::isfinite(compliance + v2 + mp.stress[p].sum()) && grid.contains(mp.position[p])))
        bad = std::min(bad, p);
    }
  });
  return {std::sqrt(modulus * max_compliance) + std::sqrt(max_v2),
          bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad};
}

}  // namespace unsatmpm::numerics
