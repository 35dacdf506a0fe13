// The jumps of a flow's start (numerics/pressure/pressure_system.hpp, start): prescribed values
// that differ from the pressures fitted to the points, switched on at once. What they bring the
// points is counted as inflow (jump_mass); where a gas value is switched on alone, the node's
// liquid is shifted so that it brings as little water as it can (keep_liquid_under_gas_jumps),
// or, once the flow is under way, the gas ramps in over the interval instead (GasSwitchOnRamps).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "numerics/pressure/pressure_operator.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/unknowns.hpp"

namespace unsatmpm::numerics {

/// The mass of each fluid [kg per unit out-of-plane measure] that the nodal jumps bring to
/// point p at base pressures (pl, pg).
template <int D, class K>
std::array<double, 2> jump_mass_at(const PointQuadrature<D, K>& q, const PressureOperator<D, K>& op,
                                   std::size_t p, double pl, double pg,
                                   const std::array<std::vector<double>, 2>& jump) {
  const auto& st = q.stencil[p];
  double dl = 0.0, dg = 0.0;
  for (int a = 0; a < st.n; ++a)
    dl += st.w[a] * jump[liquid_phase][st.node[a]], dg += st.w[a] * jump[gas_phase][st.node[a]];
  if (dl == 0.0 && dg == 0.0) return {0.0, 0.0};
  const physics::HydraulicModel& hm = op.model(q.model[p]);
  const auto content = [&](double l, double g) {
    const double s_l = hm.saturation(physics::retention_suction(l, g));
    return std::array<double, 2>{s_l * hm.liquid_density(l), (1.0 - s_l) * hm.gas_density(g)};
  };
  const auto before = content(pl, pg), after = content(pl + dl, pg + dg);
  const double nv = q.porosity[p] * q.volume[p];
  std::array<double, 2> mass{nv * (after[0] - before[0]), nv * (after[1] - before[1])};
  if (const physics::StorageMatrix* e = op.extra_storage(p)) {
    mass[liquid_phase] += q.volume[p] * (e->ll * dl + e->lg * dg);
    mass[gas_phase] += q.volume[p] * (e->gl * dl + e->gg * dg);
  }
  return mass;
}

/// A node whose gas pressure is switched on while its liquid pressure is an unknown (a gas
/// condition alone, on a face or on the free surface) keeps its liquid: the gas jump alone
/// would change the suction and so the saturation there, and make or destroy water where
/// nothing prescribes the liquid (verification/collapse, a block open to the gas at its free
/// surface: its liquid mass moved by 8.6e-3 at 5 kPa suction and 1.0e-2 at 20 kPa in 1.5 s,
/// counted as inflow; 5.3e-4 and 1.9e-3 with the shift). Its liquid starts shifted so that
/// these jumps bring the points as little liquid as a guarded Newton iteration finds (each
/// point's liquid change given to its shifted nodes by their weights, steps on the nodal storage
/// M_ll, from -M_lg/M_ll times the gas jump), and the shift is a jump of its own for the points
/// (added to y0, whose liquid unknowns it moves; true if any: the operator then needs the new
/// pressures). Jumps of prescribed liquid pressures nearby still enter, counted.
template <int D, class K>
bool keep_liquid_under_gas_jumps(const PointQuadrature<D, K>& q, const PressureOperator<D, K>& op,
                                 const PressureUnknowns& u, const std::vector<double>& base_pl,
                                 const std::vector<double>& base_pg,
                                 std::array<std::vector<double>, 2>& jump, std::span<double> y0) {
  const auto n = static_cast<std::int64_t>(jump[gas_phase].size());
  std::vector<std::int64_t> shifted;
  for (std::int64_t i = 0; i < n; ++i)
    if (jump[gas_phase][i] != 0.0 && u(liquid_phase, i) >= 0 && op.nodal_storage(i).ll > 0.0)
      shifted.push_back(i);
  if (shifted.empty()) return false;
  std::array<std::vector<double>, 2> own{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  for (const auto i : shifted) {
    const auto& m = op.nodal_storage(i);
    own[gas_phase][i] = jump[gas_phase][i];
    own[liquid_phase][i] = -m.lg / m.ll * jump[gas_phase][i];
  }
  std::vector<std::size_t> touched;  // the points with a shifted node in their stencil
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto& st = q.stencil[p];
    for (int a = 0; a < st.n; ++a)
      if (own[gas_phase][st.node[a]] != 0.0) {
        touched.push_back(p);
        break;
      }
  }
  // Newton on the diagonal M_ll, safeguarded: a shift stays within twice its node's gas jump
  // (the suction-keeping shift is about the gas jump), and the iteration stops when a step
  // brings more liquid than the last, keeping the best shifts; whatever liquid remains is
  // counted as inflow by jump_mass. Unguarded, it took shifts of 1e5 to 2e6 Pa on
  // verification/collapse at 5 kPa suction (near saturation the shared points' storage
  // collapses) and threw a point out of the grid.
  std::vector<double> change(n), best(shifted.size());
  double first = -1.0, least = std::numeric_limits<double>::infinity();
  for (int newton = 0; newton < 50; ++newton) {
    for (const auto i : shifted) change[i] = 0.0;
    for (const auto p : touched) {
      const auto& st = q.stencil[p];
      const double dm = jump_mass_at(q, op, p, base_pl[p], base_pg[p], own)[liquid_phase];
      if (dm == 0.0) continue;
      double w = 0.0;  // the point's weight on the shifted nodes, which take all of dm
      for (int a = 0; a < st.n; ++a)
        if (own[gas_phase][st.node[a]] != 0.0) w += st.w[a];
      for (int a = 0; a < st.n; ++a)
        if (own[gas_phase][st.node[a]] != 0.0) change[st.node[a]] += st.w[a] / w * dm;
    }
    double size = 0.0;
    for (const auto i : shifted) size += std::abs(change[i]);
    if (first < 0.0) first = size;
    if (!(size < least)) break;
    least = size;
    for (std::size_t k = 0; k < shifted.size(); ++k) best[k] = own[liquid_phase][shifted[k]];
    if (size <= 1e-8 * first) break;
    for (const auto i : shifted) {
      const double bound = 2.0 * std::abs(jump[gas_phase][i]);
      own[liquid_phase][i] =
          std::clamp(own[liquid_phase][i] - change[i] / op.nodal_storage(i).ll, -bound, bound);
    }
  }
  for (std::size_t k = 0; k < shifted.size(); ++k) own[liquid_phase][shifted[k]] = best[k];
  for (const auto i : shifted) {
    jump[liquid_phase][i] = own[liquid_phase][i];
    y0[u(liquid_phase, i)] += own[liquid_phase][i];
  }
  return true;
}

/// Gas values switched on at a node whose liquid is an unknown, once the flow is under way (a
/// node newly on a moving free surface that prescribes the gas alone): instead of jumping, the
/// node's gas goes linearly from the value fitted there to the prescribed one over the rest of
/// the interval. Its liquid balance is solved all along, so the suction change makes no water:
/// the liquid moves only by Darcy flux, and the gas that the ramp lets in is
/// counted like any prescribed node's (docs/balance_laws.md, "The implicit cycle: mass balances
/// in Darcy form at the nodes").
/// A jump at once cannot keep the water there: its mass is the change of saturation at the
/// points around, which only a shift of the liquid can undo (keep_liquid_under_gas_jumps, which
/// still serves the first start, where the prescribed values hold from t = 0 on).
class GasSwitchOnRamps {
 public:
  /// Ramps node i's gas from `from` [Pa] at t0 to its prescribed value at t1 [s].
  void add(std::int64_t i, double from, double t0, double t1) {
    ramps_.push_back({i, from, t0, t1});
  }
  /// Keeps the ramps still running at t on nodes still prescribed (`gas_prescribed`, per node).
  void keep_running(double t, const std::vector<std::uint8_t>& gas_prescribed) {
    std::erase_if(ramps_, [&](const Ramp& r) { return !(t < r.t1) || !gas_prescribed[r.node]; });
  }
  /// Whether a node with nodal storage m ramps: while its gas ramps, its liquid moves by
  /// -M_lg/M_ll times the gas, which the retention alone keeps below 1 (C / (C + S/K_l)). Where
  /// the fixed-stress split's skeleton term dominates (a soft skeleton near saturation, where the
  /// retention stores little), the ramp would drive the liquid by many times the gas change,
  /// across s = 0: with the split's modulus cut a thousandfold at yielding points (as it once
  /// was), M_lg reached 26 M_ll on verification/collapse at 2.5 cm cells, and CVODE's Newton
  /// iteration stalled in one interval for over 20 minutes. Such a node jumps instead
  /// (keep_liquid_under_gas_jumps).
  static bool suits(const physics::StorageMatrix& m) { return std::abs(m.lg) <= m.ll; }
  bool ramps(std::int64_t i) const {
    return std::any_of(ramps_.begin(), ramps_.end(), [i](const Ramp& r) { return r.node == i; });
  }
  /// Replaces the prescribed gas value v(t) and rate v'(t) of each ramped node by those of
  /// from + (v(t) - from) s(t), s = (t - t0)/(t1 - t0) clipped to [0, 1].
  void apply(double t, NodalPrescription& np) const {
    for (const auto& r : ramps_) {
      const double span = r.t1 - r.t0, s = std::clamp((t - r.t0) / span, 0.0, 1.0);
      double& value = np.value[gas_phase][r.node];
      double& rate = np.rate[gas_phase][r.node];
      rate = rate * s + (t < r.t1 ? (value - r.from) / span : 0.0);
      value = r.from + (value - r.from) * s;
    }
  }

 private:
  struct Ramp {
    std::int64_t node;
    double from, t0, t1;
  };
  std::vector<Ramp> ramps_;
};

/// The mass of each fluid that the nodal jumps bring into the points, exactly: the change of
/// sum_p V_p n_p S_a rho_a from P_p to P_p + sum_i N_i jump_i, plus the added storage's share
/// (the fixed-stress split's skeleton term, linear in the jump as in the flow). A jump switched
/// on at a boundary can span most of the retention curve (a wetting front: from a suction of
/// 20 kPa to a ponded surface), where the storage at the start state would misstate it (by
/// 1.3 % of the liquid in a 1 m column, measured).
template <int D, class K>
std::array<double, 2> jump_mass(const PointQuadrature<D, K>& q, const PressureOperator<D, K>& op,
                                const std::vector<double>& base_pl,
                                const std::vector<double>& base_pg,
                                const std::array<std::vector<double>, 2>& jump) {
  std::array<double, 2> mass{0.0, 0.0};
  for (std::size_t p = 0; p < q.size(); ++p) {
    const auto m = jump_mass_at(q, op, p, base_pl[p], base_pg[p], jump);
    mass[0] += m[0], mass[1] += m[1];
  }
  return mass;
}

}  // namespace unsatmpm::numerics
