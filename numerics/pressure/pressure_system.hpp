// The nodal pressure system of the implicit cycle (docs/cycles.md): the liquid and gas mass
// balances in Darcy form, assembled with the material points as quadrature points, as an ODE in the
// nodal pressures for CVODE,
//   M_i(P) dP_i/dt = F_i(P, t),   F_a,i = sum_p V_p [grad N_i . J_a - N_i sigma_a (+ N_i T_a)],
//   M_i = sum_p N_i V_p A_p (lumped: one 2x2 block per node),
// with J, sigma, T, A the point quantities of pressure_point.hpp at P_p = sum_j N_j P_j,
// grad P_p = sum_j grad N_j P_j. Impervious is the natural condition (no boundary term);
// prescribed pressures (a node and a fluid) are not unknowns: their values and rates come from
// a callback, and their balance, M P' - F, is the mass rate entering there.
//
// Unknowns (numerics/pressure/unknowns.hpp): for each active node (sum_p N_i V_p > 0) in node
// order, P_l then P_g, each unless prescribed. At a node without gas storage (M_gg = 0: every point
// around it saturated) P_g is held (dP_g/dt = 0), as in the explicit cycle.
//
// Two more unknowns follow the pressures: the mass of each fluid that has entered through the
// prescribed nodes since the start, Q_a, divided by a storage scale so that it reads in Pa (CVODE's
// error control then treats it like a pressure): dQ_a/dt = sum over prescribed (i, a) of
// (M_i P'_i - F_i)_a, plus the supplies (a mass rate given at nodes where the fluid is an unknown:
// rainfall). Integrating it with the pressures gives the conservation report an inflow as
// accurate as the pressures.
//
// rhs() gives y' = M^-1 F node by node; jacobian() its exact derivative
// (numerics/pressure/pressure_jacobian.hpp) in the CSR pattern of pattern(). Both, and every
// inflow query, start from one evaluation at (t, y): nodal pressures, then M and F over the
// points, then the nodal rates. The points are frozen at prepare()
// (numerics/pressure/quadrature.hpp); start() fits the nodal start values to them and
// add_increments() returns the nodal increments (numerics/pressure/nodal_projection.hpp). With a
// drop tolerance (set_jacobian_drop_tolerance), a point's part of the Jacobian leaves out the
// stencil nodes it barely touches; rhs() always keeps them, so only CVODE's Newton iteration
// sees the difference.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure/nodal_projection.hpp"
#include "numerics/pressure/pressure_point.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/sparse_pattern.hpp"
#include "numerics/three_phase_transfers.hpp"

namespace unsatmpm::numerics {

/// Prescribed nodal pressures of one fluid at a time t: which nodes, their values and rates.
struct NodalPrescription {
  std::array<std::vector<std::uint8_t>, 2> prescribed;  // per fluid, per node: 1 if prescribed
  std::array<std::vector<double>, 2> value, rate;       // [Pa], [Pa/s] at the current t
};

template <int D, class K>
class PressureSystem {
 public:
  /// Fills value and rate of the prescribed nodes at time t [s].
  using Prescribe = std::function<void(double t, NodalPrescription&)>;

  PressureSystem(const Grid<D>& grid, std::vector<physics::HydraulicModel> models, MassBalance form,
                 const Vec<D>& gravity)
      : grid_(grid),
        models_(std::move(models)),
        form_(form),
        gravity_(gravity),
        points_(grid.n_nodes()),
        unknowns_(grid.n_nodes()) {
    const auto n = grid_.n_nodes();
    for (int a = 0; a < 2; ++a) {
      prescription_.prescribed[a].assign(n, 0);
      prescription_.value[a].assign(n, 0.0);
      prescription_.rate[a].assign(n, 0.0);
      pressure_[a].assign(n, 0.0);
      rate_[a].assign(n, 0.0);
      force_[a].assign(n, 0.0);
    }
    storage_.assign(n, {0.0, 0.0, 0.0, 0.0});
  }

  /// Which nodes carry a prescribed pressure of fluid a (call before prepare), and the callback
  /// that gives their values and rates.
  void set_prescribed(int a, const std::vector<std::uint8_t>& flags) {
    fixed_prescribed_[a] = flags;
    prescription_.prescribed[a] = flags;
  }
  void set_prescription(Prescribe f) { prescribe_ = std::move(f); }

  /// Prescribes fluid a on the free surface as well (numerics/pressure/free_surface.hpp), found
  /// again by every prepare.
  void set_surface_prescribed(int a, bool on) { surface_fluid_[a] = on; }
  /// Free-surface nodes (flag 1) where fluid a's surface condition is not applied from the next
  /// prepare on: fluid a is an unknown there, fed by its supply (set_supply). Empty: none. The
  /// rainfall condition switches nodes between the two (cycles/implicit_solver.hpp).
  void set_surface_exempt(int a, std::vector<std::uint8_t> flags) {
    surface_exempt_[a] = std::move(flags);
  }
  /// Mass rate of fluid a supplied at each node [kg/s per unit out-of-plane measure in 2D, kg/s
  /// in 3D], constant until changed: it enters the balance of the active nodes where fluid a is
  /// an unknown and counts as inflow; at other nodes it is ignored (a prescribed node takes what
  /// its balance needs). Empty: none.
  void set_supply(int a, std::vector<double> rate) { supply_[a] = std::move(rate); }
  /// Index in y of fluid a's pressure at node i, or -1 if it is not an unknown.
  std::int64_t unknown(int a, std::int64_t i) const { return unknowns_(a, i); }
  /// The Jacobian (not the rhs) leaves out, point by point, the stencil nodes where both the
  /// point's weight N_a and its scaled gradient h_min |grad N_a|_max are below `tau` (from the
  /// next prepare on). GIMP's stencil reaches 3 nodes per direction, but a point well inside its
  /// cell has only 2 with weights of any size: dropping the others narrows the Jacobian's node
  /// coupling from 5 x 5 to about 3 x 3 in 2D, and KLU's fill with it. Each dropped term (one
  /// point, one pair of nodes) is below tau of a full one. tau = 0 (the default) keeps the exact
  /// Jacobian.
  void set_jacobian_drop_tolerance(double tau) {
    if (!(tau >= 0.0 && tau < 1.0))
      throw std::invalid_argument("PressureSystem: Jacobian drop tolerance must be in [0, 1)");
    jacobian_drop_ = tau;
  }
  /// 1 for the free-surface nodes of the last prepare.
  const std::vector<std::uint8_t>& surface_nodes() const { return surface_; }

  /// Sets up one integration at the points' current configuration: stencils, the active nodes,
  /// the unknowns and the Jacobian's pattern. `ranges` splits the points by material (models_).
  /// Returns true if the pattern differs from the previous one (the caller then re-analyses the
  /// sparse factorisation).
  bool prepare(const MaterialPoints<D>& mp, const FluidPoints<D>& fp,
               const std::vector<std::int64_t>& ranges) {
    was_active_.resize(grid_.n_nodes());
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) was_active_[i] = points_.active(i);
    points_.fill(grid_, mp, fp, ranges, solid_rate_, jacobian_drop_);
    const auto active = [this](std::int64_t i) { return points_.active(i); };
    surface_ = free_surface_nodes<D>(grid_, active);
    for (int a = 0; a < 2; ++a) {
      was_prescribed_[a] = prescription_.prescribed[a];
      for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
        prescription_.prescribed[a][i] =
            (!fixed_prescribed_[a].empty() && fixed_prescribed_[a][i]) ||
            (surface_fluid_[a] && surface_[i] &&
             (surface_exempt_[a].empty() || !surface_exempt_[a][i]));
    }
    unknowns_.number(active, prescription_.prescribed);
    SparsePattern pattern = unknowns_.jacobian_pattern(
        points_, [this](int a, std::int64_t i) { return prescribed_active(a, i); });
    const bool changed = !(pattern == pattern_);
    pattern_ = std::move(pattern);
    return changed;
  }

  /// Storage added to each point's A (constant over an integration) [kg/(m^3 Pa)]: the
  /// fixed-stress split's stabilisation (cycles/implicit_solver.hpp). Empty: none.
  void set_extra_storage(std::vector<physics::StorageMatrix> extra) {
    extra_storage_ = std::move(extra);
  }

  /// Each point's solid volumetric strain rate div v_s [1/s] from the next prepare on, for the
  /// source term -S_a rho_a div v_s of the mass balances (docs/balance_laws.md). Empty (the
  /// default): none. The main cycle's fixed-stress split hands the flow no solid rate today
  /// (cycles/implicit_solver.hpp).
  void set_solid_rate(std::vector<double> div_vs) { solid_rate_ = std::move(div_vs); }

  std::int64_t n_unknowns() const { return unknowns_.size(); }
  std::int64_t n_pressure_unknowns() const { return unknowns_.n_pressures(); }
  /// Index of the inflow integral of fluid a in y.
  std::int64_t inflow_unknown(int a) const { return unknowns_.inflow(a); }
  /// Mass [kg per unit out-of-plane measure] per unit of the inflow unknowns [Pa].
  double inflow_scale(int a) const { return inflow_scale_[a]; }
  const SparsePattern& pattern() const { return pattern_; }
  /// Node and fluid of unknown k (for messages); (-1, a) for the inflow integral of fluid a.
  std::pair<std::int64_t, int> unknown_location(std::int64_t k) const {
    return unknowns_.location(k);
  }

  /// How start() treats the prescribed nodes: at the first start their prescribed values switch
  /// on (the field the points' increments are measured from holds the projected values there, so
  /// the points near them receive the jump); at later starts they continue (the field holds the
  /// prescribed values, so no jump is applied twice).
  enum class Prescribed { switch_on, continuing };

  /// The start of an integration at time t: the nodal pressures fitted to the points
  /// (fit_pressures_to_nodes) for every active node (prescribed ones as `prescribed` says), the
  /// unknowns y0 (inflow integrals 0), and the inflow scales (sum of the nodal storages at this
  /// state).
  void start(double t, const FluidPoints<D>& fp, std::span<double> y0,
             std::array<std::vector<double>, 2>& projected, Prescribed prescribed) {
    fit_pressures_to_nodes<D, K>(grid_, points_, fp, projected);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a)
        if (unknowns_(a, i) >= 0) y0[unknowns_(a, i)] = projected[a][i];
    y0[unknowns_.inflow(0)] = y0[unknowns_.inflow(1)] = 0.0;
    inflow_scale_ = {1.0, 1.0};
    set_nodal_pressures(t, y0);
    assemble_balances();
    std::array<double, 2> sum{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (points_.active(i)) sum[0] += storage_[i].ll, sum[1] += storage_[i].gg;
    for (int a = 0; a < 2; ++a) inflow_scale_[a] = sum[a] > 0.0 ? sum[a] : 1.0;
    // A prescribed value that differs from the projected one (a boundary condition switched on
    // at t) moves the points near it at once: the mass M_i dP_i enters there.
    // A node that was already prescribed and active at the previous start continues (its
    // field holds the prescribed value); a node prescribed for the first time (a free-surface
    // node newly exposed, or every node at the first start) switches on.
    start_inflow_ = {0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!points_.active(i)) continue;
      std::array<double, 2> jump{0.0, 0.0};
      for (int a = 0; a < 2; ++a) {
        if (!prescription_.prescribed[a][i]) continue;
        const bool continues =
            prescribed == Prescribed::continuing && was_prescribed_[a][i] && was_active_[i];
        if (continues)
          projected[a][i] = pressure_[a][i];
        else
          jump[a] = pressure_[a][i] - projected[a][i];
      }
      const double dl = jump[0], dg = jump[1];
      const auto& m = storage_[i];
      start_inflow_[0] += m.ll * dl + m.lg * dg;
      start_inflow_[1] += m.gl * dl + m.gg * dg;
    }
  }

  /// Mass [kg per unit out-of-plane measure] entering at start() through prescribed values that
  /// differ from the projected ones.
  const std::array<double, 2>& start_inflow() const { return start_inflow_; }

  /// Nodal pressures of every active node at time t: the unknowns, or the prescribed values.
  void nodal_pressures(double t, std::span<const double> y,
                       std::array<std::vector<double>, 2>& out) {
    set_nodal_pressures(t, y);
    out = pressure_;
  }

  /// The points' pressures moved by the nodal increments between two nodal fields (each from
  /// nodal_pressures), at the configuration of the last prepare.
  void add_increments(const std::array<std::vector<double>, 2>& start,
                      const std::array<std::vector<double>, 2>& end, FluidPoints<D>& fp) const {
    add_nodal_increments<D, K>(points_, start, end, fp);
  }

  /// y' = M^-1 F. Returns 0, or 1 (recoverable: CVODE retries with a smaller step) if a value is
  /// not finite.
  int rhs(double t, std::span<const double> y, std::span<double> ydot) {
    evaluate(t, y);
    for (const auto i : unknowns_.nodes())
      for (int a = 0; a < 2; ++a)
        if (unknowns_(a, i) >= 0) ydot[unknowns_(a, i)] = rate_[a][i];
    const auto q = inflow();
    for (int a = 0; a < 2; ++a) ydot[unknowns_.inflow(a)] = q[a] / inflow_scale_[a];
    for (const double v : ydot)
      if (!std::isfinite(v)) return 1;
    return 0;
  }

  /// dy'/dy in the order of pattern() (numerics/pressure/pressure_jacobian.hpp). Returns 0, or 1
  /// if a value is not finite.
  int jacobian(double t, std::span<const double> y, std::span<double> values);

  /// Mass rates entering through the prescribed nodes and the supplies at (t, y) [kg/s per unit
  /// out-of-plane measure]: the balance M P' - F of each prescribed node and fluid plus the
  /// supplies (set_supply), summed per fluid.
  std::array<double, 2> boundary_inflow(double t, std::span<const double> y) {
    evaluate(t, y);
    return inflow();
  }

  /// The same node by node for fluid a: (M P' - F)_a at the prescribed active nodes, the supply
  /// at the active nodes where fluid a is an unknown, 0 elsewhere [kg/s per unit out-of-plane
  /// measure].
  std::vector<double> inflow_by_node(int a, double t, std::span<const double> y) {
    evaluate(t, y);
    std::vector<double> q(grid_.n_nodes(), 0.0);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) q[i] = node_inflow(a, i);
    return q;
  }

  /// Rate of change of the stored mass of each fluid, sum over the active nodes of M_i P'_i
  /// [kg/s per unit out-of-plane measure], prescribed rates included.
  std::array<double, 2> storage_rate(double t, std::span<const double> y) {
    evaluate(t, y);
    std::array<double, 2> q{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!points_.active(i)) continue;
      const auto& m = storage_[i];
      q[0] += m.ll * rate_[0][i] + m.lg * rate_[1][i];
      q[1] += m.gl * rate_[0][i] + m.gg * rate_[1][i];
    }
    return q;
  }

 private:
  /// The one evaluation at (t, y) every query starts from: nodal pressures, the balances M and
  /// F assembled over the points, and the nodal rates P'.
  void evaluate(double t, std::span<const double> y) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
  }

  bool held(std::int64_t i) const { return !(storage_[i].gg > 0.0); }

  bool prescribed_active(int a, std::int64_t i) const {
    return prescription_.prescribed[a][i] && points_.active(i);
  }

  bool supplied(int a, std::int64_t i) const {
    return !supply_[a].empty() && unknowns_(a, i) >= 0 && supply_[a][i] != 0.0;
  }

  /// Mass rate of fluid a entering at node i (after evaluate): M P' - F at a prescribed active
  /// node, the supply where fluid a is an unknown.
  double node_inflow(int a, std::int64_t i) const {
    if (prescribed_active(a, i)) {
      const auto& m = storage_[i];
      return a == 0 ? m.ll * rate_[0][i] + m.lg * rate_[1][i] - force_[0][i]
                    : m.gl * rate_[0][i] + m.gg * rate_[1][i] - force_[1][i];
    }
    return supplied(a, i) ? supply_[a][i] : 0.0;
  }

  /// Sum over the nodes of node_inflow, per fluid (after evaluate).
  std::array<double, 2> inflow() const {
    std::array<double, 2> q{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a) q[a] += node_inflow(a, i);
    return q;
  }

  void set_nodal_pressures(double t, std::span<const double> y) {
    if (prescribe_) prescribe_(t, prescription_);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a) {
        if (unknowns_(a, i) >= 0) {
          pressure_[a][i] = y[unknowns_(a, i)];
        } else if (prescription_.prescribed[a][i]) {
          pressure_[a][i] = prescription_.value[a][i];
          rate_[a][i] = prescription_.rate[a][i];
        }
      }
  }

  /// What a pass over the points needs: the balances only, or the Jacobian's derivatives too.
  enum class Pass { balances, jacobian };

  PointFlow<D> flow_at(std::size_t p, Pass pass) const {
    const auto& st = points_.stencil[p];
    std::array<double, 2> pr{0.0, 0.0};
    std::array<Vec<D>, 2> gr{Vec<D>::Zero(), Vec<D>::Zero()};
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) {
        pr[f] += st.w[a] * pressure_[f][st.node[a]];
        gr[f] += st.grad[a] * pressure_[f][st.node[a]];
      }
    PointFlow<D> f = point_flow<D>(models_[points_.model[p]],
                                   {points_.porosity[p], points_.div_vs[p],
                                    form_ == MassBalance::simplified, pass == Pass::jacobian},
                                   pr, gr, gravity_, points_.grad_ln_n[p]);
    if (!extra_storage_.empty()) {
      const auto& e = extra_storage_[p];
      f.storage.ll += e.ll, f.storage.lg += e.lg, f.storage.gl += e.gl, f.storage.gg += e.gg;
    }
    return f;
  }

  void assemble_balances() {
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!points_.active(i)) continue;
      storage_[i] = {0.0, 0.0, 0.0, 0.0};
      force_[0][i] = force_[1][i] = 0.0;
    }
    for (std::size_t p = 0; p < points_.size(); ++p) {
      const auto& st = points_.stencil[p];
      const double v = points_.volume[p];
      const PointFlow<D> f = flow_at(p, Pass::balances);
      for (int a = 0; a < st.n; ++a) {
        const auto i = st.node[a];
        const double w = st.w[a] * v;
        auto& m = storage_[i];
        m.ll += w * f.storage.ll, m.lg += w * f.storage.lg;
        m.gl += w * f.storage.gl, m.gg += w * f.storage.gg;
        for (int fl = 0; fl < 2; ++fl)
          force_[fl][i] += v * st.grad[a].dot(f.flux[fl]) - w * (f.source[fl] - f.advective[fl]);
      }
    }
    for (const auto i : unknowns_.nodes())
      for (int a = 0; a < 2; ++a)
        if (supplied(a, i)) force_[a][i] += supply_[a][i];
  }

  /// Nodal rates of the unknowns from M P' = F, with the prescribed rates known.
  void solve_rates() {
    for (const auto i : unknowns_.nodes()) {
      const auto& m = storage_[i];
      const bool free_l = unknowns_(0, i) >= 0, free_g = unknowns_(1, i) >= 0;
      if (free_g && held(i)) rate_[1][i] = 0.0;
      const bool solve_g = free_g && !held(i);
      if (free_l && solve_g) {
        const double det = m.ll * m.gg - m.lg * m.gl;
        rate_[0][i] = (m.gg * force_[0][i] - m.lg * force_[1][i]) / det;
        rate_[1][i] = (m.ll * force_[1][i] - m.gl * force_[0][i]) / det;
      } else if (free_l) {
        rate_[0][i] = (force_[0][i] - m.lg * rate_[1][i]) / m.ll;
      } else if (solve_g) {
        rate_[1][i] = (force_[1][i] - m.gl * rate_[0][i]) / m.gg;
      }
    }
  }

  const Grid<D>& grid_;
  std::vector<physics::HydraulicModel> models_;
  MassBalance form_;
  Vec<D> gravity_;
  // Configuration, kept across integrations.
  Prescribe prescribe_;
  std::array<std::vector<std::uint8_t>, 2> fixed_prescribed_;  // from set_prescribed
  std::array<bool, 2> surface_fluid_{false, false};
  std::array<std::vector<std::uint8_t>, 2> surface_exempt_;
  std::array<std::vector<double>, 2> supply_;
  std::vector<physics::StorageMatrix> extra_storage_;
  std::vector<double> solid_rate_;  // div v_s per point [1/s]; empty: none
  double jacobian_drop_ = 0.0;
  // One integration, from prepare and start.
  PointQuadrature<D, K> points_;
  NodalPrescription prescription_;
  std::array<std::vector<std::uint8_t>, 2> was_prescribed_;  // at the previous prepare
  std::vector<std::uint8_t> surface_, was_active_;
  PressureUnknowns unknowns_;
  SparsePattern pattern_;
  std::array<double, 2> inflow_scale_{1.0, 1.0}, start_inflow_{0.0, 0.0};
  // One evaluation at (t, y).
  std::array<std::vector<double>, 2> pressure_;  // nodal P [Pa]
  std::array<std::vector<double>, 2> rate_;      // nodal dP/dt [Pa/s]
  std::array<std::vector<double>, 2> force_;     // F [kg/s]
  std::vector<physics::StorageMatrix> storage_;  // M [kg/Pa]
};

}  // namespace unsatmpm::numerics

#include "numerics/pressure/pressure_jacobian.hpp"
