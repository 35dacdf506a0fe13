// The choices of formulation a case makes once (docs/balance_laws.md, docs/models.md), one type
// each, shared by the input, the cycles and the numerics.
#pragma once

#include <variant>

#include "physics/linear_elastic.hpp"
#include "physics/mohr_coulomb.hpp"
#include "physics/suction_strength.hpp"

namespace unsatmpm::physics {

/// Form of the fluid mass balances: `full` keeps the advective term (v_a - v_s) . grad(n S_a
/// rho_a), `simplified` drops it (the paper's eqs. 11-12).
enum class MassBalance { full, simplified };

/// The solid skeleton: deformable, or rigid (flow only: the solid never moves).
enum class Skeleton { deformable, rigid };

/// Index of a pore fluid in per-fluid arrays.
enum Fluid : int { liquid_phase = 0, gas_phase = 1 };

/// A material's constitutive model of the solid skeleton.
using SolidModel = std::variant<LinearElastic, MohrCoulomb, SuctionMohrCoulomb>;

}  // namespace unsatmpm::physics
