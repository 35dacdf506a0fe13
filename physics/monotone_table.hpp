// A measured curve given as points: monotone piecewise-cubic Hermite interpolation (Fritsch &
// Carlson 1980, SIAM J. Numer. Anal. 17; the slopes of Fritsch & Butland 1984), for retention and
// relative-permeability data (docs/models.md).
//
// Through knots x_0 < ... < x_{n-1} (n >= 2) with monotone values y_k, each interval is a cubic
// Hermite segment with the knot slopes m_k: where the neighbouring secants d_{k-1}, d_k have the
// same sign, m_k is their weighted harmonic mean,
//   m_k = (w1 + w2) / (w1 / d_{k-1} + w2 / d_k),  w1 = 2 h_k + h_{k-1},  w2 = h_k + 2 h_{k-1},
// else 0; at the ends m_0 = d_0 and m_{n-1} = d_{n-2}. These slopes lie within three times the
// secants, which keeps every segment monotone (Fritsch & Carlson's condition), so the curve never
// overshoots its data, is continuously differentiable, and has a finite second derivative in
// each interval (one-sided at the knots, the later interval's). Outside [x_0, x_{n-1}] it is
// constant with zero derivatives. value, slope and curvature are exact derivatives of one
// another, so a Jacobian built from them is consistent with the residual.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace unsatmpm::physics {

class MonotoneTable {
 public:
  enum class Direction { increasing, decreasing };  // non-strict

  /// Validated construction from (x, y) points; throws ParameterError("points[k]", ...) naming
  /// the first offending point: fewer than 2 points, x not strictly ascending, y not monotone in
  /// `direction`, y outside [lo, hi], a non-finite number.
  static MonotoneTable create(const std::vector<std::array<double, 2>>& points, Direction direction,
                              double lo, double hi, const char* x_name, const char* y_name);

  double value(double x) const;
  double slope(double x) const;      // dy/dx
  double curvature(double x) const;  // d2y/dx2
  double front() const { return y_.front(); }
  double back() const { return y_.back(); }
  double first_x() const { return x_.front(); }
  double last_x() const { return x_.back(); }
  const std::vector<double>& xs() const { return x_; }
  const std::vector<double>& ys() const { return y_; }

 private:
  /// The interval [x_k, x_{k+1}] holding x (x inside the range), and t = (x - x_k) / h_k.
  std::size_t interval(double x, double& t) const;

  std::vector<double> x_, y_, m_;  // knots, values, slopes
};

}  // namespace unsatmpm::physics
