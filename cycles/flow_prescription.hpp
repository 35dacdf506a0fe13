// What the main cycle's flow is held to: the pressures prescribed on boundary planes
// (boundaries[].liquid/gas) and on the free surface (free_surface.liquid/gas), and rain on the
// free surface with its ponding and seepage faces (cycles/rainfall.hpp). It tells the pressure
// system which nodes are prescribed and their values and rates at any time, and, under rain,
// switches surface nodes between held and flux, hands the flow the rain's supply and watches the
// flux nodes for ponding through CVODE's rootfinding. A node that carries points of a column's top
// row ponds when the highest of their liquid pressures reaches the gas pressure
// (cycles/top_row_pressures.hpp says why not its own). With the face's penalty
// (solver.implicit.surface_penalty) the held part of the face is drawn to its value on the face's
// trace instead, the light nodes alone held (numerics/pressure/surface_penalty.hpp, held_part).
//
// The free surface is applied first: conditions on planes take precedence where both apply.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "cycles/rainfall.hpp"
#include "cycles/three_phase_setup.hpp"
#include "cycles/top_row_pressures.hpp"
#include "numerics/cvode_integrator.hpp"
#include "numerics/pressure/pressure_system.hpp"

namespace unsatmpm {

template <int D, class K>
class FlowPrescription {
 public:
  /// Sets the prescribed nodes and the prescription callback on `system`, which must outlive
  /// this object (the callback refers to it).
  FlowPrescription(const Case& c, const numerics::Grid<D>& grid,
                   numerics::PressureSystem<D, K>& system)
      : case_(c), grid_(grid), system_(system) {
    numerics::ThreePhaseNodes<D> scratch;
    scratch.resize(grid_.n_nodes(), 1);
    boundaries_ = hydraulic_boundaries<D>(case_, grid_, scratch);
    std::array<std::vector<std::uint8_t>, 2> flags{std::vector<std::uint8_t>(grid_.n_nodes(), 0),
                                                   std::vector<std::uint8_t>(grid_.n_nodes(), 0)};
    for (const auto& f : boundaries_.liquid)
      for (const auto i : f.nodes) flags[numerics::liquid_phase][i] = 1;
    for (const auto& f : boundaries_.gas)
      for (const auto i : f.nodes) flags[numerics::gas_phase][i] = 1;
    system_.set_prescribed(numerics::liquid_phase, flags[numerics::liquid_phase]);
    system_.set_prescribed(numerics::gas_phase, flags[numerics::gas_phase]);
    if (const auto& surface = case_.free_surface) {
      system_.set_surface_prescribed(numerics::liquid_phase,
                                     surface->liquid.has_value() || surface->rainfall.has_value());
      system_.set_surface_prescribed(numerics::gas_phase, surface->gas_pressure.has_value());
      // The parser allows the penalty only with a liquid condition or rain; under rain it acts
      // on the held (ponded or seeping) part of the face (supply_rain, PressureSystem::prepare).
      if (surface->liquid || surface->rainfall)
        system_.set_surface_penalty(numerics::liquid_phase, case_.solver.implicit.surface_penalty);
      if (surface->rainfall) {
        const int axis = gravity_axis(case_);  // checked by the parser: >= 0 with rain
        rain_.emplace(grid_, *surface->rainfall, case_.fluids->liquid.reference_density, axis,
                      case_.gravity[axis] < 0.0 ? -1 : 1);
      }
    }
    system_.set_prescription(
        [this](double t, numerics::NodalPrescription& np) { prescribe(t, np); });
  }

  FlowPrescription(const FlowPrescription&) = delete;
  FlowPrescription& operator=(const FlowPrescription&) = delete;

  /// Rain changes the flow's supply and modes every interval, so the flow restarts each time.
  bool has_rain() const { return rain_.has_value(); }

  /// Before the system's prepare: the surface nodes' modes (held or flux) from the end of the
  /// previous interval, its nodal pressures `nodal` [Pa], with the points `mp` where it left them.
  void update_surface_modes(const std::array<std::vector<double>, 2>& nodal,
                            const numerics::MaterialPoints<D>& mp) {
    if (!rain_) return;
    top_row_.build(grid_, mp, rain_->top_row(mp));
    std::array<std::vector<double>, 2> test = nodal;
    const auto& liquid = nodal[numerics::liquid_phase];
    for (std::size_t i = 0; i < liquid.size(); ++i)
      test[numerics::liquid_phase][i] = top_row_.at(static_cast<std::int64_t>(i), liquid[i],
                                                    [&](std::int64_t a) { return liquid[a]; });
    system_.set_surface_exempt(numerics::liquid_phase,
                               rain_->update_modes(system_.surface_nodes(), test, inflow_));
  }

  /// After the system's prepare: the rain's supply over [t0, t1] from the points' configuration
  /// (that of update_surface_modes), and the flux nodes under rain as CVODE's roots (their
  /// ponding stops the integration).
  void supply_rain(double t0, double t1, const numerics::MaterialPoints<D>& mp,
                   numerics::CvodeIntegrator& cvode) {
    if (!rain_) return;
    const auto& surface = system_.surface_nodes();
    std::vector<double> supply = rain_->nodal_supply(t0, t1, mp, surface);
    // A held node's entry is what the rain would bring it (for the next modes): under the face's
    // penalty a held node is an unknown, which would take it in, so the rain there runs off.
    if (case_.solver.implicit.surface_penalty > 0.0)
      for (std::size_t i = 0; i < supply.size(); ++i)
        if (surface[i] && !rain_->flux()[i]) supply[i] = 0.0;
    system_.set_supply(numerics::liquid_phase, supply);
    roots_.clear();
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (const auto k = system_.unknown(numerics::liquid_phase, i);
          supply[i] > 0.0 && k >= 0 && surface[i])
        roots_.push_back({i, k});
    // At each watched node: the gas pressure (held on the surface) minus its ponding pressure,
    // which falls through zero where the node ponds. A node that is not an unknown is held at the
    // surface's gas pressure (or, on a boundary plane, counted so: a held value is not in y).
    cvode.set_roots(static_cast<int>(roots_.size()),
                    [this](double t, std::span<const double> y, std::span<double> g) {
                      const double pg = (*case_.free_surface->gas_pressure)(t);
                      const auto value = [&](std::int64_t a) {
                        const auto k = system_.unknown(numerics::liquid_phase, a);
                        return k >= 0 ? y[k] : pg;
                      };
                      for (std::size_t j = 0; j < roots_.size(); ++j)
                        g[j] = pg - top_row_.at(roots_[j].node, y[roots_[j].unknown], value);
                      return 0;
                    });
  }

  /// Holds at zero suction the nodes whose roots CVODE found (they ponded).
  void hold_ponded(const std::vector<int>& found) {
    for (const int k : found) rain_->hold(roots_[k].node);
  }

  /// At the end of an update: each node's liquid inflow at (t, y), for the next modes.
  void record_inflow(double t, std::span<const double> y) {
    if (rain_) inflow_ = system_.inflow_by_node(numerics::liquid_phase, t, y);
  }

  /// The state the next interval's modes start from (a checkpoint keeps it): the last update's
  /// nodal inflow and the rain's modes and supply.
  void save(CheckpointWriter& w) const {
    w.put("rain.inflow", inflow_);
    w.value("rain.on", std::uint8_t{rain_.has_value()});
    if (rain_) rain_->save(w);
  }
  void restore(CheckpointReader& r) {
    r.get("rain.inflow", inflow_);
    if ((r.value<std::uint8_t>("rain.on") != 0) != rain_.has_value())
      r.fail("the case's rainfall and the checkpoint's differ");
    if (rain_) rain_->restore(r);
  }

  /// After the system's prepare: the free-surface nodes that hold the surface's liquid pressure or
  /// suction, or under rain its zero suction (ponded or seeping), and how many of them the points
  /// barely reach (less than an eighth of a full node's volume, numerics::light_node) where no
  /// penalty acts on the face. At those the condition is held outside the face, and the soil under
  /// it takes in too little water (docs/input.md, "Known limitation of the main cycle";
  /// numerics/pressure/free_surface.hpp; docs/known_failures.md for rain). {0, 0} with the
  /// penalty or without a liquid condition or rain on the surface.
  std::array<std::int64_t, 2> held_surface_nodes() const {
    std::array<std::int64_t, 2> n{0, 0};
    const auto& surface = case_.free_surface;
    if (!surface || !(surface->liquid || surface->rainfall) ||
        case_.solver.implicit.surface_penalty > 0.0)
      return n;
    const auto& on = system_.surface_nodes();
    const auto& held = system_.prescribed(numerics::liquid_phase);
    const auto& volume = system_.quadrature().node_volume;
    for (std::int64_t i = 0; i < grid_.n_nodes(); ++i)
      if (on[i] && held[i]) ++n[0], n[1] += numerics::light_node<D>(grid_, volume[i], i);
    return n;
  }

  /// Free-surface nodes held at zero suction (ponded or seeping) in the current interval.
  std::int64_t held_nodes() const { return rain_ ? rain_->held_nodes() : 0; }
  /// Liquid mass rate entering at each node at the last update [kg/s per unit out-of-plane
  /// measure]; empty without rain.
  const std::vector<double>& liquid_inflow() const { return inflow_; }

 private:
  void prescribe(double t, numerics::NodalPrescription& np) const {
    if (const auto& surface = case_.free_surface) {
      const auto& on = system_.surface_nodes();
      const auto set = [&](int a, double value, double rate) {
        for (std::size_t i = 0; i < on.size(); ++i)
          if (on[i]) np.value[a][i] = value, np.rate[a][i] = rate;
      };
      if (surface->liquid) {
        np.surface_value[numerics::liquid_phase] =
            prescribed_liquid_pressure(*surface->liquid, surface->gas_pressure, t);
        set(numerics::liquid_phase, np.surface_value[numerics::liquid_phase],
            prescribed_liquid_pressure_rate(*surface->liquid, surface->gas_pressure, t));
      } else if (surface->rainfall) {  // held surface nodes: zero suction
        np.surface_value[numerics::liquid_phase] = (*surface->gas_pressure)(t);
        set(numerics::liquid_phase, (*surface->gas_pressure)(t), surface->gas_pressure->rate(t));
      }
      if (surface->gas_pressure)
        set(1, (*surface->gas_pressure)(t), surface->gas_pressure->rate(t));
    }
    for (const auto& f : boundaries_.liquid) {
      const double v = prescribed_liquid_pressure(*f.spec, t);
      const double r = prescribed_liquid_pressure_rate(*f.spec, t);
      for (const auto i : f.nodes)
        np.value[numerics::liquid_phase][i] = v, np.rate[numerics::liquid_phase][i] = r;
    }
    for (const auto& f : boundaries_.gas) {
      const double v = (*f.spec->gas_pressure)(t), r = f.spec->gas_pressure->rate(t);
      for (const auto i : f.nodes)
        np.value[numerics::gas_phase][i] = v, np.rate[numerics::gas_phase][i] = r;
    }
  }

  struct Root {
    std::int64_t node, unknown;
  };

  const Case& case_;
  const numerics::Grid<D>& grid_;
  numerics::PressureSystem<D, K>& system_;
  HydraulicBoundaries boundaries_;
  std::optional<RainfallSurface<D, K>> rain_;  // with a rainfall on the free surface
  std::vector<double> inflow_;                 // liquid inflow per node at the last update
  std::vector<Root> roots_;                    // the nodes watched for ponding in this run
  TopRowPressures<D, K> top_row_;              // the ponding pressures of this interval
};

}  // namespace unsatmpm
