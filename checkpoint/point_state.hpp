// The material points' and their fluids' columns in a checkpoint (checkpoint/checkpoint_file.hpp):
// every column, scratch included, so that a resumed run starts from exactly the state the
// interrupted one had.
#pragma once

#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"

namespace unsatmpm {

template <int D>
void save_points(CheckpointWriter& w, const std::string& prefix,
                 const numerics::MaterialPoints<D>& mp) {
  w.put(prefix + "id", mp.id);
  w.put(prefix + "material", mp.material);
  w.put(prefix + "position", mp.position);
  w.put(prefix + "displacement", mp.displacement);
  w.put(prefix + "velocity", mp.velocity);
  w.put(prefix + "half_size", mp.half_size);
  w.put(prefix + "mass", mp.mass);
  w.put(prefix + "volume", mp.volume);
  w.put(prefix + "stress", mp.stress);
  w.put(prefix + "strain", mp.strain);
  w.put(prefix + "plastic_strain", mp.plastic_strain);
}

/// Reads the columns into `mp`, which holds the case's points: their count must match.
template <int D>
void restore_points(CheckpointReader& r, const std::string& prefix,
                    numerics::MaterialPoints<D>& mp) {
  const std::size_t n = mp.size();
  r.get_sized(prefix + "id", mp.id, n);
  r.get_sized(prefix + "material", mp.material, n);
  r.get_sized(prefix + "position", mp.position, n);
  r.get_sized(prefix + "displacement", mp.displacement, n);
  r.get_sized(prefix + "velocity", mp.velocity, n);
  r.get_sized(prefix + "half_size", mp.half_size, n);
  r.get_sized(prefix + "mass", mp.mass, n);
  r.get_sized(prefix + "volume", mp.volume, n);
  r.get_sized(prefix + "stress", mp.stress, n);
  r.get_sized(prefix + "strain", mp.strain, n);
  r.get_sized(prefix + "plastic_strain", mp.plastic_strain, n);
}

template <int D>
void save_fluids(CheckpointWriter& w, const std::string& prefix,
                 const numerics::FluidPoints<D>& fp) {
  w.put(prefix + "porosity", fp.porosity);
  w.put(prefix + "liquid_pressure", fp.liquid_pressure);
  w.put(prefix + "gas_pressure", fp.gas_pressure);
  w.put(prefix + "saturation", fp.saturation);
  w.put(prefix + "liquid_density", fp.liquid_density);
  w.put(prefix + "gas_density", fp.gas_density);
  w.put(prefix + "liquid_velocity", fp.liquid_velocity);
  w.put(prefix + "gas_velocity", fp.gas_velocity);
  w.put(prefix + "liquid_rate", fp.liquid_rate);
  w.put(prefix + "gas_rate", fp.gas_rate);
  w.put(prefix + "liquid_increment", fp.liquid_increment);
  w.put(prefix + "gas_increment", fp.gas_increment);
  w.put(prefix + "storage", fp.storage);
  w.put(prefix + "volumetric_strain_increment", fp.volumetric_strain_increment);
}

/// Reads the columns into `fp`; each must hold `n` points (0 for a one-phase run).
template <int D>
void restore_fluids(CheckpointReader& r, const std::string& prefix, numerics::FluidPoints<D>& fp,
                    std::size_t n) {
  r.get_sized(prefix + "porosity", fp.porosity, n);
  r.get_sized(prefix + "liquid_pressure", fp.liquid_pressure, n);
  r.get_sized(prefix + "gas_pressure", fp.gas_pressure, n);
  r.get_sized(prefix + "saturation", fp.saturation, n);
  r.get_sized(prefix + "liquid_density", fp.liquid_density, n);
  r.get_sized(prefix + "gas_density", fp.gas_density, n);
  r.get_sized(prefix + "liquid_velocity", fp.liquid_velocity, n);
  r.get_sized(prefix + "gas_velocity", fp.gas_velocity, n);
  r.get_sized(prefix + "liquid_rate", fp.liquid_rate, n);
  r.get_sized(prefix + "gas_rate", fp.gas_rate, n);
  r.get_sized(prefix + "liquid_increment", fp.liquid_increment, n);
  r.get_sized(prefix + "gas_increment", fp.gas_increment, n);
  r.get_sized(prefix + "storage", fp.storage, n);
  r.get_sized(prefix + "volumetric_strain_increment", fp.volumetric_strain_increment, n);
}

}  // namespace unsatmpm
