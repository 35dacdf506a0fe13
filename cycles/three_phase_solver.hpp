// The paper's explicit dynamic three-phase cycle (docs/cycles.md).
//
// One step: boundary tractions of the prescribed fluid pressures at the step's end time ->
// p2g_three_phase, and the surface loads (cycles/tractions.hpp) on the mixture -> the
// conductivities at the prescribed pressures (numerics/face_conductivity.hpp) ->
// solve_grid_three_phase (implicit drag, damping, boundary conditions, Euler-Cromer) ->
// g2p_three_phase (velocities, positions, net stress, mass balances, porosity) -> the rain on
// the free surface's flux nodes into the top rows' liquid balances (cycles/explicit_rain.hpp)
// -> point_ or nodal_pressure_increments (the mass balances at the points or at the nodes, as the
// case says; P_g held where there is no gas phase) -> relax_pressure_offsets (each fluid's
// offsets between the points of a cell, numerics/pressure_offsets.hpp) -> apply_pressure_increments
// (porosity, pressures, saturation, densities) -> boundary inflow of each fluid (and the gas
// supplied where P_g is held) for the conservation report. The stable step is h_min / max(c + |v|)
// over the solid's and the fluids' wave speeds.
#pragma once

#include <optional>
#include <variant>

#include "cycles/explicit_rain.hpp"
#include "cycles/explicit_solver.hpp"
#include "cycles/three_phase_setup.hpp"
#include "numerics/face_conductivity.hpp"
#include "numerics/pressure/free_surface.hpp"
#include "numerics/pressure_offsets.hpp"
#include "numerics/three_phase_pressures.hpp"

namespace unsatmpm {

template <int D, class K>
class ThreePhaseSolver {
 public:
  ThreePhaseSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : case_(c),
        grid_(std::move(grid)),
        points_(std::move(points)),
        hydraulics_(hydraulic_models(c)),
        fluids_(initial_fluid_state<D>(c, points_, hydraulics_)),
        form_(c.mass_balance),
        skeleton_(c.skeleton) {
    gravity_ = gravity_vector<D>(c);
    nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, nodes_.solid_fixed);
    nodes_.plates = make_rigid_plates<D>(c, grid_);
    boundaries_ = hydraulic_boundaries<D>(c, grid_, nodes_);
    for (auto [faces, on] :
         {std::pair{&boundaries_.liquid, &liquid_face_}, std::pair{&boundaries_.gas, &gas_face_}}) {
      on->assign(grid_.n_nodes(), 0);
      for (const PressureFace& f : *faces)
        for (const auto i : f.nodes) (*on)[i] = 1;
    }
    nodes_.liquid_prescribed = liquid_face_, nodes_.gas_prescribed = gas_face_;
    if (c.free_surface && c.free_surface->rainfall) rain_.emplace(c, grid_);
    refresh_laws();
    mass_floor_ = mass_floor(points_.points);
    initial_speed_ = max_wave_speed_ = initial_wave_speed();
  }

  /// The CFL limit h_min / max_p (c + |v|) over the solid's and the fluids' wave speeds [s].
  double critical_time_step() const { return grid_.min_spacing() / max_wave_speed_; }
  /// The largest c + |v| of the last step [m/s] (explicit_time_step).
  double max_wave_speed() const { return max_wave_speed_; }

  /// Advances from t to t + dt [s]. Throws BlowUpError naming the point.
  void step(double t, double dt) {
    physics::with_mass_balance(form_, [&](auto form) {
      physics::with_skeleton(skeleton_, [&](auto skeleton) {
        step_with<decltype(form)::value, decltype(skeleton)::value>(t, dt);
      });
    });
  }

  /// The points' state projected to the grid without a step (the output at t = 0): each phase's
  /// nodal velocity (momentum / mass) and the fluids' theta, where the grid is otherwise empty
  /// until the first step.
  void project_to_grid() {
    using L = numerics::ThreePhaseLayout<D>;
    numerics::p2g_three_phase<D, K>(grid_, points_.points, fluids_, gravity_, nodes_);
    for (std::int64_t i = 0; i < nodes_.n_nodes(); ++i) {
      const double* r = nodes_.record(i);
      if (r[L::solid_mass] <= mass_floor_) continue;
      for (int d = 0; d < D; ++d) {
        nodes_.solid_velocity[i][d] = r[L::solid_momentum + d] / r[L::solid_mass];
        if (r[L::liquid_mass] > 0.0)
          nodes_.liquid_velocity[i][d] = r[L::liquid_momentum + d] / r[L::liquid_mass];
        if (r[L::gas_mass] > 0.0)
          nodes_.gas_velocity[i][d] = r[L::gas_momentum + d] / r[L::gas_mass];
      }
      nodes_.liquid_theta[i] = r[L::liquid_theta] / r[L::volume];
      nodes_.gas_theta[i] = r[L::gas_theta] / r[L::volume];
    }
  }

  /// Gravity loading before t = 0 (unsatmpm::load_gravity, cycles/explicit_solver.hpp): mixture
  /// mechanics with the fluids held (their pressures, and velocities equal to the solid's, which
  /// are zero at the end); the porosity follows the volume change.
  GravityLoadingReport load_gravity() {
    numerics::NodalState<D> nodes;
    nodes.resize(grid_.n_nodes(), static_cast<int>(nodes_.scatter.size()));
    mark_boundaries<D>(case_, grid_, nodes.fixed);
    nodes.plates = make_rigid_plates<D>(case_, grid_);
    const auto r = load_gravity_with_fluids<D, K>(case_, grid_, models_, hydraulics_, gravity_,
                                                  mass_floor_, nodes, points_, fluids_);
    refresh_laws();  // the porosity followed the volume change
    initial_speed_ = max_wave_speed_ = initial_wave_speed();
    return r;
  }

  numerics::FluidBalance balance() const {
    const auto m = fluid_masses(points_.points, fluids_);
    return {m[0], m[1], liquid_inflow_, gas_inflow_, m[2], m[3]};
  }

  /// The state a checkpoint keeps: the points, their fluids, the wave speed that sets the next
  /// step and the inflows so far.
  void save(CheckpointWriter& w) const {
    save_points<D>(w, "points.", points_.points);
    save_fluids<D>(w, "fluids.", fluids_);
    w.value("wave_speed", max_wave_speed_);
    w.value("initial_wave_speed", initial_speed_);
    w.value("liquid_inflow", liquid_inflow_);
    w.value("gas_inflow", gas_inflow_);
    if (rain_) rain_->save(w);
  }
  void restore(CheckpointReader& r) {
    restore_points<D>(r, "points.", points_.points);
    restore_fluids<D>(r, "fluids.", fluids_, points_.points.size());
    max_wave_speed_ = r.value<double>("wave_speed");
    initial_speed_ = r.value<double>("initial_wave_speed");
    liquid_inflow_ = r.value<double>("liquid_inflow");
    gas_inflow_ = r.value<double>("gas_inflow");
    if (rain_) rain_->restore(r);
    refresh_laws();
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  const numerics::FluidPoints<D>& fluids() const { return fluids_; }
  /// Mutable access for setting up initial states that a case cannot express yet; the laws at
  /// the state are evaluated again at the next step.
  numerics::FluidPoints<D>& mutable_fluids() {
    laws_current_ = false;
    return fluids_;
  }
  const numerics::ThreePhaseNodes<D>& nodes() const { return nodes_; }
  bool has_plastic_model() const { return any_plastic(models_); }
  /// Free-surface nodes held at zero suction under rain in the last step (0 without rain).
  std::int64_t rain_held_nodes() const { return rain_ ? rain_->held_nodes() : 0; }

 private:
  /// One step with the case's mass-balance form and skeleton as compile-time choices.
  template <physics::MassBalance Form, physics::Skeleton S>
  void step_with(double t, double dt) {
    auto& mp = points_.points;
    if (!laws_current_) refresh_laws();
    set_tractions(t + dt);
    numerics::p2g_three_phase<D, K>(grid_, mp, fluids_, gravity_, nodes_);
    mark_free_surface(t, t + dt);
    add_surface_loads(t + dt);
    if (any_prescribed_) {
      numerics::mark_near_prescribed<D>(grid_, nodes_, near_prescribed_);
      for (std::size_t m = 0; m < models_.size(); ++m)
        numerics::add_face_conductivities<D, K>(grid_, mp, fluids_, hydraulics_[m],
                                                points_.ranges[m], points_.ranges[m + 1],
                                                near_prescribed_, nodes_);
    }
    numerics::solve_grid_three_phase<D, S>(dt, case_.solver.damping, mass_floor_, nodes_);
    for (std::size_t m = 0; m < models_.size(); ++m)
      std::visit(
          [&](const auto& model) {
            numerics::g2p_three_phase<D, K, Form>(grid_, nodes_, model, hydraulics_[m], dt,
                                                  case_.solver.flip_fraction, points_.ranges[m],
                                                  points_.ranges[m + 1], mp, fluids_);
          },
          models_[m]);
    const double rain = rain_ ? rain_->add_to_rates(t, t + dt, mp, free_surface_, fluids_) : 0.0;
    // Gas supplied where the soil holds no gas phase (docs/balance_laws.md, "Saturated soil").
    const double gas_supplied =
        case_.pressure_update == PressureUpdate::nodal
            ? numerics::nodal_pressure_increments<D, K>(grid_, mp, dt, nodes_, fluids_)
            : numerics::point_pressure_increments<D>(dt, 0, static_cast<std::int64_t>(mp.size()),
                                                     mp, fluids_);
    numerics::relax_pressure_offsets<D, K>(grid_, mp, dt, nodes_.pressure_offsets, fluids_);
    double speed = 0.0, gas_held = 0.0;
    std::int64_t bad = -1;
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const double modulus =
          std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models_[m]);
      const auto rep = numerics::apply_pressure_increments<D, S>(
          grid_, hydraulics_[m], modulus, points_.ranges[m], points_.ranges[m + 1], mp, fluids_,
          static_cast<int>(nodes_.scatter.size()));
      speed = std::max(speed, rep.max_wave_speed), gas_held += rep.gas_supplied;
      if (rep.first_bad >= 0 && bad < 0) bad = rep.first_bad;
    }
    laws_current_ = true;  // apply_pressure_increments left them at the new state
    if (bad >= 0) throw BlowUpError(describe_point(bad));
    max_wave_speed_ = speed;
    if (speed > wave_speed_blowup_factor * initial_speed_) throw BlowUpError(describe_collapse());
    liquid_inflow_ +=
        dt * (rain + numerics::prescribed_inflow(nodes_, nodes_.liquid_prescribed,
                                                 nodes_.liquid_velocity, nodes_.liquid_theta,
                                                 mass_floor_, rain_ ? &rain_->inflow() : nullptr));
    gas_inflow_ +=
        dt * numerics::prescribed_inflow(nodes_, nodes_.gas_prescribed, nodes_.gas_velocity,
                                         nodes_.gas_theta, mass_floor_, nullptr) +
        gas_supplied + gas_held;
  }

  /// The free-surface nodes of the step over [t0, t] (numerics/pressure/free_surface.hpp: the
  /// nodes holding material of a cell with an empty corner), for each fluid that no face
  /// prescribes there: closed, the fluid moves with the solid (no flux out of the body), or, where
  /// the case gives the fluid a `free_surface` condition, open at the pressure P̄ of time t: the
  /// nodal force takes the boundary term -P̄ A_i (A_i = sum_p V_p grad N_i, the body's outward
  /// area there) and the flux divergence is left uncorrected, as on a face (docs/balance_laws.md,
  /// "The body's free surface"). Under rain (cycles/explicit_rain.hpp) the liquid is open at
  /// P̄ = P_g at the held nodes and closed at the flux nodes.
  void mark_free_surface(double t0, double t) {
    using L = numerics::ThreePhaseLayout<D>;
    const auto active = [&](std::int64_t i) { return nodes_.solid_mass(i) > mass_floor_; };
    const auto occupied = numerics::occupied_cells<D>(grid_, points_.points);
    free_surface_ = numerics::free_surface_nodes<D>(grid_, occupied, active);
    // The layer inside too, open or closed (numerics/pressure/free_surface.hpp): the node
    // on a node line just inside the face carries most of the surface's area, and closed there
    // (its flux divergence corrected to no flow through the surface) it let water in through the
    // light node beyond and not out (verification/embankment/investigations.md, "Why only the
    // explicit cycle loosens surface points").
    const auto& surface = free_surface_;
    const auto& fs = case_.free_surface;
    const bool open_l = fs && (fs->liquid || fs->rainfall), open_g = fs && fs->gas_pressure;
    const double full = grid_.spacing.prod();
    const auto near = numerics::free_surface_nodes<D>(grid_, occupied, active, [&](std::int64_t i) {
      return nodes_.record(i)[L::volume] >= numerics::inside_fraction * full;
    });
    const double p_g = open_g ? (*fs->gas_pressure)(t) : 0.0;
    const double p_l = fs && fs->liquid
                           ? prescribed_liquid_pressure(*fs->liquid, fs->gas_pressure, t)
                           : p_g;  // rain: held at zero suction
    const std::vector<std::uint8_t>* flux =
        rain_ ? &rain_->modes(t0, t, points_.points, fluids_, surface) : nullptr;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      const bool on_l = surface[i] && !liquid_face_[i];
      const bool open_li = open_l && !(flux && (*flux)[i]);
      // A fluid that no condition lets out is held to the solid on both layers: closed at the
      // outermost alone, a face half a cell past a node line left the node on the line, which
      // carries most of the face's area, free, and the pressure's boundary term there drove a
      // column at rest (docs/balance_laws.md, "The body's free surface").
      nodes_.liquid_surface[i] = open_l ? on_l && !open_li : near[i] && !liquid_face_[i];
      nodes_.gas_surface[i] = !open_g && near[i] && !gas_face_[i];
      if (!fs) continue;
      // Open where a pressure acts; rain decides its modes on the outermost layer
      // (cycles/explicit_rain.hpp).
      const bool at_l = open_li && (flux ? surface[i] : near[i]) && !liquid_face_[i];
      const bool at_g = open_g && near[i] && !gas_face_[i];
      nodes_.liquid_prescribed[i] = liquid_face_[i] || at_l;
      nodes_.gas_prescribed[i] = gas_face_[i] || at_g;
      if (at_l) nodes_.liquid_face_pressure[i] = p_l;
      if (at_g) nodes_.gas_face_pressure[i] = p_g;
      const double* r = nodes_.record(i);
      for (int d = 0; d < D; ++d) {
        if (!liquid_face_[i]) nodes_.liquid_traction[i][d] = at_l ? -p_l * r[L::area + d] : 0.0;
        if (!gas_face_[i]) nodes_.gas_traction[i][d] = at_g ? -p_g * r[L::area + d] : 0.0;
      }
    }
    const auto any = [](const std::vector<std::uint8_t>& v) {
      return std::any_of(v.begin(), v.end(), [](std::uint8_t x) { return x != 0; });
    };
    any_prescribed_ = any(nodes_.liquid_prescribed) || any(nodes_.gas_prescribed);
  }

  /// The collapse message naming the point of the largest c_p + |v_p| (its mixture wave speed
  /// and solid velocity).
  std::string describe_collapse() const {
    std::int64_t fastest = 0;
    double top = -1.0;
    for_each_wave_speed([&](std::int64_t p, double c2, double v2) {
      if (std::sqrt(c2) + std::sqrt(v2) > top) fastest = p, top = std::sqrt(c2) + std::sqrt(v2);
    });
    return describe_step_collapse<D>(points_.points, fastest, max_wave_speed_, initial_speed_) +
           fmt::format(" (P_l = {:.6g} Pa, P_g = {:.6g} Pa, porosity {:.4g})",
                       fluids_.liquid_pressure[fastest], fluids_.gas_pressure[fastest],
                       fluids_.porosity[fastest]);
  }

  /// f(p, c_p^2, |v_p|^2) for every point, c_p its mixture wave speed.
  template <class F>
  void for_each_wave_speed(F&& f) const {
    physics::with_skeleton(skeleton_, [&](auto skeleton) {
      const auto& mp = points_.points;
      for (std::size_t m = 0; m < models_.size(); ++m) {
        const double modulus =
            std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models_[m]);
        for (auto p = points_.ranges[m]; p < points_.ranges[m + 1]; ++p)
          f(p,
            numerics::wave_speed_squared<decltype(skeleton)::value>(
                hydraulics_[m], modulus, fluids_.porosity[p], fluids_.liquid_pressure[p],
                fluids_.gas_pressure[p], fluids_.saturation[p], fluids_.liquid_density[p],
                fluids_.gas_density[p], mp.volume[p] / mp.mass[p], grid_.min_spacing()),
            mp.velocity[p].squaredNorm());
      }
      return 0;
    });
  }

  /// Each point's state and laws at its porosity and pressures (numerics::refresh_point_laws).
  void refresh_laws() {
    for (std::size_t m = 0; m < hydraulics_.size(); ++m)
      numerics::refresh_point_laws<D>(hydraulics_[m], points_.ranges[m], points_.ranges[m + 1],
                                      fluids_);
    laws_current_ = true;
  }

  double initial_wave_speed() const {
    double c2 = 0.0, v2 = 0.0;
    for_each_wave_speed(
        [&](std::int64_t, double c, double v) { c2 = std::max(c2, c), v2 = std::max(v2, v); });
    return std::sqrt(c2) + std::sqrt(v2);
  }
  void set_tractions(double t) {
    for (const PressureFace& f : boundaries_.liquid) {
      const double p = prescribed_liquid_pressure(*f.spec, t);
      for (std::size_t k = 0; k < f.nodes.size(); ++k) {
        nodes_.liquid_traction[f.nodes[k]][f.axis] = -p * f.outward * f.area[k];
        nodes_.liquid_face_pressure[f.nodes[k]] = p;
      }
    }
    for (const PressureFace& f : boundaries_.gas) {
      const double p = (*f.spec->gas_pressure)(t);
      for (std::size_t k = 0; k < f.nodes.size(); ++k) {
        nodes_.gas_traction[f.nodes[k]][f.axis] = -p * f.outward * f.area[k];
        nodes_.gas_face_pressure[f.nodes[k]] = p;
      }
    }
  }

  /// The boundary tractions of time t added to the mixture's nodal forces (cycles/tractions.hpp).
  void add_surface_loads(double t) {
    if (surface_.empty()) return;
    using L = numerics::ThreePhaseLayout<D>;
    surface_.forces(t, points_.points, loads_);
    for (const auto& f : loads_)
      for (int d = 0; d < D; ++d)
        nodes_.scatter[0][f.node * L::record + L::mixture_force + d] += f.force[d];
    require_loaded_nodes_reached<D>(
        surface_, grid_, [&](std::int64_t i) { return nodes_.solid_mass(i); }, mass_floor_, t);
  }

  std::string describe_point(std::int64_t p) const {
    const auto& mp = points_.points;
    const double pl = fluids_.liquid_pressure[p], pg = fluids_.gas_pressure[p];
    const std::string state = fmt::format("P_l = {:.6g} Pa, P_g = {:.6g} Pa, porosity {:.6g}", pl,
                                          pg, fluids_.porosity[p]);
    const double motion = mp.velocity[p].squaredNorm() + fluids_.liquid_velocity[p].squaredNorm() +
                          fluids_.gas_velocity[p].squaredNorm();
    if (grid_.contains(mp.position[p]) && std::isfinite(pl + pg + mp.stress[p].sum() + motion))
      return point_location<D>(mp, p) +
             " holds fluid masses that no pressures hold (the inversion's last iterate: " + state +
             ")" + vacuum_hint(pg);
    return describe_failed_point<D>(grid_, mp, p) + " after the pressure update (" + state + ")";
  }

  /// What usually leads a point's gas to an absolute vacuum: water drawn out of a nearly
  /// saturated soil, whose gas cannot follow (docs/balance_laws.md, "A prescribed face on cells
  /// coarser than its front").
  static std::string vacuum_hint(double gas_pressure) {
    if (gas_pressure > 100.0 - physics::IdealGas::atmospheric_pressure) return "";
    return "; its gas has expanded to a vacuum: the liquid left faster than gas came in, as "
           "where a drying face or drainage draws water out of a nearly saturated soil whose gas "
           "relative permeability is near zero";
  }

  const Case& case_;
  numerics::Grid<D> grid_;
  PointSet<D> points_;
  std::vector<physics::HydraulicModel> hydraulics_;
  numerics::FluidPoints<D> fluids_;
  numerics::ThreePhaseNodes<D> nodes_;
  HydraulicBoundaries boundaries_;
  std::vector<std::uint8_t> liquid_face_, gas_face_;  // 1: on a face prescribing the fluid
  std::vector<std::uint8_t> free_surface_;            // 1: on the body's surface this step
  std::vector<std::uint8_t> near_prescribed_;         // numerics::mark_near_prescribed, this step
  std::optional<ExplicitRain<D, K>> rain_;            // with rainfall on the free surface
  BoundaryTractions<D> surface_{case_, grid_, points_.points};  // surface loads
  std::vector<numerics::NodalForce<D>> loads_;                  // those of the current step
  std::vector<SolidModel> models_ = solid_models(case_);
  numerics::Vec<D> gravity_;
  numerics::MassBalance form_;
  numerics::Skeleton skeleton_;
  bool laws_current_ = false;    // fluids_' laws columns at its state (refresh_laws)
  bool any_prescribed_ = false;  // a node prescribes a fluid's pressure this step
  double mass_floor_ = 0.0, max_wave_speed_ = 0.0, initial_speed_ = 0.0, liquid_inflow_ = 0.0,
         gas_inflow_ = 0.0;
};

}  // namespace unsatmpm
