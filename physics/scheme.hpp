// The choices of formulation a case makes once (docs/balance_laws.md, docs/models.md), one type
// each, shared by the input, the cycles and the numerics.
#pragma once

#include <type_traits>
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

/// A choice as a compile-time constant (std::integral_constant): with_mass_balance and
/// with_skeleton make a case's choice once, at the cycle, and the hot loops of numerics/ are
/// compiled for it instead of testing it per point.
template <auto V>
using Choice = std::integral_constant<decltype(V), V>;

template <class F>
decltype(auto) with_mass_balance(MassBalance form, F&& f) {
  if (form == MassBalance::full) return f(Choice<MassBalance::full>{});
  return f(Choice<MassBalance::simplified>{});
}

template <class F>
decltype(auto) with_skeleton(Skeleton skeleton, F&& f) {
  if (skeleton == Skeleton::deformable) return f(Choice<Skeleton::deformable>{});
  return f(Choice<Skeleton::rigid>{});
}

/// A material's constitutive model of the solid skeleton.
using SolidModel = std::variant<LinearElastic, MohrCoulomb, SuctionMohrCoulomb>;

/// The elasticity of a skeleton model.
inline const LinearElastic& elastic_of(const LinearElastic& m) { return m; }
inline const LinearElastic& elastic_of(const MohrCoulomb& m) { return m.elastic; }
inline const LinearElastic& elastic_of(const SuctionMohrCoulomb& m) { return m.elastic(); }
inline const LinearElastic& elastic_of(const SolidModel& m) {
  return std::visit([](const auto& x) -> const LinearElastic& { return elastic_of(x); }, m);
}

}  // namespace unsatmpm::physics
