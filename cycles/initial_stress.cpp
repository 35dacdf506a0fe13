#include "cycles/initial_stress.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "cycles/three_phase_setup.hpp"
#include "physics/hydrostatic.hpp"

namespace unsatmpm {

namespace {

constexpr int table_intervals = 4096;

/// |g| and the unit vector along which elevation grows (against gravity).
template <int D>
double up_direction(const Case& c, numerics::Vec<D>& up) {
  double g2 = 0.0;
  for (int d = 0; d < D; ++d) g2 += c.gravity[d] * c.gravity[d];
  const double g = std::sqrt(g2);
  for (int d = 0; d < D; ++d) up[d] = -c.gravity[d] / g;
  return g;
}

/// The body's bulk density [kg/m^3] and pore pressure p* [Pa] at elevation z.
struct Column {
  const Case& c;
  const BodySpec& body;
  const physics::HydraulicModel* hm;  // null in a one-phase case
  double g;

  void at(double z, double& density, double& pore) const {
    const MaterialSpec& m = c.materials[body.material];
    if (!hm) {
      density = m.density, pore = 0.0;
      return;
    }
    const physics::PorePressures p = initial_pressures_at(*body.initial_pressures, *hm, g, z);
    const double n = m.hydraulic->porosity;
    const double s_l = hm->saturation(physics::retention_suction(p.liquid, p.gas));
    density = (1.0 - n) * m.hydraulic->solid_density + n * s_l * hm->liquid_density(p.liquid) +
              n * (1.0 - s_l) * hm->gas_density(p.gas);
    pore = std::max(p.liquid, p.gas);
  }
};

}  // namespace

template <int D>
void apply_k0_stresses(const Case& c, PointSet<D>& points) {
  auto& mp = points.points;
  numerics::Vec<D> up;
  const double g = up_direction<D>(c, up);
  const std::vector<physics::HydraulicModel> hydraulics =
      c.phases == Phases::solid_liquid_gas ? hydraulic_models(c)
                                           : std::vector<physics::HydraulicModel>{};
  for (std::size_t b = 0; b < c.bodies.size(); ++b) {
    const BodySpec& body = c.bodies[b];
    if (!body.k0) continue;
    // The top and bottom of the body's points' domains: the weight above a point is that of the
    // material the points carry, which fills whole sub-cells and so reaches past a box face that
    // lies between two rows of points (a box to 2.03 m on 0.1 m cells with two points a cell
    // carries mass to 2.05 m: measured from the box's face, every point's stress missed 0.02 m of
    // soil). On a box whose faces lie on the points' rows these are its faces.
    double top = -std::numeric_limits<double>::infinity(), bottom = -top;
    for (std::size_t p = 0; p < mp.size(); ++p) {
      if (points.body[p] != static_cast<int>(b)) continue;
      const double z = up.dot(mp.position[p]), half = up.cwiseAbs().dot(mp.half_size[p]);
      top = std::max(top, z + half), bottom = std::min(bottom, z - half);
    }
    if (!(top > bottom)) continue;  // a body without points
    const Column column{c, body, hydraulics.empty() ? nullptr : &hydraulics[body.material], g};
    // weight[k]: int_{z_k}^{top} rho g dz at z_k = top - k dz.
    const double dz = (top - bottom) / table_intervals;
    std::vector<double> weight(table_intervals + 1, 0.0);
    double rho_above, pore;
    column.at(top, rho_above, pore);
    for (int k = 1; k <= table_intervals; ++k) {
      double rho;
      column.at(top - k * dz, rho, pore);
      weight[k] = weight[k - 1] + 0.5 * (rho + rho_above) * g * dz;
      rho_above = rho;
    }
    for (std::size_t p = 0; p < mp.size(); ++p) {
      if (points.body[p] != static_cast<int>(b)) continue;
      const double z = up.dot(mp.position[p]);
      const double f = std::clamp((top - z) / dz, 0.0, double(table_intervals));
      const int k = std::min(static_cast<int>(f), table_intervals - 1);
      const double sigma_v = -(weight[k] + (f - k) * (weight[k + 1] - weight[k]));
      double rho;
      column.at(z, rho, pore);
      const double net_v = sigma_v + pore;
      physics::Vec6 s = physics::Vec6::Zero();
      for (int d = 0; d < 3; ++d) s[d] = *body.k0 * net_v;
      // The vertical axis: gravity points along one grid axis (parser).
      for (int d = 0; d < D; ++d)
        if (std::abs(up[d]) == 1.0) s[d] = net_v;
      mp.stress[p] = s;
    }
  }
}

#define UNSATMPM_INSTANTIATE(D) template void apply_k0_stresses<D>(const Case&, PointSet<D>&);
UNSATMPM_INSTANTIATE(1)
UNSATMPM_INSTANTIATE(2)
UNSATMPM_INSTANTIATE(3)
#undef UNSATMPM_INSTANTIATE

}  // namespace unsatmpm
