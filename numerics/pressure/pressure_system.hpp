// The nodal pressure system of the implicit cycle (docs/cycles.md): the liquid and gas mass
// balances in Darcy form, assembled with the material points as quadrature points, as an ODE in the
// nodal pressures for CVODE, M_i(P) dP_i/dt = F_i(P, t) (numerics/pressure/pressure_operator.hpp
// states M and F and evaluates them). Impervious is the natural condition (no boundary term);
// prescribed pressures (a node and a fluid) are not unknowns: their values and rates come from
// a callback, and their balance, M P' - F, is the mass rate entering there.
//
// Unknowns (numerics/pressure/unknowns.hpp): for each active node (sum_p N_i V_p > 0) in node
// order, P_l then P_g, each unless prescribed. A node free of gas at prepare() (sum_p N_i V_p n_p
// S_g,p <= physics::gas_free_saturation sum_p N_i V_p n_p: no gas phase whose balance could be
// solved) has its gas pressure held over the integration at the value start() fits there: it is
// a prescribed node like a boundary's, so the gas a desaturation needs enters there and is counted
// as inflow (docs/balance_laws.md, "Saturated soil"). The explicit cycle holds it alike. Where a
// node's gas storage vanishes during an integration (M_gg = 0) P_g is held too (dP_g/dt = 0).
//
// Two more unknowns follow the pressures: the mass of each fluid that has entered through the
// prescribed nodes since the start, Q_a, over a storage scale so that it reads in Pa for CVODE's
// error control: dQ_a/dt = sum over prescribed (i, a) of (M_i P'_i - F_i)_a, plus the supplies
// (rainfall: a mass rate at nodes where the fluid is an unknown). So the conservation report's
// inflow is as accurate as the pressures.
//
// This class sets up each integration and answers CVODE's and the cycle's queries: rhs() gives
// y' = M^-1 F node by node, jacobian() its exact derivative in the CSR pattern of pattern(); each
// fills the prescription for t and then evaluates the operator once. The points are frozen at
// prepare() (numerics/pressure/quadrature.hpp); start() fits the nodal start values to them and
// add_increments() returns the nodal increments (numerics/pressure/nodal_projection.hpp). With a
// drop tolerance (set_jacobian_drop_tolerance), a point's part of the Jacobian leaves out the
// stencil nodes it barely touches; rhs() always keeps them, so only CVODE's Newton iteration
// sees the difference.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure/jumps.hpp"
#include "numerics/pressure/nodal_projection.hpp"
#include "numerics/pressure/pressure_operator.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/surface_penalty.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

template <int D, class K>
class PressureSystem {
 public:
  /// Fills value and rate of the prescribed nodes at time t [s].
  using Prescribe = std::function<void(double t, NodalPrescription&)>;

  PressureSystem(const Grid<D>& grid, std::vector<physics::HydraulicModel> models, MassBalance form,
                 const Vec<D>& gravity)
      : grid_(grid),
        points_(grid.n_nodes()),
        unknowns_(grid.n_nodes()),
        operator_(grid, std::move(models), form, gravity,
                  {points_, unknowns_, prescription_, supply_, pattern_, penalty_}) {
    const auto n = grid_.n_nodes();
    for (int a = 0; a < 2; ++a) {
      prescription_.prescribed[a].assign(n, 0);
      prescription_.value[a].assign(n, 0.0);
      prescription_.rate[a].assign(n, 0.0);
    }
  }

  // The operator refers to this object's members: it stays put.
  PressureSystem(const PressureSystem&) = delete;
  PressureSystem& operator=(const PressureSystem&) = delete;

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
  /// From the next prepare on, fluid a's surface condition is a penalty with factor γ on the
  /// face's trace (numerics/pressure/surface_penalty.hpp) towards the callback's surface_value[a];
  /// only the light surface nodes are held, below inside_fraction of a full node's volume (left
  /// free, their tiny storage stalled the integration on a settled face). γ = 0 holds them all.
  void set_surface_penalty(int a, double gamma) {
    if (!(gamma >= 0.0 && std::isfinite(gamma)))
      throw std::invalid_argument("PressureSystem: the surface penalty factor must be >= 0");
    penalty_gamma_[a] = gamma;
  }
  /// Per fluid, the surface penalty coupling c of the last prepare (empty: none).
  const FacePenalties& surface_penalty_couplings() const { return penalty_; }
  /// Free-surface nodes (flag 1) where fluid a's surface condition is not applied from the next
  /// prepare on: fluid a is an unknown there, fed by its supply (set_supply), out of the penalty.
  /// Empty: none. Rain switches nodes between the two (cycles/implicit_solver.hpp).
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
  /// The numbering of the last prepare.
  const PressureUnknowns& unknowns() const { return unknowns_; }
  /// Threads of the rhs' and Jacobian's sums over the points (>= 1; default 1).
  void set_threads(int n_threads) { operator_.set_threads(n_threads); }
  /// PressureOperator::set_nodal_permeability.
  void set_nodal_permeability(bool from_nodes) { operator_.set_nodal_permeability(from_nodes); }

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
    active_.resize(grid_.n_nodes(), 0);
    was_active_ = active_;
    points_.fill(grid_, mp, fp, ranges, solid_rate_, jacobian_drop_);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) active_[i] = points_.active(i);
    const auto active = [this](std::int64_t i) { return points_.active(i); };
    surface_ = free_surface_nodes<D>(grid_, occupied_cells<D>(grid_, mp), active);
    for (int a = 0; a < 2; ++a) {
      was_prescribed_[a] = prescription_.prescribed[a];
      for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
        prescription_.prescribed[a][i] =
            (!fixed_prescribed_[a].empty() && fixed_prescribed_[a][i]) ||
            (surface_fluid_[a] &&
             (penalty_gamma_[a] == 0.0 || light_node<D>(grid_, points_.node_volume[i], i)) &&
             surface_[i] && (surface_exempt_[a].empty() || !surface_exempt_[a][i]));
    }
    gas_free_ = gas_free_nodes<D, K>(points_, fp);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (gas_free_[i]) prescription_.prescribed[gas_phase][i] = 1;
    unknowns_.number(active, prescription_.prescribed);
    for (int a = 0; a < 2; ++a)
      penalty_[a] = penalty_gamma_[a] > 0.0
                        ? held_part(surface_penalty<D, K>(grid_, points_, operator_.models(), a,
                                                          penalty_gamma_[a]),
                                    surface_, surface_exempt_[a])
                        : FaceTrace{};
    SparsePattern pattern = unknowns_.jacobian_pattern(
        points_, [this](int a, std::int64_t i) { return operator_.prescribed_active(a, i); },
        penalty_);
    const bool changed = !(pattern == pattern_);
    pattern_ = std::move(pattern);
    return changed;
  }

  /// What the next prepare carries over from the last one (a checkpoint keeps it), and setting
  /// it before the next prepare (a resumed run).
  PrepareCarry carried() const {
    return {active_, surface_, prescription_.prescribed, surface_exempt_};
  }
  void restore_carried(PrepareCarry c) {
    active_ = std::move(c.active), surface_ = std::move(c.surface);
    prescription_.prescribed = std::move(c.prescribed), surface_exempt_ = std::move(c.exempt);
  }

  /// Storage added to each point's A (constant over an integration) [kg/(m^3 Pa)]: the
  /// fixed-stress split's stabilisation (cycles/implicit_solver.hpp). Empty: none.
  void set_extra_storage(std::vector<physics::StorageMatrix> extra) {
    operator_.set_extra_storage(std::move(extra));
  }

  /// Each point's solid volumetric strain rate div v_s [1/s] from the next prepare on, for the
  /// source term -S_a rho_a div v_s of the mass balances (docs/balance_laws.md). Empty (the
  /// default): none. The main cycle's fixed-stress split hands the flow no solid rate today
  /// (cycles/implicit_solver.hpp).
  void set_solid_rate(std::vector<double> div_vs) { solid_rate_ = std::move(div_vs); }

  /// The nodes whose pressure of fluid a is prescribed in the current integration (boundaries,
  /// the free surface, and for the gas the nodes free of gas), one flag per node.
  const std::vector<std::uint8_t>& prescribed(int a) const { return prescription_.prescribed[a]; }

  std::int64_t n_unknowns() const { return unknowns_.size(); }
  std::int64_t n_pressure_unknowns() const { return unknowns_.n_pressures(); }
  /// Index of the inflow integral of fluid a in y.
  std::int64_t inflow_unknown(int a) const { return unknowns_.inflow(a); }
  /// Mass [kg per unit out-of-plane measure] per unit of the inflow unknowns [Pa].
  double inflow_scale(int a) const { return operator_.inflow_scale(a); }
  const SparsePattern& pattern() const { return pattern_; }
  /// The points' configuration frozen at the last prepare.
  const PointQuadrature<D, K>& quadrature() const { return points_; }
  /// Node and fluid of unknown k (for messages); (-1, a) for the inflow integral of fluid a.
  std::pair<std::int64_t, int> unknown_location(std::int64_t k) const {
    return unknowns_.location(k);
  }

  /// How start() treats the prescribed nodes: at the first start their prescribed values switch
  /// on (the field the points' increments are measured from holds the projected values there, so
  /// the points near them receive the jump); at later starts they continue (the field holds the
  /// prescribed values, so no jump is applied twice).
  enum class Prescribed { switch_on, continuing };
  /// Where start() measures the mass of a switched-on prescribed value's jump from: the points'
  /// own pressures (the points then receive the jump as an increment), or the fitted field at the
  /// points (a deformable skeleton's points take the flow's mass change measured on that field,
  /// cycles/undrained.hpp, so the inflow must be measured on it too).
  enum class JumpBase { points, fitted };

  using StartFrom = numerics::StartFrom;

  /// The start of an integration at time t: the nodal pressures for every active node, fitted
  /// to the points or from `nodal` as `from` says (start_values; prescribed ones as `prescribed`
  /// says), the unknowns y0 (inflow integrals 0), and the inflow scales (sum of the nodal
  /// storages at this state).
  void start(double t, const FluidPoints<D>& fp, std::span<double> y0,
             std::array<std::vector<double>, 2>& projected, Prescribed prescribed,
             JumpBase base = JumpBase::points, StartFrom from = StartFrom::points,
             const std::array<std::vector<double>, 2>* nodal = nullptr) {
    start_values<D, K>(from, grid_, points_, fp, nodal, was_active_, projected);
    // A node free of gas holds the gas pressure of its surroundings, the fitted one; the
    // callback below leaves it alone unless a boundary prescribes it too.
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (gas_free_[i])
        prescription_.value[gas_phase][i] = projected[gas_phase][i],
        prescription_.rate[gas_phase][i] = 0.0;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      for (int a = 0; a < 2; ++a)
        if (unknowns_(a, i) >= 0) y0[unknowns_(a, i)] = projected[a][i];
    y0[unknowns_.inflow(0)] = y0[unknowns_.inflow(1)] = 0.0;
    prescribe(t);
    operator_.set_pressures(y0);
    operator_.assemble_balances();
    operator_.scale_inflows();
    const auto& pressure = operator_.pressures();
    // A prescribed value that differs from the projected one (a boundary condition switched on
    // at t) moves the points near it at once: the mass M_i dP_i enters there.
    // A node that was already prescribed and active at the previous start continues (its
    // field holds the prescribed value); a node prescribed for the first time (a free-surface
    // node newly exposed, or every node at the first start) switches on, or, a gas value after
    // the first start where the liquid is an unknown, ramps in until ramp_end (GasSwitchOnRamps).
    std::array<std::vector<double>, 2> jump{std::vector<double>(grid_.n_nodes(), 0.0),
                                            std::vector<double>(grid_.n_nodes(), 0.0)};
    ramps_.keep_running(t, prescription_.prescribed[gas_phase]);
    bool ramped = false;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (!points_.active(i)) continue;
      for (int a = 0; a < 2; ++a) {
        if (!prescription_.prescribed[a][i]) continue;
        const bool continues =
            prescribed == Prescribed::continuing && was_prescribed_[a][i] && was_active_[i];
        if (continues) {
          projected[a][i] = pressure[a][i];
        } else if (a == gas_phase && prescribed == Prescribed::continuing && t < ramp_end_ &&
                   unknowns_(liquid_phase, i) >= 0 && !gas_free_[i] && !ramps_.ramps(i) &&
                   pressure[a][i] != projected[a][i] &&
                   GasSwitchOnRamps::suits(operator_.nodal_storage(i))) {
          ramps_.add(i, projected[a][i], t, ramp_end_);
          ramped = true;
        } else {
          jump[a][i] = pressure[a][i] - projected[a][i];
        }
      }
    }
    if (ramped) {
      prescribe(t);
      operator_.set_pressures(y0);
      operator_.assemble_balances();
    }
    std::array<std::vector<double>, 2> fitted;
    if (base == JumpBase::fitted) interpolate_nodal<D, K>(points_, projected, fitted);
    const auto& base_pl = base == JumpBase::points ? fp.liquid_pressure : fitted[liquid_phase];
    const auto& base_pg = base == JumpBase::points ? fp.gas_pressure : fitted[gas_phase];
    if (keep_liquid_under_gas_jumps(points_, operator_, unknowns_, base_pl, base_pg, jump, y0)) {
      operator_.set_pressures(y0);
      operator_.assemble_balances();
    }
    start_inflow_ = jump_mass(points_, operator_, base_pl, base_pg, jump);
  }

  /// The time [s] by which a gas value switched on at a later start (Prescribed::continuing)
  /// reaches its prescribed value where the node's liquid is an unknown: the end of the
  /// coupling interval (GasSwitchOnRamps). Not set, or not after the start: it jumps at once.
  void set_ramp_end(double t1) { ramp_end_ = t1; }

  /// A nodal field (per fluid, every node) at the points of the last prepare.
  void at_points(const std::array<std::vector<double>, 2>& nodal,
                 std::array<std::vector<double>, 2>& out) const {
    interpolate_nodal<D, K>(points_, nodal, out);
  }

  /// Mass [kg per unit out-of-plane measure] entering at start() through prescribed values that
  /// differ from the projected ones.
  const std::array<double, 2>& start_inflow() const { return start_inflow_; }

  /// Nodal pressures of every active node at time t: the unknowns, or the prescribed values.
  void nodal_pressures(double t, std::span<const double> y,
                       std::array<std::vector<double>, 2>& out) {
    prescribe(t);
    operator_.set_pressures(y);
    out = operator_.pressures();
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
    return operator_.rhs(ydot);
  }

  /// dy'/dy in the order of pattern(). Returns 0, or 1 if a value is not finite.
  int jacobian(double t, std::span<const double> y, std::span<double> values) {
    evaluate(t, y);
    return operator_.jacobian(values);
  }

  /// Mass rates entering through the prescribed nodes and the supplies at (t, y) [kg/s per unit
  /// out-of-plane measure]: the balance M P' - F of each prescribed node and fluid plus the
  /// supplies (set_supply), summed per fluid.
  std::array<double, 2> boundary_inflow(double t, std::span<const double> y) {
    evaluate(t, y);
    return operator_.inflow();
  }

  /// The same node by node for fluid a: (M P' - F)_a at the prescribed active nodes, the supply
  /// at the active nodes where fluid a is an unknown, 0 elsewhere [kg/s per unit out-of-plane
  /// measure].
  std::vector<double> inflow_by_node(int a, double t, std::span<const double> y) {
    evaluate(t, y);
    std::vector<double> q(grid_.n_nodes(), 0.0);
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) q[i] = operator_.node_inflow(a, i);
    return q;
  }

  /// Rate of change of the stored mass of each fluid, sum over the active nodes of M_i P'_i
  /// [kg/s per unit out-of-plane measure], prescribed rates included.
  std::array<double, 2> storage_rate(double t, std::span<const double> y) {
    evaluate(t, y);
    return operator_.storage_rate();
  }

 private:
  void prescribe(double t) {
    if (prescribe_) prescribe_(t, prescription_);
    ramps_.apply(t, prescription_);
  }

  /// The one evaluation at (t, y) every query starts from.
  void evaluate(double t, std::span<const double> y) {
    prescribe(t);
    operator_.evaluate(y);
  }

  const Grid<D>& grid_;
  // Configuration, kept across integrations.
  Prescribe prescribe_;
  std::array<std::vector<std::uint8_t>, 2> fixed_prescribed_;  // from set_prescribed
  std::array<bool, 2> surface_fluid_{false, false};
  std::array<double, 2> penalty_gamma_{0.0, 0.0};
  std::array<std::vector<std::uint8_t>, 2> surface_exempt_;
  std::array<std::vector<double>, 2> supply_;
  std::vector<double> solid_rate_;  // div v_s per point [1/s]; empty: none
  double jacobian_drop_ = 0.0;
  // One integration, from prepare and start.
  PointQuadrature<D, K> points_;
  NodalPrescription prescription_;
  std::array<std::vector<std::uint8_t>, 2> was_prescribed_;  // at the previous prepare
  std::vector<std::uint8_t> active_, surface_, was_active_, gas_free_;
  PressureUnknowns unknowns_;
  SparsePattern pattern_;
  FacePenalties penalty_;  // per fluid, the surface penalty's coupling
  std::array<double, 2> start_inflow_{0.0, 0.0};
  GasSwitchOnRamps ramps_;  // gas values switching on after the first start
  double ramp_end_ = -std::numeric_limits<double>::infinity();
  PressureOperator<D, K> operator_;  // refers to the members above
};

}  // namespace unsatmpm::numerics
