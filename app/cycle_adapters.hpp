// What the run loop (app/run_loop.hpp) asks of each cycle, one overload per cycle: its name, its
// grid and point fields for the output, its conservation record and counters, the step it takes,
// and how often its last good state is copied.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "app/interrupt.hpp"
#include "cycles/explicit_solver.hpp"
#include "cycles/implicit_solver.hpp"
#include "cycles/three_phase_solver.hpp"
#include "writers/run_output.hpp"

namespace unsatmpm {

using Scratch = std::vector<std::vector<double>>;

/// The doubles of a vector of fixed-size Eigen vectors (stored contiguously, no padding).
template <int D>
std::span<const double> flat(const std::vector<numerics::Vec<D>>& v, int n_components) {
  if (v.empty()) return {};
  return {v.data()->data(), v.size() * n_components};
}

// Nodal fields of each cycle's grid output.
template <int D, class K>
std::vector<VtkField> nodal_fields(const ExplicitSolver<D, K>& s, Scratch& scratch) {
  const auto& nodes = s.nodes();
  const std::int64_t n = nodes.n_nodes();
  scratch.assign(2, std::vector<double>(n));
  for (std::int64_t i = 0; i < n; ++i)
    scratch[0][i] = nodes.mass(i), scratch[1][i] = nodes.fixed[i];
  return {{"mass", 1, scratch[0], false},
          {"velocity", D, flat(nodes.velocity, D), true},
          {"acceleration", D, flat(nodes.acceleration, D), true},
          {"fixed_components", 1, scratch[1], false}};
}

template <int D, class K>
std::vector<VtkField> nodal_fields(const ThreePhaseSolver<D, K>& s, Scratch& scratch) {
  const auto& nodes = s.nodes();
  const std::int64_t n = nodes.n_nodes();
  scratch.assign(1, std::vector<double>(n));
  for (std::int64_t i = 0; i < n; ++i) scratch[0][i] = nodes.solid_mass(i);
  return {{"solid_mass", 1, scratch[0], false},
          {"velocity_solid", D, flat(nodes.solid_velocity, D), true},
          {"velocity_liquid", D, flat(nodes.liquid_velocity, D), true},
          {"velocity_gas", D, flat(nodes.gas_velocity, D), true},
          {"liquid_theta", 1, nodes.liquid_theta, false},
          {"gas_theta", 1, nodes.gas_theta, false}};
}

/// The main cycle's nodal pressures of the last flow update; before the first, the points'
/// pressures fitted to the nodes as the flow starts from them
/// (numerics/pressure/nodal_projection.hpp).
template <int D, class K>
std::vector<VtkField> nodal_fields(const ImplicitSolver<D, K>& s, Scratch& scratch) {
  const auto& p = s.nodal_pressures();
  if (!p[numerics::liquid_phase].empty())
    return {{"liquid_pressure", 1, p[numerics::liquid_phase], false},
            {"gas_pressure", 1, p[numerics::gas_phase], false}};
  const auto& mp = s.points();
  numerics::PointQuadrature<D, K> quadrature(s.grid().n_nodes());
  quadrature.fill(s.grid(), mp, s.fluids(), s.material_ranges(), {}, 0.0);
  std::array<std::vector<double>, 2> fitted;
  numerics::fit_pressures_to_nodes<D, K>(s.grid(), quadrature, s.fluids(), fitted);
  scratch = {std::move(fitted[0]), std::move(fitted[1])};
  return {{"liquid_pressure", 1, scratch[0], false}, {"gas_pressure", 1, scratch[1], false}};
}

/// A signal (app/interrupt.hpp) ends a step of the main cycle at the flow's next evaluation (a
/// struggling integration can make a step last for ever); in the mechanics sub-cycle, whose end
/// is near, the first lets the step finish (the run loop then stops with a checkpoint) and a
/// second ends it before the next sub-step. The explicit cycles' steps are short, and the run
/// loop acts on a signal after each. `beat(where)` is called at each of those polls, `where()`
/// giving where the step stands (StepPosition, ImplicitSolver::position), for the progress inside
/// a long step.
template <class Solver, class Beat>
void watch_step(Solver&, Beat&&) {}
template <int D, class K, class Beat>
void watch_step(ImplicitSolver<D, K>& s, Beat beat) {
  s.set_stop_check([&s, beat] {
    beat([&s] { return s.position(); });
    return interrupt_signal() != 0 &&
           (std::string_view(s.position().part) == "flow" || interrupt_count() > 1);
  });
}

/// Before the output at t = 0: the explicit cycles project the points to their grid, which is
/// otherwise empty until the first step; the main cycle fits its pressures when asked.
template <class Solver>
void prepare_initial_output(Solver& s) {
  s.project_to_grid();
}
template <int D, class K>
void prepare_initial_output(ImplicitSolver<D, K>&) {}

/// The fluid fields of the points (names and units: docs/output.md); none for a one-phase run.
template <int D>
std::vector<VtkField> fluid_fields(const numerics::FluidPoints<D>& fp,
                                   std::vector<double>& suction) {
  if (fp.size() == 0) return {};
  suction.resize(fp.size());
  for (std::size_t p = 0; p < fp.size(); ++p)
    suction[p] = physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]);
  return {{"liquid_pressure", 1, fp.liquid_pressure, false},
          {"gas_pressure", 1, fp.gas_pressure, false},
          {"suction", 1, suction, false},
          {"degree_of_saturation", 1, fp.saturation, false},
          {"porosity", 1, fp.porosity, false}};
}

/// The fluids' motion at the points (docs/output.md): the explicit cycle's velocities of the
/// written state; none in a one-phase run.
template <int D, class Solver>
std::vector<VtkField> motion_fields(const Solver&, const numerics::FluidPoints<D>& fp,
                                    std::array<std::vector<numerics::Vec<D>>, 2>&, bool) {
  if (fp.size() == 0) return {};
  return {{"velocity_liquid", D, flat(fp.liquid_velocity, D), true},
          {"velocity_gas", D, flat(fp.gas_velocity, D), true}};
}

/// The main cycle's Darcy fluxes (it has no fluid velocities), for the current state only: a
/// last good state (`current` false) is written without them.
template <int D, class K>
std::vector<VtkField> motion_fields(const ImplicitSolver<D, K>& s, const numerics::FluidPoints<D>&,
                                    std::array<std::vector<numerics::Vec<D>>, 2>& q, bool current) {
  if (!current) return {};
  s.darcy_fluxes(q);
  return {{"darcy_flux_liquid", D, flat(q[0], D), true},
          {"darcy_flux_gas", D, flat(q[1], D), true}};
}

template <int D, class K>
void record_balance(const ExplicitSolver<D, K>&, double, RunOutput<D>&) {}
template <int D, class K>
void record_balance(const ThreePhaseSolver<D, K>& s, double t, RunOutput<D>& out) {
  out.record_balance(t, s.balance());
}

template <int D, class K>
void record_balance(const ImplicitSolver<D, K>& s, double t, RunOutput<D>& out) {
  out.record_balance(t, s.balance());
}

/// The step the run loop takes: the explicit cycles' step (explicit_time_step), the implicit
/// cycle's coupling interval.
template <class Solver>
double next_step(const Case& c, const Solver& solver) {
  return explicit_time_step(c.solver.time_step, solver.grid().min_spacing(),
                            solver.max_wave_speed());
}
template <int D, class K>
double next_step(const Case&, const ImplicitSolver<D, K>& solver) {
  return solver.interval();
}

template <class Solver>
std::string solver_statistics(const Solver&) {
  return "";
}
template <int D, class K>
std::string solver_statistics(const ImplicitSolver<D, K>& s) {
  return s.statistics_json();
}

/// The main cycle's warning where the free surface's liquid condition, or under rain its ponded
/// face, is held at nodes the points barely reach (docs/input.md, "Known limitation of the main
/// cycle"; docs/known_failures.md); empty otherwise and for the explicit cycles, which act on the
/// face's outward area. The run loop asks after every interval until it has warned once.
template <class Solver>
std::string surface_warning(const Case&, const Solver&) {
  return "";
}
template <int D, class K>
std::string surface_warning(const Case& c, const ImplicitSolver<D, K>& s) {
  const auto [held, light] = s.held_surface_nodes();
  if (light == 0) return "";
  if (c.free_surface && c.free_surface->rainfall)
    return fmt::format(
        "{} of the {} free-surface nodes held at zero suction under the rain (ponded or seeping) "
        "carry less than an eighth of a full node's volume: there the face lies between node "
        "lines, it is held outside the soil, and the rain enters too slowly (a 1D column whose "
        "top lay a sixth of a cell past a node line took in 3.07 of the 7.20 kg/m^2 it took in "
        "with its top on the line). `solver.implicit.surface_penalty: 16` acts on the face "
        "itself (docs/input.md, \"Rain with the face's penalty\")",
        light, held);
  return fmt::format(
      "{} of the {} free-surface nodes that hold the liquid's pressure or suction carry less "
      "than an eighth of a full node's volume: there the face lies between node lines, the "
      "condition is held outside it, and water crosses the face too slowly (a 1D column whose "
      "top lay a tenth of a cell past a node line took in 1.6 % of the water it should). "
      "`solver.implicit.surface_penalty: 16` acts on the face itself (docs/input.md, \"Known "
      "limitation of the main cycle\")",
      light, held);
}

template <int D, class K>
const char* cycle_name(const ImplicitSolver<D, K>&) {
  return "implicit_pressure_three_phase";
}
template <int D, class K>
const char* cycle_name(const ExplicitSolver<D, K>&) {
  return "explicit_dynamic_one_phase";
}
template <int D, class K>
const char* cycle_name(const ThreePhaseSolver<D, K>&) {
  return "explicit_dynamic_three_phase";
}

/// How often the run loop copies the last good state, in steps. An implicit-cycle step is a whole
/// coupling interval (thousands of mechanics sub-steps and a CVODE run), so it is copied after
/// every step; the embankment's failure at 141.5 s with 0.5 s intervals otherwise left its last
/// good state at 100 s. The three-phase explicit step costs ~300 ns per point, and a copy after
/// every step did not show (16,000 points, 2 threads: 310-316 against 329 ns per point-step), so
/// its last good state is the step before the failure too. The one-phase step costs ~80 ns per
/// point and a copy after each one added 10 % (81-85 to 91-92 ns, 180,000 points): it is copied
/// every 100 steps, and the summary gives the state's own time.
template <class Solver>
constexpr std::int64_t snapshot_every(const Solver&) {
  return 100;
}
template <int D, class K>
constexpr std::int64_t snapshot_every(const ImplicitSolver<D, K>&) {
  return 1;
}
template <int D, class K>
constexpr std::int64_t snapshot_every(const ThreePhaseSolver<D, K>&) {
  return 1;
}

}  // namespace unsatmpm
