// The main cycle's two-way coupling (cycles/implicit_solver.hpp, docs/balance_laws.md "Two-way
// coupling"): the pore pressures follow the skeleton's volume change at every mechanics sub-step,
// and the water and gas the flow moved over the interval reach the points over its sub-steps.
//
// Over an interval [t, t + dt] a point gains dm of each fluid from the flow (measured on the
// flow's own field, record_flow), a share h / dt of it at each sub-step of length h. At each
// sub-step its pore volume also changed by dV (the solid volume V_s kept), and the pressure
// response to that, V A dP = -S_a rho_a dV (A the storage matrix n d(S_a rho_a)/dP_b), is solved,
// as the explicit cycle's nodal update does (numerics::nodal_pressure_increments), at the nodes:
// M_i dP_i = sum_p N_i q_p with M_i = sum_p N_i V_p A_p, and dP_p = sum_i N_i dP_i. So a skeleton
// that a load compresses faster than the water can leave raises the pore pressure (the undrained
// response) and dilating pores lower it. The nodes whose pressure the flow prescribes
// (boundaries, the free surface, nodes free of gas) hold it here too: the water a compression
// drives out there leaves through the boundary and is counted. Solving the volume change at the
// nodes gives a continuous increment: with linear shape functions dV is one value per cell, and a
// pressure solved point by point would split the points of a cell (measured: 600 Pa between the
// two points of a base cell of a consolidating column, the flow's own change across them being
// 0.3 Pa). The flow's share joins that nodal solve where the liquid governs (P_l >= P_g); where
// the gas governs it goes to the point directly (flow_share_at_nodes says why). Each point then
// holds its old mass plus what the solve assigned it plus its direct share, and its pressures are
// those that hold that mass in its pore volume (physics::pressures_from_contents). The gas a
// desaturation takes where P_g is held is supplied and counted as inflow (docs/balance_laws.md,
// "Saturated soil").
#pragma once

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "cycles/fixed_stress.hpp"
#include "cycles/setup.hpp"
#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/three_phase_g2p.hpp"
#include "physics/fluid_contents.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm {

/// Per point, over one coupling interval: what the mechanics needs of the fluids
/// (numerics::PoreLoads, rewritten at every sub-step), the flow's mass changes, and the nodal
/// scratch of the undrained update.
struct UndrainedPoints {
  std::vector<double> solid_volume;              // V_s = (1 - n) V [m^3], constant
  std::vector<double> last_volume;               // V at the end of the last sub-step [m^3]
  std::array<std::vector<double>, 2> flow_mass;  // dm of the interval's flow [kg]
  std::array<std::vector<double>, 2> old_mass;   // scratch: each fluid's mass at a sub-step's start
  std::vector<double> added, pore, suction, max_volume;  // numerics::PoreLoads' columns
  std::vector<std::vector<double>> mass_balance;         // per thread, 6 sums per node
  // Per fluid, 1 at the nodes whose pressure the flow prescribes this interval (boundaries, the
  // free surface, and for the gas the nodes free of gas): the mechanics holds them too.
  std::array<std::vector<std::uint8_t>, 2> held;

  numerics::PoreLoads view() const { return {added, pore, suction, max_volume}; }
};

/// A point's liquid and gas masses n V S_a rho_a [kg].
template <int D>
std::array<double, 2> point_fluid_masses(const numerics::MaterialPoints<D>& mp,
                                         const numerics::FluidPoints<D>& fp, std::size_t p) {
  const double nv = fp.porosity[p] * mp.volume[p];
  return {nv * fp.saturation[p] * fp.liquid_density[p],
          nv * (1.0 - fp.saturation[p]) * fp.gas_density[p]};
}

/// Starts an interval at the points' current state: solid volumes and the pore loads of the first
/// sub-step (the suction, for the strength, is held over the interval). `ranges` splits the points
/// by material, as `models`. The held nodes are the flow's, set after its integration.
template <int D>
void begin_undrained_interval(const numerics::Grid<D>& grid, const numerics::MaterialPoints<D>& mp,
                              const numerics::FluidPoints<D>& fp,
                              const std::vector<physics::HydraulicModel>& models,
                              const std::vector<std::int64_t>& ranges, int n_threads,
                              UndrainedPoints& u) {
  const std::size_t n = mp.size();
  u.solid_volume.resize(n), u.added.resize(n), u.pore.resize(n);
  u.suction.resize(n), u.max_volume.resize(n);
  u.last_volume = mp.volume;
  for (auto& v : u.flow_mass) v.assign(n, 0.0);
  for (auto& v : u.old_mass) v.resize(n);
  for (std::size_t m = 0; m < models.size(); ++m)
    for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
      const auto masses = point_fluid_masses<D>(mp, fp, p);
      u.solid_volume[p] = (1.0 - fp.porosity[p]) * mp.volume[p];
      u.added[p] = masses[0] + masses[1];
      u.pore[p] = std::max(fp.liquid_pressure[p], fp.gas_pressure[p]);
      u.suction[p] = physics::suction(fp.liquid_pressure[p], fp.gas_pressure[p]);
      u.max_volume[p] = models[m].max_volume(mp.mass[p]);
    }
  u.mass_balance.assign(n_threads, std::vector<double>(6 * grid.n_nodes(), 0.0));
}

/// Adds to dm what one integration of the flow moved at each point, measured on the flow's own
/// field as the flow stores it: n V (c(P_end) - c(P_start)) with c the contents
/// (physics::fluid_contents) and P the nodal start and end fields at the point, plus the
/// fixed-stress storage the flow counted, V (extra . (P_end - P_start)) (cycles/fixed_stress.hpp).
/// Summed over the points this is the flow's own mass change (the lumped storage is the points'),
/// so the points gain exactly what entered through the boundaries, whatever their own pressures
/// (which the fit approximates; a point across a wetting front or in a dynamic pressure wave can
/// differ from it).
template <int D>
void record_flow(const numerics::MaterialPoints<D>& mp, const numerics::FluidPoints<D>& fp,
                 const std::vector<physics::HydraulicModel>& models,
                 const std::array<std::vector<double>, 2>& start,
                 const std::array<std::vector<double>, 2>& end,
                 const std::vector<physics::StorageMatrix>& extra, UndrainedPoints& u) {
  for (std::size_t p = 0; p < mp.size(); ++p) {
    const physics::HydraulicModel& hm = models[mp.material[p]];
    const auto [cl0, cg0] = physics::fluid_contents(hm, start[0][p], start[1][p]);
    const auto [cl1, cg1] = physics::fluid_contents(hm, end[0][p], end[1][p]);
    const double nv = fp.porosity[p] * mp.volume[p];
    const double dl = end[0][p] - start[0][p], dg = end[1][p] - start[1][p];
    u.flow_mass[0][p] += nv * (cl1 - cl0) + mp.volume[p] * (extra[p].ll * dl + extra[p].lg * dg);
    u.flow_mass[1][p] += nv * (cg1 - cg0) + mp.volume[p] * (extra[p].gl * dl + extra[p].gg * dg);
  }
}

/// A point's undrained stiffness K_u = |dp*/d eps_v| [Pa] from its storage matrix `a` (porosity n
/// included), saturation and densities: with its masses kept, d c_a = -(c_a / n) d eps_v for the
/// contents c_a per pore volume, so A dP = -(S_a rho_a) d eps_v; p* is the liquid's pressure where
/// P_l >= P_g, else the gas's. With `gas_held` (or no gas storage) only the liquid responds.
inline double undrained_stiffness(const physics::StorageMatrix& a, double s_l, double rho_l,
                                  double rho_g, bool liquid_governs, bool gas_held) {
  const double cl = s_l * rho_l, cg = (1.0 - s_l) * rho_g;
  double dpl = 0.0, dpg = 0.0;
  if (gas_held || !(a.gg > 0.0)) {
    dpl = a.ll > 0.0 ? cl / a.ll : 0.0;
  } else {
    const double det = a.ll * a.gg - a.lg * a.gl;
    dpl = (a.gg * cl - a.lg * cg) / det;
    dpg = (a.ll * cg - a.gl * cl) / det;
  }
  return std::abs(liquid_governs ? dpl : dpg);
}

/// The same at pressures (p_l, p_g) and porosity n.
inline double undrained_stiffness(const physics::HydraulicModel& hm, double n, double p_l,
                                  double p_g, bool gas_held) {
  const double s_l = hm.saturation(physics::suction(p_l, p_g));
  return undrained_stiffness(hm.storage(n, p_l, p_g), s_l, hm.liquid_density(p_l),
                             hm.gas_density(p_g), p_l >= p_g, gas_held);
}

/// max_p sqrt((M + K_u) V / m_s) + |v_p| [m/s] at the points' current state (the step of the
/// first sub-step; undrained_update reports it after each).
template <int D>
double undrained_wave_speed(const numerics::MaterialPoints<D>& mp,
                            const numerics::FluidPoints<D>& fp,
                            const std::vector<physics::HydraulicModel>& models,
                            const std::vector<double>& moduli,
                            const std::vector<std::int64_t>& ranges) {
  double c2 = 0.0, v2 = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m)
    for (auto p = ranges[m]; p < ranges[m + 1]; ++p) {
      const bool held = 1.0 - fp.saturation[p] <= physics::gas_free_saturation;
      const double k_u = undrained_stiffness(models[m], fp.porosity[p], fp.liquid_pressure[p],
                                             fp.gas_pressure[p], held);
      c2 = std::max(c2, (moduli[m] + k_u) * mp.volume[p] / mp.mass[p]);
      v2 = std::max(v2, mp.velocity[p].squaredNorm());
    }
  return std::sqrt(c2) + std::sqrt(v2);
}

/// The fraction of the stable interval bound that a coupling interval may take
/// (stable_coupling_interval). Measured on a saturated column loaded at its top (kappa = 1e-12 m^2,
/// K_l = 2 GPa, h = 0.05 m, K_u / K_dr = 370: bound 5e-4 s): intervals of 0.05 to 0.4 ms gave the
/// same pressures to 1e-4 of the load, 1 ms blew up. docs/balance_laws.md, "Two-way coupling".
inline constexpr double coupling_stability_fraction = 0.25;

/// The longest stable coupling interval [s] at the points' current state. The flow moves water as
/// if the skeleton followed at once (its fixed-stress storage 1/K_dr); the mechanics feels what the
/// skeleton did not follow through the undrained stiffness K_u = |dp*/d eps_v|
/// (undrained_stiffness). A pressure difference across a cell relaxes in the flow within
/// h^2 / D_fs, D_fs = (kappa k_r / mu) / (1/K_u + 1/K_dr), and the water it moves comes back as a
/// pressure K_u / K_dr times larger if the skeleton has not followed: where K_u > K_dr an interval
/// must stay below h^2 / (D_fs K_u / K_dr), and where K_u <= K_dr no bound applies (unsaturated
/// soil, or a point whose pore pressure is a held gas pressure). Returns
/// coupling_stability_fraction times the smallest bound over the points, with h the smallest grid
/// spacing, k_r and mu those of the fluid whose pressure p* is, and K_dr the split's
/// (split_drained_modulus); infinite where no point is bound.
template <int D>
double stable_coupling_interval(const std::vector<SolidModel>& solids, const PointSet<D>& points,
                                const numerics::FluidPoints<D>& fp,
                                const std::vector<physics::HydraulicModel>& models,
                                double min_spacing) {
  double bound = std::numeric_limits<double>::infinity();
  for (std::size_t m = 0; m < models.size(); ++m)
    std::visit(
        [&](const auto& solid) {
          const physics::HydraulicModel& hm = models[m];
          for (auto p = points.ranges[m]; p < points.ranges[m + 1]; ++p) {
            const double pl = fp.liquid_pressure[p], pg = fp.gas_pressure[p];
            const bool held = 1.0 - fp.saturation[p] <= physics::gas_free_saturation;
            const double k_u = undrained_stiffness(hm, fp.porosity[p], pl, pg, held);
            const double s = physics::suction(pl, pg);
            const double k_dr = split_drained_modulus<D>(solid, points.points.stress[p], s);
            if (!(k_u > k_dr)) continue;
            const double se = hm.effective_saturation(s);
            const double mobility =
                hm.intrinsic_permeability *
                (pl >= pg ? hm.liquid_relative_permeability_value(se) / hm.liquid_viscosity
                          : hm.gas_relative_permeability_value(se) / hm.gas_viscosity);
            if (!(mobility > 0.0)) continue;
            const double d_fs = mobility / (1.0 / k_u + 1.0 / k_dr);
            bound = std::min(bound, min_spacing * min_spacing * k_dr / (d_fs * k_u));
          }
        },
        solids[m]);
  return coupling_stability_fraction * bound;
}

/// What one undrained update reports.
struct UndrainedReport {
  double max_wave_speed = 0.0;  // max_p sqrt((M + K_u) V / m_s) + |v_p| [m/s]
  std::int64_t first_bad = -1;  // a point whose state is not finite, or whose pores vanished
  // Mass entering at the held nodes and points, per fluid [kg per out-of-plane measure]: water
  // a compression drives out through a drained boundary, gas a desaturation takes.
  std::array<double, 2> supplied{0.0, 0.0};
};

/// Whether a point's share of the flow joins the nodal solve (where the liquid governs,
/// P_l >= P_g: the point's storage is then the liquid's compressibility, and a share given to it
/// alone, measured on a fitted field whose storage can differ from the point's by orders of
/// magnitude across the saturation kink, raised crest points of the embankment at S_max to
/// 1-3 MPa) or goes to the point itself (the gas governs: the storage is soft and smooth, and
/// through the nodal solve the share of a point beside a held node left there, see the header).
inline bool flow_share_at_nodes(double p_l, double p_g) { return p_l >= p_g; }

/// The pressure increments (dP_l, dP_g) with A dP = (q_l, q_g) [kg/m^3]: the 2 x 2 solve, or the
/// liquid's alone where the gas is held or has no storage.
inline std::pair<double, double> flow_increment(const physics::StorageMatrix& a, double q_l,
                                                double q_g, bool gas_held) {
  const double det = a.ll * a.gg - a.lg * a.gl;
  if (gas_held || !(a.gg > 0.0) || !(std::abs(det) > 0.0))
    return {a.ll > 0.0 ? q_l / a.ll : 0.0, 0.0};
  return {(a.gg * q_l - a.lg * q_g) / det, (a.ll * q_g - a.gl * q_l) / det};
}

/// One sub-step's pore pressures (see the header): each point's volume change since the last
/// sub-step and, where the liquid governs, the share `share` = h / dt of the flow's mass changes,
/// solved at the nodes; elsewhere that share given to the point; then each point's pressures
/// from the mass it holds. Updates
/// porosity (1 - V_s / V), pressures, saturation, densities and the pore loads of the next
/// sub-step; reports the mixture's wave speed with each point's undrained stiffness added to its
/// skeleton's modulus `moduli[m]`.
template <int D, class K>
UndrainedReport undrained_update(const numerics::Grid<D>& grid,
                                 const numerics::MaterialPoints<D>& mp,
                                 const std::vector<physics::HydraulicModel>& models,
                                 const std::vector<double>& moduli,
                                 const std::vector<std::int64_t>& ranges, double share,
                                 int n_threads, numerics::FluidPoints<D>& fp, UndrainedPoints& u) {
  // Each point's storage and the mass its volume change asks, as rates of a unit step; its
  // undrained stiffness at the same state sets the wave speed of the next sub-step.
  double max_c2 = 0.0, max_v2 = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const physics::HydraulicModel& hm = models[m];
    const double modulus = moduli[m];
#pragma omp parallel for num_threads(n_threads) schedule(static) reduction(max : max_c2, max_v2)
    for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p) {
      const double dv = mp.volume[p] - u.last_volume[p];
      const double s_l = fp.saturation[p], pl = fp.liquid_pressure[p], pg = fp.gas_pressure[p];
      const double cl = s_l * fp.liquid_density[p], cg = (1.0 - s_l) * fp.gas_density[p];
      const double pores = u.last_volume[p] - u.solid_volume[p];
      u.old_mass[0][p] = pores * cl, u.old_mass[1][p] = pores * cg;
      const physics::StorageMatrix a = fp.storage[p] = hm.storage(fp.porosity[p], pl, pg);
      // Where the liquid governs (P_l >= P_g) the flow's share joins the nodal solve; where the
      // gas does, it goes to the point (flow_share_at_nodes).
      const double nodal = flow_share_at_nodes(pl, pg) ? share : 0.0;
      fp.liquid_rate[p] = (nodal * u.flow_mass[0][p] - cl * dv) / mp.volume[p];
      fp.gas_rate[p] = (nodal * u.flow_mass[1][p] - cg * dv) / mp.volume[p];
      const double k_u = undrained_stiffness(a, s_l, fp.liquid_density[p], fp.gas_density[p],
                                             pl >= pg, 1.0 - s_l <= physics::gas_free_saturation);
      max_c2 = std::max(max_c2, (modulus + k_u) * mp.volume[p] / mp.mass[p]);
      max_v2 = std::max(max_v2, mp.velocity[p].squaredNorm());
    }
  }
  UndrainedReport r;
  // At the held nodes, what the linear balance could not place there enters or leaves.
  r.supplied = numerics::nodal_pressure_increments<D, K>(grid, mp, 1.0, u.mass_balance,
                                                         {&u.held[0], &u.held[1]}, fp);
  // Each point takes the mass the nodal solve assigned it, V A dP + c dV (these sum to the old
  // masses plus the nodal shares, exactly), plus its direct share, and its pressures are those
  // that hold that mass in its new pore volume (physics::pressures_from_contents, from the
  // linear increment as the start): conservative, and right across the saturation kink, where the
  // storage jumps and a linear step would overshoot. A point free of gas holds its gas pressure and
  // takes the gas its state holds; the difference is supplied (counted as inflow).
  double supplied = 0.0;
  std::int64_t bad = std::numeric_limits<std::int64_t>::max();
  for (std::size_t m = 0; m < models.size(); ++m) {
    const physics::HydraulicModel& hm = models[m];
#pragma omp parallel for num_threads(n_threads) schedule(static) reduction(min : bad) \
    reduction(+ : supplied)
    for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p) {
      const double dl = fp.liquid_increment[p], dg = fp.gas_increment[p];
      const double dv = mp.volume[p] - u.last_volume[p];
      const physics::StorageMatrix& a = fp.storage[p];
      const double s_l0 = fp.saturation[p];
      const double own =
          flow_share_at_nodes(fp.liquid_pressure[p], fp.gas_pressure[p]) ? 0.0 : share;
      const double fl = own * u.flow_mass[0][p], fg = own * u.flow_mass[1][p];
      const double ml = u.old_mass[0][p] + mp.volume[p] * (a.ll * dl + a.lg * dg) +
                        s_l0 * fp.liquid_density[p] * dv + fl;
      const double mg = u.old_mass[1][p] + mp.volume[p] * (a.gl * dl + a.gg * dg) +
                        (1.0 - s_l0) * fp.gas_density[p] * dv + fg;
      const double pores = mp.volume[p] - u.solid_volume[p];
      bool held = 1.0 - s_l0 <= physics::gas_free_saturation || !(mg > 0.0);
      // The flow's share, as the linear start of the inversion: A dP = (fl, fg) / V.
      const auto [fdl, fdg] = flow_increment(a, fl / mp.volume[p], fg / mp.volume[p], held);
      double pl = fp.liquid_pressure[p] + dl + fdl, pg = fp.gas_pressure[p] + dg + fdg;
      bool found = pores > 0.0 &&
                   physics::pressures_from_contents(hm, ml / pores, mg / pores, held, pl, pg) >= 0;
      if (!found && !held && pores > 0.0) {  // a gas the linear step emptied: hold it instead
        pl = fp.liquid_pressure[p] + dl + fdl, pg = fp.gas_pressure[p] + dg;
        held = true;
        found = physics::pressures_from_contents(hm, ml / pores, 0.0, true, pl, pg) >= 0;
      }
      if (!found || !std::isfinite(pl + pg)) {
        bad = std::min(bad, p);
        continue;
      }
      const double n = pores / mp.volume[p];
      fp.porosity[p] = n, fp.liquid_pressure[p] = pl, fp.gas_pressure[p] = pg;
      const double s_l = fp.saturation[p] = hm.saturation(physics::suction(pl, pg));
      const double rho_l = fp.liquid_density[p] = hm.liquid_density(pl);
      const double rho_g = fp.gas_density[p] = hm.gas_density(pg);
      if (held) supplied += pores * (1.0 - s_l) * rho_g - mg;
      u.last_volume[p] = mp.volume[p];
      u.pore[p] = std::max(pl, pg);
      u.added[p] = pores * (s_l * rho_l + (1.0 - s_l) * rho_g);
    }
  }
  r.supplied[1] += supplied;
  r.max_wave_speed = std::sqrt(max_c2) + std::sqrt(max_v2);
  r.first_bad = bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad;
  return r;
}

}  // namespace unsatmpm
