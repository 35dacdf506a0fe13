// Rainfall on the free surface (SurfaceSpec::rainfall), for the implicit cycle's pressure system.
//
// Rain of intensity r(t) [mm/h] falls along gravity. Each column of the grid (the strip of
// horizontal measure — the spacings across it, halved on the grid's outer faces — around one
// column of nodes) delivers r rho_l times its measure to the topmost material point in it, which
// passes it to its free-surface nodes in proportion to its shape-function weights there (like a
// traction on a boundary point). A node that a point barely touches thus gets a share as small
// as its storage. Every free-surface node is in one of two modes, decided at the start of each
// coupling interval from the end of the previous one:
//   flux      the liquid pressure is an unknown; the node takes its share of the rain (if a
//             column's topmost point passes it some) or nothing (impervious);
//   held      the suction is zero (P_l = P_g): ponding under rain, or a seepage face where water
//             leaves.
// A flux node whose suction has reached zero (P_l >= P_g) becomes held; a held node becomes flux
// again when its inflow exceeds what the rain brings it (the soil would take more water than
// falls there; with no rain, any inflow). A node that has just become a surface node starts in
// flux mode. A node under rain ponds when it happens: the implicit solver stops the flow where
// its liquid pressure reaches the gas pressure (CVODE's rootfinding), holds it, and restarts;
// the other switches (seepage, and back to flux) wait for the end of the coupling interval.
// Rain on a held node runs off and is not counted.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "input/case.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm {

template <int D, class K>
class RainfallSurface {
 public:
  /// `axis`: the grid axis gravity points along, `down`: -1 if gravity points to decreasing
  /// coordinates, +1 otherwise. `liquid_density` [kg/m^3] of the rain.
  RainfallSurface(const numerics::Grid<D>& grid, TimeFunction intensity, double liquid_density,
                  int axis, int down)
      : grid_(grid),
        intensity_(std::move(intensity)),
        density_(liquid_density),
        axis_(axis),
        down_(down),
        flux_(grid.n_nodes(), 1),
        supply_(grid.n_nodes(), 0.0) {}

  /// Updates the modes from the end of the previous interval: `surface` the free-surface nodes
  /// it had, `pressure` its nodal pressures (liquid, gas) [Pa], `inflow` each node's liquid
  /// inflow [kg/s per unit out-of-plane measure]. Returns the flux-mode flags (1: flux).
  const std::vector<std::uint8_t>& update_modes(const std::vector<std::uint8_t>& surface,
                                                const std::array<std::vector<double>, 2>& pressure,
                                                const std::vector<double>& inflow) {
    held_ = 0;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i) {
      if (surface.empty() || !surface[i]) {
        flux_[i] = 1;
        continue;
      }
      if (flux_[i])
        flux_[i] = pressure[numerics::liquid_phase][i] >= pressure[numerics::gas_phase][i] ? 0 : 1;
      else
        flux_[i] = inflow[i] > supply_[i] ? 1 : 0;
      held_ += flux_[i] == 0;
    }
    return flux_;
  }

  /// The rain's mass rate at each node over [t0, t1] [kg/s per unit out-of-plane measure in 2D,
  /// kg/s in 3D]: the mean intensity times rho_l times each column's measure, given to the
  /// column's topmost point and passed to its nodes flagged in `surface` by their weights
  /// (renormalised over those nodes; to all its nodes if none is flagged).
  const std::vector<double>& supply(double t0, double t1, const numerics::MaterialPoints<D>& mp,
                                    const std::vector<std::uint8_t>& surface) {
    std::fill(supply_.begin(), supply_.end(), 0.0);
    const double rate = intensity_.mean(t0, t1) * 1e-3 / 3600.0 * density_;  // kg/(m^2 s)
    // The topmost point of each column, the column indexed by its node on the axis' first plane.
    std::vector<std::int64_t> top(grid_.n_nodes(), -1);
    for (std::size_t p = 0; p < mp.size(); ++p) {
      std::int64_t column = 0;
      bool inside = true;
      for (int d = 0; d < D; ++d) {
        if (d == axis_) continue;
        const double u = (mp.position[p][d] - grid_.origin[d]) / grid_.spacing[d];
        const auto k = static_cast<std::int64_t>(std::floor(u + 0.5));
        inside = inside && k >= 0 && k <= grid_.n_cells[d];
        column += k * grid_.stride[d];
      }
      if (!inside) continue;
      const auto q = top[column];
      if (q < 0 || -down_ * (mp.position[p][axis_] - mp.position[q][axis_]) > 0.0) top[column] = p;
    }
    numerics::PointStencil<D, K> st;
    for (std::int64_t column = 0; column < grid_.n_nodes(); ++column) {
      const auto p = top[column];
      if (p < 0) continue;
      const auto index = grid_.node_ijk(column);
      double measure = 1.0;
      for (int d = 0; d < D; ++d)
        if (d != axis_)
          measure *= grid_.spacing[d] * (index[d] == 0 || index[d] == grid_.n_cells[d] ? 0.5 : 1.0);
      st.evaluate(grid_, mp.position[p], mp.half_size[p]);
      double on_surface = 0.0;
      for (int a = 0; a < st.n; ++a)
        if (surface[st.node[a]]) on_surface += st.w[a];
      for (int a = 0; a < st.n; ++a) {
        const bool take = on_surface > 0.0 ? surface[st.node[a]] != 0 : true;
        if (take && st.w[a] > 0.0)
          supply_[st.node[a]] += rate * measure * st.w[a] / (on_surface > 0.0 ? on_surface : 1.0);
      }
    }
    return supply_;
  }

  /// Holds node i at zero suction from now on (it ponded during an interval).
  void hold(std::int64_t i) {
    if (flux_[i]) ++held_;
    flux_[i] = 0;
  }

  /// Surface nodes held at zero suction after the last update_modes.
  std::int64_t held_nodes() const { return held_; }

  /// The modes and supply the next update_modes starts from (a checkpoint keeps them).
  void save(CheckpointWriter& w) const {
    w.put("rain.flux", flux_);
    w.put("rain.supply", supply_);
    w.value("rain.held", held_);
  }
  void restore(CheckpointReader& r) {
    r.get_sized("rain.flux", flux_, static_cast<std::size_t>(grid_.n_nodes()));
    r.get_sized("rain.supply", supply_, static_cast<std::size_t>(grid_.n_nodes()));
    held_ = r.value<std::int64_t>("rain.held");
  }

 private:
  const numerics::Grid<D>& grid_;
  TimeFunction intensity_;  // [mm/h]
  double density_;
  int axis_, down_;
  std::vector<std::uint8_t> flux_;
  std::vector<double> supply_;
  std::int64_t held_ = 0;
};

}  // namespace unsatmpm
