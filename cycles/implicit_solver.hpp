// The project's main cycle (docs/cycles.md): explicit MPM mechanics of the mixture, and the liquid
// and gas mass balances in Darcy form as an implicit ODE in the nodal pressures, integrated by
// CVODE (BDF, Newton) with KLU (numerics/pressure/pressure_system.hpp,
// numerics/cvode_integrator.hpp).
//
// Staggering, one coupling interval [t, t + dt], a fixed-stress split (flow first):
//   1. the flow is integrated once over the interval by CVODE at the configuration at t, with the
//      solid's volumetric strain rate expressed through the pore pressure as if the mean total
//      stress stayed fixed: eps_v' = p*' / K_dr, p* = max(P_l, P_g) the pore pressure of the net
//      stress and K_dr the skeleton's drained bulk modulus in D dimensions (elastic; 1e-3 of it
//      at points on a Mohr-Coulomb apex, whose drained tangent is zero: cycles/fixed_stress.hpp).
//      The term moves into the storage, A_ab += S_a rho_a / K_dr dp*/dP_b (frozen over the
//      interval);
//   2. the nodal pressure increments are returned to the points, which update S_l and densities;
//   3. mechanics sub-cycles over the interval with explicit steps (mixture mass, total stress
//      sigma_bar - p* I, damping alpha) under the new pore pressures, and updates the porosity
//      from the points' volumes (the solid volume is kept).
// Why: the drained split (mechanics first, pressures frozen) amplifies each interval's error by
// the coupling strength (1 / storage) / K_dr, about 20 for a saturated soil with water, and
// diverges whatever the interval (Kim, Tchelepi & Juanes 2011); the fixed-stress split is stable
// (Mikelic & Wheeler 2013). The textbook sequential form also feeds the previous interval's total
// stress rate, (eps_v' - p*'/K_dr)_prev, to the flow: with this cycle's dynamic explicit mechanics
// that rate carries the skeleton's oscillations, and it made Terzaghi's consolidation diverge for
// intervals of 0.02-0.06 s (stable at 0.1 s and above; test_implicit_coupling.cpp), so the total
// stress rate is taken as zero and no solid rate reaches the flow. What that leaves out: volume
// change from a changing total stress (loading, redistribution, shear dilatancy) does not reach the
// fluid balances; the conservation report shows it as a mismatch. It is exact for one-dimensional
// consolidation under a constant load, as in the test. A rigid skeleton has no mechanics: CVODE
// then runs through the whole simulation without restart, and an interval only sets when the points
// receive their increments (outputs, histories).
//
// Damping alpha acts on the mechanics only: the Darcy form has no fluid inertia to damp.
#pragma once

#include <chrono>
#include <cmath>
#include <string>
#include <variant>

#include "cycles/explicit_solver.hpp"
#include "cycles/fixed_stress.hpp"
#include "cycles/flow_prescription.hpp"
#include "cycles/implicit_diagnostics.hpp"
#include "cycles/three_phase_setup.hpp"
#include "numerics/cvode_integrator.hpp"
#include "numerics/pressure/pressure_system.hpp"

namespace unsatmpm {

// Numerical settings of the main cycle that are not case keys (docs/input.md states them):
/// Drop tolerance of the flow's Jacobian (numerics::PressureSystem::set_jacobian_drop_tolerance):
/// GIMP's stencil nodes a point barely touches (below 5 % of a full weight or gradient) leave the
/// Jacobian, for 5 times less KLU time on the embankment at the same Newton iteration count
/// (docs/balance_laws.md). Not a key: it changes the cost, not the solution (the rhs is exact).
inline constexpr double jacobian_drop_tolerance = 0.05;
/// CVODE steps allowed per coupling interval: a flow that needs more is stuck, and is reported
/// (CV_TOO_MUCH_WORK, with its worst unknown) instead of running on for hours. Not a key: a
/// legitimate interval takes tens to hundreds of steps.
inline constexpr long max_cvode_steps_per_interval = 20000;
/// A mechanics wave speed (c + |v|) above this many times its initial value ends the run as a
/// blow-up: the explicit step would have collapsed by the same factor.
inline constexpr double wave_speed_blowup_factor = 1e3;
/// Default coupling intervals: with a deformable skeleton this many mechanics steps; with a rigid
/// one, the run's end time divided by `rigid_intervals_per_run` when no history interval is set.
inline constexpr double mechanics_steps_per_interval = 20.0;
inline constexpr double rigid_intervals_per_run = 200.0;

template <int D, class K>
class ImplicitSolver {
 public:
  ImplicitSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : case_(c),
        grid_(std::move(grid)),
        points_(std::move(points)),
        hydraulics_(hydraulic_models(c)),
        fluids_(initial_fluid_state<D>(c, points_, hydraulics_)),
        system_(grid_, hydraulics_, c.mass_balance, gravity_vector(c)),
        prescription_(c, grid_, system_),
        cvode_(
            [this](double t, std::span<const double> y, std::span<double> ydot) {
              return timed(counters_.rhs_seconds, [&] { return system_.rhs(t, y, ydot); });
            },
            [this](double t, std::span<const double> y, std::span<const double>,
                   std::span<double> values) {
              return timed(counters_.jacobian_seconds,
                           [&] { return system_.jacobian(t, y, values); });
            },
            {c.solver.implicit.relative_tolerance, c.solver.implicit.absolute_tolerance}),
        rigid_(c.skeleton == physics::Skeleton::rigid) {
    cvode_.set_max_num_steps(max_cvode_steps_per_interval);
    system_.set_jacobian_drop_tolerance(jacobian_drop_tolerance);
    gravity_ = gravity_vector(c);
    mech_nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, mech_nodes_.fixed);
    mass_floor_ = mass_floor(points_.points);
    if (!rigid_) initial_speed_ = mechanics_speed_ = solid_wave_speed(models_, points_);
    interval_ = coupling_interval();
  }

  // The pressure system refers to grid_, and CVODE's callbacks to this object: it stays put.
  ImplicitSolver(const ImplicitSolver&) = delete;
  ImplicitSolver& operator=(const ImplicitSolver&) = delete;

  /// The next coupling interval [s]; the run loop clips it to output times.
  double interval() const { return interval_; }

  /// Advances from t to t + dt [s]: one coupling interval, the flow first, then the mechanics
  /// (see the header). Throws BlowUpError on a CVODE failure or a non-finite mechanics state,
  /// naming the time, the flag and the node or point.
  void step(double t, double dt) {
    // A rigid skeleton's flow runs on through the intervals unless the rain needs a restart.
    if (!rigid_ || !started_ || prescription_.has_rain()) start_flow(t, dt);
    flow_to(t + dt);
    if (!rigid_) mechanics(t, dt);
    ++counters_.coupling_intervals;
  }

  /// Gravity loading before t = 0 (unsatmpm::load_gravity, cycles/explicit_solver.hpp) with the
  /// pore pressures held; the porosity follows the volume change. A rigid skeleton has nothing to
  /// load.
  GravityLoadingReport load_gravity() {
    if (rigid_) return {};
    const auto r = load_gravity_with_fluids<D, K>(case_, grid_, models_, hydraulics_, gravity_,
                                                  mass_floor_, mech_nodes_, points_, fluids_);
    initial_speed_ = mechanics_speed_ = solid_wave_speed(models_, points_);
    return r;
  }

  /// Free-surface nodes held at zero suction by the rainfall condition (ponded or seeping) in the
  /// current interval; 0 without rain.
  std::int64_t rain_held_nodes() const { return prescription_.held_nodes(); }

  /// Liquid mass rate entering at each node at the end of the last interval, with rain on the
  /// free surface [kg/s per unit out-of-plane measure]; empty without rain.
  const std::vector<double>& surface_liquid_inflow() const { return prescription_.liquid_inflow(); }

  numerics::FluidBalance balance() const {
    const auto m = fluid_masses(points_.points, fluids_);
    return {m[0], m[1], inflow_done_[0] + inflow_now_[0], inflow_done_[1] + inflow_now_[1],
            m[2], m[3]};
  }

  /// CVODE's counters, the coupling intervals and mechanics sub-steps, and where the time went.
  std::string statistics_json() const {
    return flow_statistics_json(cvode_.statistics(), counters_, system_.n_pressure_unknowns(),
                                system_.pattern().n_nonzeros());
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  const numerics::FluidPoints<D>& fluids() const { return fluids_; }
  numerics::FluidPoints<D>& fluids() { return fluids_; }
  /// Nodal pressures of the last update [Pa], per fluid (active nodes).
  const std::array<std::vector<double>, 2>& nodal_pressures() const { return nodal_; }
  bool has_plastic_model() const { return any_plastic(models_); }

 private:
  // The interval's steps, in the order step() runs them.

  /// Sets up the flow at the points' current configuration for [t, t + dt] and starts CVODE at
  /// t: the surface's modes, the fixed-stress storage, the system's stencils and unknowns, the
  /// rain's supply and ponding roots, the start values.
  void start_flow(double t, double dt) {
    if (!rigid_) set_fixed_stress_storage();
    prescription_.update_surface_modes(nodal_);
    system_.prepare(points_.points, fluids_, points_.ranges);
    prescription_.supply_rain(t, t + dt, points_.points, cvode_);
    std::vector<double> y0(system_.n_unknowns());
    system_.start(t, fluids_, y0, nodal_,
                  started_ ? numerics::PressureSystem<D, K>::Prescribed::continuing
                           : numerics::PressureSystem<D, K>::Prescribed::switch_on);
    cvode_.reset(system_.pattern(), t, y0);
    for (int a = 0; a < 2; ++a) inflow_done_[a] += inflow_now_[a] + system_.start_inflow()[a];
    inflow_now_ = {0.0, 0.0};
    started_ = true;
  }

  /// The fixed-stress split's storage term, handed to the flow (cycles/fixed_stress.hpp).
  void set_fixed_stress_storage() {
    system_.set_extra_storage(fixed_stress_storage<D>(models_, points_, fluids_));
  }

  /// Integrates the flow to t_end and moves the points' pressures there. Under rain, a node that
  /// ponds on the way (a root) stops the integration: the points are moved to that time, the node
  /// is held at zero suction, and the flow restarts.
  void flow_to(double t_end) {
    double t = integrate(t_end), last_root = -1.0;
    while (t < t_end) {
      const auto found = cvode_.roots_found();
      if (found.empty() || !(t > last_root))  // would restart at the same place for ever
        throw BlowUpError(fmt::format(
            "the flow stopped at t = {:.9g} s, before the interval's end ({:.9g} s), with no "
            "newly ponded node to switch",
            t, t_end));
      last_root = t;
      update_points(t);
      prescription_.hold_ponded(found);
      start_flow(t, t_end - t);
      t = integrate(t_end);
    }
    update_points(t_end);
  }

  /// CVODE to t_end, or to a root before it; returns the time reached.
  double integrate(double t_end) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto elapsed = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    double reached = t_end;
    try {
      reached = cvode_.integrate_to(t_end);
    } catch (const numerics::CvodeError& e) {
      counters_.flow_seconds += elapsed();
      std::string culprit = describe_unknown(system_, grid_, e.worst_component());
      if (culprit.empty()) {
        // No error estimate yet: name the unknown that changes fastest at the last state.
        const auto& tol = case_.solver.implicit;
        const auto k = fastest_unknown(system_, e.time(), cvode_.state(), tol.relative_tolerance,
                                       tol.absolute_tolerance);
        culprit = k >= 0 ? describe_unknown(system_, grid_, k) +
                               " (no error estimate yet: the unknown changing fastest)"
                         : ", no worst unknown (no error estimate yet, and the rates at the "
                           "last state are not finite)";
      }
      throw BlowUpError(fmt::format("CVODE failed ({}) at t = {:.9g} s{}: {}", e.flag_name(),
                                    e.time(), culprit, e.what()));
    }
    counters_.flow_seconds += elapsed();
    return reached;
  }

  /// Points' pressures from the nodal increments since the last update, then their state.
  void update_points(double t) {
    std::array<std::vector<double>, 2> now;
    system_.nodal_pressures(t, cvode_.state(), now);
    system_.add_increments(nodal_, now, fluids_);
    nodal_ = std::move(now);
    prescription_.record_inflow(t, cvode_.state());
    for (int a = 0; a < 2; ++a)
      inflow_now_[a] = cvode_.state()[system_.inflow_unknown(a)] * system_.inflow_scale(a);
    if (const auto p = update_fluid_state<D>(hydraulics_, points_.ranges, fluids_); p >= 0)
      throw BlowUpError(describe_failed_point<D>(grid_, points_.points, p));
  }

  /// Explicit mechanics of the mixture over [t, t + dt] under the points' current pore pressures
  /// and the surface loads; updates the porosity (solid volume kept).
  void mechanics(double t, double dt) {
    const std::vector<double> v0 = points_.points.volume;
    // The strength follows the suction at the start of the interval (held over its sub-steps).
    const HeldPoreLoads held =
        held_pore_loads<D>(points_.points, fluids_, hydraulics_, points_.ranges);
    const numerics::PoreLoads loads = held.view();
    const MechanicsSettings settings{case_.solver.damping, case_.solver.flip_fraction};
    double done = 0.0;
    while (done < dt * (1.0 - 1e-12)) {
      const double h = std::min(mechanics_step(), dt - done);
      if (!tractions_.empty()) tractions_.forces(t + done + h, surface_loads_);
      mechanics_speed_ =
          explicit_mechanics_step<D, K>(grid_, models_, settings, gravity_, mass_floor_, h, loads,
                                        surface_loads_, mech_nodes_, points_);
      require_loaded_nodes_reached<D>(
          tractions_, grid_, [&](std::int64_t i) { return mech_nodes_.mass(i); }, mass_floor_,
          t + done + h);
      done += h;
      ++counters_.mechanics_substeps;
      if (mechanics_speed_ > wave_speed_blowup_factor * initial_speed_)
        throw BlowUpError(describe_fastest_point<D>(models_, points_, fluids_, initial_speed_));
    }
    update_porosity<D>(v0, points_.points, fluids_);
  }

  // Step sizes.

  /// Rigid skeleton: the points' update interval (the history interval, else a fixed fraction
  /// of the run). Deformable: the case's interval, else a fixed number of mechanics steps.
  double coupling_interval() const {
    if (case_.solver.implicit.coupling_interval) return *case_.solver.implicit.coupling_interval;
    if (rigid_)
      return case_.output.history_interval > 0.0 ? case_.output.history_interval
                                                 : case_.solver.end_time / rigid_intervals_per_run;
    return mechanics_steps_per_interval * mechanics_step();
  }

  double mechanics_step() const {
    return explicit_time_step(case_.solver.time_step, grid_.min_spacing(), mechanics_speed_);
  }

  static numerics::Vec<D> gravity_vector(const Case& c) {
    numerics::Vec<D> g;
    for (int d = 0; d < D; ++d) g[d] = c.gravity[d];
    return g;
  }

  template <class F>
  static int timed(double& seconds, F&& f) {
    const auto t0 = std::chrono::steady_clock::now();
    const int r = f();
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return r;
  }

  const Case& case_;
  numerics::Grid<D> grid_;
  PointSet<D> points_;
  std::vector<physics::HydraulicModel> hydraulics_;
  numerics::FluidPoints<D> fluids_;
  numerics::Vec<D> gravity_;
  numerics::PressureSystem<D, K> system_;
  FlowPrescription<D, K> prescription_;  // refers to system_
  numerics::CvodeIntegrator cvode_;
  numerics::NodalState<D> mech_nodes_;
  std::vector<SolidModel> models_ = solid_models(case_);
  BoundaryTractions<D> tractions_{case_, grid_, points_.points};  // surface loads
  std::vector<numerics::NodalForce<D>> surface_loads_;            // those of the current sub-step
  std::array<std::vector<double>, 2> nodal_;  // nodal pressures at the last update [Pa]
  std::array<double, 2> inflow_done_{0.0, 0.0}, inflow_now_{0.0, 0.0};  // [kg]
  bool rigid_, started_ = false;
  double interval_ = 0.0, mass_floor_ = 0.0, mechanics_speed_ = 1.0, initial_speed_ = 1.0;
  FlowCounters counters_;
};

}  // namespace unsatmpm
