// When a run has come to rest (solver.stop_at_rest, docs/input.md): the body's kinetic energy
// E_k = 1/2 sum_p m_p |v_p|^2 (that of globals.csv: the solid's; per metre out of plane in 2D),
// checked after every step, has stayed below `fraction` times its largest value so far for
// `hold` seconds, once that largest value has exceeded `min_peak`. A body that never moves that
// much is never at rest in this sense: it runs to the end time. So a slide's run-out is taken when
// the slide has stopped, not at whatever time the case happens to end.
#pragma once

#include <fmt/core.h>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "input/case.hpp"
#include "numerics/material_points.hpp"

namespace unsatmpm {

/// 1/2 sum_p m_p |v_p|^2 [J, per metre out of plane in 2D, per square metre in 1D].
template <int D>
double kinetic_energy(const numerics::MaterialPoints<D>& mp) {
  double e = 0.0;
  for (std::size_t p = 0; p < mp.size(); ++p) e += 0.5 * mp.mass[p] * mp.velocity[p].squaredNorm();
  return e;
}

class RestMonitor {
 public:
  /// No rule: never at rest.
  RestMonitor() = default;
  explicit RestMonitor(const std::optional<RestSpec>& spec) : spec_(spec) {}

  bool active() const { return spec_.has_value(); }

  /// The kinetic energy `energy` [J] reached at time t [s]; true when the run is at rest then.
  bool at_rest(double t, double energy) {
    if (!spec_ || stopped_) return stopped_;
    if (energy > peak_) peak_ = energy, peak_time_ = t;
    if (peak_ <= spec_->min_peak || !(energy < spec_->fraction * peak_)) {
      below_since_ = nan;
      return false;
    }
    if (!(below_since_ <= t)) below_since_ = t;
    stopped_ = t - below_since_ >= spec_->hold * (1.0 - 1e-12);
    return stopped_;
  }

  /// True once at_rest has said so; a resumed run that had stopped has nothing left to do.
  bool stopped() const { return stopped_; }

  /// The summary's message for a run that stopped at rest at time t [s].
  std::string message(double t, double energy) const {
    return fmt::format(
        "at rest at t = {:.9g} s: kinetic energy {:.6g} J, below {:.6g} of its peak {:.6g} J "
        "(t = {:.9g} s) since t = {:.9g} s",
        t, energy, spec_->fraction, peak_, peak_time_, below_since_);
  }

  void save(CheckpointWriter& w) const {
    w.value("rest.peak", peak_);
    w.value("rest.peak_time", peak_time_);
    w.value("rest.below_since", below_since_);
    w.value("rest.stopped", std::int64_t{stopped_});
  }
  void restore(CheckpointReader& r) {
    peak_ = r.value<double>("rest.peak");
    peak_time_ = r.value<double>("rest.peak_time");
    below_since_ = r.value<double>("rest.below_since");
    stopped_ = r.value<std::int64_t>("rest.stopped") != 0;
  }

 private:
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::optional<RestSpec> spec_;
  double peak_ = 0.0, peak_time_ = 0.0;  // the largest kinetic energy so far [J], and when [s]
  double below_since_ = nan;             // start of the current stretch below the fraction [s]
  bool stopped_ = false;
};

}  // namespace unsatmpm
