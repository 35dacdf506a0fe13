// From a three-phase Case to the fluid state and the hydraulic boundary conditions of a run.
//
// Hydraulic conditions act on the grid's outer faces. A face with a prescribed liquid (gas)
// pressure or suction receives the traction -P n A on its nodes (the boundary term of the fluid
// balance integrated by parts); every other outer face is impervious to that fluid: the fluid's
// velocity normal to it equals the solid's. A body surface inside the grid is a free surface at
// atmospheric (zero gauge) fluid pressure: its boundary term vanishes.
#pragma once

#include <array>
#include <vector>

#include "drivers/case.hpp"
#include "drivers/setup.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/hydraulic_model.hpp"
#include "numerics/three_phase_nodes.hpp"

namespace unsatmpm::drivers {

std::vector<numerics::HydraulicModel> hydraulic_models(const Case& c);

/// Porosity, pressures, saturation and densities of every point from its body's initial state.
template <int D>
numerics::FluidPoints<D> initial_fluid_state(const Case& c, const PointSet<D>& points,
                                             const std::vector<numerics::HydraulicModel>& models);

/// Liquid and gas mass in the points [kg per unit out-of-plane measure]: sum n S_a rho_a V.
template <int D>
std::array<double, 2> fluid_masses(const numerics::MaterialPoints<D>& mp,
                                   const numerics::FluidPoints<D>& fp) {
  std::array<double, 2> m{0.0, 0.0};
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const double nv = fp.porosity[p] * mp.volume[p];
    m[0] += nv * fp.saturation[p] * fp.liquid_density[p];
    m[1] += nv * (1.0 - fp.saturation[p]) * fp.gas_density[p];
  }
  return m;
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

/// Liquid pressure a boundary prescribes at time t (from a pressure, or gas pressure - suction).
double prescribed_liquid_pressure(const BoundarySpec& b, double t);
/// Its rate d/dt [Pa/s].
double prescribed_liquid_pressure_rate(const BoundarySpec& b, double t);

}  // namespace unsatmpm::drivers
