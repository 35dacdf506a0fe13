// K0 initial stresses (docs/input.md, "bodies"): a body with a horizontal top surface, at rest
// under gravity with nothing above it, starts in equilibrium instead of being loaded.
//
// With elevation z measured against gravity (physics/hydrostatic.hpp) and z_s the body's top:
//   total vertical stress  sigma_v(z) = -int_z^z_s rho(z') |g| dz'   (tension positive)
//   net vertical stress    sigma_bar_v = sigma_v + p*(z),  p* = max(P_l, P_g) (three phases)
//   horizontal             sigma_bar_h = K0 sigma_bar_v,  no shear,
// rho the bulk density: the material's in a one-phase case, the mixture's
// (1 - n) rho_s + n S_l rho_l + n (1 - S_l) rho_g at the body's initial pressures (uniform or
// about its water table) in a three-phase case. The integral is taken on a fine table (trapezoid
// rule, 4096 intervals over the body's height: relative error below 1e-7 for the curves here)
// and interpolated linearly at each point's elevation. Where it applies: bodies whose top is
// horizontal (a box, with gravity along a grid axis: the parser checks it) and carries no other
// body; sigma_bar_h = K0 sigma_bar_v balances only where the sides are held laterally (rollers,
// or a body wide enough that its edges are far away). Points of the other bodies are untouched.
#pragma once

#include "cycles/setup.hpp"
#include "input/case.hpp"

namespace unsatmpm {

/// Sets the net stress of the points of every body that gives `initial_stress.k0`.
template <int D>
void apply_k0_stresses(const Case& c, PointSet<D>& points);

}  // namespace unsatmpm
