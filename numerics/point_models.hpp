// The per-point face of each constitutive model, as overloads the hot loops are templated on.
//
// `stress_update(model, d_eps, suction, sigma, plastic_strain)` advances the stress of one material
// point by a strain increment; `suction` [Pa] is the point's current suction (0 in a one-phase
// case), which only the suction-dependent model reads, either as a number or as a HeldSuction,
// whose memo keeps the strength prepared at it while it holds. `wave_modulus(model)` is the
// constrained modulus K + 4G/3 [Pa] that sets the P-wave speed of the CFL limit. No virtual calls:
// the model type is fixed per material range.
#pragma once

#include <cmath>
#include <limits>

#include "physics/linear_elastic.hpp"
#include "physics/mohr_coulomb.hpp"
#include "physics/scheme.hpp"
#include "physics/suction_strength.hpp"

namespace unsatmpm::numerics {

/// A point's suction-dependent strength, prepared at the suction it was prepared for
/// (physics::PreparedStrength): the main cycle holds each point's suction, for the strength, over
/// a coupling interval of hundreds of sub-steps, so the strength's exponential and trigonometry are
/// evaluated once per interval instead of at every sub-step (docs/performance.md). Keyed by the
/// exact suction: a memo can never serve another.
struct StrengthMemo {
  double suction = std::numeric_limits<double>::quiet_NaN();
  physics::PreparedStrength strength{};
};

/// A point's suction [Pa] with its strength memo.
struct HeldSuction {
  double suction;
  StrengthMemo& memo;
};

template <class Suction>
inline void stress_update(const physics::LinearElastic& m, const physics::Vec6& d_eps,
                          const Suction& /*suction*/, physics::Vec6& sigma,
                          double& /*plastic_strain*/) {
  m.add_elastic_increment(d_eps, sigma);
}

template <class Suction>
inline void stress_update(const physics::MohrCoulomb& m, const physics::Vec6& d_eps,
                          const Suction& /*suction*/, physics::Vec6& sigma,
                          double& plastic_strain) {
  physics::MohrCoulombState state{plastic_strain};
  m.update(d_eps, sigma, state);
  plastic_strain = state.deviatoric_plastic_strain;
}

inline void stress_update(const physics::SuctionMohrCoulomb& m, const physics::Vec6& d_eps,
                          double suction, physics::Vec6& sigma, double& plastic_strain) {
  physics::MohrCoulombState state{plastic_strain};
  m.update(d_eps, suction, sigma, state);
  plastic_strain = state.deviatoric_plastic_strain;
}

inline void stress_update(const physics::SuctionMohrCoulomb& m, const physics::Vec6& d_eps,
                          const HeldSuction& held, physics::Vec6& sigma, double& plastic_strain) {
  if (!(held.memo.suction == held.suction)) held.memo = {held.suction, m.prepared(held.suction)};
  physics::MohrCoulombState state{plastic_strain};
  m.update(d_eps, held.memo.strength, sigma, state);
  plastic_strain = state.deviatoric_plastic_strain;
}

/// The P-wave (constrained) modulus of a skeleton model's elasticity [Pa].
template <class Model>
double wave_modulus(const Model& m) {
  return physics::elastic_of(m).constrained_modulus();
}

/// The drained bulk modulus of the skeleton in D dimensions [Pa]: the volumetric stiffness the
/// fixed-stress split needs. 1D (uniaxial strain): K + 4G/3; 2D (plane strain): K + G/3; 3D: K.
template <int D, class Model>
double drained_bulk_modulus(const Model& model) {
  const physics::LinearElastic& m = physics::elastic_of(model);
  const double k = m.bulk_modulus(), g = m.shear_modulus();
  return D == 1 ? k + 4.0 * g / 3.0 : (D == 2 ? k + g / 3.0 : k);
}

}  // namespace unsatmpm::numerics
