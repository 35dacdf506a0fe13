// Surface loads on boundary planes (case key boundaries[].traction, docs/input.md): a normal
// pressure that pushes into the body and a shear traction along a grid axis in the plane, each a
// function of time, applied as nodal forces
//     f_i(t) = t(t) A_i,   A_i = integral over G of N_i dG,
// with the grid's linear shape functions N_i on the plane's nodes (whatever the points' kernel).
// G is the part of the plane that the bodies cover at t = 0: the union of the footprints
// [x_p - l_p, x_p + l_p] (l_p the point's half size) of the points within one cell of the plane,
// integrated on a raster of `raster` sub-cells per cell and direction (midpoint rule: exact for
// the linear N_i over each sub-cell).
// The load follows the body's face along the plane's normal as the body moves: each loaded node's
// force goes to the face of the outermost cell of its column that the points occupy (the cell
// holding the outermost point centre among the points its in-plane shape function sees), split
// between that cell's outer and inner nodes in the fraction phi_i = sum_p N_i(y_p) V_p / (h A_i)
// of the cell that those points fill (capped at 1; y_p the in-plane position, h the cell size
// along the normal). With linear shape functions this is the split under which a uniform stress
// equal to the load balances both nodes, whatever part of the cell the body has left: on the
// plane's node alone, as a body that leaves the outer cell half empty keeps it, the points left
// in the cell took the whole load on their volume (h / sum V_p times it: twice the load at the top
// of the loaded wetting column of docs/known_failures.md). A column no point sees
// any more keeps its load on the plane's node, and the cycles end the run if no material reaches
// it. A traction is a total-stress load: in a three-phase case the mixture carries it, and the
// pore fluids take their share through the skeleton (docs/balance_laws.md).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
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

  /// Finds each loaded plane's nodes and areas from the points at t = 0. Throws InputError
  /// (naming the traction key) if no material lies within one cell of a loaded plane, or if
  /// material lies on both sides of it (a traction acts on a body's surface).
  BoundaryTractions(const Case& c, const numerics::Grid<D>& grid,
                    const numerics::MaterialPoints<D>& mp);

  bool empty() const { return loads_.empty(); }

  /// The nodal forces at time t [s] on the points `mp` as they are [N per unit out-of-plane
  /// measure], replacing `out`'s content.
  void forces(double t, const numerics::MaterialPoints<D>& mp,
              std::vector<numerics::NodalForce<D>>& out);

  /// The first node of the last forces() that kept the load of a column no point sees, if its
  /// mass is at most `floor`, with its boundary's name; `mass(i)` gives node i's mass [kg].
  template <class Mass>
  std::optional<std::pair<std::int64_t, std::string>> unreached_node(Mass&& mass,
                                                                     double floor) const {
    for (const auto& [i, name] : unseen_)
      if (mass(i) <= floor) return std::make_pair(i, *name);
    return std::nullopt;
  }

 private:
  struct Load {
    const BoundarySpec* spec;
    double inward;  // +1: the body lies on the plane's +axis side, -1: on its -axis side
    int plane_index;
    std::vector<std::int64_t> nodes;
    std::vector<double> area;    // A_i [m^(D-1)]
    std::vector<int> column_of;  // per node of the plane (plane_slot): its column, -1: none
  };
  /// A node's place among the plane's nodes (normal to `axis`), from its in-plane indices `j`.
  std::int64_t plane_slot(int axis, const std::array<int, D>& j) const;
  /// Per column of `load` (its nodes' order): the outer cell, counted in cells inward from the
  /// plane, that holds the outermost point centre (unseen: none seen), and the fraction phi of
  /// that cell the points fill.
  void find_faces(const Load& load, const numerics::MaterialPoints<D>& mp);
  /// Calls f(k, w) for the columns k of `load` whose in-plane shape function sees a point at
  /// in-plane position y, with the weight w = N_k(y) > 0.
  template <class F>
  void columns_seeing(const Load& load, const numerics::Vec<D>& y, F&& f) const;

  numerics::Grid<D> grid_;
  std::vector<Load> loads_;
  static constexpr int unseen = std::numeric_limits<int>::max();
  std::vector<int> outer_;      // per column: find_faces' outer cell
  std::vector<double> filled_;  // per column: find_faces' phi
  std::vector<std::pair<std::int64_t, const std::string*>> unseen_;
};

}  // namespace unsatmpm
