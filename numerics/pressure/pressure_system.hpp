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
// Unknowns: for each active node (sum_p N_i V_p > 0) in node order, P_l then P_g, each unless
// prescribed. At a node without gas storage (M_gg = 0: every point around it saturated) P_g is
// held (dP_g/dt = 0), as in the explicit cycle.
//
// Two more unknowns follow the pressures: the mass of each fluid that has entered through the
// prescribed nodes since the start, Q_a, divided by a storage scale so that it reads in Pa (CVODE's
// error control then treats it like a pressure): dQ_a/dt = sum over prescribed (i, a) of
// (M_i P'_i - F_i)_a, plus the supplies (a mass rate given at nodes where the fluid is an unknown:
// rainfall). Integrating it with the pressures gives the conservation report an inflow as
// accurate as the pressures.
//
// rhs() gives y' = M^-1 F node by node; jacobian() its exact derivative,
//   dy'_i/dP_j = M_i^-1 (dF_i/dP_j - (dM_i/dP_j) P'_i),
// in the CSR pattern of pattern(), checked against finite differences in the unit tests. With a
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

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "numerics/cvode_integrator.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"
#include "numerics/pressure/pressure_point.hpp"
#include "numerics/shape_functions.hpp"
#include "numerics/three_phase_transfers.hpp"

namespace unsatmpm::numerics {

/// Prescribed nodal pressures of one fluid at a time t: which nodes, their values and rates.
struct NodalPrescription {
  std::array<std::vector<std::uint8_t>, 2> prescribed;  // per fluid, per node: 1 if prescribed
  std::array<std::vector<double>, 2> value, rate;       // [Pa], [Pa/s] at the current t
};

/// The least spread, in grid spacings, that the points around a node must have in every direction
/// for their pressures to be fitted linearly there (PressureSystem::start; else their mean). With
/// 2 points per cell and direction, a node on the body's edge sees a spread of 0.22 h across it;
/// a single row of points, 0.
inline constexpr double min_fit_spread = 0.1;

template <int D, class K>
class PressureSystem {
 public:
  /// Fills value and rate of the prescribed nodes at time t [s].
  using Prescribe = std::function<void(double t, NodalPrescription&)>;

  PressureSystem(const Grid<D>& grid, std::vector<physics::HydraulicModel> models, MassBalance form,
                 const Vec<D>& gravity)
      : grid_(grid), models_(std::move(models)), form_(form), gravity_(gravity) {
    const auto n = grid_.n_nodes();
    for (int a = 0; a < 2; ++a) {
      prescription_.prescribed[a].assign(n, 0);
      prescription_.value[a].assign(n, 0.0);
      prescription_.rate[a].assign(n, 0.0);
      unknown_[a].assign(n, -1);
      pressure_[a].assign(n, 0.0);
      rate_[a].assign(n, 0.0);
      force_[a].assign(n, 0.0);
    }
    storage_.assign(n, {0.0, 0.0, 0.0, 0.0});
    volume_.assign(n, 0.0);
  }

  /// Which nodes carry a prescribed pressure of fluid a (call before prepare), and the callback
  /// that gives their values and rates.
  void set_prescribed(int a, const std::vector<std::uint8_t>& flags) {
    fixed_prescribed_[a] = flags;
    prescription_.prescribed[a] = flags;
  }
  void set_prescription(Prescribe f) { prescribe_ = std::move(f); }

  /// Prescribes fluid a on the free surface as well: the active nodes of every grid cell that
  /// also has an inactive node (the outer layer of the active region, found again by every
  /// prepare, so it follows the body as it deforms). Nodes on the grid's outer faces count only
  /// through the cells inside the grid: a face where the body touches the grid's boundary is not
  /// a free surface.
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
  std::int64_t unknown(int a, std::int64_t i) const { return unknown_[a][i]; }
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
    const auto n_mp = static_cast<std::int64_t>(mp.size());
    stencils_.resize(n_mp);
    jacobian_nodes_.resize(n_mp);
    points_.resize(n_mp);
    positions_.resize(n_mp);
    was_active_.resize(volume_.size());
    for (std::size_t i = 0; i < volume_.size(); ++i) was_active_[i] = volume_[i] > 0.0;
    std::fill(volume_.begin(), volume_.end(), 0.0);
    std::vector<double> porosity_sum(grid_.n_nodes(), 0.0);
    for (std::size_t m = 0; m + 1 < ranges.size(); ++m)
      for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
        auto& st = stencils_[p];
        st.evaluate(grid_, mp.position[p], mp.half_size[p]);
        jacobian_nodes_[p] = jacobian_nodes(st);
        positions_[p] = mp.position[p];
        points_[p] = {static_cast<int>(m), mp.volume[p], fp.porosity[p],
                      solid_rate_.empty() ? 0.0 : solid_rate_[p], Vec<D>::Zero()};
        for (int a = 0; a < st.n; ++a) {
          volume_[st.node[a]] += st.w[a] * mp.volume[p];
          porosity_sum[st.node[a]] += st.w[a] * mp.volume[p] * fp.porosity[p];
        }
      }
    // grad ln n at the points, from the volume-weighted nodal porosity.
    for (std::int64_t p = 0; p < n_mp; ++p) {
      const auto& st = stencils_[p];
      Vec<D> g = Vec<D>::Zero();
      for (int a = 0; a < st.n; ++a)
        if (volume_[st.node[a]] > 0.0)
          g += st.grad[a] * (porosity_sum[st.node[a]] / volume_[st.node[a]]);
      points_[p].grad_ln_n = g / points_[p].porosity;
    }
    mark_surface();
    for (int a = 0; a < 2; ++a) {
      was_prescribed_[a] = prescription_.prescribed[a];
      for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
        prescription_.prescribed[a][i] =
            (!fixed_prescribed_[a].empty() && fixed_prescribed_[a][i]) ||
            (surface_fluid_[a] && surface_[i] &&
             (surface_exempt_[a].empty() || !surface_exempt_[a][i]));
    }
    // Unknowns, node-major, then the two inflow integrals.
    n_unknowns_ = 0;
    unknown_nodes_.clear();
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      const bool active = volume_[i] > 0.0;
      bool any = false;
      for (int a = 0; a < 2; ++a) {
        unknown_[a][i] = active && !prescription_.prescribed[a][i] ? n_unknowns_++ : -1;
        any = any || unknown_[a][i] >= 0;
      }
      if (any) unknown_nodes_.push_back(i);
    }
    n_pressures_ = n_unknowns_;
    n_unknowns_ += 2;
    SparsePattern pattern = build_pattern();
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

  std::int64_t n_unknowns() const { return n_unknowns_; }
  std::int64_t n_pressure_unknowns() const { return n_pressures_; }
  /// Index of the inflow integral of fluid a in y.
  std::int64_t inflow_unknown(int a) const { return n_pressures_ + a; }
  /// Mass [kg per unit out-of-plane measure] per unit of the inflow unknowns [Pa].
  double inflow_scale(int a) const { return inflow_scale_[a]; }
  const SparsePattern& pattern() const { return pattern_; }
  /// Node and fluid of unknown k (for messages).
  /// (-1, a) for the inflow integral of fluid a.
  std::pair<std::int64_t, int> unknown_location(std::int64_t k) const {
    if (k >= n_pressures_) return {-1, static_cast<int>(k - n_pressures_)};
    for (const auto i : unknown_nodes_)
      for (int a = 0; a < 2; ++a)
        if (unknown_[a][i] == k) return {i, a};
    return {-1, 0};
  }

  /// How start() treats the prescribed nodes: at the first start their prescribed values switch
  /// on (the field the points' increments are measured from holds the projected values there, so
  /// the points near them receive the jump); at later starts they continue (the field holds the
  /// prescribed values, so no jump is applied twice).
  enum class Prescribed { switch_on, continuing };

  /// The start of an integration at time t: the nodal pressures projected from the points,
  /// volume-weighted, P_i = sum N V P_p / sum N V, for every active node (prescribed ones as
  /// `prescribed` says), the unknowns y0 (inflow integrals 0), and the inflow scales (sum of the
  /// nodal storages at this state).
  void start(double t, const FluidPoints<D>& fp, std::span<double> y0,
             std::array<std::vector<double>, 2>& projected, Prescribed prescribed) {
    for (auto& v : projected) v.assign(grid_.n_nodes(), 0.0);
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      const double v = points_[p].volume;
      for (int a = 0; a < st.n; ++a) {
        projected[0][st.node[a]] += st.w[a] * v * fp.liquid_pressure[p];
        projected[1][st.node[a]] += st.w[a] * v * fp.gas_pressure[p];
      }
    }
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a)
        if (volume_[i] > 0.0) projected[a][i] /= volume_[i];
    fit_nodes(fp, projected);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a)
        if (unknown_[a][i] >= 0) y0[unknown_[a][i]] = projected[a][i];
    y0[n_pressures_] = y0[n_pressures_ + 1] = 0.0;
    inflow_scale_ = {1.0, 1.0};
    set_nodal_pressures(t, y0);
    assemble_balances();
    std::array<double, 2> sum{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (volume_[i] > 0.0) sum[0] += storage_[i].ll, sum[1] += storage_[i].gg;
    for (int a = 0; a < 2; ++a) inflow_scale_[a] = sum[a] > 0.0 ? sum[a] : 1.0;
    // A prescribed value that differs from the projected one (a boundary condition switched on
    // at t) moves the points near it at once: the mass M_i dP_i enters there.
    // A node that was already prescribed and active at the previous start continues (its
    // field holds the prescribed value); a node prescribed for the first time (a free-surface
    // node newly exposed, or every node at the first start) switches on.
    start_inflow_ = {0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (volume_[i] <= 0.0) continue;
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

  /// y' = M^-1 F. Returns 0, or 1 (recoverable: CVODE retries with a smaller step) if a value is
  /// not finite.
  int rhs(double t, std::span<const double> y, std::span<double> ydot) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
    for (const auto i : unknown_nodes_)
      for (int a = 0; a < 2; ++a)
        if (unknown_[a][i] >= 0) ydot[unknown_[a][i]] = rate_[a][i];
    const auto q = inflow();
    for (int a = 0; a < 2; ++a) ydot[n_pressures_ + a] = q[a] / inflow_scale_[a];
    for (const double v : ydot)
      if (!std::isfinite(v)) return 1;
    return 0;
  }

  /// dy'/dy in the order of pattern(). Returns 0, or 1 if a value is not finite.
  int jacobian(double t, std::span<const double> y, std::span<double> values) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
    std::fill(values.begin(), values.end(), 0.0);
    const bool simplified = form_ == MassBalance::simplified;
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      const auto& pt = points_[p];
      const PointFlow<D> f = flow_at(p, Pass::jacobian);
      const NodeMask kept = jacobian_nodes_[p];
      for (int a = 0; a < st.n; ++a) {
        if (!(kept >> a & 1u)) continue;
        const auto i = st.node[a];
        for (int al = 0; al < 2; ++al) {
          // A prescribed balance feeds the inflow integral's row, with the opposite sign.
          const bool inflow_row = prescribed_active(al, i);
          const auto row = inflow_row ? n_pressures_ + al : unknown_[al][i];
          const double sign = inflow_row ? -1.0 / inflow_scale_[al] : 1.0;
          if (unknown_[al][i] < 0 && !inflow_row) continue;
          const double pl = rate_[0][i], pg = rate_[1][i];
          for (int b = 0; b < st.n; ++b) {
            if (!(kept >> b & 1u)) continue;
            const auto j = st.node[b];
            const double nn = st.w[a] * st.w[b];
            for (int be = 0; be < 2; ++be) {
              const auto col = unknown_[be][j];
              if (col < 0) continue;
              const auto& da = f.d_storage[be];
              const double dm = al == 0 ? da.ll * pl + da.lg * pg : da.gl * pl + da.gg * pg;
              double k =
                  st.grad[a].dot(f.d_flux[al][be]) * st.w[b] - f.d_source[al][be] * nn - dm * nn;
              if (al == be) k -= f.conductivity[al] * st.grad[a].dot(st.grad[b]);
              if (simplified)
                k += st.w[a] * (f.d_advective[al][be] * st.w[b] +
                                f.d_advective_d_grad[al][be].dot(st.grad[b]));
              values[position(row, col)] += sign * pt.volume * k;
            }
          }
        }
      }
    }
    // Left-multiply each node's rows by M_UU^-1 (U: its unknown, not held, fluids).
    for (const auto i : unknown_nodes_) {
      const auto rl = unknown_[0][i], rg = unknown_[1][i];
      const auto& m = storage_[i];
      const bool gas_held = held(i);
      if (rl >= 0 && rg >= 0 && !gas_held) {
        const double det = m.ll * m.gg - m.lg * m.gl;
        for (auto q = pattern_.row_ptr[rl], r = pattern_.row_ptr[rg]; q < pattern_.row_ptr[rl + 1];
             ++q, ++r) {
          const double kl = values[q], kg = values[r];
          values[q] = (m.gg * kl - m.lg * kg) / det;
          values[r] = (m.ll * kg - m.gl * kl) / det;
        }
      } else {
        if (rl >= 0)
          for (auto q = pattern_.row_ptr[rl]; q < pattern_.row_ptr[rl + 1]; ++q) values[q] /= m.ll;
        if (rg >= 0)
          for (auto q = pattern_.row_ptr[rg]; q < pattern_.row_ptr[rg + 1]; ++q)
            values[q] = gas_held ? 0.0 : values[q] / m.gg;
      }
    }
    // A node with one fluid prescribed and the other free: its inflow also moves with the free
    // fluid's rate, M_aU dP'_U/dP_j.
    for (const auto i : unknown_nodes_)
      for (int al = 0; al < 2; ++al) {
        const int other = 1 - al;
        const auto r = unknown_[other][i];
        if (!prescribed_active(al, i) || r < 0 || (other == 1 && held(i))) continue;
        const auto& m = storage_[i];
        const double coupling = (al == 0 ? m.lg : m.gl) / inflow_scale_[al];
        for (auto q = pattern_.row_ptr[r]; q < pattern_.row_ptr[r + 1]; ++q)
          values[position(n_pressures_ + al, pattern_.col[q])] += coupling * values[q];
      }
    for (const double v : values)
      if (!std::isfinite(v)) return 1;
    return 0;
  }

  /// Mass rates entering through the prescribed nodes and the supplies at (t, y) [kg/s per unit
  /// out-of-plane measure]: the balance M P' - F of each prescribed node and fluid plus the
  /// supplies (set_supply), summed per fluid.
  std::array<double, 2> boundary_inflow(double t, std::span<const double> y) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
    return inflow();
  }

  /// The same node by node for fluid a: (M P' - F)_a at the prescribed active nodes, the supply
  /// at the active nodes where fluid a is an unknown, 0 elsewhere [kg/s per unit out-of-plane
  /// measure].
  std::vector<double> inflow_by_node(int a, double t, std::span<const double> y) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
    std::vector<double> q(grid_.n_nodes(), 0.0);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) q[i] = node_inflow(a, i);
    return q;
  }

  /// Rate of change of the stored mass of each fluid, sum over the active nodes of M_i P'_i
  /// [kg/s per unit out-of-plane measure], prescribed rates included.
  std::array<double, 2> storage_rate(double t, std::span<const double> y) {
    set_nodal_pressures(t, y);
    assemble_balances();
    solve_rates();
    std::array<double, 2> q{0.0, 0.0};
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (volume_[i] <= 0.0) continue;
      const auto& m = storage_[i];
      q[0] += m.ll * rate_[0][i] + m.lg * rate_[1][i];
      q[1] += m.gl * rate_[0][i] + m.gg * rate_[1][i];
    }
    return q;
  }

  /// The points' pressures moved by the nodal increments between two nodal fields (each from
  /// nodal_pressures): dP_p = sum_i N_i (P_i,end - P_i,start).
  void add_increments(const std::array<std::vector<double>, 2>& start,
                      const std::array<std::vector<double>, 2>& end, FluidPoints<D>& fp) const {
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      double dl = 0.0, dg = 0.0;
      for (int a = 0; a < st.n; ++a) {
        const auto i = st.node[a];
        dl += st.w[a] * (end[0][i] - start[0][i]);
        dg += st.w[a] * (end[1][i] - start[1][i]);
      }
      fp.liquid_pressure[p] += dl;
      fp.gas_pressure[p] += dg;
    }
  }

 private:
  using NodeMask = std::uint64_t;  // one bit per stencil node
  static_assert(PointStencil<D, K>::n <= 64, "a stencil of more than 64 nodes");

  struct PointData {
    int model;
    double volume, porosity, div_vs;
    Vec<D> grad_ln_n;
  };

  bool held(std::int64_t i) const { return !(storage_[i].gg > 0.0); }

  /// The nodal values of the points' pressures. The volume-weighted mean is biased wherever a
  /// node's support is one-sided — on the body's boundary: a linear field P = rho g depth
  /// projects to rho g h/4 instead of 0 at the surface node, and the flow would start from that
  /// error (a spurious flux toward the node, a jump where a prescribed value switches on). So each
  /// node takes the value of a weighted least-squares linear fit to the points around it (exact
  /// for linear fields, equal to the mean for a symmetric support). The mean stays where the
  /// points cannot carry a fit: too few of them, or spread less than min_fit_spread h (weighted
  /// standard deviation of their offsets) in some direction. Such a cloud is nearly a line, and
  /// the fit's slope across it, extrapolated to the node, is noise: on the embankment a crest
  /// squeezed into one column of points (offsets from the node 0.084-0.11 m in x, 0.2 m cells)
  /// gave a fitted 3.59 MPa where the points held -71 to +8 kPa (mean -12.3 kPa); the flow
  /// started from it and threw the crest out of the grid (t = 138.6 s).
  void fit_nodes(const FluidPoints<D>& fp, std::array<std::vector<double>, 2>& nodal) {
    using Row = Eigen::Matrix<double, D + 1, 1>;
    using Normal = Eigen::Matrix<double, D + 1, D + 1>;
    std::vector<std::int64_t> fitted;
    std::vector<std::int64_t> slot(grid_.n_nodes(), -1);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (volume_[i] > 0.0) slot[i] = static_cast<std::int64_t>(fitted.size()), fitted.push_back(i);
    std::vector<Normal> normal(fitted.size(), Normal::Zero());
    std::vector<std::array<Row, 2>> rhs(fitted.size(), {Row::Zero(), Row::Zero()});
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      for (int a = 0; a < st.n; ++a) {
        const auto k = slot[st.node[a]];
        if (k < 0 || st.w[a] <= 0.0) continue;
        Row r;
        r[0] = 1.0;
        r.template tail<D>() = positions_[p] - grid_.node_position(st.node[a]);
        const double w = st.w[a] * points_[p].volume;
        normal[k] += w * r * r.transpose();
        rhs[k][0] += w * fp.liquid_pressure[p] * r;
        rhs[k][1] += w * fp.gas_pressure[p] * r;
      }
    }
    const double min_variance = std::pow(min_fit_spread * grid_.spacing.minCoeff(), 2);
    for (std::size_t k = 0; k < fitted.size(); ++k) {
      // Weighted covariance of the offsets, sum w d d^T / sum w - mean mean^T; at least
      // min_variance in every direction also makes the normal matrix invertible (too few points
      // fail here too).
      const double w = normal[k](0, 0);
      const Vec<D> mean = normal[k].template block<D, 1>(1, 0) / w;
      const Eigen::Matrix<double, D, D> cov =
          normal[k].template block<D, D>(1, 1) / w - mean * mean.transpose();
      if (Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, D, D>>(cov, Eigen::EigenvaluesOnly)
              .eigenvalues()
              .minCoeff() < min_variance)
        continue;
      const Eigen::FullPivLU<Normal> lu(normal[k]);
      for (int a = 0; a < 2; ++a) nodal[a][fitted[k]] = lu.solve(rhs[k][a])[0];
    }
  }
  bool prescribed_active(int a, std::int64_t i) const {
    return prescription_.prescribed[a][i] && volume_[i] > 0.0;
  }

  bool supplied(int a, std::int64_t i) const {
    return !supply_[a].empty() && unknown_[a][i] >= 0 && supply_[a][i] != 0.0;
  }

  /// Mass rate of fluid a entering at node i (after solve_rates): M P' - F at a prescribed active
  /// node, the supply where fluid a is an unknown.
  double node_inflow(int a, std::int64_t i) const {
    if (prescribed_active(a, i)) {
      const auto& m = storage_[i];
      return a == 0 ? m.ll * rate_[0][i] + m.lg * rate_[1][i] - force_[0][i]
                    : m.gl * rate_[0][i] + m.gg * rate_[1][i] - force_[1][i];
    }
    return supplied(a, i) ? supply_[a][i] : 0.0;
  }

  /// Sum over the nodes of node_inflow, per fluid (after solve_rates).
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
        if (unknown_[a][i] >= 0) {
          pressure_[a][i] = y[unknown_[a][i]];
        } else if (prescription_.prescribed[a][i]) {
          pressure_[a][i] = prescription_.value[a][i];
          rate_[a][i] = prescription_.rate[a][i];
        }
      }
  }

  /// What a pass over the points needs: the balances only, or the Jacobian's derivatives too.
  enum class Pass { balances, jacobian };

  PointFlow<D> flow_at(std::size_t p, Pass pass) const {
    const auto& st = stencils_[p];
    const auto& pt = points_[p];
    std::array<double, 2> pr{0.0, 0.0};
    std::array<Vec<D>, 2> gr{Vec<D>::Zero(), Vec<D>::Zero()};
    for (int a = 0; a < st.n; ++a)
      for (int f = 0; f < 2; ++f) {
        pr[f] += st.w[a] * pressure_[f][st.node[a]];
        gr[f] += st.grad[a] * pressure_[f][st.node[a]];
      }
    PointFlow<D> f = point_flow<D>(
        models_[pt.model],
        {pt.porosity, pt.div_vs, form_ == MassBalance::simplified, pass == Pass::jacobian}, pr, gr,
        gravity_, pt.grad_ln_n);
    if (!extra_storage_.empty()) {
      const auto& e = extra_storage_[p];
      f.storage.ll += e.ll, f.storage.lg += e.lg, f.storage.gl += e.gl, f.storage.gg += e.gg;
    }
    return f;
  }

  void assemble_balances() {
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (volume_[i] <= 0.0) continue;
      storage_[i] = {0.0, 0.0, 0.0, 0.0};
      force_[0][i] = force_[1][i] = 0.0;
    }
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      const double v = points_[p].volume;
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
    for (const auto i : unknown_nodes_)
      for (int a = 0; a < 2; ++a)
        if (supplied(a, i)) force_[a][i] += supply_[a][i];
  }

  /// Nodal rates of the unknowns from M P' = F, with the prescribed rates known.
  void solve_rates() {
    for (const auto i : unknown_nodes_) {
      const auto& m = storage_[i];
      const bool free_l = unknown_[0][i] >= 0, free_g = unknown_[1][i] >= 0;
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

  std::int64_t position(std::int64_t row, std::int64_t col) const {
    const auto first = pattern_.col.begin() + pattern_.row_ptr[row];
    const auto last = pattern_.col.begin() + pattern_.row_ptr[row + 1];
    return std::lower_bound(first, last, col) - pattern_.col.begin();
  }

  /// surface_: the active nodes of the grid cells that have both active and inactive nodes.
  void mark_surface() {
    surface_.assign(grid_.n_nodes(), 0);
    constexpr int corners = 1 << D;
    std::array<std::int64_t, corners> node;
    for (std::int64_t c = 0; c < grid_.n_cells_total(); ++c) {
      std::int64_t rest = c, base = 0;
      for (int d = 0; d < D; ++d) {
        base += (rest % grid_.n_cells[d]) * grid_.stride[d];
        rest /= grid_.n_cells[d];
      }
      int active = 0;
      for (int k = 0; k < corners; ++k) {
        node[k] = base;
        for (int d = 0; d < D; ++d)
          if ((k >> d) & 1) node[k] += grid_.stride[d];
        active += volume_[node[k]] > 0.0;
      }
      if (active == 0 || active == corners) continue;
      for (int k = 0; k < corners; ++k)
        if (volume_[node[k]] > 0.0) surface_[node[k]] = 1;
    }
  }

  /// The stencil nodes that take part in point st's Jacobian (bit a: node a).
  NodeMask jacobian_nodes(const PointStencil<D, K>& st) const {
    const double h = grid_.spacing.minCoeff();
    NodeMask kept = 0;
    for (int a = 0; a < st.n; ++a)
      if (jacobian_drop_ == 0.0 || st.w[a] >= jacobian_drop_ ||
          h * st.grad[a].cwiseAbs().maxCoeff() >= jacobian_drop_)
        kept |= NodeMask{1} << a;
    return kept;
  }

  SparsePattern build_pattern() const {
    std::vector<std::vector<std::int64_t>> rows(n_unknowns_);
    for (std::size_t p = 0; p < stencils_.size(); ++p) {
      const auto& st = stencils_[p];
      const NodeMask kept = jacobian_nodes_[p];
      for (int a = 0; a < st.n; ++a)
        for (int al = 0; al < 2; ++al) {
          const auto i = st.node[a];
          const auto r = prescribed_active(al, i) ? n_pressures_ + al : unknown_[al][i];
          if (r < 0 || !(kept >> a & 1u)) continue;
          for (int b = 0; b < st.n; ++b)
            for (int be = 0; be < 2; ++be)
              if (const auto c = unknown_[be][st.node[b]]; c >= 0 && (kept >> b & 1u))
                rows[r].push_back(c);
        }
    }
    SparsePattern pattern;
    pattern.n = n_unknowns_;
    pattern.row_ptr.assign(1, 0);
    for (std::int64_t r = 0; r < n_unknowns_; ++r) {
      auto& c = rows[r];
      c.push_back(r);
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end()), c.end());
      pattern.col.insert(pattern.col.end(), c.begin(), c.end());
      pattern.row_ptr.push_back(static_cast<std::int64_t>(pattern.col.size()));
    }
    return pattern;
  }

  const Grid<D>& grid_;
  std::vector<physics::HydraulicModel> models_;
  MassBalance form_;
  Vec<D> gravity_;
  Prescribe prescribe_;
  NodalPrescription prescription_;
  std::array<std::vector<std::uint8_t>, 2> fixed_prescribed_;  // from set_prescribed
  std::array<std::vector<std::uint8_t>, 2> was_prescribed_;    // at the previous prepare
  std::array<bool, 2> surface_fluid_{false, false};
  std::array<std::vector<std::uint8_t>, 2> surface_exempt_;
  std::array<std::vector<double>, 2> supply_;
  std::vector<std::uint8_t> surface_, was_active_;
  std::vector<PointStencil<D, K>> stencils_;
  double jacobian_drop_ = 0.0;
  std::vector<NodeMask> jacobian_nodes_;  // per point: the stencil nodes in the Jacobian
  std::vector<PointData> points_;
  std::vector<physics::StorageMatrix> extra_storage_;
  std::vector<Vec<D>> positions_;   // of the points at prepare() [m]
  std::vector<double> solid_rate_;  // div v_s per point [1/s]; empty: none
  std::array<std::vector<std::int64_t>, 2> unknown_;
  std::vector<std::int64_t> unknown_nodes_;
  std::int64_t n_unknowns_ = 0, n_pressures_ = 0;
  std::array<double, 2> inflow_scale_{1.0, 1.0}, start_inflow_{0.0, 0.0};
  SparsePattern pattern_;
  std::vector<double> volume_;                   // sum_p N_i V_p
  std::array<std::vector<double>, 2> pressure_;  // nodal P [Pa]
  std::array<std::vector<double>, 2> rate_;      // nodal dP/dt [Pa/s]
  std::array<std::vector<double>, 2> force_;     // F [kg/s]
  std::vector<physics::StorageMatrix> storage_;  // M [kg/Pa]
};

}  // namespace unsatmpm::numerics
