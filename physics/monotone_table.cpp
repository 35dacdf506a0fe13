#include "physics/monotone_table.hpp"

#include <cmath>
#include <string>

#include "physics/parameter_error.hpp"

namespace unsatmpm::physics {

namespace {

[[noreturn]] void bad_point(std::size_t k, const std::array<double, 2>& p, const std::string& why) {
  throw ParameterError("points[" + std::to_string(k) + "]", "point " + std::to_string(k) + " [" +
                                                                number_text(p[0]) + ", " +
                                                                number_text(p[1]) + "]: " + why);
}

}  // namespace

MonotoneTable MonotoneTable::create(const std::vector<std::array<double, 2>>& points,
                                    Direction direction, double lo, double hi, const char* x_name,
                                    const char* y_name) {
  if (points.size() < 2)
    throw ParameterError("points",
                         "a table needs at least 2 points, got " + std::to_string(points.size()));
  MonotoneTable t;
  const bool up = direction == Direction::increasing;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& p = points[k];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1])) bad_point(k, p, "not a finite number");
    if (k > 0 && !(p[0] > points[k - 1][0]))
      bad_point(k, p, std::string(x_name) + " must be strictly ascending");
    if (p[1] < lo || p[1] > hi)
      bad_point(
          k, p,
          std::string(y_name) + " must lie in [" + number_text(lo) + ", " + number_text(hi) + "]");
    if (k > 0 && (up ? p[1] < points[k - 1][1] : p[1] > points[k - 1][1]))
      bad_point(k, p,
                std::string(y_name) + " must not " + (up ? "decrease" : "increase") + " as " +
                    x_name + " grows");
    t.x_.push_back(p[0]);
    t.y_.push_back(p[1]);
  }
  const std::size_t n = t.x_.size();
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = t.x_[k + 1] - t.x_[k];
    d[k] = (t.y_[k + 1] - t.y_[k]) / h[k];
  }
  t.m_.assign(n, 0.0);
  t.m_[0] = d[0];
  t.m_[n - 1] = d[n - 2];
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (d[k - 1] * d[k] <= 0.0) continue;
    const double w1 = 2.0 * h[k] + h[k - 1], w2 = h[k] + 2.0 * h[k - 1];
    t.m_[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
  }
  return t;
}

std::size_t MonotoneTable::interval(double x, double& t) const {
  const auto it = std::upper_bound(x_.begin(), x_.end(), x);
  std::size_t k = static_cast<std::size_t>(it - x_.begin());
  k = std::min(std::max<std::size_t>(k, 1), x_.size() - 1) - 1;
  t = (x - x_[k]) / (x_[k + 1] - x_[k]);
  return k;
}

// Hermite basis on t in [0, 1] with h = x_{k+1} - x_k:
//   y = (2t^3 - 3t^2 + 1) y_k + (t^3 - 2t^2 + t) h m_k + (-2t^3 + 3t^2) y_{k+1} + (t^3 - t^2) h
//   m_{k+1}.
double MonotoneTable::value(double x) const {
  if (x <= x_.front()) return y_.front();
  if (x >= x_.back()) return y_.back();
  double t;
  const std::size_t k = interval(x, t);
  const double h = x_[k + 1] - x_[k], t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * y_[k] + (t3 - 2 * t2 + t) * h * m_[k] +
         (-2 * t3 + 3 * t2) * y_[k + 1] + (t3 - t2) * h * m_[k + 1];
}

double MonotoneTable::slope(double x) const {
  if (x <= x_.front() || x >= x_.back()) return 0.0;
  double t;
  const std::size_t k = interval(x, t);
  const double h = x_[k + 1] - x_[k], t2 = t * t;
  return ((6 * t2 - 6 * t) * y_[k] + (6 * t - 6 * t2) * y_[k + 1]) / h +
         (3 * t2 - 4 * t + 1) * m_[k] + (3 * t2 - 2 * t) * m_[k + 1];
}

double MonotoneTable::curvature(double x) const {
  if (x <= x_.front() || x >= x_.back()) return 0.0;
  double t;
  const std::size_t k = interval(x, t);
  const double h = x_[k + 1] - x_[k];
  return ((12 * t - 6) * (y_[k] - y_[k + 1]) / h + (6 * t - 4) * m_[k] + (6 * t - 2) * m_[k + 1]) /
         h;
}

}  // namespace unsatmpm::physics
