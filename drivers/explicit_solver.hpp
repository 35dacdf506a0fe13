// The explicit dynamic MPM cycle for one solid phase (SPEC §5A without the fluids).
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

#include "drivers/case.hpp"
#include "drivers/setup.hpp"
#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"

namespace unsatmpm::drivers {

/// Thrown when a step produces a non-finite state or a point leaves the grid.
class BlowUpError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

using SolidModel = std::variant<physics::LinearElastic, physics::MohrCoulomb>;

inline std::vector<SolidModel> solid_models(const Case& c) {
  std::vector<SolidModel> models;
  for (const auto& m : c.materials) models.push_back(m.model);
  return models;
}

inline bool any_plastic(const std::vector<SolidModel>& models) {
  for (const auto& m : models)
    if (std::holds_alternative<physics::MohrCoulomb>(m)) return true;
  return false;
}

/// "material point ID at (x, y) m left the grid" or "... has a non-finite state".
template <int D>
std::string describe_failed_point(const numerics::Grid<D>& grid,
                                  const numerics::MaterialPoints<D>& mp, std::int64_t p) {
  std::string where;
  for (int d = 0; d < D; ++d) where += (d ? ", " : "") + std::to_string(mp.position[p][d]);
  return "material point " + std::to_string(mp.id[p]) + " at (" + where + ") m " +
         (grid.contains(mp.position[p]) ? "has a non-finite state" : "left the grid");
}

/// Nodes lighter than this [kg] count as empty: 1e-9 of the lightest point.
template <int D>
double mass_floor(const numerics::MaterialPoints<D>& mp) {
  double min_mass = mp.mass[0];
  for (const double m : mp.mass) min_mass = std::min(min_mass, m);
  return 1e-9 * min_mass;
}

/// max_p (c_p + |v_p|) with the solid's P-wave speed c_p = sqrt(M V / m) [m/s].
template <int D>
double solid_wave_speed(const std::vector<SolidModel>& models, const PointSet<D>& points) {
  const auto& mp = points.points;
  double c = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double modulus =
        std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models[m]);
    for (auto p = points.ranges[m]; p < points.ranges[m + 1]; ++p)
      c = std::max(c, std::sqrt(modulus * mp.volume[p] / mp.mass[p]) + mp.velocity[p].norm());
  }
  return c;
}

/// Damping and FLIP blend of an explicit mechanics step (SolverSpec's).
struct MechanicsSettings {
  double damping, flip_fraction;
};

/// One explicit mechanics step of the points (p2g, solve_grid, g2p per material): the one-phase
/// cycle's step, and the implicit cycle's mixture step when `pore` is given. Returns the wave
/// speed for the next step [m/s]; throws BlowUpError naming the first failed point.
template <int D, class K>
double explicit_mechanics_step(const numerics::Grid<D>& grid, const std::vector<SolidModel>& models,
                               MechanicsSettings settings, const numerics::Vec<D>& gravity,
                               double mass_floor, double dt, const numerics::PoreLoads* pore,
                               numerics::NodalState<D>& nodes, PointSet<D>& points) {
  auto& mp = points.points;
  numerics::p2g<D, K>(grid, mp, gravity, nodes, pore);
  numerics::solve_grid<D>(dt, settings.damping, mass_floor, nodes);
  double speed = 0.0;
  std::int64_t bad = -1;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const auto rep = std::visit(
        [&](const auto& model) {
          return numerics::g2p<D, K>(grid, nodes, model, dt, settings.flip_fraction,
                                     points.ranges[m], points.ranges[m + 1], mp);
        },
        models[m]);
    speed = std::max(speed, rep.max_wave_speed);
    if (rep.first_bad >= 0 && bad < 0) bad = rep.first_bad;
  }
  if (bad >= 0) throw BlowUpError(describe_failed_point<D>(grid, mp, bad));
  return speed;
}

template <int D, class K>
class ExplicitSolver {
 public:
  ExplicitSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : grid_(std::move(grid)),
        points_(std::move(points)),
        models_(solid_models(c)),
        settings_{c.solver.damping, c.solver.flip_fraction} {
    for (int d = 0; d < D; ++d) gravity_[d] = c.gravity[d];
    nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, nodes_.fixed);
    mass_floor_ = mass_floor(points_.points);
    max_wave_speed_ = solid_wave_speed(models_, points_);
  }

  /// Largest stable step [s] for the current state (before the safety factor).
  double critical_time_step() const { return grid_.min_spacing() / max_wave_speed_; }

  /// Advances the state from t to t + dt [s] (nothing here depends on t itself).
  void step(double /*t*/, double dt) { step(dt); }

  /// Advances the state by dt [s]. Throws BlowUpError naming the point; the state is then invalid.
  void step(double dt) {
    max_wave_speed_ = explicit_mechanics_step<D, K>(grid_, models_, settings_, gravity_,
                                                    mass_floor_, dt, nullptr, nodes_, points_);
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  numerics::MaterialPoints<D>& points() { return points_.points; }
  /// A one-phase run has no pore fluids.
  const numerics::FluidPoints<D>& fluids() const { return no_fluids_; }
  const numerics::NodalState<D>& nodes() const { return nodes_; }
  bool has_plastic_model() const { return any_plastic(models_); }

 private:
  numerics::Grid<D> grid_;
  PointSet<D> points_;
  numerics::NodalState<D> nodes_;
  numerics::FluidPoints<D> no_fluids_;
  std::vector<SolidModel> models_;
  MechanicsSettings settings_;
  numerics::Vec<D> gravity_;
  double mass_floor_ = 0.0, max_wave_speed_ = 0.0;
};

}  // namespace unsatmpm::drivers
