// Surface loads on boundary planes (case key boundaries[].traction, docs/input.md): a normal
// pressure that pushes into the body and a shear traction along a grid axis in the plane, each a
// function of time, applied as consistent nodal forces
//     f_i(t) = t(t) A_i,   A_i = integral over G of N_i dG,
// with the grid's linear shape functions N_i on the plane's nodes (whatever the points' kernel).
// G is the part of the plane that the bodies cover at t = 0: the union of the footprints
// [x_p - l_p, x_p + l_p] (l_p the point's half size) of the points within one cell of the plane,
// integrated on a raster of `raster` sub-cells per cell and direction (midpoint rule: exact for
// the linear N_i over each sub-cell). The load stays on these nodes: it suits surfaces that move
// by less than a cell; the cycles end the run if no material reaches a loaded node any more.
// A traction is a total-stress load: in a three-phase case the mixture carries it, and the pore
// fluids take their share through the skeleton (docs/balance_laws.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "input/case.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/nodal_state.hpp"

namespace unsatmpm {

template <int D>
class BoundaryTractions {
 public:
  /// Sub-cells per cell and in-plane direction of the coverage raster.
  static constexpr int raster = 8;

  BoundaryTractions() = default;
  /// Finds each loaded plane's nodes and areas from the points at t = 0. Throws InputError
  /// (naming the traction key) if no material lies within one cell of a loaded plane, or if
  /// material lies on both sides of it (a traction acts on a body's surface).
  BoundaryTractions(const Case& c, const numerics::Grid<D>& grid,
                    const numerics::MaterialPoints<D>& mp);

  bool empty() const { return loads_.empty(); }

  /// The nodal forces at time t [s] [N per unit out-of-plane measure], replacing `out`'s content.
  void forces(double t, std::vector<numerics::NodalForce<D>>& out) const;

  /// The first loaded node whose mass is at most `floor`, with its boundary's name; `mass(i)`
  /// gives node i's mass [kg]. Empty if every loaded node carries material.
  template <class Mass>
  std::optional<std::pair<std::int64_t, std::string>> unreached_node(Mass&& mass,
                                                                     double floor) const {
    for (const Load& load : loads_)
      for (const std::int64_t i : load.nodes)
        if (mass(i) <= floor) return std::make_pair(i, load.spec->name);
    return std::nullopt;
  }

 private:
  struct Load {
    const BoundarySpec* spec;
    double inward;  // +1: the body lies on the plane's +axis side, -1: on its -axis side
    std::vector<std::int64_t> nodes;
    std::vector<double> area;  // A_i [m^(D-1)]
  };
  std::vector<Load> loads_;
};

}  // namespace unsatmpm
