// The pressure ODE's operator at (t, y) for one integration that PressureSystem has set up
// (numerics/pressure/pressure_system.hpp): the nodal pressures, the balances assembled over the
// points as quadrature points,
//   M_i = sum_p N_i V_p A_p (one 2x2 block per node),
//   F_a,i = sum_p V_p [grad N_i . J_a - N_i sigma_a (+ N_i T_a)] (+ the supply),
// with J, sigma, T, A the point quantities of pressure_point.hpp at P_p = sum_j N_j P_j and
// grad P_p = sum_j grad N_j P_j; the nodal rates from M P' = F; and from them y' = M^-1 F, its
// exact Jacobian
//   dy'_i/dP_j = M_i^-1 (dF_i/dP_j - (dM_i/dP_j) P'_i)
// in the pattern of the integration (checked against finite differences in
// tests/numerics/test_pressure_system.cpp), and the mass entering through prescribed nodes and
// supplies. Every query starts from one evaluate().
//
// The sums over the points run on set_threads() threads, each over a contiguous block of points
// into its own copy of the nodal sums (numerics/pressure/thread_sums.hpp), added in thread order:
// the same threads give the same bits; one thread gives the serial sums.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "numerics/pressure/integration_setup.hpp"
#include "numerics/pressure/nodal_permeability.hpp"
#include "numerics/pressure/pressure_point.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/surface_penalty.hpp"
#include "numerics/pressure/thread_sums.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/sparse_pattern.hpp"
#include "numerics/three_phase_transfers.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm::numerics {

template <int D, class K>
class PressureOperator {
 public:
  PressureOperator(const Grid<D>& grid, std::vector<physics::HydraulicModel> models,
                   MassBalance form, const Vec<D>& gravity, IntegrationSetup<D, K> setup)
      : grid_(grid), models_(std::move(models)), form_(form), gravity_(gravity), q_(setup) {
    const auto n = grid_.n_nodes();
    for (int a = 0; a < 2; ++a) {
      pressure_[a].assign(n, 0.0);
      rate_[a].assign(n, 0.0);
      force_[a].assign(n, 0.0);
      penalty_[a].assign(n, 0.0);
    }
    storage_.assign(n, {0.0, 0.0, 0.0, 0.0});
  }

  /// Threads of the sums over the points (>= 1; default 1).
  void set_threads(int n_threads) { sums_.set_threads(n_threads); }
  /// Each point's k_r from its stencil nodes (numerics/pressure/nodal_permeability.hpp), or not.
  void set_nodal_permeability(bool from_nodes) { from_nodes_ = from_nodes; }

  /// Storage added to each point's A (constant over an integration) [kg/(m^3 Pa)]. Empty: none.
  void set_extra_storage(std::vector<physics::StorageMatrix> extra) {
    extra_storage_ = std::move(extra);
  }

  /// The nodal pressures: y's unknowns, or the prescription's values at y's time (rates too).
  void set_pressures(std::span<const double> y) {
    const auto& np = q_.prescription;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a) {
        if (q_.unknowns(a, i) >= 0) {
          pressure_[a][i] = y[q_.unknowns(a, i)];
        } else if (np.prescribed[a][i]) {
          pressure_[a][i] = np.value[a][i];
          rate_[a][i] = np.rate[a][i];
        }
      }
  }

  /// The one evaluation every query below starts from: pressures, balances, rates.
  void evaluate(std::span<const double> y) {
    set_pressures(y);
    assemble_balances();
    solve_rates();
  }

  /// M and F over the points at the current pressures.
  void assemble_balances() {
    with_choices([&](auto form, auto nodes) { assemble<form(), nodes()>(); });
  }

  /// Scales of the inflow unknowns: the sum of the nodal storages of each fluid (after
  /// assemble_balances), so that an inflow integral reads in Pa.
  void scale_inflows() {
    std::array<double, 2> sum{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (q_.points.active(i)) sum[0] += storage_[i].ll, sum[1] += storage_[i].gg;
    for (int a = 0; a < 2; ++a) inflow_scale_[a] = sum[a] > 0.0 ? sum[a] : 1.0;
  }
  /// Mass [kg per unit out-of-plane measure] per unit of the inflow unknowns [Pa].
  double inflow_scale(int a) const { return inflow_scale_[a]; }

  /// y' = M^-1 F (after evaluate). Returns 0, or 1 if a value is not finite.
  int rhs(std::span<double> ydot) const {
    for (const auto i : q_.unknowns.nodes())
      for (int a = 0; a < 2; ++a)
        if (q_.unknowns(a, i) >= 0) ydot[q_.unknowns(a, i)] = rate_[a][i];
    const auto q = inflow();
    for (int a = 0; a < 2; ++a) ydot[q_.unknowns.inflow(a)] = q[a] / inflow_scale_[a];
    for (const double v : ydot)
      if (!std::isfinite(v)) return 1;
    return 0;
  }

  /// dy'/dy in the pattern's order (after evaluate). Returns 0, or 1 if a value is not finite.
  int jacobian(std::span<double> values) const {
    return with_choices(
        [&](auto form, auto nodes) { return jacobian_values<form(), nodes()>(values); });
  }

  /// Mass rate of fluid a entering at node i (after evaluate): M P' - F at a prescribed active
  /// node, and at a node whose gas is an unknown held for want of gas storage (M_gg = 0: the gas
  /// vanished there during the integration, so nothing stores what its balance asks; with a
  /// relative permeability that does not vanish with the gas, gas still flows through it); the
  /// supply where fluid a is an unknown; and the surface penalty's Π_i, which F holds too.
  double node_inflow(int a, std::int64_t i) const {
    const double penalty = q_.penalty[a].value.empty() ? 0.0 : penalty_[a][i];
    const bool held_gas = a == gas_phase && q_.unknowns(a, i) >= 0 && held(i);
    if (prescribed_active(a, i) || held_gas) {
      const auto& m = storage_[i];
      return penalty + (a == liquid_phase ? m.ll * rate_[liquid_phase][i] +
                                                m.lg * rate_[gas_phase][i] - force_[liquid_phase][i]
                                          : m.gl * rate_[liquid_phase][i] +
                                                m.gg * rate_[gas_phase][i] - force_[gas_phase][i]);
    }
    return penalty + (supplied(a, i) ? q_.supply[a][i] : 0.0);
  }

  /// Sum over the nodes of node_inflow, per fluid (after evaluate).
  std::array<double, 2> inflow() const {
    std::array<double, 2> q{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a) q[a] += node_inflow(a, i);
    return q;
  }

  /// Sum over the active nodes of M_i P'_i per fluid (after evaluate) [kg/s].
  std::array<double, 2> storage_rate() const {
    std::array<double, 2> q{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!q_.points.active(i)) continue;
      const auto& m = storage_[i];
      q[0] += m.ll * rate_[liquid_phase][i] + m.lg * rate_[gas_phase][i];
      q[1] += m.gl * rate_[liquid_phase][i] + m.gg * rate_[gas_phase][i];
    }
    return q;
  }

  const std::array<std::vector<double>, 2>& pressures() const { return pressure_; }
  /// Node i's storage M [kg/Pa per unit out-of-plane measure] (after assemble_balances).
  const physics::StorageMatrix& nodal_storage(std::int64_t i) const { return storage_[i]; }
  /// The hydraulics of material m.
  const physics::HydraulicModel& model(int m) const { return models_[m]; }
  const std::vector<physics::HydraulicModel>& models() const { return models_; }
  /// The storage added to point p's A (set_extra_storage), or null if none.
  const physics::StorageMatrix* extra_storage(std::size_t p) const {
    return extra_storage_.empty() ? nullptr : &extra_storage_[p];
  }
  /// The lumped storage block of node i [kg/Pa] (after assemble_balances).
  const physics::StorageMatrix& storage(std::int64_t i) const { return storage_[i]; }

  bool prescribed_active(int a, std::int64_t i) const {
    return q_.prescription.prescribed[a][i] && q_.points.active(i);
  }

 private:
  /// f(form, from nodes) with the mass balance's form and set_nodal_permeability's choice as
  /// compile-time constants (physics::Choice), made once per pass over the points.
  template <class F>
  decltype(auto) with_choices(F&& f) const {
    return physics::with_mass_balance(form_, [&](auto form) {
      return from_nodes_ ? f(form, physics::Choice<true>{}) : f(form, physics::Choice<false>{});
    });
  }
  bool held(std::int64_t i) const { return !(storage_[i].gg > 0.0); }
  bool supplied(int a, std::int64_t i) const {
    return !q_.supply[a].empty() && q_.unknowns(a, i) >= 0 && q_.supply[a][i] != 0.0;
  }

  /// The balances' assembly for one mass-balance form (assemble_balances).
  template <MassBalance Form, bool FromNodes>
  void assemble() {
    if constexpr (FromNodes)
      nodal_laws_.fill(models_, pressure_, [&](std::int64_t i) { return q_.points.active(i); });
    // Per node: M_ll, M_lg, M_gl, M_gg, F_l, F_g.
    sums_.scatter(q_.points.size(), static_cast<std::size_t>(grid_.n_nodes()) * 6,
                  [&](std::size_t p, std::span<double> sum) {
                    const auto& st = q_.points.stencil[p];
                    const double v = q_.points.volume[p];
                    const PointFlow<D> f = flow_at<Form, false, FromNodes>(p);
                    for (int a = 0; a < st.n; ++a) {
                      double* m = &sum[static_cast<std::size_t>(st.node[a]) * 6];
                      const double w = st.w[a] * v;
                      m[0] += w * f.storage.ll, m[1] += w * f.storage.lg;
                      m[2] += w * f.storage.gl, m[3] += w * f.storage.gg;
                      for (int fl = 0; fl < 2; ++fl)
                        m[4 + fl] +=
                            v * st.grad[a].dot(f.flux[fl]) - w * (f.source[fl] - f.advective[fl]);
                    }
                  });
    const std::span<const double> total = sums_.reduce();
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!q_.points.active(i)) continue;
      const double* m = &total[static_cast<std::size_t>(i) * 6];
      storage_[i] = {m[0], m[1], m[2], m[3]};
      force_[liquid_phase][i] = m[4], force_[gas_phase][i] = m[5];
    }
    for (const auto i : q_.unknowns.nodes())
      for (int a = 0; a < 2; ++a)
        if (supplied(a, i)) force_[a][i] += q_.supply[a][i];
    add_penalty();
  }

  /// The surface penalty's Π_i = Σ_j c_ij (P̄ - P_j), into F (assemble).
  void add_penalty() {
    for (int a = 0; a < 2; ++a)
      if (!q_.penalty[a].value.empty())
        add_penalty_mass(q_.penalty[a], q_.prescription.surface_value[a], pressure_[a], penalty_[a],
                         force_[a]);
  }

  /// The Jacobian's values for one mass-balance form (jacobian).
  template <MassBalance Form, bool FromNodes>
  int jacobian_values(std::span<double> values) const {
    sums_.scatter(q_.points.size(), values.size(), [&](std::size_t p, std::span<double> sum) {
      const auto& st = q_.points.stencil[p];
      const double volume = q_.points.volume[p];
      // k_r's derivatives by node where it comes from the nodes (J = k_r u, T = J . h).
      NodalPermeabilityDerivatives<D, K> dk;
      const PointFlow<D> f = flow_at<Form, true, FromNodes>(p, &dk);
      const auto kept = q_.points.jacobian_nodes[p];
      for (int a = 0; a < st.n; ++a) {
        if (!(kept >> a & 1u)) continue;
        const auto i = st.node[a];
        for (int al = 0; al < 2; ++al) {
          // A prescribed balance feeds the inflow integral's row, with the opposite sign.
          const bool inflow_row = prescribed_active(al, i);
          const auto row = inflow_row ? q_.unknowns.inflow(al) : q_.unknowns(al, i);
          const double sign = inflow_row ? -1.0 / inflow_scale_[al] : 1.0;
          if (q_.unknowns(al, i) < 0 && !inflow_row) continue;
          const double pl = rate_[liquid_phase][i], pg = rate_[gas_phase][i];
          for (int b = 0; b < st.n; ++b) {
            if (!(kept >> b & 1u)) continue;
            const auto j = st.node[b];
            const double nn = st.w[a] * st.w[b];
            for (int be = 0; be < 2; ++be) {
              const auto col = q_.unknowns(be, j);
              if (col < 0) continue;
              const auto& da = f.d_storage[be];
              const double dm = al == 0 ? da.ll * pl + da.lg * pg : da.gl * pl + da.gg * pg;
              double k =
                  st.grad[a].dot(f.d_flux[al][be]) * st.w[b] - f.d_source[al][be] * nn - dm * nn;
              if (al == be) k -= f.conductivity[al] * st.grad[a].dot(st.grad[b]);
              if constexpr (FromNodes)
                k += (st.grad[a] + st.w[a] * f.grad_ln_theta[al]).dot(f.unit_flux[al]) *
                     dk[b][al][be];
              if constexpr (Form == MassBalance::simplified)
                k += st.w[a] * (f.d_advective[al][be] * st.w[b] +
                                f.d_advective_d_grad[al][be].dot(st.grad[b]));
              sum[q_.pattern.position(row, col)] += sign * volume * k;
            }
          }
        }
      }
    });
    const std::span<const double> total = sums_.reduce();
    std::copy(total.begin(), total.end(), values.begin());
    for (int a = 0; a < 2; ++a)
      add_penalty_jacobian(q_.penalty[a], a, q_.unknowns, q_.pattern, inflow_scale_[a], values);
    // Left-multiply each node's rows by M_UU^-1 (U: its unknown, not held, fluids).
    for (const auto i : q_.unknowns.nodes()) {
      const auto rl = q_.unknowns(0, i), rg = q_.unknowns(1, i);
      const auto& m = storage_[i];
      const bool gas_held = held(i);
      if (rl >= 0 && rg >= 0 && !gas_held) {
        const double det = m.ll * m.gg - m.lg * m.gl;
        for (auto q = q_.pattern.row_ptr[rl], r = q_.pattern.row_ptr[rg];
             q < q_.pattern.row_ptr[rl + 1]; ++q, ++r) {
          const double kl = values[q], kg = values[r];
          values[q] = (m.gg * kl - m.lg * kg) / det;
          values[r] = (m.ll * kg - m.gl * kl) / det;
        }
      } else {
        if (rl >= 0)
          for (auto q = q_.pattern.row_ptr[rl]; q < q_.pattern.row_ptr[rl + 1]; ++q)
            values[q] /= m.ll;
        if (rg >= 0 && gas_held) {
          // Its gas balance is inflow (node_inflow): -d(F_g - M' P')/dP + M_gl dP'_l/dP.
          const auto row = q_.unknowns.inflow(gas_phase);
          const double scale = inflow_scale_[gas_phase];
          for (auto q = q_.pattern.row_ptr[rg]; q < q_.pattern.row_ptr[rg + 1]; ++q) {
            values[q_.pattern.position(row, q_.pattern.col[q])] -= values[q] / scale;
            values[q] = 0.0;
          }
          if (rl >= 0)
            for (auto q = q_.pattern.row_ptr[rl]; q < q_.pattern.row_ptr[rl + 1]; ++q)
              values[q_.pattern.position(row, q_.pattern.col[q])] += m.gl / scale * values[q];
        } else if (rg >= 0) {
          for (auto q = q_.pattern.row_ptr[rg]; q < q_.pattern.row_ptr[rg + 1]; ++q)
            values[q] /= m.gg;
        }
      }
    }
    // A node with one fluid prescribed and the other free: its inflow also moves with the free
    // fluid's rate, M_aU dP'_U/dP_j.
    for (const auto i : q_.unknowns.nodes())
      for (int al = 0; al < 2; ++al) {
        const int other = 1 - al;
        const auto r = q_.unknowns(other, i);
        if (!prescribed_active(al, i) || r < 0 || (other == 1 && held(i))) continue;
        const auto& m = storage_[i];
        const double coupling = (al == 0 ? m.lg : m.gl) / inflow_scale_[al];
        for (auto q = q_.pattern.row_ptr[r]; q < q_.pattern.row_ptr[r + 1]; ++q)
          values[q_.pattern.position(q_.unknowns.inflow(al), q_.pattern.col[q])] +=
              coupling * values[q];
      }
    for (const double v : values)
      if (!std::isfinite(v)) return 1;
    return 0;
  }

  /// Point p's flow quantities at the current pressures; with `Jacobian`, their derivatives too;
  /// with FromNodes, k_r from the nodes (after assemble) and its derivatives by node into `dk`.
  template <MassBalance Form, bool Jacobian, bool FromNodes>
  PointFlow<D> flow_at(std::size_t p, NodalPermeabilityDerivatives<D, K>* dk = nullptr) const {
    const auto& pts = q_.points;
    const auto& st = pts.stencil[p];
    std::array<double, 2> pr{0.0, 0.0};
    std::array<Vec<D>, 2> gr{Vec<D>::Zero(), Vec<D>::Zero()};
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) {
        pr[f] += st.w[a] * pressure_[f][st.node[a]];
        gr[f] += st.grad[a] * pressure_[f][st.node[a]];
      }
    std::array<double, 2> k{0.0, 0.0};
    if constexpr (FromNodes) k = nodal_laws_.at(pts.model[p], st, dk);
    PointFlow<D> f =
        point_flow<D, Form, Jacobian>(models_[pts.model[p]], {pts.porosity[p], pts.div_vs[p]}, pr,
                                      gr, gravity_, pts.grad_ln_n[p], FromNodes ? &k : nullptr);
    if (!extra_storage_.empty()) {
      const auto& e = extra_storage_[p];
      f.storage.ll += e.ll, f.storage.lg += e.lg, f.storage.gl += e.gl, f.storage.gg += e.gg;
    }
    return f;
  }

  /// Nodal rates of the unknowns from M P' = F, with the prescribed rates known.
  void solve_rates() {
    for (const auto i : q_.unknowns.nodes()) {
      const auto& m = storage_[i];
      const bool free_l = q_.unknowns(0, i) >= 0, free_g = q_.unknowns(1, i) >= 0;
      if (free_g && held(i)) rate_[gas_phase][i] = 0.0;
      const bool solve_g = free_g && !held(i);
      if (free_l && solve_g) {
        const double det = m.ll * m.gg - m.lg * m.gl;
        rate_[liquid_phase][i] =
            (m.gg * force_[liquid_phase][i] - m.lg * force_[gas_phase][i]) / det;
        rate_[gas_phase][i] = (m.ll * force_[gas_phase][i] - m.gl * force_[liquid_phase][i]) / det;
      } else if (free_l) {
        rate_[liquid_phase][i] = (force_[liquid_phase][i] - m.lg * rate_[gas_phase][i]) / m.ll;
      } else if (solve_g) {
        rate_[gas_phase][i] = (force_[gas_phase][i] - m.gl * rate_[liquid_phase][i]) / m.gg;
      }
    }
  }

  const Grid<D>& grid_;
  std::vector<physics::HydraulicModel> models_;
  MassBalance form_;
  Vec<D> gravity_;
  IntegrationSetup<D, K> q_;
  std::vector<physics::StorageMatrix> extra_storage_;
  bool from_nodes_ = false;       // set_nodal_permeability
  NodalPermeability nodal_laws_;  // with from_nodes_: the laws at the nodes (assemble)
  std::array<double, 2> inflow_scale_{1.0, 1.0};
  std::array<std::vector<double>, 2> pressure_;  // nodal P [Pa]
  std::array<std::vector<double>, 2> rate_;      // nodal dP/dt [Pa/s]
  std::array<std::vector<double>, 2> force_;     // F [kg/s]
  std::array<std::vector<double>, 2> penalty_;   // the surface penalty's Π [kg/s]
  std::vector<physics::StorageMatrix> storage_;  // M [kg/Pa]
  mutable ThreadSums sums_;                      // the threads' partial sums over the points
};

}  // namespace unsatmpm::numerics
