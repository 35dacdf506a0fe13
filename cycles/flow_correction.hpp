// The main cycle's flow correction (docs/balance_laws.md, "Two-way coupling in the main cycle"):
// the water and gas the flow moved over a coupling interval were computed for the pressures the
// flow predicted, with the skeleton following at once (the fixed-stress split); where the
// mechanics' pressures depart from that prediction — a mode of the pressure field the skeleton
// cannot answer, a ringing skeleton, a point whose own storage differs from the fitted field's —
// the Darcy flux of the difference is added at every mechanics sub-step, implicitly.
//
// At a sub-step [tau, tau + h] of the interval [t, t + dt], each point's departure is
//   d_p = P_p(tau) - P_p(t) - (tau / dt) (P^_p(t + dt) - P^_p(t)),
// its actual pressure change against the flow's nodal field P^ at the point (the flow's mass
// reaches the points linearly in time, cycles/undrained.hpp, so the matching pressure change is
// linear too). Projected to the flow's free nodes, delta_i = sum_p N_i V_p d_p / sum_p N_i V_p,
// its Darcy flux is taken backward in time with the nodes' undrained storage S,
//   (S_f + h_f L) x = -h_f L delta,    c = -h L (delta + x),
// L the conductance at the interval's start (numerics/pressure/conductance.hpp; with a face whose
// condition is a penalty, its coupling too, so that a departure there drains through the face
// within the interval as the flow's own penalty drains it), and the masses c join the sub-step's
// nodal solve (they sum to what enters at the prescribed nodes and through a penalised face,
// counted as inflow). S_f and h_f are the storage and step of the matrix's last renewal. For a
// mode of L with eigenvalue l the departure then changes by the factor
// 1 - (h l / S) S_f / (S_f + h_f l), which lies in (-1, 1] whenever (h / h_f)(S_f / S) <= 2: the
// matrix is renewed when a node's storage or the step moves past `refactor_ratio` of that limit.
//
// The solve for x: GMRES (numerics/sparse_gmres.hpp) from the last sub-step's x, until each
// row's residual over its storage is within `solve_fraction` of the flow's own tolerance there.
// For storage plus a conductance whose rows sum to zero (an M-matrix, as the linear kernel's is)
// the error's largest entry is at most the largest of those ratios, so the pressure error is far
// below what the correction acts on; GIMP's conductance, a penalised face's coupling and the
// fluids' coupled storage make this an estimate rather than a bound. Where GMRES does not get
// there, KLU's LU of the same matrix (numerics/sparse_lu.hpp) solves, for the rest of the matrix's
// life. The masses c conserve whatever x is (L's columns sum to zero but for what leaves the body,
// which is counted), so the solve's error only perturbs the correction (docs/performance.md).
#pragma once

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/pressure/conductance.hpp"
#include "numerics/pressure/pressure_system.hpp"
#include "numerics/sparse_gmres.hpp"
#include "numerics/sparse_lu.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm {

/// The matrix is renewed when (h / h_f)(S_f / S) exceeds this at a free node (the
/// correction is stable up to 2; see the header).
inline constexpr double refactor_ratio = 1.5;

/// The correction's iterative solve stops when each unknown's residual, in pressure, is within
/// this fraction of the flow's tolerance there (rtol |P| + atol): a tenth of the departure below
/// which the correction acts at all (begin), so the solve's error is a tenth of what the flow
/// itself leaves unresolved; it conserves mass whatever it is, and what it leaves shows as a
/// departure at the next sub-step and is corrected there (docs/performance.md: with a
/// thousandth KLU took over at 51,776 of the embankment's 57,970 sub-steps to 30 s, with a tenth
/// at 8,953, and the control points' pressures moved by at most 0.05 Pa).
inline constexpr double solve_fraction = 0.1;

/// GMRES iterations per sub-step before KLU takes over for the matrix's life: a KLU solve cost
/// about as much as 7 iterations on the embankment (2D, 3,634 unknowns) and on its 3D slice
/// (10,902), so a matrix that needs more is cheaper to factorise (docs/performance.md).
inline constexpr int correction_gmres_iterations = 8;

template <int D, class K>
class FlowCorrection {
 public:
  /// GMRES takes at most `max_iterations` per sub-step before KLU does the solve.
  explicit FlowCorrection(int max_iterations = correction_gmres_iterations)
      : gmres_(max_iterations) {}

  /// Starts an interval [t, t + dt] after its flow: the flow's quadrature and unknowns, each
  /// point's conductivities at the start state `fp`, its pressures there `start`, and the change
  /// of the flow's field at it over the interval `predicted` [Pa]. A departure within the flow's
  /// own error tolerance, rtol |P| + atol with `nodal` the flow's end pressures (per fluid, per
  /// node), is left alone: the flow does not resolve it either.
  void begin(const numerics::PressureSystem<D, K>& system,
             const std::vector<physics::HydraulicModel>& models, const numerics::FluidPoints<D>& fp,
             const std::array<std::vector<double>, 2>& start,
             const std::array<std::vector<double>, 2>& predicted, double dt,
             const std::array<std::vector<double>, 2>& nodal, double rtol, double atol) {
    const auto& q = system.quadrature();
    unknowns_ = &system.unknowns();
    start_ = &start, predicted_ = &predicted, dt_ = dt;
    for (auto& c : conductivity_) c.resize(q.size());
    for (std::size_t p = 0; p < q.size(); ++p) {
      const physics::HydraulicModel& hm = models[q.model[p]];
      const double pl = fp.liquid_pressure[p], pg = fp.gas_pressure[p];
      const double se = hm.effective_saturation(physics::retention_suction(pl, pg));
      conductivity_[0][p] = hm.liquid_density(pl) * hm.intrinsic_permeability *
                            hm.liquid_relative_permeability_value(se) / hm.liquid_viscosity;
      conductivity_[1][p] = hm.gas_density(pg) * hm.intrinsic_permeability *
                            hm.gas_relative_permeability_value(se) / hm.gas_viscosity;
    }
    const numerics::FacePenalties& face = system.surface_penalty_couplings();
    pattern_ = numerics::conductance_pattern<D, K>(q, *unknowns_, face);
    conductance_.resize(pattern_.n_nonzeros());
    numerics::assemble_conductance<D, K>(q, *unknowns_, conductivity_, pattern_, conductance_,
                                         face);
    matrix_.resize(conductance_.size());
    const auto n = static_cast<std::size_t>(pattern_.n);
    delta_.resize(n), x_.resize(n), flux_.resize(n), factored_storage_.resize(n);
    tolerance_.resize(n), rhs_.resize(n), weight_.resize(n);
    guess_.assign(n, 0.0), partner_.assign(n, -1);
    for (const auto i : unknowns_->nodes()) {
      for (int f = 0; f < 2; ++f)
        if (const auto k = (*unknowns_)(f, i); k >= 0)
          tolerance_[k] = rtol * std::abs(nodal[f][i]) + atol;
      if (const auto kl = (*unknowns_)(0, i), kg = (*unknowns_)(1, i); kl >= 0 && kg >= 0)
        partner_[kl] = kg, partner_[kg] = kl;
    }
    factored_step_ = 0.0;
    lu_current_ = false;
  }

  /// The solve's choice: GMRES first (the default), or KLU only (`direct`).
  void set_direct(bool direct) { direct_ = direct; }
  /// Threads for GMRES's products (>= 1).
  void set_threads(int n_threads) { n_threads_ = n_threads; }

  /// Per point, the columns the correction sums at the nodes besides the storage (the nodal
  /// solve's first four): V, V d_l, V d_g at the fraction `along` = tau / dt of the interval.
  static constexpr int n_columns = 3;
  struct Columns {
    const FlowCorrection* c;
    const numerics::MaterialPoints<D>* mp;
    const numerics::FluidPoints<D>* fp;
    double along;
    void operator()(std::int64_t p, double* q) const {
      const double v = mp->volume[p];
      const auto &p0 = *c->start_, &dp = *c->predicted_;
      q[0] = v;
      q[1] = v * (fp->liquid_pressure[p] - p0[0][p] - along * dp[0][p]);
      q[2] = v * (fp->gas_pressure[p] - p0[1][p] - along * dp[1][p]);
    }
  };

  /// The correction as a source of numerics::nodal_pressure_increments (numerics::NodalMasses)
  /// at the sub-step [tau, tau + h] (tau from the interval's start): its columns are summed with
  /// the nodal solve's at the points' current positions, pressures and storages, and from those
  /// sums, before the solve, it forms the masses [kg per out-of-plane measure] that the
  /// departures' flux brings to each node, per fluid (into `nodal_mass`; zero at the nodes that
  /// are not the flow's unknowns). What entered at the prescribed nodes is left in `entered`,
  /// per fluid, the time taken added to `seconds`.
  struct Source {
    FlowCorrection* c;
    Columns columns_;
    double h;
    std::int64_t n_nodes;
    std::array<std::vector<double>, 2>* nodal_mass;
    std::array<double, 2>* entered;
    double* seconds;
    static constexpr int n_columns = FlowCorrection::n_columns;
    void columns(std::int64_t p, double* q) const { columns_(p, q); }
    const std::array<std::vector<double>, 2>* at_nodes(const double* sums, int stride) {
      const auto t0 = std::chrono::steady_clock::now();
      *entered = c->masses(sums, stride, h, n_nodes, *nodal_mass);
      *seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return nodal_mass;
    }
  };
  Source source(const numerics::Grid<D>& grid, const numerics::MaterialPoints<D>& mp,
                const numerics::FluidPoints<D>& fp, double tau, double h,
                std::array<std::vector<double>, 2>& nodal_mass, std::array<double, 2>& entered,
                double& seconds) {
    return {this, {this, &mp, &fp, tau / dt_}, h, grid.n_nodes(), &nodal_mass, &entered, &seconds};
  }

  /// The matrix's renewals; KLU's factorisations, GMRES's iterations, and the solves KLU made
  /// (after GMRES fell short, or all with set_direct).
  long n_renewals() const { return renewals_; }
  long n_factorisations() const { return lu_.n_factorisations(); }
  long n_iterations() const { return gmres_.n_iterations(); }
  long n_direct_solves() const { return direct_solves_; }

  /// KLU's factorisations, GMRES's iterations and KLU's solves since the last call.
  struct Counts {
    long factorisations = 0, iterations = 0, direct_solves = 0;
  };
  Counts take_counts() {
    const Counts now{n_factorisations(), n_iterations(), n_direct_solves()};
    const Counts since{now.factorisations - taken_.factorisations,
                       now.iterations - taken_.iterations,
                       now.direct_solves - taken_.direct_solves};
    taken_ = now;
    return since;
  }

 private:
  // The nodal sums of a node, `stride` values: the storage block sum N V A (ll, lg, gl, gg) first,
  // then at offset 6 sum N V, sum N V d_l, sum N V d_g (the columns above).
  static constexpr int storage_at = 0, volume_at = 6, departure_at = 7;

  /// The masses from the nodal sums (see Source; `sums` as above, `stride` values per node).
  std::array<double, 2> masses(const double* sums, int stride, double h, std::int64_t n_nodes,
                               std::array<std::vector<double>, 2>& nodal_mass) {
    for (auto& m : nodal_mass) m.assign(static_cast<std::size_t>(n_nodes), 0.0);
    if (pattern_.n == 0) return {0.0, 0.0};
    const auto& u = *unknowns_;
    const auto at = [&](std::int64_t i, int k) { return sums[stride * i + k]; };
    // Departures at the free nodes; none beyond the flow's tolerance: nothing to correct.
    bool departed = false;
    for (const auto i : u.nodes())
      for (int f = 0; f < 2; ++f)
        if (const auto k = u(f, i); k >= 0) {
          const double nv = at(i, volume_at);
          delta_[k] = nv > 0.0 ? at(i, departure_at + f) / nv : 0.0;
          departed = departed || std::abs(delta_[k]) > tolerance_[k];
        }
    if (!departed) return {0.0, 0.0};
    bool renew = !(factored_step_ > 0.0);
    for (const auto i : u.nodes())
      for (int f = 0; f < 2; ++f) {
        const auto k = u(f, i);
        const double s = at(i, storage_at + 3 * f);  // S_ll or S_gg
        if (k >= 0 && !renew && factored_storage_[k] > 0.0)
          renew = !(s > 0.0) || (h / factored_step_) * factored_storage_[k] / s > refactor_ratio;
      }
    if (renew) renew_matrix(sums, stride, h);
    // x from (S_f + h_f L) x = -h_f L delta, then c = -h L (delta + x). An unknown without
    // storage at the matrix's renewal is held at delta = x = 0 (as the nodal solve holds a fluid
    // without storage): it takes what its neighbours send, and the nodal solve lets it out.
    for (std::size_t k = 0; k < x_.size(); ++k)
      if (!(factored_storage_[k] > 0.0)) delta_[k] = 0.0;
    numerics::multiply(pattern_, conductance_, delta_, flux_, n_threads_);
    for (std::size_t k = 0; k < x_.size(); ++k)
      rhs_[k] = factored_storage_[k] > 0.0 ? -factored_step_ * flux_[k] : 0.0;
    solve();
    for (std::size_t k = 0; k < x_.size(); ++k) x_[k] += delta_[k];
    numerics::multiply(pattern_, conductance_, x_, flux_, n_threads_);
    // A node that no point touches any more takes nothing (the nodal solve could not place it):
    // what its neighbours sent towards it has left the body, and is counted with the rest.
    std::array<double, 2> entered{0.0, 0.0};
    for (const auto i : u.nodes())
      for (int f = 0; f < 2; ++f)
        if (const auto k = u(f, i); k >= 0 && at(i, volume_at) > 0.0) {
          nodal_mass[f][i] = -h * flux_[k];
          entered[f] += nodal_mass[f][i];
        }
    return entered;
  }

  /// x_ from (S_f + h_f L) x = rhs_ (see the header); guess_ keeps it for the next sub-step.
  void solve() {
    if (!direct_ && !lu_current_) {
      x_ = guess_;
      if (gmres_.solve(rhs_, weight_, x_, n_threads_)) {
        guess_ = x_;
        return;
      }
    }
    if (!lu_current_) lu_.factorise(pattern_, matrix_);
    lu_current_ = true;
    x_ = rhs_;
    lu_.solve(x_);
    guess_ = x_;
    ++direct_solves_;
  }

  /// S + h L at the current nodal storages, set up for the solves.
  void renew_matrix(const double* sums, int stride, double h) {
    const auto& u = *unknowns_;
    for (std::size_t k = 0; k < matrix_.size(); ++k) matrix_[k] = h * conductance_[k];
    for (const auto i : u.nodes()) {
      const double* r = sums + stride * i + storage_at;  // ll, lg, gl, gg
      const std::int64_t kl = u(0, i), kg = u(1, i);
      // The storage block's entries between the node's free fluids.
      if (kl >= 0) matrix_[pattern_.position(kl, kl)] += r[0];
      if (kg >= 0) matrix_[pattern_.position(kg, kg)] += r[3];
      if (kl >= 0 && kg >= 0) {
        matrix_[pattern_.position(kl, kg)] += r[1];
        matrix_[pattern_.position(kg, kl)] += r[2];
      }
      if (kl >= 0) factored_storage_[kl] = r[0];
      if (kg >= 0) factored_storage_[kg] = r[3];
    }
    // An unknown without storage (a node the points have left, or a fluid that vanished there)
    // is held: its row is x = 0.
    for (std::int64_t k = 0; k < pattern_.n; ++k)
      if (!(factored_storage_[k] > 0.0)) {
        for (auto e = pattern_.row_ptr[k]; e < pattern_.row_ptr[k + 1]; ++e) matrix_[e] = 0.0;
        matrix_[pattern_.position(k, k)] = 1.0;
      }
    factored_step_ = h;
    lu_current_ = false;
    ++renewals_;
    if (direct_) return;
    // Each row's residual measured against its storage (see the header); a held row's is x = 0
    // itself.
    for (std::int64_t k = 0; k < pattern_.n; ++k) {
      const double s = factored_storage_[k] > 0.0 ? factored_storage_[k] : 1.0;
      weight_[k] = 1.0 / (s * solve_fraction * tolerance_[k]);
    }
    gmres_.set(pattern_, matrix_, partner_);
  }

  const numerics::PressureUnknowns* unknowns_ = nullptr;
  const std::array<std::vector<double>, 2>* start_ = nullptr;      // P_p(t) [Pa]
  const std::array<std::vector<double>, 2>* predicted_ = nullptr;  // P^_p change [Pa]
  double dt_ = 1.0;
  std::array<std::vector<double>, 2> conductivity_;  // c per point and fluid [kg/(m s Pa)]
  numerics::SparsePattern pattern_;
  std::vector<double> conductance_, matrix_;  // L, and S_f + h_f L, in pattern_
  std::vector<double> delta_, x_, flux_, factored_storage_, tolerance_;  // per unknown
  std::vector<double> rhs_, weight_, guess_;                             // the solve's, per unknown
  std::vector<std::int64_t> partner_;  // the other fluid's unknown at the node, or -1
  double factored_step_ = 0.0;         // h_f [s]; 0: none yet
  numerics::SparseGmres gmres_;
  numerics::SparseLu lu_;
  bool direct_ = false, lu_current_ = false;  // lu_ holds the current matrix
  int n_threads_ = 1;
  long renewals_ = 0, direct_solves_ = 0;
  Counts taken_;  // at the last take_counts
};

}  // namespace unsatmpm
