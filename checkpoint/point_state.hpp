// The material points' and their fluids' columns in a checkpoint (checkpoint/checkpoint_file.hpp):
// every column, scratch included, so that a resumed run starts from exactly the state the
// interrupted one had. One list per struct names the columns for both directions.
#pragma once

#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/material_points.hpp"

namespace unsatmpm {

/// f(name, column) for every column of the points (`Points` a MaterialPoints, const or not).
template <class Points, class F>
void for_each_point_column(Points& mp, F&& f) {
  f("id", mp.id), f("material", mp.material), f("position", mp.position);
  f("displacement", mp.displacement), f("velocity", mp.velocity), f("half_size", mp.half_size);
  f("mass", mp.mass), f("volume", mp.volume), f("stress", mp.stress), f("strain", mp.strain);
  f("plastic_strain", mp.plastic_strain);
}

/// f(name, column) for every column of the fluids (`Fluids` a FluidPoints, const or not).
template <class Fluids, class F>
void for_each_fluid_column(Fluids& fp, F&& f) {
  f("porosity", fp.porosity), f("liquid_pressure", fp.liquid_pressure);
  f("gas_pressure", fp.gas_pressure), f("saturation", fp.saturation);
  f("liquid_density", fp.liquid_density), f("gas_density", fp.gas_density);
  f("liquid_velocity", fp.liquid_velocity), f("gas_velocity", fp.gas_velocity);
  f("liquid_rate", fp.liquid_rate), f("gas_rate", fp.gas_rate);
  f("liquid_increment", fp.liquid_increment), f("gas_increment", fp.gas_increment);
  f("storage", fp.storage), f("volumetric_strain_increment", fp.volumetric_strain_increment);
  f("liquid_shortfall", fp.liquid_shortfall), f("gas_shortfall", fp.gas_shortfall);
}

template <int D>
void save_points(CheckpointWriter& w, const std::string& prefix,
                 const numerics::MaterialPoints<D>& mp) {
  for_each_point_column(
      mp, [&](const char* name, const auto& column) { w.put(prefix + name, column); });
}

/// Reads the columns into `mp`, which holds the case's points: their count must match.
template <int D>
void restore_points(CheckpointReader& r, const std::string& prefix,
                    numerics::MaterialPoints<D>& mp) {
  const std::size_t n = mp.size();
  for_each_point_column(
      mp, [&](const char* name, auto& column) { r.get_sized(prefix + name, column, n); });
}

template <int D>
void save_fluids(CheckpointWriter& w, const std::string& prefix,
                 const numerics::FluidPoints<D>& fp) {
  for_each_fluid_column(
      fp, [&](const char* name, const auto& column) { w.put(prefix + name, column); });
}

/// Reads the columns into `fp`; each must hold `n` points (0 for a one-phase run).
template <int D>
void restore_fluids(CheckpointReader& r, const std::string& prefix, numerics::FluidPoints<D>& fp,
                    std::size_t n) {
  for_each_fluid_column(
      fp, [&](const char* name, auto& column) { r.get_sized(prefix + name, column, n); });
}

}  // namespace unsatmpm
