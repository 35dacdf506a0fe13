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

template <int D, class K>
class ExplicitSolver {
 public:
  ExplicitSolver(const Case& c, numerics::Grid<D> grid, PointSet<D> points, int n_threads)
      : grid_(std::move(grid)),
        points_(std::move(points)),
        models_(solid_models(c)),
        damping_(c.solver.damping),
        flip_(c.solver.flip_fraction) {
    for (int d = 0; d < D; ++d) gravity_[d] = c.gravity[d];
    nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, nodes_.fixed);
    double min_mass = points_.points.mass[0];
    for (const double m : points_.points.mass) min_mass = std::min(min_mass, m);
    mass_floor_ = 1e-9 * min_mass;
    max_wave_speed_ = initial_wave_speed();
  }

  /// Largest stable step [s] for the current state (before the safety factor).
  double critical_time_step() const { return grid_.min_spacing() / max_wave_speed_; }

  /// Advances the state from t to t + dt [s] (nothing here depends on t itself).
  void step(double /*t*/, double dt) { step(dt); }

  /// Advances the state by dt [s]. Throws BlowUpError naming the point; the state is then invalid.
  void step(double dt) {
    auto& mp = points_.points;
    numerics::p2g<D, K>(grid_, mp, gravity_, nodes_);
    numerics::solve_grid<D>(dt, damping_, mass_floor_, nodes_);
    double speed = 0.0;
    std::int64_t bad = -1;
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const auto rep = std::visit(
          [&](const auto& model) {
            return numerics::g2p<D, K>(grid_, nodes_, model, dt, flip_, points_.ranges[m],
                                       points_.ranges[m + 1], mp);
          },
          models_[m]);
      speed = std::max(speed, rep.max_wave_speed);
      if (rep.first_bad >= 0 && bad < 0) bad = rep.first_bad;
    }
    if (bad >= 0) throw BlowUpError(describe_failed_point<D>(grid_, points_.points, bad));
    max_wave_speed_ = speed;
  }

  const numerics::Grid<D>& grid() const { return grid_; }
  const numerics::MaterialPoints<D>& points() const { return points_.points; }
  numerics::MaterialPoints<D>& points() { return points_.points; }
  /// A one-phase run has no pore fluids.
  const numerics::FluidPoints<D>& fluids() const { return no_fluids_; }
  const numerics::NodalState<D>& nodes() const { return nodes_; }
  bool has_plastic_model() const { return any_plastic(models_); }

 private:
  double initial_wave_speed() const {
    const auto& mp = points_.points;
    double c = 0.0;
    for (std::size_t m = 0; m < models_.size(); ++m) {
      const double modulus =
          std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models_[m]);
      for (auto p = points_.ranges[m]; p < points_.ranges[m + 1]; ++p)
        c = std::max(c, std::sqrt(modulus * mp.volume[p] / mp.mass[p]) + mp.velocity[p].norm());
    }
    return c;
  }

  numerics::Grid<D> grid_;
  PointSet<D> points_;
  numerics::NodalState<D> nodes_;
  numerics::FluidPoints<D> no_fluids_;
  std::vector<SolidModel> models_;
  numerics::Vec<D> gravity_;
  double damping_, flip_, mass_floor_ = 0.0, max_wave_speed_ = 0.0;
};

}  // namespace unsatmpm::drivers
