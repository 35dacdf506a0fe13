// The main cycle's relaxation of the points' pressure offsets within a cell over part of a
// coupling interval (docs/balance_laws.md, "The points' pressure offsets"), called by the
// undrained update (cycles/undrained.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/parallel.hpp"
#include "numerics/pressure_offsets.hpp"
#include "physics/hydraulic_model.hpp"

namespace unsatmpm {

/// The points' pressure offsets within a cell relaxed over time dt (numerics/pressure_offsets.hpp,
/// docs/balance_laws.md "The points' pressure offsets"), applied to the sub-step's nodal
/// increments before the masses are assigned, so that the fluid moved between the points sums to
/// zero. The flow sees the points' pressures only through nodal fits and hands them nodal
/// increments, and the undrained update solves at the nodes too: an offset between the points of
/// a cell is seen by neither and is never drained. On the embankment (main cycle, 2026-11-28) the
/// crushed crest's points held liquid pressures 190 kPa apart within one cell at 292.5 s, one at
/// +83 kPa at its porosity bound and tension cut-off, until it was thrown out of the grid. The
/// fluids' drag coefficients, which the main cycle does not keep, are taken here from the laws.
/// The coupling interval's time is relaxed in offset_relaxations_per_interval parts, each at the
/// sub-step that closes it (cycles/implicit_solver.hpp), so that an offset grows over a tenth of
/// the interval at most before it is relaxed, and no point's pressure jumps by the interval's whole
/// offset at once (the embankment on 0.4 m cells, verification/embankment_cycles' fast variant,
/// before the fit was bounded, numerics/pressure_offsets.hpp: a crest-corner point torn loose, the
/// kinetic energy 28.7 J/m at 13.5 s relaxed once at the interval's end, 15.8 J/m at 14 s in ten
/// parts spread over it). And a pair of passes (the liquid's, at the gas's content fixed, then the
/// gas's, at the liquid's) leaves a liquid offset c = A_lg A_gl / (A_ll A_gg) of itself where both
/// fluids move across a cell within a part (the gas's pass moves the liquid's pressure back), so
/// the parts let such coupled offsets approach the state the explicit cycle's step-by-step passes
/// reach (c^10 = 0.06 at c = 0.75; c = 0 where the retention law is flat, at S_max).
inline constexpr int offset_relaxations_per_interval = 10;

template <int D, class K>
void relax_interval_offsets(const numerics::Grid<D>& grid, const numerics::MaterialPoints<D>& mp,
                            const std::vector<physics::HydraulicModel>& models,
                            const std::vector<std::int64_t>& ranges, double dt,
                            numerics::FluidPoints<D>& fp, numerics::OffsetScratch& scratch) {
  const int n_threads = static_cast<int>(scratch.threads.size());
  for (std::size_t m = 0; m < models.size(); ++m) {
    const physics::HydraulicModel& hm = models[m];
    numerics::parallel_region(n_threads, [&] {
#pragma omp for schedule(static)
      for (std::int64_t p = ranges[m]; p < ranges[m + 1]; ++p) {
        const physics::LocalFluidState f = hm.state(fp.liquid_pressure[p], fp.gas_pressure[p]);
        fp.liquid_drag[p] = hm.liquid_drag(fp.porosity[p], f.s_l, f.se);
        fp.gas_drag[p] = hm.gas_drag(fp.porosity[p], f.s_l, f.se);
      }
    });
  }
  numerics::relax_pressure_offsets<D, K>(grid, mp, dt, scratch, fp);
}

}  // namespace unsatmpm
