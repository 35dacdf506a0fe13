// The explicit dynamic MPM cycle for one solid phase (docs/cycles.md).
//
// One step, in the paper's order: p2g (mass, momentum, forces) -> solve_grid (damped accelerations,
// boundary conditions, Euler-Cromer velocities) -> g2p (velocities, positions, strain, volume and
// stress: update stress last). The stable step is dt <= h_min / max_p (c_p + |v_p|) with the
// P-wave speed c_p = sqrt(M / rho_p); the caller applies the safety factor.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <fmt/core.h>

#include "checkpoint/point_state.hpp"
#include "cycles/setup.hpp"
#include "cycles/tractions.hpp"
#include "input/case.hpp"
#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/velocity_remap.hpp"

namespace unsatmpm {

/// Thrown when a step produces a non-finite state or a point leaves the grid.
class BlowUpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The explicit mechanics step [s], one formula for every cycle and for gravity loading: the
/// case's fixed step, or cfl_safety h_min / max_p (c_p + |v_p|) with `max_speed` the largest
/// c_p + |v_p| [m/s] (docs/conventions.md).
inline double explicit_time_step(const TimeStepSpec& spec, double min_spacing, double max_speed) {
  return spec.fixed ? *spec.fixed : spec.cfl_safety * min_spacing / max_speed;
}

using physics::SolidModel;

inline std::vector<SolidModel> solid_models(const Case& c) {
  std::vector<SolidModel> models;
  for (const auto& m : c.materials) models.push_back(m.model);
  return models;
}

inline bool any_plastic(const std::vector<SolidModel>& models) {
  for (const auto& m : models)
    if (!std::holds_alternative<physics::LinearElastic>(m)) return true;
  return false;
}

/// "material point ID at (x, y) m".
template <int D>
std::string point_location(const numerics::MaterialPoints<D>& mp, std::int64_t p) {
  std::string where;
  for (int d = 0; d < D; ++d) where += (d ? ", " : "") + std::to_string(mp.position[p][d]);
  return "material point " + std::to_string(mp.id[p]) + " at (" + where + ") m";
}

/// "material point ID at (x, y) m left the grid" or "... has a non-finite state".
template <int D>
std::string describe_failed_point(const numerics::Grid<D>& grid,
                                  const numerics::MaterialPoints<D>& mp, std::int64_t p) {
  return point_location<D>(mp, p) +
         (grid.contains(mp.position[p]) ? " has a non-finite state" : " left the grid");
}

/// A wave speed c + |v| above this many times its initial value ends the run as a blow-up
/// (BlowUpError): the explicit step has collapsed by the same factor, and a run crawling on at
/// steps of 1e-30 s is a hang, not a simulation.
inline constexpr double wave_speed_blowup_factor = 1e3;

/// "the explicit step collapsed: ..." naming point p, the fastest, with its speed [m/s] against
/// the initial largest one.
template <int D>
std::string describe_step_collapse(const numerics::MaterialPoints<D>& mp, std::int64_t p,
                                   double speed, double initial_speed) {
  std::string at;
  for (int d = 0; d < D; ++d) at += fmt::format("{}{:.6g}", d ? ", " : "", mp.position[p][d]);
  return fmt::format(
      "the explicit step collapsed: c + |v| = {:.4g} m/s exceeds {:g} times its initial {:.4g} "
      "m/s at material point {} at ({}) m (velocity {:.4g} m/s)",
      speed, wave_speed_blowup_factor, initial_speed, mp.id[p], at, mp.velocity[p].norm());
}

/// Nodes lighter than this [kg] count as empty: 1e-9 of the lightest point.
template <int D>
double mass_floor(const numerics::MaterialPoints<D>& mp) {
  double min_mass = mp.mass[0];
  for (const double m : mp.mass) min_mass = std::min(min_mass, m);
  return 1e-9 * min_mass;
}

/// The point of the largest c_p + |v_p| with the solid's P-wave speed c_p = sqrt(M V / m), and
/// that speed [m/s].
template <int D>
std::pair<std::int64_t, double> fastest_solid_point(const std::vector<SolidModel>& models,
                                                    const PointSet<D>& points) {
  const auto& mp = points.points;
  std::pair<std::int64_t, double> fastest{0, 0.0};
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double modulus =
        std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models[m]);
    for (auto p = points.ranges[m]; p < points.ranges[m + 1]; ++p) {
      const double c = std::sqrt(modulus * mp.volume[p] / mp.mass[p]) + mp.velocity[p].norm();
      if (c > fastest.second) fastest = {p, c};
    }
  }
  return fastest;
}

/// Throws BlowUpError naming the fastest point (describe_step_collapse) where a step's largest
/// c + |v|, `speed` [m/s], has grown past wave_speed_blowup_factor times `initial_speed`.
template <int D>
void require_no_step_collapse(const std::vector<SolidModel>& models, const PointSet<D>& points,
                              double speed, double initial_speed) {
  if (!(speed > wave_speed_blowup_factor * initial_speed)) return;
  const auto [p, fastest] = fastest_solid_point<D>(models, points);
  throw BlowUpError(describe_step_collapse<D>(points.points, p, fastest, initial_speed));
}

/// max_p (c_p + |v_p|) with the solid's P-wave speed c_p = sqrt(M V / m) [m/s].
template <int D>
double solid_wave_speed(const std::vector<SolidModel>& models, const PointSet<D>& points) {
  return fastest_solid_point<D>(models, points).second;
}

/// Damping and FLIP blend of an explicit mechanics step (SolverSpec's).
struct MechanicsSettings {
  double damping, flip_fraction;
};

/// One explicit mechanics step of the points (p2g, the external nodal forces `loads` added,
/// solve_grid, g2p per material): the one-phase cycle's step (numerics::NoPoreLoads), and the
/// implicit cycle's mixture step (PoreLoads). Returns the wave speed for the next step [m/s];
/// throws BlowUpError naming the first failed point.
template <int D, class K, class Pore>
double explicit_mechanics_step(const numerics::Grid<D>& grid, const std::vector<SolidModel>& models,
                               MechanicsSettings settings, const numerics::Vec<D>& gravity,
                               double mass_floor, double dt, const Pore& pore,
                               const std::vector<numerics::NodalForce<D>>& loads,
                               numerics::NodalState<D>& nodes, PointSet<D>& points) {
  auto& mp = points.points;
  numerics::p2g<D, K>(grid, mp, gravity, nodes, pore);
  numerics::add_nodal_forces<D>(loads, nodes);
  numerics::solve_grid<D>(dt, settings.damping, mass_floor, nodes);
  if constexpr (numerics::remaps_velocity<K, Pore>)
    numerics::remap_velocities<D, K>(grid, dt, settings.flip_fraction, mp, nodes);
  double speed = 0.0;
  std::int64_t bad = -1;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const auto rep = std::visit(
        [&](const auto& model) {
          return numerics::g2p<D, K>(grid, nodes, model, dt, settings.flip_fraction,
                                     points.ranges[m], points.ranges[m + 1], mp, pore);
        },
        models[m]);
    speed = std::max(speed, rep.max_wave_speed);
    if (rep.first_bad >= 0 && bad < 0) bad = rep.first_bad;
  }
  if (bad >= 0) throw BlowUpError(describe_failed_point<D>(grid, mp, bad));
  return speed;
}

/// Throws BlowUpError if a boundary traction's column that no point sees any more loads a node
/// without material (the body has left that part of the loaded plane, cycles/tractions.hpp);
/// `mass(i)` is node i's mass [kg] of the last p2g, t [s] for the message.
template <int D, class Mass>
void require_loaded_nodes_reached(const BoundaryTractions<D>& tractions,
                                  const numerics::Grid<D>& grid, Mass&& mass, double mass_floor,
                                  double t) {
  if (tractions.empty()) return;
  const auto missed = tractions.unreached_node(mass, mass_floor);
  if (!missed) return;
  const auto x = grid.node_position(missed->first);
  std::string where;
  for (int d = 0; d < D; ++d) where += fmt::format("{}{:.6g}", d ? ", " : "", x[d]);
  throw BlowUpError(fmt::format(
      "at t = {:.9g} s no material reaches the node at ({}) m that the traction of boundary "
      "'{}' loads: no point lies under that part of the loaded plane any more (the body has "
      "left it sideways or torn; a traction's extent is the body's at t = 0)",
      t, where, missed->second));
}

/// What gravity loading reached (solver.gravity_loading; the run summary's "gravity_loading").
struct GravityLoadingReport {
  std::int64_t steps = 0;
  double time = 0.0;                // loading time [s]
  double force_ratio = 0.0;         // at the end [-]
  double max_displacement = 0.0;    // largest point displacement before the reset [m]
  double max_plastic_strain = 0.0;  // largest deviatoric plastic strain before the reset [-]

  std::string json() const {
    return fmt::format(
        "{{\"steps\": {}, \"time_s\": {:.6g}, \"force_ratio\": {:.3e}, "
        "\"max_displacement_m\": {:.6e}, \"max_plastic_strain\": {:.6e}}}",
        steps, time, force_ratio, max_displacement, max_plastic_strain);
  }
};

/// The unbalanced force of the last p2g relative to the weight: sum over the free components of
/// the nodes heavier than the mass floor of |f|, over sum_i m_i |g|. A rigid plate's normal
/// components count as one: |sum of the plate's nodal forces| (numerics/rigid_plates.hpp).
template <int D>
double force_ratio(const numerics::NodalState<D>& nodes, const numerics::Vec<D>& gravity,
                   double mass_floor) {
  std::vector<std::uint8_t> on_plate(nodes.plates.empty() ? 0 : nodes.n_nodes(), 0);
  double unbalanced = 0.0, weight = 0.0;
  for (const numerics::RigidPlate& plate : nodes.plates) {
    double sum = 0.0;
    for (const std::int64_t i : plate.nodes) {
      on_plate[i] |= std::uint8_t(1u << plate.axis);
      if (nodes.mass(i) > mass_floor) sum += nodes.force(i)[plate.axis];
    }
    unbalanced += std::abs(sum);
  }
  for (std::int64_t i = 0; i < nodes.n_nodes(); ++i) {
    const double m = nodes.mass(i);
    if (m <= mass_floor) continue;
    weight += m * gravity.norm();
    const auto f = nodes.force(i);
    const std::uint8_t skip = nodes.fixed[i] | (on_plate.empty() ? 0 : on_plate[i]);
    for (int d = 0; d < D; ++d)
      if (!((skip >> d) & 1)) unbalanced += std::abs(f[d]);
  }
  return weight > 0.0 ? unbalanced / weight : 0.0;
}

/// Steps of gravity loading between copies of the points' last good state (load_gravity).
inline constexpr std::int64_t gravity_loading_snapshot_steps = 100;

/// Gravity loading (GravityLoadingSpec): explicit mechanics steps with the loading's damping, the
/// pore loads `pore` held (numerics::NoPoreLoads in a one-phase case), until the force ratio
/// reaches the tolerance; then displacements, velocities and plastic strains are reset (the
/// positions, volumes and stresses reached are kept). Throws BlowUpError if the ratio is not
/// reached within max_time, on a non-finite state, or when c + |v| grows past
/// wave_speed_blowup_factor times its start (a loading that cannot balance accelerates a point
/// without bound, and its shrinking step would crawl on until the point left the grid: a slope's
/// toe under a water table above its surface took 248,034 steps to leave it, and its last copy
/// held velocities of 1e149 m/s); those name the loading's step and time and leave the points at
/// their last good state (copied every gravity_loading_snapshot_steps steps), which the message
/// states.
template <int D, class K, class Pore>
GravityLoadingReport load_gravity(const GravityLoadingSpec& spec, const TimeStepSpec& time_step,
                                  const numerics::Grid<D>& grid,
                                  const std::vector<SolidModel>& models, double flip_fraction,
                                  const numerics::Vec<D>& gravity, double floor, const Pore& pore,
                                  numerics::NodalState<D>& nodes, PointSet<D>& points) {
  auto& mp = points.points;
  const MechanicsSettings settings{spec.damping, flip_fraction};
  GravityLoadingReport r;
  double speed = solid_wave_speed(models, points);
  const double initial_speed = speed;
  r.force_ratio = 1.0;
  numerics::MaterialPoints<D> good = mp;
  std::int64_t good_step = 0;
  double good_time = 0.0;
  while (r.force_ratio > spec.tolerance) {
    if (r.time >= spec.max_time)
      throw BlowUpError(fmt::format(
          "gravity loading did not balance within max_time = {:g} s ({} steps): force ratio "
          "{:.3e} > tolerance {:.3e}; raise solver.gravity_loading.max_time or damping",
          spec.max_time, r.steps, r.force_ratio, spec.tolerance));
    const double dt = explicit_time_step(time_step, grid.min_spacing(), speed);
    try {
      speed = explicit_mechanics_step<D, K>(grid, models, settings, gravity, floor, dt, pore, {},
                                            nodes, points);
      require_no_step_collapse<D>(models, points, speed, initial_speed);
    } catch (const BlowUpError& e) {
      mp = std::move(good);
      throw BlowUpError(fmt::format(
          "gravity loading (before t = 0) failed at its step {} (loading time {:.9g} s -> "
          "{:.9g} s): {}; the points are left at the loading's last good state (step {}, "
          "loading time {:.9g} s)",
          r.steps + 1, r.time, r.time + dt, e.what(), good_step, good_time));
    }
    r.force_ratio = force_ratio<D>(nodes, gravity, floor);
    r.time += dt;
    ++r.steps;
    if (r.steps % gravity_loading_snapshot_steps == 0)
      good = mp, good_step = r.steps, good_time = r.time;
  }
  for (std::size_t p = 0; p < mp.size(); ++p) {
    r.max_displacement = std::max(r.max_displacement, mp.displacement[p].norm());
    r.max_plastic_strain = std::max(r.max_plastic_strain, mp.plastic_strain[p]);
    mp.displacement[p].setZero();
    mp.velocity[p].setZero();
    mp.plastic_strain[p] = 0.0;
  }
  return r;
}

template <int D, class K>
class ExplicitSolver {
 public:
  ExplicitSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : case_(c),
        grid_(std::move(grid)),
        points_(std::move(points)),
        models_(solid_models(c)),
        settings_{c.solver.damping, c.solver.flip_fraction} {
    gravity_ = gravity_vector<D>(c);
    nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, nodes_.fixed);
    nodes_.plates = make_rigid_plates<D>(c, grid_);
    mass_floor_ = mass_floor(points_.points);
    initial_speed_ = max_wave_speed_ = solid_wave_speed(models_, points_);
  }

  /// Largest stable step [s] for the current state (before the safety factor).
  /// The CFL limit h_min / max_p (c_p + |v_p|) [s].
  double critical_time_step() const { return grid_.min_spacing() / max_wave_speed_; }
  /// The largest c_p + |v_p| of the last step [m/s] (explicit_time_step).
  double max_wave_speed() const { return max_wave_speed_; }

  /// Gravity loading before t = 0 (see load_gravity).
  GravityLoadingReport load_gravity() {
    const auto r = unsatmpm::load_gravity<D, K>(
        *case_.solver.gravity_loading, case_.solver.time_step, grid_, models_,
        settings_.flip_fraction, gravity_, mass_floor_, numerics::NoPoreLoads{}, nodes_, points_);
    initial_speed_ = max_wave_speed_ = solid_wave_speed(models_, points_);
    return r;
  }

  /// Advances the state from t to t + dt [s], under the surface loads of t + dt. Throws
  /// BlowUpError naming the point; the state is then invalid.
  void step(double t, double dt) {
    if (!tractions_.empty()) tractions_.forces(t + dt, points_.points, loads_);
    max_wave_speed_ =
        explicit_mechanics_step<D, K>(grid_, models_, settings_, gravity_, mass_floor_, dt,
                                      numerics::NoPoreLoads{}, loads_, nodes_, points_);
    require_loaded_nodes_reached<D>(
        tractions_, grid_, [&](std::int64_t i) { return nodes_.mass(i); }, mass_floor_, t + dt);
    require_no_step_collapse<D>(models_, points_, max_wave_speed_, initial_speed_);
  }
  /// The same from t = 0 (the tests' steps of a case without time-dependent loads).
  void step(double dt) { step(0.0, dt); }

  /// The points' state projected to the grid without a step (the output at t = 0): nodal mass,
  /// velocity (momentum / mass) and acceleration (force / mass under gravity and the stresses,
  /// zero in held components), where the grid is otherwise empty until the first step.
  void project_to_grid() {
    numerics::p2g<D, K>(grid_, points_.points, gravity_, nodes_);
    for (std::int64_t i = 0; i < nodes_.n_nodes(); ++i) {
      const double m = nodes_.mass(i);
      if (m <= mass_floor_) continue;
      nodes_.velocity[i] = nodes_.momentum(i) / m;
      nodes_.acceleration[i] = nodes_.force(i) / m;
      for (int d = 0; d < D; ++d)
        if (nodes_.fixed[i] & (1u << d)) nodes_.velocity[i][d] = nodes_.acceleration[i][d] = 0.0;
    }
  }

  /// The state a checkpoint keeps: the points and the wave speed that sets the next step.
  void save(CheckpointWriter& w) const {
    save_points<D>(w, "points.", points_.points);
    w.value("wave_speed", max_wave_speed_);
    w.value("initial_wave_speed", initial_speed_);
  }
  void restore(CheckpointReader& r) {
    restore_points<D>(r, "points.", points_.points);
    max_wave_speed_ = r.value<double>("wave_speed");
    initial_speed_ = r.value<double>("initial_wave_speed");
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  numerics::MaterialPoints<D>& points() { return points_.points; }
  /// A one-phase run has no pore fluids.
  const numerics::FluidPoints<D>& fluids() const { return no_fluids_; }
  const numerics::NodalState<D>& nodes() const { return nodes_; }
  bool has_plastic_model() const { return any_plastic(models_); }

 private:
  const Case& case_;
  numerics::Grid<D> grid_;
  PointSet<D> points_;
  numerics::NodalState<D> nodes_;
  numerics::FluidPoints<D> no_fluids_;
  std::vector<SolidModel> models_;
  MechanicsSettings settings_;
  numerics::Vec<D> gravity_;
  BoundaryTractions<D> tractions_{case_, grid_, points_.points};
  std::vector<numerics::NodalForce<D>> loads_;  // the surface loads of the current step
  double mass_floor_ = 0.0, max_wave_speed_ = 0.0, initial_speed_ = 0.0;
};

}  // namespace unsatmpm
