// The main cycle's mechanics (cycles/implicit_solver.hpp, step 2 of an interval): explicit MPM
// sub-steps of the mixture over a coupling interval under the surface loads and the pore loads,
// each followed by the caller's update of the points' pore pressures (cycles/undrained.hpp and the
// flow correction), whose wave speed sets the next sub-step. A stop check, polled before every
// sub-step, ends the interval (numerics::StopRequested), as the flow's integration does.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <fmt/core.h>

#include "cycles/explicit_solver.hpp"
#include "cycles/implicit_diagnostics.hpp"
#include "cycles/implicit_settings.hpp"
#include "cycles/three_phase_setup.hpp"
#include "cycles/undrained.hpp"
#include "numerics/cvode_integrator.hpp"

namespace unsatmpm {

template <int D, class K>
class ImplicitMechanics {
 public:
  ImplicitMechanics(const Case& c, const numerics::Grid<D>& grid, PointSet<D>& points,
                    int n_threads)
      : case_(c), grid_(grid), points_(points), tractions_(c, grid, points.points) {
    gravity_ = gravity_vector<D>(c);
    nodes_.resize(grid_.n_nodes(), n_threads);
    mark_boundaries<D>(c, grid_, nodes_.fixed);
    nodes_.plates = make_rigid_plates<D>(c, grid_);
    mass_floor_ = mass_floor(points_.points);
    for (const auto& model : models_)
      moduli_.push_back(std::visit([](const auto& x) { return numerics::wave_modulus(x); }, model));
  }

  const std::vector<SolidModel>& models() const { return models_; }
  const numerics::NodalState<D>& nodes() const { return nodes_; }
  const numerics::Vec<D>& gravity() const { return gravity_; }
  int n_threads() const { return static_cast<int>(nodes_.scatter.size()); }
  /// Each material's wave modulus [Pa].
  const std::vector<double>& moduli() const { return moduli_; }

  /// The step's state a checkpoint keeps: the last sub-step's wave speed and the one a collapse
  /// of the step is measured against [m/s].
  std::array<double, 2> speeds() const { return {speed_, initial_speed_}; }
  void set_speeds(double speed, double initial) { speed_ = speed, initial_speed_ = initial; }

  /// Ends the sub-cycle once `check` is true (the run loop's, app/cycle_adapters.hpp).
  void set_stop_check(numerics::CvodeIntegrator::StopCheck check) { stop_ = std::move(check); }
  /// Whether the sub-cycle runs, and the sub-step it starts: {t, h} [s].
  bool running() const { return running_; }
  std::array<double, 2> position() const { return at_; }
  void leave() { running_ = false; }

  /// Gravity loading before t = 0 with the pore pressures held (cycles/three_phase_setup.hpp).
  GravityLoadingReport load_gravity(const std::vector<physics::HydraulicModel>& hydraulics,
                                    numerics::FluidPoints<D>& fluids) {
    return load_gravity_with_fluids<D, K>(case_, grid_, models_, hydraulics, gravity_, mass_floor_,
                                          nodes_, points_, fluids);
  }

  /// Sub-steps over [t, t + dt] with the pore loads `loads`, counting them in `substeps`. After
  /// each, `pores(h, done, relax)` updates the points' pore pressures over the sub-step h that
  /// starts `done` [s] into the interval (relaxing the offsets over `relax` [s] when positive) and
  /// returns the next sub-step's wave speed [m/s]. Throws BlowUpError where the wave speed grew by
  /// wave_speed_blowup_factor, numerics::StopRequested where the stop check asked.
  template <class Pores>
  void sub_cycle(double t, double dt, const numerics::PoreLoads& loads,
                 const numerics::FluidPoints<D>& fluids, std::int64_t& substeps, Pores&& pores) {
    const MechanicsSettings settings{case_.solver.damping, case_.solver.flip_fraction};
    double done = 0.0, unrelaxed = 0.0;  // the time since the offsets were last relaxed
    running_ = true;
    while (done < dt * (1.0 - 1e-12)) {
      const double h = std::min(
          explicit_time_step(case_.solver.time_step, grid_.min_spacing(), speed_), dt - done);
      at_ = {t + done, h};
      if (stop_ && stop_())
        throw numerics::StopRequested(
            "stop requested", -1,
            fmt::format("the mechanics had reached t = {:.9g} s in sub-steps of {:.3g} s", t + done,
                        h));
      const bool last = h == dt - done;
      unrelaxed += h;
      const double relax =
          last || unrelaxed >= dt / offset_relaxations_per_interval ? unrelaxed : 0.0;
      if (relax > 0.0) unrelaxed = 0.0;
      if (!tractions_.empty()) tractions_.forces(t + done + h, points_.points, surface_loads_);
      explicit_mechanics_step<D, K>(grid_, models_, settings, gravity_, mass_floor_, h, loads,
                                    surface_loads_, nodes_, points_);
      require_loaded_nodes_reached<D>(
          tractions_, grid_, [&](std::int64_t i) { return nodes_.mass(i); }, mass_floor_,
          t + done + h);
      speed_ = pores(h, done, relax);
      done = last ? dt : done + h;
      ++substeps;
      if (speed_ > wave_speed_blowup_factor * initial_speed_)
        throw BlowUpError(describe_fastest_point<D>(models_, points_, fluids, initial_speed_));
    }
  }

 private:
  const Case& case_;
  const numerics::Grid<D>& grid_;
  PointSet<D>& points_;
  std::vector<SolidModel> models_ = solid_models(case_);
  numerics::NodalState<D> nodes_;
  BoundaryTractions<D> tractions_;                      // surface loads
  std::vector<numerics::NodalForce<D>> surface_loads_;  // those of the current sub-step
  std::vector<double> moduli_;
  numerics::Vec<D> gravity_;
  double mass_floor_ = 0.0, speed_ = 1.0, initial_speed_ = 1.0;
  numerics::CvodeIntegrator::StopCheck stop_;
  bool running_ = false;
  std::array<double, 2> at_{0.0, 0.0};
};

}  // namespace unsatmpm
