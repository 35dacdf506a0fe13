// From a three-phase Case to the fluid state and the hydraulic boundary conditions of a run.
//
// Hydraulic conditions act on the grid's outer faces. A face with a prescribed liquid (gas)
// pressure or suction receives the traction -P n A on its nodes (the boundary term of the fluid
// balance integrated by parts); every other outer face is impervious to that fluid: the fluid's
// velocity normal to it equals the solid's. A body surface inside the grid is a free surface at
// atmospheric (zero gauge) fluid pressure: its boundary term vanishes.
#pragma once

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cycles/explicit_solver.hpp"
#include "cycles/setup.hpp"
#include "input/case.hpp"
#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/three_phase_nodes.hpp"
#include "physics/hydraulic_model.hpp"
#include "physics/hydrostatic.hpp"

namespace unsatmpm {

std::vector<physics::HydraulicModel> hydraulic_models(const Case& c);

/// Porosity, pressures, saturation and densities of every point from its body's initial state.
template <int D>
numerics::FluidPoints<D> initial_fluid_state(const Case& c, const PointSet<D>& points,
                                             const std::vector<physics::HydraulicModel>& models);

/// A body's initial pore pressures at elevation z [m] (against gravity |g| [m/s^2]).
inline physics::PorePressures initial_pressures_at(const InitialPressures& init,
                                                   const physics::HydraulicModel& hm, double g,
                                                   double z) {
  if (init.water_table)
    return physics::water_table_pressures(hm.liquid, hm.gas, *init.water_table, g, z);
  if (init.liquid_profile) return {(*init.liquid_profile)(z), init.gas_pressure};
  return {init.liquid_pressure, init.gas_pressure};
}

/// The bodies' initial pore pressures at the points' current positions, with saturation and
/// densities (porosity untouched): uniform, or at rest about a water table
/// (physics/hydrostatic.hpp), or tabulated against elevation. `water_tables_only`: only the
/// points of bodies with a water table.
template <int D>
void set_initial_pressures(const Case& c, const PointSet<D>& points,
                           const std::vector<physics::HydraulicModel>& models,
                           numerics::FluidPoints<D>& fp, bool water_tables_only);

/// Liquid and gas mass in the points, sum n S_a rho_a V, then their capacities sum n rho_a V
/// [kg per unit out-of-plane measure].
template <int D>
std::array<double, 4> fluid_masses(const numerics::MaterialPoints<D>& mp,
                                   const numerics::FluidPoints<D>& fp) {
  std::array<double, 4> m{0.0, 0.0, 0.0, 0.0};
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double nv = fp.porosity[p] * mp.volume[p];
    m[0] += nv * fp.saturation[p] * fp.liquid_density[p];
    m[1] += nv * (1.0 - fp.saturation[p]) * fp.gas_density[p];
    m[2] += nv * fp.liquid_density[p];
    m[3] += nv * fp.gas_density[p];
  }
  return m;
}

/// What the pore fluids add to the mixture's mechanics when they move with the solid
/// (numerics::PoreLoads), taken at the points' current state and held over an interval: their
/// mass n V (S_l rho_l + S_g rho_g) [kg], the pore pressure max(P_l, P_g) [Pa], the suction [Pa]
/// for a suction-dependent strength, and the largest volume of each point [m^3].
struct HeldPoreLoads {
  std::vector<double> added, pore, suction, max_volume;
  std::vector<numerics::StrengthMemo> strength;  // the strength's memo at that suction
  numerics::PoreLoads view() { return {added, pore, suction, strength, max_volume}; }
};
/// `ranges` splits the points by material, as `models`.
template <int D>
HeldPoreLoads held_pore_loads(const numerics::MaterialPoints<D>& mp,
                              const numerics::FluidPoints<D>& fp,
                              const std::vector<physics::HydraulicModel>& models,
                              const std::vector<std::int64_t>& ranges) {
  const auto n = mp.size();
  HeldPoreLoads h{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n),
                  std::vector<double>(n), std::vector<numerics::StrengthMemo>(n)};
  for (std::size_t m = 0; m < models.size(); ++m)
    for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
      const double nv = fp.porosity[p] * mp.volume[p];
      h.added[p] = nv * (fp.saturation[p] * fp.liquid_density[p] +
                         (1.0 - fp.saturation[p]) * fp.gas_density[p]);
      h.pore[p] = std::max(fp.liquid_pressure[p], fp.gas_pressure[p]);
      h.suction[p] = physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]);
      h.max_volume[p] = models[m].max_volume(mp.mass[p]);
    }
  return h;
}

/// The porosity after each point's volume changed from v0 to its current volume, the solid
/// volume (1 - n) V kept (a volume held at its bound gives n = n_max).
template <int D>
void update_porosity(const std::vector<double>& v0, const numerics::MaterialPoints<D>& mp,
                     numerics::FluidPoints<D>& fp) {
  for (std::size_t p = 0; p < mp.size(); ++p)
    fp.porosity[p] = 1.0 - (1.0 - fp.porosity[p]) * v0[p] / mp.volume[p];
}

/// Gravity loading of a three-phase mixture before t = 0 (unsatmpm::load_gravity,
/// cycles/explicit_solver.hpp) with the fluids held: their mass, pore pressure and suction stay as
/// they are; the porosity follows the volume change. Shared by the explicit and the implicit
/// three-phase cycles.
template <int D, class K>
GravityLoadingReport load_gravity_with_fluids(
    const Case& c, const numerics::Grid<D>& grid, const std::vector<SolidModel>& models,
    const std::vector<physics::HydraulicModel>& hydraulics, const numerics::Vec<D>& gravity,
    double mass_floor, numerics::NodalState<D>& nodes, PointSet<D>& points,
    numerics::FluidPoints<D>& fluids) {
  const auto load = [&] {
    const std::vector<double> v0 = points.points.volume;
    HeldPoreLoads held = held_pore_loads<D>(points.points, fluids, hydraulics, points.ranges);
    const numerics::PoreLoads loads = held.view();
    GravityLoadingReport r;
    try {
      r = load_gravity<D, K>(*c.solver.gravity_loading, c.solver.time_step, grid, models,
                             c.solver.flip_fraction, gravity, mass_floor, loads, nodes, points);
    } catch (const BlowUpError& e) {
      throw BlowUpError(std::string(e.what()) +
                        "; the pore pressures are held during the loading, so it cannot balance "
                        "where they exceed what the soil can hold against them (a water table "
                        "above the ground's surface, say)");
    }
    update_porosity<D>(v0, points.points, fluids);
    return r;
  };
  GravityLoadingReport r = load();
  const bool water_table = std::any_of(c.bodies.begin(), c.bodies.end(), [](const BodySpec& b) {
    return b.initial_pressures && b.initial_pressures->water_table;
  });
  if (!water_table) return r;
  // A water table is fixed in space: the pressures of the settled points are those at their new
  // elevations. They differ from the held ones by rho_l g times the settlement, so the loading
  // is repeated once under them (its settlement is that fraction of the first) and the
  // pressures are taken at the final positions.
  set_initial_pressures<D>(c, points, hydraulics, fluids, true);
  const GravityLoadingReport second = load();
  set_initial_pressures<D>(c, points, hydraulics, fluids, true);
  r.steps += second.steps;
  r.time += second.time;
  r.force_ratio = second.force_ratio;
  r.max_displacement = std::max(r.max_displacement, second.max_displacement);
  r.max_plastic_strain = std::max(r.max_plastic_strain, second.max_plastic_strain);
  return r;
}

/// The nodes of one outer grid face that carries a prescribed fluid pressure.
struct PressureFace {
  const BoundarySpec* spec;
  int axis;
  double outward;                   // +1 on the max face, -1 on the min face
  std::vector<std::int64_t> nodes;  // on the face
  std::vector<double> area;         // tributary area of each node [m^(D-1)]
};

struct HydraulicBoundaries {
  std::vector<PressureFace> liquid, gas;
};

/// Finds the prescribed-pressure faces and locks the normal component of every other face.
template <int D>
HydraulicBoundaries hydraulic_boundaries(const Case& c, const numerics::Grid<D>& grid,
                                         numerics::ThreePhaseNodes<D>& nodes);

/// Liquid pressure a condition prescribes at time t (from a pressure, or gas pressure -
/// suction; a suction needs `gas`).
double prescribed_liquid_pressure(const LiquidCondition& liquid,
                                  const std::optional<TimeFunction>& gas, double t);
/// Its rate d/dt [Pa/s].
double prescribed_liquid_pressure_rate(const LiquidCondition& liquid,
                                       const std::optional<TimeFunction>& gas, double t);
/// The same for a boundary's liquid condition.
inline double prescribed_liquid_pressure(const BoundarySpec& b, double t) {
  return prescribed_liquid_pressure(*b.liquid, b.gas_pressure, t);
}
inline double prescribed_liquid_pressure_rate(const BoundarySpec& b, double t) {
  return prescribed_liquid_pressure_rate(*b.liquid, b.gas_pressure, t);
}

}  // namespace unsatmpm
