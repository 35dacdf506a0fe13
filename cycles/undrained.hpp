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
// 0.3 Pa).
//
// Of its share of the flow a point takes itself the mass that moves its own pressures by the
// flow's field change at it (own_share, at its own storage); the rest, the difference between
// the fitted field's storage and its own, joins the nodal solve and reaches its neighbours. So a
// point follows the flow's pressure change whatever its storage: across a wetting front, where a
// point near saturation is far stiffer than the field fitted to it, the mass measured on the field
// would overfill it (on the embankment: a surface point at S_max driven to +8 kPa beside the
// face held at 0, which then tore the surface open), and beside a held node the share still
// reaches the point (solved at the nodes, most of it went to the held node and left). The flow
// correction's masses (cycles/flow_correction.hpp) join the nodal solve too. Each point then
// holds its old mass plus what the solve assigned it plus its own share, and its pressures are
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
#include "cycles/interval_offsets.hpp"
#include "cycles/setup.hpp"
#include "numerics/explicit_transfers.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/parallel.hpp"
#include "numerics/three_phase_g2p.hpp"
#include "physics/fluid_contents.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm {

/// Per point, over one coupling interval: what the mechanics needs of the fluids
/// (numerics::PoreLoads, rewritten at every sub-step), the flow's mass changes, and the nodal
/// scratch of the undrained update.
struct UndrainedPoints {
  std::vector<double> solid_volume;                // V_s = (1 - n) V [m^3], constant
  std::vector<double> last_volume;                 // V at the end of the last sub-step [m^3]
  std::array<std::vector<double>, 2> flow_mass;    // dm of the interval's flow [kg]
  std::array<std::vector<double>, 2> flow_change;  // the flow's field change at the point [Pa]
  // Each fluid's mass at a sub-step's start [kg]: from the state at an interval's first, then
  // what the last sub-step assigned (undrained_apply), so the interval keeps its masses exactly
  // while the pressures are found to undrained_pressure_tolerance.
  std::array<std::vector<double>, 2> old_mass;
  std::vector<double> added, pore, suction, max_volume;  // numerics::PoreLoads' columns
  std::vector<numerics::StrengthMemo> strength;          // and its memo, kept across intervals
  std::vector<std::vector<double>> mass_balance;         // per thread, 6 sums per node
  numerics::OffsetScratch offsets;  // the offsets' relaxation's (numerics/offset_bounds.hpp)
  // Per fluid, 1 at the nodes whose pressure the flow prescribes this interval (boundaries, the
  // free surface, and for the gas the nodes free of gas): the mechanics holds them too.
  std::array<std::vector<std::uint8_t>, 2> held;
  // Some material can lose its gas (HydraulicModel::can_be_free_of_gas): each sub-step then also
  // holds the nodes free of gas at its state (numerics::nodal_pressure_increments, HoldGasFree).
  bool gas_can_vanish = false;

  numerics::PoreLoads view() { return {added, pore, suction, strength, max_volume}; }
};

/// The pressure accuracy [Pa] of the pressures that hold a sub-step's masses
/// (physics::pressures_from_contents' pressure test). The masses are kept over the interval
/// whatever the pressures (UndrainedPoints::old_mass), and the state's are taken again at the
/// next interval's start: there each point's masses move by at most its storage times this, about
/// 1e-7 of them at a retention slope dS/ds of 5e-5 /Pa. A millipascal is also far below any
/// pressure the mechanics or the flow resolves. With the contents' test alone (1e-13 of the
/// densities, about 1e-7 Pa) an inversion took 1.47 evaluations of the laws on the embankment,
/// with this 1.09 (docs/performance.md).
inline constexpr double undrained_pressure_tolerance = 1e-3;

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
  u.suction.resize(n), u.max_volume.resize(n), u.strength.resize(n);
  u.last_volume = mp.volume;
  for (auto& v : u.flow_mass) v.assign(n, 0.0);
  for (auto& v : u.flow_change) v.assign(n, 0.0);
  for (auto& v : u.old_mass) v.resize(n);
  u.gas_can_vanish = std::any_of(models.begin(), models.end(),
                                 [](const auto& hm) { return hm.can_be_free_of_gas(); });
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
  u.offsets.resize(n_threads);
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
    u.flow_change[0][p] += dl, u.flow_change[1][p] += dg;
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
  const double s_l = hm.saturation(physics::retention_suction(p_l, p_g));
  return undrained_stiffness(hm.storage(n, p_l, p_g), s_l, hm.liquid_density(p_l),
                             hm.gas_density(p_g), p_l >= p_g, gas_held);
}

/// max_p sqrt((M + K_u) V / (m_s + m_f)) + |v_p| [m/s] at the points' current state (the step of
/// the first sub-step; undrained_rates reports it after each): the mixture's P wave, its density
/// the solid's and the pore fluids' that move with it (the mass p2g gives the nodes, PoreLoads).
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
      const auto fluids = point_fluid_masses<D>(mp, fp, p);
      c2 = std::max(c2, (moduli[m] + k_u) * mp.volume[p] / (mp.mass[p] + fluids[0] + fluids[1]));
      v2 = std::max(v2, mp.velocity[p].squaredNorm());
    }
  return std::sqrt(c2) + std::sqrt(v2);
}

/// What one undrained update reports.
struct UndrainedReport {
  double max_wave_speed = 0.0;  // max_p sqrt((M + K_u) V / (m_s + m_f)) + |v_p| [m/s]
  std::int64_t first_bad = -1;  // a point whose state is not finite, or whose pores vanished
  // Mass entering at the held nodes and points, per fluid [kg per out-of-plane measure]: water
  // a compression drives out through a drained boundary, gas a desaturation takes.
  std::array<double, 2> supplied{0.0, 0.0};
};

/// The part of the flow's share a point takes itself over a sub-step: the mass that moves its own
/// pressures by `share` (= h / dt) of the flow's field change at it, at its own storage `a`
/// (linear); the gas's change is left out where the gas is held (a point free of gas). Returns
/// the pressure changes; `mass` gets the masses per unit volume [kg/m^3].
inline std::array<double, 2> own_share(const physics::StorageMatrix& a, double share,
                                       double change_l, double change_g, bool gas_held,
                                       std::array<double, 2>& mass) {
  const double dl = share * change_l, dg = gas_held ? 0.0 : share * change_g;
  mass = {a.ll * dl + a.lg * dg, a.gl * dl + a.gg * dg};
  return {dl, dg};
}

/// One sub-step's pore pressures (see the header), first half: each point's storage and masses
/// (kept from the last undrained_apply of the interval with `continuing`, else from its state),
/// and the mass rates left for the nodal solve: what its volume change since the last
/// sub-step asks, and the share `share` = h / dt of the flow's mass change at it less what it
/// takes itself (own_share). Returns the mixture's wave speed with each point's undrained
/// stiffness added to its skeleton's modulus `moduli[m]`, over the mixture's density (the fluids'
/// masses of the last update, u.added).
template <int D>
double undrained_rates(const numerics::MaterialPoints<D>& mp,
                       const std::vector<physics::HydraulicModel>& models,
                       const std::vector<double>& moduli, const std::vector<std::int64_t>& ranges,
                       double share, int n_threads, bool continuing, numerics::FluidPoints<D>& fp,
                       UndrainedPoints& u) {
  if (!continuing)
    for (std::size_t m = 0; m < models.size(); ++m)
      numerics::parallel_region(n_threads, [&] {
#pragma omp for schedule(static)
        for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p)
          fp.storage[p] =
              models[m].storage(fp.porosity[p], fp.liquid_pressure[p], fp.gas_pressure[p]);
      });
  // The mass each point's volume change asks, as rates of a unit step; its undrained stiffness
  // at the same state sets the wave speed of the next sub-step.
  double max_c2 = 0.0, max_v2 = 0.0;
  for (std::size_t m = 0; m < models.size(); ++m) {
    const double modulus = moduli[m];
    numerics::parallel_region(n_threads, [&] {
#pragma omp for schedule(static) reduction(max : max_c2, max_v2)
      for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p) {
        const double dv = mp.volume[p] - u.last_volume[p];
        const double s_l = fp.saturation[p], pl = fp.liquid_pressure[p], pg = fp.gas_pressure[p];
        const double cl = s_l * fp.liquid_density[p], cg = (1.0 - s_l) * fp.gas_density[p];
        if (!continuing) {
          const double pores = u.last_volume[p] - u.solid_volume[p];
          u.old_mass[0][p] = pores * cl, u.old_mass[1][p] = pores * cg;
        }
        const physics::StorageMatrix& a = fp.storage[p];
        const bool gas_held = 1.0 - s_l <= physics::gas_free_saturation;
        std::array<double, 2> own;
        own_share(a, share, u.flow_change[0][p], u.flow_change[1][p], gas_held, own);
        fp.liquid_rate[p] = (share * u.flow_mass[0][p] - cl * dv) / mp.volume[p] - own[0];
        fp.gas_rate[p] = (share * u.flow_mass[1][p] - cg * dv) / mp.volume[p] - own[1];
        const double k_u = undrained_stiffness(a, s_l, fp.liquid_density[p], fp.gas_density[p],
                                               pl >= pg, gas_held);
        max_c2 = std::max(max_c2, (modulus + k_u) * mp.volume[p] / (mp.mass[p] + u.added[p]));
        max_v2 = std::max(max_v2, mp.velocity[p].squaredNorm());
      }
    });
  }
  return std::sqrt(max_c2) + std::sqrt(max_v2);
}

/// Second half: the rates of undrained_rates solved at the nodes, with the masses of `source`
/// added there (numerics::NodalMasses, per fluid and node [kg]; the flow correction's); each
/// point's direct share where the gas governs; then each point's pressures from the mass it holds.
/// Updates porosity (1 - V_s / V), pressures, saturation, densities, storage and the pore loads of
/// the next sub-step. The report's wave speed is left for the caller (undrained_rates gives it).
template <int D, class K, class Source = numerics::NodalMasses>
UndrainedReport undrained_apply(const numerics::Grid<D>& grid,
                                const numerics::MaterialPoints<D>& mp,
                                const std::vector<physics::HydraulicModel>& models,
                                const std::vector<std::int64_t>& ranges, double share,
                                int n_threads, double relax_dt, numerics::FluidPoints<D>& fp,
                                UndrainedPoints& u, Source&& source = Source{}) {
  UndrainedReport r;
  // At the held nodes, what the linear balance could not place there enters or leaves.
  r.supplied = u.gas_can_vanish ? numerics::nodal_pressure_increments<D, K, false, Source, true>(
                                      grid, mp, 1.0, u.mass_balance, {&u.held[0], &u.held[1]}, fp,
                                      std::forward<Source>(source))
                                : numerics::nodal_pressure_increments<D, K, false, Source, false>(
                                      grid, mp, 1.0, u.mass_balance, {&u.held[0], &u.held[1]}, fp,
                                      std::forward<Source>(source));
  if (relax_dt > 0.0)
    relax_interval_offsets<D, K>(grid, mp, models, ranges, relax_dt, fp, u.offsets);
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
    numerics::parallel_region(n_threads, [&] {
#pragma omp for schedule(static) reduction(min : bad) reduction(+ : supplied)
      for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p) {
        const double dl = fp.liquid_increment[p], dg = fp.gas_increment[p];
        const double dv = mp.volume[p] - u.last_volume[p];
        const physics::StorageMatrix& a = fp.storage[p];
        const double s_l0 = fp.saturation[p];
        std::array<double, 2> own;
        const auto [fdl, fdg] = own_share(a, share, u.flow_change[0][p], u.flow_change[1][p],
                                          1.0 - s_l0 <= physics::gas_free_saturation, own);
        const double ml = u.old_mass[0][p] + mp.volume[p] * (a.ll * dl + a.lg * dg + own[0]) +
                          s_l0 * fp.liquid_density[p] * dv;
        const double mg = u.old_mass[1][p] + mp.volume[p] * (a.gl * dl + a.gg * dg + own[1]) +
                          (1.0 - s_l0) * fp.gas_density[p] * dv;
        const double pores = mp.volume[p] - u.solid_volume[p];
        bool held = 1.0 - s_l0 <= physics::gas_free_saturation || !(mg > 0.0);
        // The linear start of the inversion: the nodal increments and the point's own share.
        double pl = fp.liquid_pressure[p] + dl + fdl, pg = fp.gas_pressure[p] + dg + fdg;
        physics::LocalFluidState state{};
        const double tol =
            physics::mass_keeping_tolerance(undrained_pressure_tolerance, a, ml, mg, mp.volume[p]);
        bool found = pores > 0.0 && physics::pressures_from_contents(
                                        hm, ml / pores, mg / pores, held, pl, pg, &state, tol) >= 0;
        if (!found && !held && pores > 0.0) {  // a gas the linear step emptied: hold it instead
          pl = fp.liquid_pressure[p] + dl + fdl, pg = fp.gas_pressure[p] + dg;
          held = true;
          found =
              physics::pressures_from_contents(hm, ml / pores, 0.0, true, pl, pg, &state, tol) >= 0;
        }
        // A density the law cannot give at a physical pressure is a failure too: an exponential
        // law underflows to 0 only some 700 bulk moduli below its reference, an ideal gas's turns
        // negative below vacuum (a held gas pressure is not searched).
        if (!found || !std::isfinite(pl + pg) || !(state.rho_l > 0.0 && state.rho_g > 0.0)) {
          bad = std::min(bad, p);
          continue;
        }
        const double n = pores / mp.volume[p];
        fp.porosity[p] = n, fp.liquid_pressure[p] = pl, fp.gas_pressure[p] = pg;
        const double s_l = fp.saturation[p] = state.s_l;  // the laws at (pl, pg)
        const double rho_l = fp.liquid_density[p] = state.rho_l;
        const double rho_g = fp.gas_density[p] = state.rho_g;
        fp.storage[p] = physics::storage_matrix(n, state);           // the next sub-step's
        const double gas = held ? pores * (1.0 - s_l) * rho_g : mg;  // held: what the state holds
        if (held) supplied += gas - mg;
        u.old_mass[0][p] = ml, u.old_mass[1][p] = gas;  // the next sub-step's start
        u.last_volume[p] = mp.volume[p];
        u.pore[p] = std::max(pl, pg);
        u.added[p] = pores * (s_l * rho_l + (1.0 - s_l) * rho_g);
      }
    });
  }
  r.supplied[1] += supplied;
  r.first_bad = bad == std::numeric_limits<std::int64_t>::max() ? -1 : bad;
  return r;
}

/// One sub-step's pore pressures without a flow correction: undrained_rates, then
/// undrained_apply.
template <int D, class K>
UndrainedReport undrained_update(const numerics::Grid<D>& grid,
                                 const numerics::MaterialPoints<D>& mp,
                                 const std::vector<physics::HydraulicModel>& models,
                                 const std::vector<double>& moduli,
                                 const std::vector<std::int64_t>& ranges, double share,
                                 int n_threads, numerics::FluidPoints<D>& fp, UndrainedPoints& u) {
  const double speed =
      undrained_rates<D>(mp, models, moduli, ranges, share, n_threads, false, fp, u);
  UndrainedReport r = undrained_apply<D, K>(grid, mp, models, ranges, share, n_threads, 0.0, fp, u);
  r.max_wave_speed = speed;
  return r;
}

}  // namespace unsatmpm
