// The per-point face of each constitutive model, as overloads the hot loops are templated on.
//
// `stress_update(model, d_eps, suction, sigma, plastic_strain)` advances the stress of one material
// point by a strain increment; `suction` [Pa] is the point's current suction (0 in a one-phase
// case), which only the suction-dependent model reads. `wave_modulus(model)` is the constrained
// modulus K + 4G/3 [Pa] that sets the P-wave speed of the CFL limit. No virtual calls: the model
// type is fixed per material range.
#pragma once

#include <cmath>

#include "physics/linear_elastic.hpp"
#include "physics/mohr_coulomb.hpp"
#include "physics/suction_strength.hpp"

namespace unsatmpm::numerics {

inline void stress_update(const physics::LinearElastic& m, const physics::Vec6& d_eps,
                          double /*suction*/, physics::Vec6& sigma, double& /*plastic_strain*/) {
  m.add_elastic_increment(d_eps, sigma);
}

inline void stress_update(const physics::MohrCoulomb& m, const physics::Vec6& d_eps,
                          double /*suction*/, physics::Vec6& sigma, double& plastic_strain) {
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

inline double wave_modulus(const physics::LinearElastic& m) { return m.constrained_modulus(); }
inline double wave_modulus(const physics::MohrCoulomb& m) {
  return m.elastic.constrained_modulus();
}
inline double wave_modulus(const physics::SuctionMohrCoulomb& m) {
  return m.elastic().constrained_modulus();
}

/// The drained bulk modulus of the skeleton in D dimensions [Pa]: the volumetric stiffness the
/// fixed-stress split needs. 1D (uniaxial strain): K + 4G/3; 2D (plane strain): K + G/3; 3D: K.
template <int D>
inline double drained_bulk_modulus(const physics::LinearElastic& m) {
  const double k = m.bulk_modulus(), g = m.shear_modulus();
  return D == 1 ? k + 4.0 * g / 3.0 : (D == 2 ? k + g / 3.0 : k);
}
template <int D>
inline double drained_bulk_modulus(const physics::MohrCoulomb& m) {
  return drained_bulk_modulus<D>(m.elastic);
}
template <int D>
inline double drained_bulk_modulus(const physics::SuctionMohrCoulomb& m) {
  return drained_bulk_modulus<D>(m.elastic());
}

/// True if a point's net stress (Voigt, tension positive) [Pa] sits at the apex of its
/// Mohr-Coulomb cone at suction `suction` [Pa]: hydrostatic tension (deviator zero to round-off,
/// as an apex return leaves it) on or beyond the yield surface. There the skeleton's drained
/// tangent is zero: it expands under further tension, or pore pressure, without carrying it.
/// An elastic model has no apex.
inline bool at_apex(const physics::LinearElastic&, const physics::Vec6&, double) { return false; }
inline bool at_apex(const physics::MohrCoulombStrength& strength, const physics::Vec6& sigma) {
  const double mean = (sigma[0] + sigma[1] + sigma[2]) / 3.0;
  if (!(mean > 0.0)) return false;
  double deviator = 0.0;
  for (int d = 0; d < 3; ++d) deviator += std::abs(sigma[d] - mean) + std::abs(sigma[3 + d]);
  return deviator <= 1e-9 * mean &&
         physics::MohrCoulomb::yield_function(sigma, strength) >= -1e-9 * mean;
}
inline bool at_apex(const physics::MohrCoulomb& m, const physics::Vec6& sigma, double) {
  return at_apex(m.strength, sigma);
}
inline bool at_apex(const physics::SuctionMohrCoulomb& m, const physics::Vec6& sigma,
                    double suction) {
  return at_apex(m.strength.at(suction), sigma);
}

}  // namespace unsatmpm::numerics
