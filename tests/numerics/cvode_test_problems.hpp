// Problems with known solutions shared by the CVODE/KLU wrapper's tests (test_cvode_integrator.cpp,
// test_cvode_integrator_errors.cpp): 1D diffusion against its exact modal decay, and helpers.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "numerics/cvode_integrator.hpp"

namespace unsatmpm::numerics::test_cvode_integrator {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ---- 1D diffusion y' = A y on (0, 1), zero Dirichlet ends, n interior nodes -------------------
// A = tridiag(1, -2, 1) / h^2 with h = 1 / (n + 1). Its eigenvectors are the sampled sine modes
// sin(k pi x_i), x_i = (i + 1) h, with eigenvalues -lambda_k, lambda_k = 4 / h^2 sin^2(k pi h / 2),
// so y(t) = exp(-lambda_k t) sin(k pi x) exactly for the semi-discrete system.

inline SparsePattern tridiagonal_pattern(std::int64_t n) {
  SparsePattern p{n, {0}, {}};
  for (std::int64_t i = 0; i < n; ++i) {
    for (std::int64_t j = std::max<std::int64_t>(i - 1, 0); j <= std::min(i + 1, n - 1); ++j)
      p.col.push_back(j);
    p.row_ptr.push_back(static_cast<std::int64_t>(p.col.size()));
  }
  return p;
}

struct Diffusion {
  double inv_h2(std::size_t n) const { return (n + 1.0) * (n + 1.0); }

  int rhs(double, std::span<const double> y, std::span<double> ydot) const {
    const std::size_t n = y.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double left = i > 0 ? y[i - 1] : 0.0, right = i + 1 < n ? y[i + 1] : 0.0;
      ydot[i] = (left - 2.0 * y[i] + right) * inv_h2(n);
    }
    return 0;
  }
  // Values in the order of tridiagonal_pattern: (i, i-1), (i, i), (i, i+1).
  int jacobian(double, std::span<const double> y, std::span<const double>,
               std::span<double> values) const {
    const std::size_t n = y.size();
    std::size_t k = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) values[k++] = inv_h2(n);
      values[k++] = -2.0 * inv_h2(n);
      if (i + 1 < n) values[k++] = inv_h2(n);
    }
    return 0;
  }
};

inline CvodeIntegrator diffusion_integrator(CvodeTolerances tolerances) {
  return CvodeIntegrator([](double t, std::span<const double> y,
                            std::span<double> ydot) { return Diffusion{}.rhs(t, y, ydot); },
                         [](double t, std::span<const double> y, std::span<const double> f,
                            std::span<double> v) { return Diffusion{}.jacobian(t, y, f, v); },
                         tolerances);
}

inline std::vector<double> sine_mode(std::int64_t n, int k) {
  std::vector<double> y(static_cast<std::size_t>(n));
  const double h = 1.0 / static_cast<double>(n + 1);
  for (std::int64_t i = 0; i < n; ++i) y[i] = std::sin(k * std::numbers::pi * (i + 1) * h);
  return y;
}

inline double decay_rate(std::int64_t n, int k) {
  const double h = 1.0 / static_cast<double>(n + 1), s = std::sin(k * std::numbers::pi * h / 2.0);
  return 4.0 / (h * h) * s * s;
}

// Max-norm error of the state against the exact decay of mode k at time t.
inline double mode_error(std::span<const double> y, int k, double t) {
  const auto n = static_cast<std::int64_t>(y.size());
  const std::vector<double> shape = sine_mode(n, k);
  const double amplitude = std::exp(-decay_rate(n, k) * t);
  double error = 0.0;
  for (std::size_t i = 0; i < y.size(); ++i)
    error = std::max(error, std::abs(y[i] - amplitude * shape[i]));
  return error;
}

// rtol = 1e-6, atol = 1e-10. CVODE holds the local error per step near rtol |y|; over the ~40
// steps to t = 0.2 the global error stays within 10 rtol of the unit initial amplitude:
// |y - y_exact|_inf <= 1e-5 (measured: 3.1e-6). With rtol = 1e-5 (3.2e-5) or 1e-3 (1.0e-3) the
// same check fails.
constexpr CvodeTolerances kDiffusionTolerances{1e-6, 1e-10};
inline constexpr double kDiffusionErrorBound = 10.0 * 1e-6;

}  // namespace unsatmpm::numerics::test_cvode_integrator
