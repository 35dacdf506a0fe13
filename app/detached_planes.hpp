// The warning a run gives when a body leaves a boundary plane whose fluid conditions it relied on
// (docs/input.md, "Three-phase boundaries"): a liquid or gas condition on a plane acts at the
// plane's nodes, which a body that settles or shrinks away by more than a cell no longer reaches,
// so the condition then acts on nothing (a loaded wetting column that settled 14 mm on 12.5 mm
// cells stopped taking in the ponded water; docs/known_failures.md). A `free_surface` condition
// follows the body instead.
#pragma once

#include <fmt/core.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "input/case.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"

namespace unsatmpm {

template <int D>
class DetachedPlanes {
 public:
  /// The planes with a fluid condition that some point lies within one cell of at the start.
  DetachedPlanes(const Case& c, const numerics::Grid<D>& grid,
                 const numerics::MaterialPoints<D>& mp)
      : grid_(grid) {
    for (const BoundarySpec& b : c.boundaries)
      if ((b.liquid || b.gas_pressure) && reached(b.region, mp)) watched_.push_back(&b);
  }

  /// One message per watched plane that no point lies within one cell of at time t [s], the
  /// first time it is found so; the plane is not watched after that.
  std::vector<std::string> check(double t, const numerics::MaterialPoints<D>& mp) {
    std::vector<std::string> out;
    for (auto it = watched_.begin(); it != watched_.end();) {
      if (reached((*it)->region, mp)) {
        ++it;
        continue;
      }
      static const char* axes[] = {"x", "y", "z"};
      out.push_back(fmt::format(
          "at t = {:.6g} s no material point lies within one cell of boundary '{}' (plane {} = "
          "{:g}) any more: its {} at the plane's nodes, which the body has left, so on nothing; "
          "a `free_surface` condition follows the body (docs/input.md)",
          t, (*it)->name, axes[(*it)->region.axis], (*it)->region.coordinate,
          (*it)->liquid && (*it)->gas_pressure ? "liquid and gas conditions act"
          : (*it)->liquid                      ? "liquid condition acts"
                                               : "gas condition acts"));
      it = watched_.erase(it);
    }
    return out;
  }

 private:
  bool reached(const PlaneRegion& plane, const numerics::MaterialPoints<D>& mp) const {
    const double h = grid_.spacing[plane.axis];
    for (std::size_t p = 0; p < mp.size(); ++p)
      if (std::abs(mp.position[p][plane.axis] - plane.coordinate) < h) return true;
    return false;
  }

  numerics::Grid<D> grid_;
  std::vector<const BoundarySpec*> watched_;
};

}  // namespace unsatmpm
