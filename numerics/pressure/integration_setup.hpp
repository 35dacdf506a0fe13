// What the pressure ODE's operator (numerics/pressure/pressure_operator.hpp) reads of one
// integration that PressureSystem (numerics/pressure/pressure_system.hpp) has set up: the
// points as quadrature points, the unknowns, the prescribed values, supplies and the surface
// penalty's coupling.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "numerics/pressure/face_trace.hpp"
#include "numerics/pressure/quadrature.hpp"
#include "numerics/pressure/unknowns.hpp"
#include "numerics/sparse_pattern.hpp"

namespace unsatmpm::numerics {

/// Prescribed nodal pressures at a time t: which nodes, their values and rates, per fluid; and
/// the free surface's value of a fluid whose surface condition is a penalty (IntegrationSetup).
struct NodalPrescription {
  std::array<std::vector<std::uint8_t>, 2> prescribed;  // per fluid, per node: 1 if prescribed
  std::array<std::vector<double>, 2> value, rate;       // [Pa], [Pa/s] at the current t
  std::array<double, 2> surface_value{0.0, 0.0};        // P̄ [Pa] at the current t
};

/// What the operator reads of one integration; PressureSystem owns it.
template <int D, class K>
struct IntegrationSetup {
  const PointQuadrature<D, K>& points;
  const PressureUnknowns& unknowns;
  const NodalPrescription& prescription;
  const std::array<std::vector<double>, 2>& supply;  // [kg/s] per node; empty: none
  const SparsePattern& pattern;
  // Per fluid, its surface penalty's coupling c [kg/(s Pa)] (surface_penalty.hpp); empty: none.
  const std::array<FaceTrace, 2>& penalty;
};

}  // namespace unsatmpm::numerics
