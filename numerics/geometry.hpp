// Point-membership tests for the bodies that are filled with material points.
#pragma once

#include <array>
#include <vector>

namespace unsatmpm::numerics {

/// Even-odd (crossing number) test of a point against a simple polygon in the x-y plane.
/// Points exactly on an edge may go either way; body filling never samples edges of cells that
/// coincide with the polygon's edges because it samples cell interiors.
inline bool inside_polygon(const std::vector<std::array<double, 2>>& poly, double x, double y) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const double xi = poly[i][0], yi = poly[i][1], xj = poly[j][0], yj = poly[j][1];
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) inside = !inside;
  }
  return inside;
}

}  // namespace unsatmpm::numerics
