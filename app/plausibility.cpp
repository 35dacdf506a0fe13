#include "app/plausibility.hpp"

#include <fmt/core.h>

#include "physics/scheme.hpp"

namespace unsatmpm {

std::vector<std::string> implausible_parameters(const Case& c) {
  constexpr double e_min = 1e4, e_max = 1e12, rho_min = 100.0, rho_max = 2e4, kappa_max = 1e-7;
  std::vector<std::string> out;
  for (std::size_t m = 0; m < c.materials.size(); ++m) {
    const MaterialSpec& mat = c.materials[m];
    const std::string key = fmt::format("materials[{}] ('{}')", m, mat.name);
    const double e = physics::elastic_of(mat.model).young_modulus;
    if (e < e_min || e > e_max)
      out.push_back(fmt::format(
          "{}.young_modulus = {:g} Pa lies outside [{:g}, {:g}] Pa, the range of soils and rocks: "
          "is it in Pa (10 MPa is 1.0e+7)?",
          key, e, e_min, e_max));
    const bool grains = mat.hydraulic.has_value();
    const double rho = grains ? mat.hydraulic->solid_density : mat.density;
    if (rho < rho_min || rho > rho_max)
      out.push_back(fmt::format(
          "{}.{} = {:g} kg/m^3 lies outside [{:g}, {:g}] kg/m^3: is it in kg/m^3 (2.7 g/cm^3 is "
          "2700)?",
          key, grains ? "solid_density" : "density", rho, rho_min, rho_max));
    if (grains && mat.hydraulic->intrinsic_permeability > kappa_max)
      out.push_back(fmt::format(
          "{}.intrinsic_permeability = {:g} m^2 exceeds {:g} m^2 (a gravel's is about 1e-9): "
          "kappa is the intrinsic permeability in m^2, not the hydraulic conductivity in m/s "
          "(K = 1e-5 m/s of water at 20 C is kappa = K mu / (rho g) = 1.0e-12 m^2)",
          key, mat.hydraulic->intrinsic_permeability, kappa_max));
  }
  return out;
}

}  // namespace unsatmpm
