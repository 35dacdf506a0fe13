// Material points as columns: one contiguous std::vector per field (struct of arrays).
//
// Extensive quantities are per unit out-of-plane measure: in 2D (plane strain) per metre of
// thickness, in 1D per square metre of cross-section. So `volume` is m^D times that measure and
// `mass` is kg per the same measure. Stress and strain are full 6-component Voigt vectors in every
// dimension (plane strain and uniaxial strain keep sigma_zz).
#pragma once

#include <cstdint>
#include <vector>

#include "numerics/grid.hpp"
#include "numerics/shape_functions.hpp"
#include "physics/voigt.hpp"

namespace unsatmpm::numerics {

template <int D>
struct MaterialPoints {
  std::vector<std::int64_t> id;        // stable identifier, 0..n-1 at generation
  std::vector<int> material;           // index into the case's material list
  std::vector<Vec<D>> position;        // current position [m]
  std::vector<Vec<D>> displacement;    // position minus initial position [m]
  std::vector<Vec<D>> velocity;        // solid velocity [m/s]
  std::vector<Vec<D>> half_size;       // GIMP particle half-length per direction [m]
  std::vector<double> mass;            // [kg] (per unit out-of-plane measure)
  std::vector<double> volume;          // current volume [m^D]
  std::vector<physics::Vec6> stress;   // Cauchy stress [Pa], tension positive
  std::vector<physics::Vec6> strain;   // accumulated small strain (engineering shear) [-]
  std::vector<double> plastic_strain;  // accumulated deviatoric plastic strain [-]
  // Derived, not state: each point's GIMP kernels at its position (KernelMemo), filled by the
  // transfers; never written to output or checkpoints.
  mutable KernelMemo<D> kernel_memo;

  std::size_t size() const { return id.size(); }

  void reserve(std::size_t n) {
    id.reserve(n), material.reserve(n), position.reserve(n), displacement.reserve(n);
    velocity.reserve(n), half_size.reserve(n), mass.reserve(n), volume.reserve(n);
    stress.reserve(n), strain.reserve(n), plastic_strain.reserve(n);
  }

  /// Appends one point at rest with zero stress and strain.
  void push_back(int material_index, const Vec<D>& x, const Vec<D>& half, double m, double v) {
    id.push_back(static_cast<std::int64_t>(id.size()));
    material.push_back(material_index);
    position.push_back(x);
    displacement.push_back(Vec<D>::Zero());
    velocity.push_back(Vec<D>::Zero());
    half_size.push_back(half);
    mass.push_back(m);
    volume.push_back(v);
    stress.push_back(physics::Vec6::Zero());
    strain.push_back(physics::Vec6::Zero());
    plastic_strain.push_back(0.0);
  }
};

}  // namespace unsatmpm::numerics
