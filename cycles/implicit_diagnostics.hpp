// What the main cycle reports: where a failure happened (the point whose wave speed collapsed the
// mechanics step, the unknown CVODE could not converge), and its counters as JSON for the run
// summary (docs/output.md).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <fmt/core.h>

#include "cycles/explicit_solver.hpp"
#include "numerics/cvode_integrator.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/pressure/pressure_system.hpp"

namespace unsatmpm {

/// Where a step of the main cycle stands, for the progress inside it and a stop's message: the
/// part running ("flow" or "mechanics"), the time it has reached and its last step [s].
struct StepPosition {
  const char* part;
  double t, h;
};

/// "the mechanics step collapsed: ..." naming the point of the largest c + |v|, its place and
/// state; `initial_speed` [m/s] is the speed the collapse is measured against.
template <int D>
std::string describe_fastest_point(const std::vector<SolidModel>& models, const PointSet<D>& points,
                                   const numerics::FluidPoints<D>& fluids, double initial_speed) {
  const auto& mp = points.points;
  std::int64_t worst = 0;
  double worst_speed = -1.0, worst_c = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double modulus =
        std::visit([](const auto& x) { return numerics::wave_modulus(x); }, models[m]);
    for (auto p = points.ranges[m]; p < points.ranges[m + 1]; ++p) {
      const double c = std::sqrt(modulus * mp.volume[p] / mp.mass[p]);
      if (c + mp.velocity[p].norm() > worst_speed)
        worst = p, worst_c = c, worst_speed = c + mp.velocity[p].norm();
    }
  }
  std::string at;
  for (int d = 0; d < D; ++d) at += fmt::format("{}{:.6g}", d ? ", " : "", mp.position[worst][d]);
  return fmt::format(
      "the mechanics step collapsed: c + |v| = {:.4g} m/s exceeds 1000 times its initial {:.4g} "
      "m/s at material point {} at ({}) m (wave speed {:.4g} m/s, velocity {:.4g} m/s, porosity "
      "{:.4g}, P_l = {:.6g} Pa, P_g = {:.6g} Pa)",
      worst_speed, initial_speed, mp.id[worst], at, worst_c, mp.velocity[worst].norm(),
      fluids.porosity[worst], fluids.liquid_pressure[worst], fluids.gas_pressure[worst]);
}

/// ", worst unknown: liquid pressure at node 12 (0.5, 1) m", or "" for an index out of range.
template <int D, class K>
std::string describe_unknown(const numerics::PressureSystem<D, K>& system,
                             const numerics::Grid<D>& grid, std::int64_t unknown) {
  if (unknown < 0 || unknown >= system.n_unknowns()) return "";
  const auto [node, fluid] = system.unknown_location(unknown);
  if (node < 0)
    return fmt::format(", worst unknown: the {} inflow integral", fluid ? "gas" : "liquid");
  const auto x = grid.node_position(node);
  std::string at;
  for (int d = 0; d < D; ++d) at += fmt::format("{}{:.6g}", d ? ", " : "", x[d]);
  return fmt::format(", worst unknown: {} pressure at node {} ({}) m", fluid ? "gas" : "liquid",
                     node, at);
}

/// A point whose pore pressures the mechanics' sub-step ending at t [s] left unusable
/// (cycles/undrained.hpp: no finite pressures with positive densities hold its fluid masses in its
/// new pore volume): where it is, and its pressures and porosity before that update.
template <int D>
std::string describe_failed_pressures(const numerics::Grid<D>& grid,
                                      const numerics::MaterialPoints<D>& mp,
                                      const numerics::FluidPoints<D>& fp, std::int64_t p,
                                      double t) {
  return point_location<D>(mp, p) + (grid.contains(mp.position[p]) ? "" : ", outside the grid,") +
         fmt::format(
             " holds fluid masses that no pressures hold after the pore pressures' update at "
             "t = {:.9g} s (before it: P_l = {:.6g} Pa, P_g = {:.6g} Pa, porosity {:.6g})",
             t, fp.liquid_pressure[p], fp.gas_pressure[p], fp.porosity[p]);
}

/// The main cycle's own counters, and where its wall time went [s].
struct FlowCounters {
  std::int64_t coupling_intervals = 0, mechanics_substeps = 0;
  // The flow correction's KLU factorisations, GMRES iterations, sub-steps solved by KLU after
  // GMRES fell short, and wall time [s] (cycles/flow_correction.hpp).
  std::int64_t correction_factorisations = 0, correction_iterations = 0;
  std::int64_t correction_direct_solves = 0;
  double correction_seconds = 0.0;
  double flow_seconds = 0.0, rhs_seconds = 0.0, jacobian_seconds = 0.0;
  double mechanics_seconds = 0.0;  // the sub-steps, the correction's time included [s]

  /// Adds the correction's counts since it last gave them (FlowCorrection::take_counts).
  template <class Counts>
  void add_correction(const Counts& c) {
    correction_factorisations += c.factorisations, correction_iterations += c.iterations;
    correction_direct_solves += c.direct_solves;
  }
};

/// f(), its wall time added to `seconds` (also when it throws); returns what f returns, if any.
template <class F>
decltype(auto) timed(double& seconds, F&& f) {
  struct AddOnExit {
    double& seconds;
    std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    ~AddOnExit() {
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
  } add{seconds};
  return f();
}

/// The unknown of `y` changing fastest against its error weight, |y'_i| / (rtol |y_i| + atol), at
/// (t, y); -1 if the rates are not finite. The culprit to name when CVODE fails before any step
/// gave an error estimate (a Newton iteration that does not converge at an interval's start).
template <int D, class K>
std::int64_t fastest_unknown(numerics::PressureSystem<D, K>& system, double t,
                             std::span<const double> y, double rtol, double atol) {
  std::vector<double> rate(y.size());
  if (system.rhs(t, y, rate) != 0) return -1;
  std::int64_t worst = -1;
  double worst_value = -1.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double v = std::abs(rate[i]) / (rtol * std::abs(y[i]) + atol);
    if (v > worst_value) worst = static_cast<std::int64_t>(i), worst_value = v;
  }
  return worst;
}

/// The unknown a failed or stopped flow integration names: the one with the largest weighted
/// local error of CVODE's last step attempt (`worst`; -1: none estimated), else the one changing
/// fastest at the state `y` at time t, said so, else why there is none.
template <int D, class K>
std::string flow_culprit(numerics::PressureSystem<D, K>& system, const numerics::Grid<D>& grid,
                         std::int64_t worst, double t, std::span<const double> y,
                         numerics::CvodeTolerances tol) {
  if (std::string culprit = describe_unknown(system, grid, worst); !culprit.empty()) return culprit;
  const auto k = fastest_unknown(system, t, y, tol.relative, tol.absolute);
  return k >= 0 ? describe_unknown(system, grid, k) +
                      " (no error estimate yet: the unknown changing fastest)"
                : ", no worst unknown (no error estimate yet, and the rates at the last state "
                  "are not finite)";
}

/// What a failed CVODE integration reports: the flag, the time, the worst unknown (or, with no
/// error estimate yet, the unknown changing fastest at the last state `y`) and CVODE's message.
template <int D, class K>
std::string describe_flow_failure(numerics::PressureSystem<D, K>& system,
                                  const numerics::Grid<D>& grid, const numerics::CvodeError& e,
                                  std::span<const double> y, numerics::CvodeTolerances tol) {
  return fmt::format("CVODE failed ({}) at t = {:.9g} s{}: {}", e.flag_name(), e.time(),
                     flow_culprit(system, grid, e.worst_component(), e.time(), y, tol), e.what());
}

/// Where a flow integration stopped on request stood, what a user needs to see why a run stalled:
/// "the flow had reached t = 11.73 s in steps of 8e-06 s, worst unknown: liquid pressure at node
/// ... m" (the largest weighted local error of its last step attempt, or with none estimated yet
/// the unknown changing fastest at the last state `y`).
template <int D, class K>
std::string describe_stop(numerics::PressureSystem<D, K>& system, const numerics::Grid<D>& grid,
                          const numerics::StopRequested& e, const numerics::CvodeStatistics& s,
                          std::span<const double> y, numerics::CvodeTolerances tol) {
  return fmt::format("the flow had reached t = {:.9g} s in steps of {:.3g} s{}", s.current_time,
                     s.last_step,
                     flow_culprit(system, grid, e.worst_component(), s.current_time, y, tol));
}

/// The sparse LU's fill-reducing ordering by its number in numerics::LuOrdering.
inline const char* lu_ordering_name(int ordering) {
  return ordering == 0 ? "AMD" : ordering == 1 ? "COLAMD" : "none";
}

/// The sparse LU's name.
inline const char* direct_solver_name(numerics::DirectSolverChoice s) {
  return s == numerics::DirectSolverChoice::klu ? "KLU" : "UMFPACK";
}

/// CVODE's counters, the cycle's, and the pressure system's size, as one JSON object.
inline std::string flow_statistics_json(const numerics::CvodeStatistics& s, const FlowCounters& c,
                                        std::int64_t pressure_unknowns,
                                        std::int64_t jacobian_nonzeros, bool iterative) {
  return fmt::format(
      "{{\"coupling_intervals\": {}, \"mechanics_substeps\": {}, "
      "\"correction_factorisations\": {}, \"correction_iterations\": {}, "
      "\"correction_direct_solves\": {}, \"correction_wall_time_s\": {:.6f}, \"cvode_steps\": {}, "
      "\"rhs_evaluations\": {}, \"newton_iterations\": {}, \"jacobian_evaluations\": {}, "
      "\"error_test_failures\": {}, \"convergence_failures\": {}, \"lu_analyses\": {}, "
      "\"lu_factorisations\": {}, \"lu_factorisation_wall_time_s\": {:.6f}, "
      "\"last_cvode_step_s\": {:.6g}, \"flow_wall_time_s\": {:.6f}, \"rhs_wall_time_s\": {:.6f}, "
      "\"jacobian_wall_time_s\": {:.6f}, \"lu_wall_time_s\": {:.6f}, "
      "\"mechanics_wall_time_s\": {:.6f}, \"linear_solver\": \"{}\", \"direct_solver\": \"{}\", "
      "\"lu_ordering\": \"{}\", "
      "\"linear_iterations\": {}, "
      "\"linear_failures\": {}, \"preconditioner_setups\": {}, "
      "\"preconditioner_wall_time_s\": {:.6f}, "
      "\"pressure_unknowns\": {}, \"jacobian_nonzeros\": {}}}",
      c.coupling_intervals, c.mechanics_substeps, c.correction_factorisations,
      c.correction_iterations, c.correction_direct_solves, c.correction_seconds, s.steps,
      s.rhs_evaluations, s.newton_iterations, s.jacobian_evaluations, s.error_test_failures,
      s.convergence_failures, s.lu_analyses, s.lu_factorisations, s.lu_setup_seconds, s.last_step,
      c.flow_seconds, c.rhs_seconds, c.jacobian_seconds, s.lu_seconds, c.mechanics_seconds,
      iterative ? "iterative" : "direct", direct_solver_name(s.direct_solver),
      lu_ordering_name(s.lu_ordering), s.linear_iterations, s.linear_failures,
      s.preconditioner_setups, s.preconditioner_seconds, pressure_unknowns, jacobian_nonzeros);
}

}  // namespace unsatmpm
