#include "cycles/three_phase_setup.hpp"

#include <cmath>
#include <stdexcept>

namespace unsatmpm {

std::vector<physics::HydraulicModel> hydraulic_models(const Case& c) {
  std::vector<physics::HydraulicModel> out;
  const FluidsSpec& f = *c.fluids;
  for (const MaterialSpec& m : c.materials) {
    const HydraulicSpec& h = *m.hydraulic;
    out.push_back({f.liquid, f.gas, h.retention, h.liquid_relative_permeability,
                   h.gas_relative_permeability, h.solid_density, h.intrinsic_permeability,
                   f.liquid_viscosity, f.gas_viscosity, h.maximum_porosity.value_or(1.0)});
  }
  return out;
}

template <int D>
void set_initial_pressures(const Case& c, const PointSet<D>& points,
                           const std::vector<physics::HydraulicModel>& models,
                           numerics::FluidPoints<D>& fp, bool water_tables_only) {
  const auto& mp = points.points;
  double g = 0.0;
  for (const double v : c.gravity) g += v * v;
  g = std::sqrt(g);
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const InitialPressures& init = *c.bodies[points.body[p]].initial_pressures;
    if (water_tables_only && !init.water_table) continue;
    const physics::HydraulicModel& hm = models[mp.material[p]];
    // Elevation against gravity (used only with a table: the parser checked g > 0 then).
    double z = 0.0;
    if (g > 0.0)
      for (int d = 0; d < D; ++d) z -= c.gravity[d] / g * mp.position[p][d];
    const physics::PorePressures pressure = initial_pressures_at(init, hm, g, z);
    fp.liquid_pressure[p] = pressure.liquid;
    fp.gas_pressure[p] = pressure.gas;
    fp.saturation[p] = hm.saturation(physics::retention_suction(pressure.liquid, pressure.gas));
    fp.liquid_density[p] = hm.liquid_density(pressure.liquid);
    fp.gas_density[p] = hm.gas_density(pressure.gas);
  }
}

template <int D>
numerics::FluidPoints<D> initial_fluid_state(const Case& c, const PointSet<D>& points,
                                             const std::vector<physics::HydraulicModel>& models) {
  numerics::FluidPoints<D> fp;
  const auto& mp = points.points;
  fp.resize(mp.size());
  for (std::size_t p = 0; p < mp.size(); ++p)
    fp.porosity[p] = c.materials[mp.material[p]].hydraulic->porosity;
  set_initial_pressures<D>(c, points, models, fp, false);
  return fp;
}

namespace {

/// Tributary area of a face node: the product of the other directions' spacings, halved at the
/// face's own edges.
template <int D>
double tributary_area(const numerics::Grid<D>& grid, const std::array<int, D>& ijk, int axis) {
  double area = 1.0;
  for (int e = 0; e < D; ++e) {
    if (e == axis) continue;
    const bool edge = ijk[e] == 0 || ijk[e] == grid.n_cells[e];
    area *= grid.spacing[e] * (edge ? 0.5 : 1.0);
  }
  return area;
}

}  // namespace

template <int D>
HydraulicBoundaries hydraulic_boundaries(const Case& c, const numerics::Grid<D>& grid,
                                         numerics::ThreePhaseNodes<D>& nodes) {
  HydraulicBoundaries out;
  for (int axis = 0; axis < D; ++axis) {
    for (const int side : {0, 1}) {
      const int plane_index = side == 0 ? 0 : grid.n_cells[axis];
      const double coordinate = grid.origin[axis] + plane_index * grid.spacing[axis];
      const BoundarySpec *liquid = nullptr, *gas = nullptr;
      for (const BoundarySpec& b : c.boundaries) {
        if (b.region.axis != axis ||
            std::abs(b.region.coordinate - coordinate) > 1e-9 * grid.spacing[axis])
          continue;
        if (b.liquid) liquid = &b;
        if (b.gas_pressure) gas = &b;
      }
      PressureFace lf{liquid, axis, side == 0 ? -1.0 : 1.0, {}, {}};
      PressureFace gf{gas, axis, lf.outward, {}, {}};
      for (std::int64_t i = 0; i < grid.n_nodes(); ++i) {
        const auto ijk = grid.node_ijk(i);
        if (ijk[axis] != plane_index) continue;
        const double area = tributary_area<D>(grid, ijk, axis);
        if (liquid)
          lf.nodes.push_back(i), lf.area.push_back(area);
        else
          nodes.liquid_locked[i] |= std::uint8_t(1u << axis);
        if (gas)
          gf.nodes.push_back(i), gf.area.push_back(area);
        else
          nodes.gas_locked[i] |= std::uint8_t(1u << axis);
      }
      if (liquid) out.liquid.push_back(std::move(lf));
      if (gas) out.gas.push_back(std::move(gf));
    }
  }
  return out;
}

double prescribed_liquid_pressure(const LiquidCondition& liquid,
                                  const std::optional<TimeFunction>& gas, double t) {
  if (liquid.kind == LiquidCondition::Kind::pressure) return liquid.value(t);
  if (!gas) throw std::logic_error("a suction condition needs a gas pressure beside it");
  return (*gas)(t)-liquid.value(t);
}

double prescribed_liquid_pressure_rate(const LiquidCondition& liquid,
                                       const std::optional<TimeFunction>& gas, double t) {
  if (liquid.kind == LiquidCondition::Kind::pressure) return liquid.value.rate(t);
  if (!gas) throw std::logic_error("a suction condition needs a gas pressure beside it");
  return gas->rate(t) - liquid.value.rate(t);
}

#define UNSATMPM_INSTANTIATE(D)                                                               \
  template numerics::FluidPoints<D> initial_fluid_state<D>(                                   \
      const Case&, const PointSet<D>&, const std::vector<physics::HydraulicModel>&);          \
  template void set_initial_pressures<D>(const Case&, const PointSet<D>&,                     \
                                         const std::vector<physics::HydraulicModel>&,         \
                                         numerics::FluidPoints<D>&, bool);                    \
  template HydraulicBoundaries hydraulic_boundaries<D>(const Case&, const numerics::Grid<D>&, \
                                                       numerics::ThreePhaseNodes<D>&);
UNSATMPM_INSTANTIATE(1)
UNSATMPM_INSTANTIATE(2)
UNSATMPM_INSTANTIATE(3)
#undef UNSATMPM_INSTANTIATE

}  // namespace unsatmpm
