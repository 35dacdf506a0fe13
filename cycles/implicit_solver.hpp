// The project's main cycle (docs/cycles.md): explicit MPM mechanics of the mixture, and the liquid
// and gas mass balances in Darcy form as an implicit ODE in the nodal pressures, integrated by
// CVODE (BDF, Newton) with KLU (numerics/pressure/pressure_system.hpp,
// numerics/cvode_integrator.hpp).
//
// One coupling interval [t, t + dt], the two-way coupling of docs/balance_laws.md ("Two-way
// coupling in the main cycle"):
//   1. the flow is integrated once over the interval by CVODE at the configuration at t, with the
//      skeleton's drained compliance in the storage of the pore pressure p* = max(P_l, P_g) (the
//      fixed-stress split, cycles/fixed_stress.hpp); what it moved and how its field changed are
//      measured per point (record_flow);
//   2. the mechanics sub-cycles over the interval with explicit steps (mixture mass, total stress
//      sigma_bar - p* I, surface loads, damping alpha); after each sub-step the pore pressures
//      follow the points' volume change, their share of the flow's mass change and the flow
//      correction's masses (cycles/undrained.hpp): the undrained response, each fluid's mass
//      kept. The correction (cycles/flow_correction.hpp) adds, implicitly, the Darcy flux of
//      where the points' pressures depart from the flow's prediction, which makes the coupling
//      stable for any interval.
// A rigid skeleton has no mechanics: the nodal increments go to the points, and CVODE runs
// through the whole simulation without restart; an interval only sets when the points receive
// their increments (outputs, histories).
//
// Damping alpha acts on the mechanics only: the Darcy form has no fluid inertia to damp.
#pragma once

#include <chrono>
#include <cmath>
#include <string>
#include <variant>

#include "cycles/explicit_solver.hpp"
#include "cycles/fixed_stress.hpp"
#include "cycles/flow_correction.hpp"
#include "cycles/flow_prescription.hpp"
#include "cycles/implicit_checkpoint.hpp"
#include "cycles/implicit_diagnostics.hpp"
#include "cycles/implicit_mechanics.hpp"
#include "cycles/implicit_settings.hpp"
#include "cycles/three_phase_setup.hpp"
#include "cycles/undrained.hpp"
#include "numerics/cvode_integrator.hpp"
#include "numerics/pressure/darcy_flux.hpp"
#include "numerics/pressure/pressure_system.hpp"

namespace unsatmpm {

template <int D, class K>
class ImplicitSolver {
 public:
  ImplicitSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : case_(c),
        grid_(std::move(grid)),
        points_(std::move(points)),
        hydraulics_(hydraulic_models(c)),
        fluids_(initial_fluid_state<D>(c, points_, hydraulics_)),
        mechanics_(c, grid_, points_, n_threads),
        system_(grid_, hydraulics_, c.mass_balance, gravity_vector<D>(c)),
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
    choose_linear_solver(cvode_, c.solver.implicit, D);
    system_.set_jacobian_drop_tolerance(jacobian_drop_tolerance(D));
    system_.set_threads(n_threads);
    system_.set_nodal_permeability(c.solver.implicit.relative_permeability ==
                                   RelativePermeabilityAt::nodes);
    correction_.set_threads(n_threads);
    if (!rigid_) {
      const double speed = undrained_speed();
      mechanics_.set_speeds(speed, speed);
    }
    interval_ = coupling_interval();
  }

  // The pressure system refers to grid_, and CVODE's callbacks to this object: it stays put.
  ImplicitSolver(const ImplicitSolver&) = delete;
  ImplicitSolver& operator=(const ImplicitSolver&) = delete;

  /// The next coupling interval [s]; the run loop clips it to output times.
  double interval() const { return interval_; }
  /// Ends a step once `check` is true: step() throws numerics::StopRequested. The check is polled
  /// at every evaluation of the flow and before every mechanics sub-step; position() says where
  /// the step stands then.
  void set_stop_check(numerics::CvodeIntegrator::StopCheck check) {
    cvode_.set_stop_check(check);
    mechanics_.set_stop_check(std::move(check));
  }
  StepPosition position() const {
    if (mechanics_.running())
      return {"mechanics", mechanics_.position()[0], mechanics_.position()[1]};
    const auto [t, h] = cvode_.position();
    return {"flow", t, h};
  }

  /// Advances from t to t + dt [s]: one coupling interval, the flow first, then the mechanics
  /// (see the header). Throws BlowUpError on a CVODE failure or a non-finite mechanics state,
  /// naming the time, the flag and the node or point.
  void step(double t, double dt) {
    mechanics_.leave();
    if (rigid_) {
      // A rigid skeleton's flow runs on through the intervals unless rain or a resume restarts it.
      if (!started_ || restart_flow_ || prescription_.has_rain()) start_flow(t, dt);
      restart_flow_ = false;
      flow_to(t + dt);
    } else {
      begin_undrained_interval<D>(grid_, points_.points, fluids_, hydraulics_, points_.ranges,
                                  mechanics_.n_threads(), undrained_);
      start_pressures_ = {fluids_.liquid_pressure, fluids_.gas_pressure};
      start_flow(t, dt);
      flow_to(t + dt);
      for (int a = 0; a < 2; ++a) undrained_.held[a] = system_.prescribed(a);
      // The mechanics starts from the interval's start state; the flow's mass changes reach the
      // points over its sub-steps (cycles/undrained.hpp).
      fluids_.liquid_pressure = start_pressures_[0], fluids_.gas_pressure = start_pressures_[1];
      update_fluid_state<D>(hydraulics_, points_.ranges, fluids_);
      const auto& tol = case_.solver.implicit;
      correction_.begin(system_, hydraulics_, fluids_, start_pressures_, undrained_.flow_change, dt,
                        nodal_, tol.relative_tolerance, tol.absolute_tolerance);
      timed(counters_.mechanics_seconds, [&] { mechanics(t, dt); });
    }
    ++counters_.coupling_intervals;
  }

  /// Gravity loading before t = 0 (unsatmpm::load_gravity, cycles/explicit_solver.hpp) with the
  /// pore pressures held; the porosity follows the volume change. A rigid skeleton has nothing to
  /// load.
  GravityLoadingReport load_gravity() {
    if (rigid_) return {};
    const auto r = mechanics_.load_gravity(hydraulics_, fluids_);
    const double speed = undrained_speed();
    mechanics_.set_speeds(speed, speed);
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

  /// CVODE's counters, the coupling intervals and mechanics sub-steps, and where the time went
  /// (over the whole run, a resumed one's earlier parts included).
  std::string statistics_json() const {
    return flow_statistics_json(cvode_statistics(), counters_, system_.n_pressure_unknowns(),
                                system_.pattern().n_nonzeros(), cvode_.iterative());
  }
  const FlowCounters& counters() const { return counters_; }
  numerics::CvodeStatistics cvode_statistics() const {
    return add_counts(earlier_cvode_, cvode_.statistics());
  }
  std::int64_t pressure_unknowns() const { return system_.n_pressure_unknowns(); }
  /// The surface nodes holding the liquid's condition at the last interval, and the light ones
  /// among them (FlowPrescription::held_surface_nodes).
  std::array<std::int64_t, 2> held_surface_nodes() const {
    return prescription_.held_surface_nodes();
  }

  /// The state a checkpoint keeps at the end of an interval: the points and their fluids, the
  /// nodal pressures, the inflows, the step sizes' state, what the flow's next start carries over
  /// (cycles/implicit_checkpoint.hpp) and the counters.
  void save(CheckpointWriter& w) const {
    save_points<D>(w, "points.", points_.points);
    save_fluids<D>(w, "fluids.", fluids_);
    save_flow_carry(w, nodal_, inflow_done_, inflow_now_, system_.carried());
    prescription_.save(w);
    w.value("started", std::uint8_t{started_});
    for (const double x : {interval_, mechanics_.speeds()[0], mechanics_.speeds()[1]})
      w.value("step_state", x);
    save_counters(w, counters_, cvode_statistics());
  }
  /// Reads what save() wrote into a solver of the same case: it goes on exactly as the saved one,
  /// except a rigid skeleton's flow without rain, which restarts CVODE from the saved nodal
  /// pressures (within CVODE's tolerances; docs/output.md, "Checkpoints and resume").
  void restore(CheckpointReader& r) {
    restore_points<D>(r, "points.", points_.points);
    restore_fluids<D>(r, "fluids.", fluids_, points_.points.size());
    system_.restore_carried(
        restore_flow_carry(r, grid_.n_nodes(), nodal_, inflow_done_, inflow_now_));
    prescription_.restore(r);
    started_ = r.value<std::uint8_t>("started") != 0;
    interval_ = r.value<double>("step_state");
    const double speed = r.value<double>("step_state");
    mechanics_.set_speeds(speed, r.value<double>("step_state"));
    restore_counters(r, counters_, earlier_cvode_, cvode_);
    // Rain restarts it at every interval; a flow saved before its start starts afresh.
    restart_flow_ = rigid_ && !prescription_.has_rain() && started_;
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  /// Where each material's points start (ordered by material), as fill_bodies made them.
  const std::vector<std::int64_t>& material_ranges() const { return points_.ranges; }
  const numerics::FluidPoints<D>& fluids() const { return fluids_; }
  numerics::FluidPoints<D>& fluids() { return fluids_; }
  /// Nodal pressures of the last update [Pa], per fluid (active nodes).
  const std::array<std::vector<double>, 2>& nodal_pressures() const { return nodal_; }
  /// Each point's Darcy flux q_a [m/s] per fluid on the nodal pressures of the last update, at
  /// the configuration the flow last started from (numerics/pressure/darcy_flux.hpp).
  void darcy_fluxes(std::array<std::vector<numerics::Vec<D>>, 2>& q) const {
    if (nodal_[0].empty()) {
      for (auto& v : q) v.assign(points_.points.size(), numerics::Vec<D>::Zero());
      return;
    }
    numerics::darcy_fluxes<D, K>(system_.quadrature(), hydraulics_, mechanics_.gravity(), nodal_,
                                 q);
  }
  /// The mechanics' grid of the last sub-step.
  const numerics::NodalState<D>& mechanics_nodes() const { return mechanics_.nodes(); }
  bool has_plastic_model() const { return any_plastic(mechanics_.models()); }

 private:
  // The interval's steps, in the order step() runs them.

  /// Sets up the flow at the points' current configuration for [t, t + dt] and starts CVODE at
  /// t: the surface's modes, the fixed-stress storage, the system's stencils and unknowns, the
  /// rain's supply and ponding roots, the start values.
  void start_flow(double t, double dt) {
    if (!rigid_) {
      set_fixed_stress_storage();
      system_.set_ramp_end(t + dt);  // gas switching on at a moving surface ramps in (jumps.hpp)
    }
    prescription_.update_surface_modes(nodal_, points_.points);
    system_.prepare(points_.points, fluids_, points_.ranges);
    prescription_.supply_rain(t, t + dt, points_.points, cvode_);
    std::vector<double> y0(system_.n_unknowns());
    using System = numerics::PressureSystem<D, K>;
    using From = numerics::StartFrom;
    // A resumed rigid flow starts from the nodal pressures it had (cycles/implicit_checkpoint.hpp);
    // a later start, from those the flow reached and what the points depart from them.
    const std::array<std::vector<double>, 2> reached = nodal_;
    system_.start(t, fluids_, y0, nodal_,
                  started_ ? System::Prescribed::continuing : System::Prescribed::switch_on,
                  rigid_ ? System::JumpBase::points : System::JumpBase::fitted,
                  restart_flow_ ? From::given : (started_ ? From::reached : From::points),
                  &reached);
    if (!rigid_) system_.at_points(nodal_, fitted_start_);
    cvode_.reset(system_.pattern(), t, y0);
    for (int a = 0; a < 2; ++a) inflow_done_[a] += inflow_now_[a] + system_.start_inflow()[a];
    inflow_now_ = {0.0, 0.0};
    started_ = true;
  }

  /// The fixed-stress split's storage term, handed to the flow (cycles/fixed_stress.hpp) and
  /// kept for the points' share of the mass it moves (record_flow).
  void set_fixed_stress_storage() {
    extra_storage_ = fixed_stress_storage<D>(mechanics_.models(), hydraulics_, points_, fluids_);
    system_.set_extra_storage(extra_storage_);
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

  numerics::CvodeTolerances tolerances() const {
    return {case_.solver.implicit.relative_tolerance, case_.solver.implicit.absolute_tolerance};
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
      throw BlowUpError(describe_flow_failure(system_, grid_, e, cvode_.state(), tolerances()));
    } catch (const numerics::StopRequested& e) {
      counters_.flow_seconds += elapsed();
      throw numerics::StopRequested(
          e.what(), e.worst_component(),
          describe_stop(system_, grid_, e, cvode_.statistics(), cvode_.state(), tolerances()));
    }
    counters_.flow_seconds += elapsed();
    return reached;
  }

  /// Points' pressures from the nodal increments since the last update, then their state; with a
  /// deformable skeleton, the mass each point gained is recorded for the mechanics.
  void update_points(double t) {
    std::array<std::vector<double>, 2> now;
    system_.nodal_pressures(t, cvode_.state(), now);
    if (!rigid_) {
      std::array<std::vector<double>, 2> fitted_end;
      system_.at_points(now, fitted_end);
      record_flow<D>(points_.points, fluids_, hydraulics_, fitted_start_, fitted_end,
                     extra_storage_, undrained_);
      fitted_start_ = std::move(fitted_end);
    }
    system_.add_increments(nodal_, now, fluids_);
    nodal_ = std::move(now);
    prescription_.record_inflow(t, cvode_.state());
    for (int a = 0; a < 2; ++a)
      inflow_now_[a] = cvode_.state()[system_.inflow_unknown(a)] * system_.inflow_scale(a);
    if (const auto p = update_fluid_state<D>(hydraulics_, points_.ranges, fluids_); p >= 0)
      throw BlowUpError(describe_failed_point<D>(grid_, points_.points, p));
  }

  /// Explicit mechanics of the mixture over [t, t + dt] under the surface loads, each sub-step
  /// followed by the points' pore pressures from their fluid masses and pore volumes
  /// (cycles/undrained.hpp).
  void mechanics(double t, double dt) {
    const int n_threads = mechanics_.n_threads();
    mechanics_.sub_cycle(
        t, dt, undrained_.view(), fluids_, counters_.mechanics_substeps,
        [&](double h, double done, double relax) {
          const double speed =
              undrained_rates<D>(points_.points, hydraulics_, mechanics_.moduli(), points_.ranges,
                                 h / dt, n_threads, done > 0.0, fluids_, undrained_);
          std::array<double, 2> corrected{0.0, 0.0};
          const UndrainedReport rep = undrained_apply<D, K>(
              grid_, points_.points, hydraulics_, points_.ranges, h / dt, n_threads, relax, fluids_,
              undrained_,
              correction_.source(grid_, points_.points, fluids_, done, h, correction_mass_,
                                 corrected, counters_.correction_seconds));
          for (int a = 0; a < 2; ++a) inflow_done_[a] += rep.supplied[a] + corrected[a];
          if (rep.first_bad >= 0)
            throw BlowUpError(describe_failed_pressures<D>(grid_, points_.points, fluids_,
                                                           rep.first_bad, t + done + h));
          counters_.add_correction(correction_.take_counts());
          return speed;
        });
  }

  /// The mixture's wave speed with the fluids' undrained stiffness (cycles/undrained.hpp).
  double undrained_speed() const {
    return undrained_wave_speed<D>(points_.points, fluids_, hydraulics_, mechanics_.moduli(),
                                   points_.ranges);
  }

  // Step sizes.

  /// Rigid skeleton: the points' update interval (the history interval, else a fixed fraction
  /// of the run). Deformable: the case's interval, else a fixed number of mechanics steps.
  double coupling_interval() const {
    if (case_.solver.implicit.coupling_interval) return *case_.solver.implicit.coupling_interval;
    if (rigid_)
      return case_.output.history_interval > 0.0 ? case_.output.history_interval
                                                 : case_.solver.end_time / rigid_intervals_per_run;
    return mechanics_steps_per_interval *
           explicit_time_step(case_.solver.time_step, grid_.min_spacing(),
                              solid_wave_speed(mechanics_.models(), points_));
  }

  const Case& case_;
  numerics::Grid<D> grid_;
  PointSet<D> points_;
  std::vector<physics::HydraulicModel> hydraulics_;
  numerics::FluidPoints<D> fluids_;
  ImplicitMechanics<D, K> mechanics_;  // refers to grid_ and points_
  numerics::PressureSystem<D, K> system_;
  FlowPrescription<D, K> prescription_;  // refers to system_
  numerics::CvodeIntegrator cvode_;
  UndrainedPoints undrained_;                           // the coupling's per-point state
  FlowCorrection<D, K> correction_;                     // and the flow's correction
  std::array<std::vector<double>, 2> correction_mass_;  // per node, of the current sub-step
  std::vector<physics::StorageMatrix> extra_storage_;   // the interval's fixed-stress storage
  std::array<std::vector<double>, 2> start_pressures_;
  std::array<std::vector<double>, 2> fitted_start_;
  std::array<std::vector<double>, 2> nodal_;  // nodal pressures at the last update [Pa]
  std::array<double, 2> inflow_done_{0.0, 0.0}, inflow_now_{0.0, 0.0};  // [kg]
  bool rigid_, started_ = false, restart_flow_ = false;  // restart: after a resume (rigid)
  numerics::CvodeStatistics earlier_cvode_;              // CVODE's counts before a resume
  double interval_ = 0.0;
  FlowCounters counters_;
};

}  // namespace unsatmpm
