// Rainfall on the free surface (SurfaceSpec::rainfall), for the implicit cycle's pressure system
// and the explicit cycle's points (point_supply; cycles/three_phase_solver.hpp).
//
// Rain of intensity r(t) [mm/h] falls along gravity. Each column of the grid (the strip of
// horizontal measure — the spacings across it, halved on the grid's outer faces — around one
// column of nodes) delivers r rho_l times its measure to the top row of material points in it
// (those within half a point of its topmost one, each by its horizontal extent). In the main
// cycle they pass it to all their nodes by their shape-function weights, as a flux through the
// face in the nodal balances (nodal_supply; like a traction on a boundary point), so that a node
// that a point barely touches gets a share as small as its storage; in the explicit cycle the
// points take it into their own balances, and their free-surface nodes decide which part runs off
// (supply, point_supply). Every free-surface node is in one of two modes, decided at the start of
// each coupling interval (main cycle) or step (explicit) from the end of the previous one:
//   flux      the liquid pressure is an unknown; the node takes its share of the rain (if a
//             column's top row passes it some) or nothing (impervious);
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
#include "numerics/fluid_points.hpp"
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

  /// The explicit cycle's rain at each node over [t0, t1] [kg/s per unit out-of-plane measure in
  /// 2D, kg/s in 3D], what a held node's inflow is compared with: the mean intensity times rho_l
  /// times each column's measure, given to the column's top row (topmost_points) and passed to
  /// its nodes flagged in `surface` by their weights (renormalised over those nodes; to all its
  /// nodes if none is flagged), as point_supply takes it in.
  const std::vector<double>& supply(double t0, double t1, const numerics::MaterialPoints<D>& mp,
                                    const std::vector<std::uint8_t>& surface) {
    std::fill(supply_.begin(), supply_.end(), 0.0);
    const double rate = mass_flux(t0, t1);
    numerics::PointStencil<D, K> st;
    for (const auto& [p, measure] : topmost_points(mp)) {
      st.evaluate(grid_, mp.position[p], mp.half_size[p]);
      const double on_surface = weight_on(st, surface);
      for (int a = 0; a < st.n; ++a) {
        const bool take = on_surface > 0.0 ? surface[st.node[a]] != 0 : true;
        if (take && st.w[a] > 0.0)
          supply_[st.node[a]] += rate * measure * st.w[a] / (on_surface > 0.0 ? on_surface : 1.0);
      }
    }
    return supply_;
  }

  /// The main cycle's rain over [t0, t1] at each node [kg/s per unit out-of-plane measure in 2D,
  /// kg/s in 3D], with the modes of the last update_modes (and hold): the rain through the body's
  /// top face as a flux in the nodal balances. Each column's rain goes to its top row
  /// (topmost_points); of a point's share the part its held surface nodes carry runs off (its
  /// weights on held nodes over its weights on all its surface nodes, as point_supply takes it:
  /// all of it where the face is ponded), and the rest goes to all its nodes but the held ones by
  /// their weights, the weak form's integral of N_i times the flux over the face taken at the
  /// face's points. A node thus gets rain in proportion to its share of the top points, as its
  /// storage there is. Passed to the surface nodes alone, the rain of a top lying half a cell past
  /// a node line all fell on the node beyond, which holds an eighth of a full node's volume
  /// (cycles/top_row_pressures.hpp). Given to the nodes inside as well once the face had ponded,
  /// the rain was forced in: the ponded column's top point stood 312 Pa above hydrostatic
  /// (tests/cycles/test_rainfall.cpp, HeavyRainPondsAndRunsOff).
  const std::vector<double>& nodal_supply(double t0, double t1,
                                          const numerics::MaterialPoints<D>& mp,
                                          const std::vector<std::uint8_t>& surface) {
    std::fill(supply_.begin(), supply_.end(), 0.0);
    const double rate = mass_flux(t0, t1);
    const auto held = [&](std::int64_t i) { return !surface.empty() && surface[i] && !flux_[i]; };
    numerics::PointStencil<D, K> st;
    for (const auto& [p, measure] : topmost_points(mp)) {
      st.evaluate(grid_, mp.position[p], mp.half_size[p]);
      double on_surface = 0.0, on_held = 0.0, open = 0.0;
      for (int a = 0; a < st.n; ++a) {
        const auto i = st.node[a];
        if (!surface.empty() && surface[i]) on_surface += st.w[a];
        if (held(i))
          on_held += st.w[a];
        else
          open += st.w[a];
      }
      const double taken = on_surface > 0.0 ? 1.0 - on_held / on_surface : 1.0;
      for (int a = 0; a < st.n; ++a) {
        if (!(st.w[a] > 0.0)) continue;
        // A held node's entry is what the rain would bring it, for update_modes' comparison with
        // its inflow; the pressure system ignores a supply at a prescribed node.
        const double share = held(st.node[a]) ? st.w[a] / (on_held + open) : taken * st.w[a] / open;
        supply_[st.node[a]] += rate * measure * share;
      }
    }
    return supply_;
  }

  /// The explicit cycle's rain over [t0, t1]: the mass rate each point of a column's top row takes
  /// in [kg/s per unit out-of-plane measure in 2D], pairs (point, rate). Of its share it takes
  /// the share that falls on flux nodes (its weights on the flux nodes among those `supply` gives
  /// it, over its weights on all of them), each flux node's part scaled by `delivered` (per node,
  /// in [0, 1]; all of it if empty); the rest runs off. Call after supply() and update_modes().
  std::vector<std::pair<std::int64_t, double>> point_supply(
      double t0, double t1, const numerics::MaterialPoints<D>& mp,
      const std::vector<std::uint8_t>& surface, const std::vector<double>& delivered = {}) const {
    std::vector<std::pair<std::int64_t, double>> out;
    const double rate = mass_flux(t0, t1);
    numerics::PointStencil<D, K> st;
    for (const auto& [p, measure] : topmost_points(mp)) {
      st.evaluate(grid_, mp.position[p], mp.half_size[p]);
      const double on_surface = weight_on(st, surface);
      // Without surface nodes (supply gives it to all its nodes, none of which is then held).
      double share = 1.0;
      if (on_surface > 0.0) {
        share = 0.0;
        for (int a = 0; a < st.n; ++a) {
          const auto i = st.node[a];
          if ((surface.empty() || surface[i]) && flux_[i])
            share += st.w[a] * (delivered.empty() ? 1.0 : delivered[i]);
        }
        share /= on_surface;
      }
      if (share > 0.0) out.emplace_back(p, rate * measure * share);
    }
    return out;
  }

  /// The top rows' points with their shares of their columns' measure (topmost_points).
  std::vector<std::pair<std::int64_t, double>> top_row(
      const numerics::MaterialPoints<D>& mp) const {
    return topmost_points(mp);
  }

  /// Holds node i at zero suction from now on (it ponded during an interval).
  void hold(std::int64_t i) {
    if (flux_[i]) ++held_;
    flux_[i] = 0;
  }

  /// The flux-mode flags (1: flux) and each node's rain [kg/s per unit out-of-plane measure] of
  /// the last update_modes and supply.
  const std::vector<std::uint8_t>& flux() const { return flux_; }
  const std::vector<double>& supplied() const { return supply_; }

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
  /// The rain's mass per unit horizontal area and time over [t0, t1] [kg/(m^2 s)].
  double mass_flux(double t0, double t1) const {
    return intensity_.mean(t0, t1) * 1e-3 / 3600.0 * density_;
  }

  /// The points that take each column's rain, with their shares of the column's horizontal
  /// measure [m in 2D, m^2 in 3D]: the column's top row, the points within half a point (the
  /// topmost one's half-size along gravity) of its topmost point, each in proportion to its
  /// horizontal extent. On a flat surface every point of the top row then takes the rain over its
  /// own width, and every surface node the same rain per unit of its measure; a single topmost
  /// point would take all of a column whose points tie, and the nodes beside it (measured on a 2D
  /// column two cells wide: 1.25 and 0.75 times the mean rain per unit measure) pond early.
  std::vector<std::pair<std::int64_t, double>> topmost_points(
      const numerics::MaterialPoints<D>& mp) const {
    // Columns indexed by their node on the axis' first plane; -1: outside every column.
    const auto n = static_cast<std::int64_t>(mp.size());
    std::vector<std::int64_t> column(n, -1), top(grid_.n_nodes(), -1);
    for (std::int64_t p = 0; p < n; ++p) {
      std::int64_t c = 0;
      bool inside = true;
      for (int d = 0; d < D; ++d) {
        if (d == axis_) continue;
        const double u = (mp.position[p][d] - grid_.origin[d]) / grid_.spacing[d];
        const auto k = static_cast<std::int64_t>(std::floor(u + 0.5));
        inside = inside && k >= 0 && k <= grid_.n_cells[d];
        c += k * grid_.stride[d];
      }
      if (!inside) continue;
      column[p] = c;
      const auto q = top[c];
      if (q < 0 || height(mp, p) > height(mp, q)) top[c] = p;
    }
    // The top rows' horizontal extents, summed per column.
    const auto in_top_row = [&](std::int64_t p) {
      const auto q = top[column[p]];
      return height(mp, p) >= height(mp, q) - mp.half_size[q][axis_];
    };
    const auto width = [&](std::int64_t p) {
      double w = 1.0;
      for (int d = 0; d < D; ++d)
        if (d != axis_) w *= 2.0 * mp.half_size[p][d];
      return w;
    };
    std::vector<double> row_width(grid_.n_nodes(), 0.0);
    std::vector<std::int32_t> row_points(grid_.n_nodes(), 0);
    for (std::int64_t p = 0; p < n; ++p)
      if (column[p] >= 0 && in_top_row(p))
        row_width[column[p]] += width(p), ++row_points[column[p]];
    std::vector<std::pair<std::int64_t, double>> out;
    for (std::int64_t p = 0; p < n; ++p) {
      if (column[p] < 0 || !in_top_row(p)) continue;
      const auto c = column[p];
      const auto index = grid_.node_ijk(c);
      double measure = 1.0;
      for (int d = 0; d < D; ++d)
        if (d != axis_)
          measure *= grid_.spacing[d] * (index[d] == 0 || index[d] == grid_.n_cells[d] ? 0.5 : 1.0);
      // Points without extent (none in practice) share equally.
      out.emplace_back(
          p, measure * (row_width[c] > 0.0 ? width(p) / row_width[c] : 1.0 / row_points[c]));
    }
    return out;
  }

  /// A point's height against gravity [m].
  double height(const numerics::MaterialPoints<D>& mp, std::int64_t p) const {
    return -down_ * mp.position[p][axis_];
  }

  /// The stencil's weight on the nodes flagged in `on` (all if empty).
  static double weight_on(const numerics::PointStencil<D, K>& st,
                          const std::vector<std::uint8_t>& on) {
    double w = 0.0;
    for (int a = 0; a < st.n; ++a)
      if (on.empty() || on[st.node[a]]) w += st.w[a];
    return w;
  }

  const numerics::Grid<D>& grid_;
  TimeFunction intensity_;  // [mm/h]
  double density_;
  int axis_, down_;
  std::vector<std::uint8_t> flux_;
  std::vector<double> supply_;
  std::int64_t held_ = 0;
};

}  // namespace unsatmpm
