// Rain on the free surface in the explicit three-phase cycle (cycles/three_phase_solver.hpp), with
// the main cycle's meaning (cycles/rainfall.hpp): every free-surface node is either flux (closed
// to the liquid, which moves with the solid there; the rain that falls on it enters) or held at
// zero suction (open to the liquid at P_l = P_g through the boundary term -P_g A_i, as a face or
// a free surface with a pressure condition: ponded, or a seepage face; the rain on it runs off).
// The modes are decided at every step from the end of the previous one: a flux node becomes held
// when its liquid pressure has reached the gas pressure, a held node flux again when the soil
// takes in more there than the rain brings (with no rain, any inflow). A node's liquid pressure
// for that test is the highest of its points' (a node beside a saturated point ponds, or
// seeps), and the gas pressure it is compared with the free surface's prescribed one, the air's
// above the face, as in the main cycle (cycles/flow_prescription.hpp). (Compared with its points'
// projected gas pressure, a top point past a node line whose gas the rain compressed never
// ponded: on V16's column with its top half a cell past a node line, 1/64 m cells, the top point
// at S_l = 0.999 kept its suction at 450 Pa while the rain drove both its pressures up together,
// to 10 kPa in 4 ms, until its water rushed out and its gas went to a vacuum at 1.94 s.) The rain
// that falls on flux nodes enters each column's top row of points as a mass rate in their liquid
// balances (RainfallSurface::point_supply), and is counted as inflow.
//
// No node takes in more than has fallen on it. A held node draws water through its boundary term,
// and a held step can take in more than the rain brings in that step (1.05-1.25 times on the
// coarse columns of verification/rain/README.md, where the top node alternates step by step
// between held and flux once its top point has filled). The rain that runs off is not stored,
// so that excess has no source: each surface node keeps it as a debt [kg per unit out-of-plane
// measure in 2D], and the rain later falling on it in flux mode goes to pay it first, counted as
// run-off, not as inflow. A node's intake by any time then exceeds the rain fallen on it by at
// most one held step's excess. A node that leaves the surface drops its debt.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "cycles/rainfall.hpp"
#include "input/case.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/shape_functions.hpp"

namespace unsatmpm {

template <int D, class K>
class ExplicitRain {
 public:
  /// A case with rainfall on its free surface (the parser checks gravity's axis and the gas
  /// condition).
  ExplicitRain(const Case& c, const numerics::Grid<D>& grid)
      : grid_(grid),
        surface_gas_(*c.free_surface->gas_pressure),
        rain_(grid, *c.free_surface->rainfall, c.fluids->liquid.reference_density, gravity_axis(c),
              c.gravity[gravity_axis(c)] < 0.0 ? -1 : 1),
        inflow_(grid.n_nodes(), 0.0),
        debt_(grid.n_nodes(), 0.0),
        delivered_(grid.n_nodes(), 1.0) {}

  /// At the start of a step over [t0, t1]: the modes of the free-surface nodes `surface` from the
  /// points' state (the end of the last step) and the inflow the last step recorded; returns the
  /// flux flags (1: flux, 0: held).
  const std::vector<std::uint8_t>& modes(double t0, double t1,
                                         const numerics::MaterialPoints<D>& mp,
                                         const numerics::FluidPoints<D>& fp,
                                         const std::vector<std::uint8_t>& surface) {
    project_pressures(t0, mp, fp);
    const auto n = static_cast<std::size_t>(grid_.n_nodes());
    for (std::size_t i = 0; i < n; ++i)  // the last step's excess at its held nodes
      if (!rain_.flux()[i])
        debt_[i] = std::max(0.0, debt_[i] + (inflow_[i] - rain_.supplied()[i]) * last_step_);
    const auto& flux = rain_.update_modes(surface, pressure_, inflow_);
    const auto& supplied = rain_.supply(t0, t1, mp, surface);  // what the next update compares a
                                                               // held node's inflow to
    last_step_ = t1 - t0;
    for (std::size_t i = 0; i < n; ++i) {
      delivered_[i] = 1.0;
      if (surface.empty() || !surface[i]) {
        debt_[i] = 0.0;
      } else if (flux[i] && debt_[i] > 0.0) {
        const double falls = supplied[i] * last_step_;
        const double paid = std::min(debt_[i], falls);
        debt_[i] -= paid;
        if (falls > 0.0) delivered_[i] = 1.0 - paid / falls;
      }
    }
    return flux;
  }

  /// Adds the rain on the flux nodes over [t0, t1] to the top rows' liquid mass rates
  /// (fp.liquid_rate [kg/(m^3 s)]); returns the mass rate that enters [kg/s per unit
  /// out-of-plane measure in 2D].
  double add_to_rates(double t0, double t1, const numerics::MaterialPoints<D>& mp,
                      const std::vector<std::uint8_t>& surface,
                      numerics::FluidPoints<D>& fp) const {
    double total = 0.0;
    for (const auto& [p, rate] : rain_.point_supply(t0, t1, mp, surface, delivered_)) {
      fp.liquid_rate[p] += rate / mp.volume[p];
      total += rate;
    }
    return total;
  }

  /// Each node's liquid inflow over the last step [kg/s per unit out-of-plane measure], filled
  /// by the cycle at the nodes open to the liquid (zero elsewhere).
  std::vector<double>& inflow() { return inflow_; }

  /// Free-surface nodes held at zero suction in the current step.
  std::int64_t held_nodes() const { return rain_.held_nodes(); }

  void save(CheckpointWriter& w) const {
    w.put("rain.inflow", inflow_);
    w.put("rain.debt", debt_);
    w.value("rain.last_step", last_step_);
    rain_.save(w);
  }
  void restore(CheckpointReader& r) {
    const auto n = static_cast<std::size_t>(grid_.n_nodes());
    r.get_sized("rain.inflow", inflow_, n);
    r.get_sized("rain.debt", debt_, n);
    last_step_ = r.value<double>("rain.last_step");
    rain_.restore(r);
  }

 private:
  /// The modes' pressures at time t: per node the highest liquid pressure of its points and the
  /// free surface's gas pressure.
  void project_pressures(double t, const numerics::MaterialPoints<D>& mp,
                         const numerics::FluidPoints<D>& fp) {
    const auto n = static_cast<std::size_t>(grid_.n_nodes());
    auto& liquid = pressure_[numerics::liquid_phase];
    liquid.assign(n, -std::numeric_limits<double>::infinity());
    pressure_[numerics::gas_phase].assign(n, surface_gas_(t));
    numerics::PointStencil<D, K> st;
    for (std::size_t p = 0; p < mp.size(); ++p) {
      st.evaluate(grid_, mp.position[p], mp.half_size[p]);
      for (int a = 0; a < st.n; ++a)
        if (st.w[a] > 0.0) liquid[st.node[a]] = std::max(liquid[st.node[a]], fp.liquid_pressure[p]);
    }
  }

  const numerics::Grid<D>& grid_;
  TimeFunction surface_gas_;  // the free surface's gas pressure [Pa]
  RainfallSurface<D, K> rain_;
  std::vector<double> inflow_;                   // [kg/s per unit out-of-plane measure]
  std::vector<double> debt_;                     // [kg per unit out-of-plane measure]
  std::vector<double> delivered_;                // each flux node's part of its rain delivered
                                                 // this step (set by modes())
  double last_step_ = 0.0;                       // the last step's length [s]
  std::array<std::vector<double>, 2> pressure_;  // per node: the highest P_l, the surface's P_g
                                                 // [Pa]
};

}  // namespace unsatmpm
