// Tests of the CVODE/KLU wrapper: accuracy on problems with known solutions (linear diffusion
// against its exact modal decay, Robertson's kinetics against literature values), KLU symbolic
// analyses kept or redone on reset(), and the error paths (callback exceptions, failed steps,
// invalid input).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "numerics/cvode_integrator.hpp"

namespace unsatmpm::numerics {
namespace test_cvode_integrator {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// ---- 1D diffusion y' = A y on (0, 1), zero Dirichlet ends, n interior nodes -------------------
// A = tridiag(1, -2, 1) / h^2 with h = 1 / (n + 1). Its eigenvectors are the sampled sine modes
// sin(k pi x_i), x_i = (i + 1) h, with eigenvalues -lambda_k, lambda_k = 4 / h^2 sin^2(k pi h / 2),
// so y(t) = exp(-lambda_k t) sin(k pi x) exactly for the semi-discrete system.

SparsePattern tridiagonal_pattern(std::int64_t n) {
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

CvodeIntegrator diffusion_integrator(CvodeTolerances tolerances) {
  return CvodeIntegrator([](double t, std::span<const double> y,
                            std::span<double> ydot) { return Diffusion{}.rhs(t, y, ydot); },
                         [](double t, std::span<const double> y, std::span<const double> f,
                            std::span<double> v) { return Diffusion{}.jacobian(t, y, f, v); },
                         tolerances);
}

std::vector<double> sine_mode(std::int64_t n, int k) {
  std::vector<double> y(static_cast<std::size_t>(n));
  const double h = 1.0 / static_cast<double>(n + 1);
  for (std::int64_t i = 0; i < n; ++i) y[i] = std::sin(k * std::numbers::pi * (i + 1) * h);
  return y;
}

double decay_rate(std::int64_t n, int k) {
  const double h = 1.0 / static_cast<double>(n + 1), s = std::sin(k * std::numbers::pi * h / 2.0);
  return 4.0 / (h * h) * s * s;
}

// Max-norm error of the state against the exact decay of mode k at time t.
double mode_error(std::span<const double> y, int k, double t) {
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
constexpr double kDiffusionErrorBound = 10.0 * 1e-6;

TEST(CvodeIntegrator, DiffusionMatchesExactModalDecay) {
  const std::int64_t n = 50;
  const int k = 1;
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(n), 0.0, sine_mode(n, k));
  const double* buffer = integrator.state().data();
  double worst = 0.0;
  for (int out = 1; out <= 10; ++out) {
    const double t_out = 0.02 * out;
    EXPECT_DOUBLE_EQ(integrator.integrate_to(t_out), t_out);
    worst = std::max(worst, mode_error(integrator.state(), k, t_out));
  }
  EXPECT_LT(worst, kDiffusionErrorBound);
  EXPECT_GT(worst, 0.0);                         // the comparison is not vacuous
  EXPECT_EQ(integrator.state().data(), buffer);  // CVODE wrote into the buffer it wraps

  const CvodeStatistics& s = integrator.statistics();
  EXPECT_GT(s.steps, 10);
  EXPECT_GT(s.rhs_evaluations, s.steps);
  EXPECT_GT(s.newton_iterations, 0);
  EXPECT_GE(s.jacobian_evaluations, 1);
  EXPECT_LT(s.jacobian_evaluations, s.steps);  // CVODE reuses the Jacobian across steps
  EXPECT_EQ(s.klu_analyses, 1);
  // Every Jacobian is factorised; CVODE also refactorises I - gamma J when gamma changes.
  EXPECT_GE(s.klu_factorisations, s.jacobian_evaluations);
  EXPECT_LE(s.klu_factorisations, s.steps);
  EXPECT_GT(s.klu_setup_seconds, 0.0);
  EXPECT_LE(s.klu_setup_seconds, s.klu_seconds);
  EXPECT_GT(s.last_step, 0.0);
  EXPECT_GE(s.current_time, 0.2);
}

TEST(CvodeIntegrator, LooseToleranceIsDetectedByTheDiffusionCheck) {
  // The accuracy bound above can fail: with rtol = 1e-3 the error exceeds it.
  const std::int64_t n = 50;
  CvodeIntegrator integrator = diffusion_integrator({1e-3, 1e-6});
  integrator.reset(tridiagonal_pattern(n), 0.0, sine_mode(n, 1));
  integrator.integrate_to(0.2);
  EXPECT_GT(mode_error(integrator.state(), 1, 0.2), kDiffusionErrorBound);
}

TEST(CvodeIntegrator, ResetKeepsKluAnalysisOnlyForTheSamePattern) {
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.1);
  const CvodeStatistics first = integrator.statistics();
  ASSERT_EQ(first.klu_analyses, 1);

  // Same pattern, new initial condition (mode 2) and start time: CVodeReInit only.
  const double* buffer = integrator.state().data();
  integrator.reset(tridiagonal_pattern(50), 1.0, sine_mode(50, 2));
  EXPECT_EQ(integrator.state().data(), buffer);
  EXPECT_EQ(integrator.statistics().steps, first.steps);  // cumulative, nothing lost at reset
  EXPECT_DOUBLE_EQ(integrator.integrate_to(1.05), 1.05);
  EXPECT_LT(mode_error(integrator.state(), 2, 0.05), kDiffusionErrorBound);
  const CvodeStatistics second = integrator.statistics();
  EXPECT_EQ(second.klu_analyses, 1);
  EXPECT_GT(second.steps, first.steps);
  EXPECT_GT(second.jacobian_evaluations, first.jacobian_evaluations);  // new values, same analysis

  // A different size: new matrix, new KLU, one more symbolic analysis.
  integrator.reset(tridiagonal_pattern(40), 0.0, sine_mode(40, 1));
  ASSERT_EQ(integrator.state().size(), 40u);
  integrator.integrate_to(0.2);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.2), kDiffusionErrorBound);
  const CvodeStatistics third = integrator.statistics();
  EXPECT_EQ(third.klu_analyses, 2);
  EXPECT_GT(third.steps, second.steps);

  // Restart from the current state itself (y0 aliasing state()), as the coupling does.
  integrator.reset(tridiagonal_pattern(40), 0.2, integrator.state());
  integrator.integrate_to(0.3);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.3), kDiffusionErrorBound);
  EXPECT_EQ(integrator.statistics().klu_analyses, 2);

  // Back to 50 nodes: a pattern change again.
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.01);
  EXPECT_EQ(integrator.statistics().klu_analyses, 3);
}

TEST(CvodeIntegrator, StopTimeIsNotPassed) {
  double t_max_seen = 0.0;
  CvodeIntegrator integrator(
      [&](double t, std::span<const double> y, std::span<double> ydot) {
        t_max_seen = std::max(t_max_seen, t);
        return Diffusion{}.rhs(t, y, ydot);
      },
      [](double t, std::span<const double> y, std::span<const double> f, std::span<double> v) {
        return Diffusion{}.jacobian(t, y, f, v);
      },
      kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(20), 0.0, sine_mode(20, 1));
  integrator.set_stop_time(0.05);
  EXPECT_DOUBLE_EQ(integrator.integrate_to(0.1), 0.05);
  EXPECT_LE(t_max_seen, 0.05);
  EXPECT_LE(integrator.statistics().current_time, 0.05);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.05), kDiffusionErrorBound);
  // One-shot: the next call goes on to t_out.
  EXPECT_DOUBLE_EQ(integrator.integrate_to(0.1), 0.1);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.1), kDiffusionErrorBound);
}

// Rootfinding: the first sine mode decays as exp(-lambda_1 t); the root function y_mid - 0.5 falls
// through zero at t* = ln(2 y_mid(0)) / lambda_1, where integrate_to stops (within CVODE's root
// tolerance and the solution's own error, 1e-4 relative here). A rising function (0.5 - y_mid)
// is ignored, and after a reset without roots the integration runs to t_out.
TEST(CvodeIntegrator, StopsWhereARootFunctionFallsThroughZero) {
  const std::int64_t n = 21, mid = 10;  // y_mid(0) = sin(pi / 2) = 1
  const double h = 1.0 / (n + 1.0);
  const double lambda = 4.0 / (h * h) * std::pow(std::sin(std::numbers::pi * h / 2.0), 2);
  const double t_root = std::log(2.0) / lambda;
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  integrator.set_roots(2, [&](double, std::span<const double> y, std::span<double> g) {
    g[0] = 0.5 - y[mid];  // rises: ignored
    g[1] = y[mid] - 0.5;  // falls
    return 0;
  });
  integrator.reset(tridiagonal_pattern(n), 0.0, sine_mode(n, 1));
  const double t = integrator.integrate_to(1.0);
  EXPECT_NEAR(t, t_root, 1e-4 * t_root);
  EXPECT_EQ(integrator.roots_found(), std::vector<int>{1});
  EXPECT_NEAR(integrator.state()[mid], 0.5, 1e-4);
  integrator.set_roots(0, {});
  integrator.reset(tridiagonal_pattern(n), t, integrator.state());
  EXPECT_DOUBLE_EQ(integrator.integrate_to(2.0 * t_root), 2.0 * t_root);
  EXPECT_TRUE(integrator.roots_found().empty());
}

// ---- Robertson's chemical kinetics (Robertson 1966; Hairer & Wanner, Solving ODEs II) ----------
// y1' = -0.04 y1 + 1e4 y2 y3, y2' = 0.04 y1 - 1e4 y2 y3 - 3e7 y2^2, y3' = 3e7 y2^2, y(0) = (1,0,0).
// Literature values at t = 40: y1 = 0.7158, y2 = 9.185e-6, y3 = 0.2842 (4 digits).

TEST(CvodeIntegrator, RobertsonKineticsMatchesLiteratureAtT40) {
  const SparsePattern full{3, {0, 3, 6, 9}, {0, 1, 2, 0, 1, 2, 0, 1, 2}};
  CvodeIntegrator integrator(
      [](double, std::span<const double> y, std::span<double> ydot) {
        ydot[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
        ydot[2] = 3e7 * y[1] * y[1];
        ydot[1] = -ydot[0] - ydot[2];
        return 0;
      },
      [](double, std::span<const double> y, std::span<const double>, std::span<double> J) {
        J[0] = -0.04, J[1] = 1e4 * y[2], J[2] = 1e4 * y[1];
        J[6] = 0.0, J[7] = 6e7 * y[1], J[8] = 0.0;
        J[3] = -J[0] - J[6], J[4] = -J[1] - J[7], J[5] = -J[2] - J[8];
        return 0;
      },
      {1e-8, 1e-14});
  const std::vector<double> y0{1.0, 0.0, 0.0};
  integrator.reset(full, 0.0, y0);
  integrator.set_max_num_steps(5000);
  EXPECT_DOUBLE_EQ(integrator.integrate_to(40.0), 40.0);
  const auto y = integrator.state();
  // Half a unit in the 4th significant digit of the literature values, plus rounding slack.
  EXPECT_NEAR(y[0], 0.7158, 1e-4);
  EXPECT_NEAR(y[1], 9.185e-6, 1e-9);
  EXPECT_NEAR(y[2], 0.2842, 1e-4);
  EXPECT_NEAR(y[0] + y[1] + y[2], 1.0, 1e-10);  // the rhs conserves the total exactly
  EXPECT_EQ(integrator.statistics().klu_analyses, 1);
  EXPECT_GT(integrator.statistics().steps, 0);
}

// ---- error paths ------------------------------------------------------------------------------

struct ModelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

TEST(CvodeIntegrator, ExceptionInRhsReachesTheCaller) {
  CvodeIntegrator integrator(
      [](double t, std::span<const double> y, std::span<double> ydot) {
        if (t > 0.05) throw ModelError("saturation out of range at t > 0.05");
        return Diffusion{}.rhs(t, y, ydot);
      },
      [](double t, std::span<const double> y, std::span<const double> f, std::span<double> v) {
        return Diffusion{}.jacobian(t, y, f, v);
      },
      kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(10), 0.0, sine_mode(10, 1));
  try {
    integrator.integrate_to(0.1);
    ADD_FAILURE() << "no exception";
  } catch (const ModelError& e) {
    EXPECT_EQ(std::string(e.what()), "saturation out of range at t > 0.05");
  }
  EXPECT_LE(integrator.statistics().current_time, 0.05 + 1e-12);
  EXPECT_LT(mode_error(integrator.state(), 1, integrator.statistics().current_time),
            kDiffusionErrorBound);  // the last successful state, not garbage

  // The object stays usable: start again before the failure time.
  integrator.reset(tridiagonal_pattern(10), 0.0, sine_mode(10, 1));
  EXPECT_DOUBLE_EQ(integrator.integrate_to(0.04), 0.04);
}

TEST(CvodeIntegrator, ExceptionInJacobianReachesTheCaller) {
  CvodeIntegrator integrator(
      [](double t, std::span<const double> y, std::span<double> ydot) {
        return Diffusion{}.rhs(t, y, ydot);
      },
      [](double, std::span<const double>, std::span<const double>, std::span<double>) -> int {
        throw std::out_of_range("tangent undefined");
      },
      kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(10), 0.0, sine_mode(10, 1));
  try {
    integrator.integrate_to(0.1);
    ADD_FAILURE() << "no exception";
  } catch (const std::out_of_range& e) {
    EXPECT_EQ(std::string(e.what()), "tangent undefined");
  }
}

// Decoupled decays y_i' = -(i + 1) y_i whose component 3 turns NaN from the 40th rhs evaluation on
// (a model broken from then on). A NaN that depends on t or y instead lets CVODE creep up to the
// threshold with ever smaller steps until CV_TOO_MUCH_WORK; here every retry fails, so CVODE gives
// up with CV_CONV_FAILURE, and only component 3 of the Newton correction is NaN (diagonal J).
TEST(CvodeIntegrator, NanInRhsThrowsCvodeErrorNamingFlagTimeAndComponent) {
  const std::int64_t n = 5;
  SparsePattern diagonal{n, {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4}};
  long calls = 0;
  double t_last_good = 0.0;
  CvodeIntegrator integrator(
      [&](double t, std::span<const double> y, std::span<double> ydot) {
        for (std::size_t i = 0; i < y.size(); ++i) ydot[i] = -(i + 1.0) * y[i];
        if (++calls >= 40)
          ydot[3] = kNaN;
        else
          t_last_good = t;
        return 0;
      },
      [](double, std::span<const double>, std::span<const double>, std::span<double> J) {
        for (std::size_t i = 0; i < J.size(); ++i) J[i] = -(i + 1.0);
        return 0;
      },
      {1e-6, 1e-10});
  integrator.reset(diagonal, 0.0, std::vector<double>(n, 1.0));
  try {
    integrator.integrate_to(10.0);
    ADD_FAILURE() << "no CvodeError";
  } catch (const CvodeError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.flag_name(), "CV_CONV_FAILURE") << what;
    EXPECT_EQ(e.flag(), -4);
    EXPECT_TRUE(contains(what, "CV_CONV_FAILURE")) << what;
    EXPECT_TRUE(contains(what, "t = ")) << what;
    EXPECT_EQ(e.worst_component(), 3) << what;
    EXPECT_TRUE(contains(what, "worst component 3")) << what;
    EXPECT_GT(e.time(), 0.0);
    EXPECT_LE(e.time(), t_last_good);
    EXPECT_DOUBLE_EQ(e.time(), integrator.statistics().current_time);
    EXPECT_GE(integrator.statistics().convergence_failures, 10);  // CVODE's default limit
    for (std::size_t i = 0; i < n; ++i)                           // the last successful state
      EXPECT_NEAR(integrator.state()[i], std::exp(-(i + 1.0) * e.time()), 1e-4);
  }
}

TEST(CvodeIntegrator, PersistentRecoverableRhsErrorThrowsCvodeError) {
  CvodeIntegrator integrator([](double, std::span<const double>, std::span<double>) { return 1; },
                             [](double t, std::span<const double> y, std::span<const double> f,
                                std::span<double> v) { return Diffusion{}.jacobian(t, y, f, v); },
                             kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(10), 0.0, sine_mode(10, 1));
  try {
    integrator.integrate_to(0.1);
    ADD_FAILURE() << "no CvodeError";
  } catch (const CvodeError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.flag_name(), "CV_FIRST_RHSFUNC_ERR") << what;
    EXPECT_TRUE(contains(what, "CV_FIRST_RHSFUNC_ERR")) << what;
    EXPECT_TRUE(contains(what, "t = 0")) << what;
    EXPECT_EQ(e.worst_component(), -1);  // no step attempted
  }
}

TEST(CvodeIntegrator, TransientRecoverableRhsErrorIsRetriedWithSmallerSteps) {
  // The first three calls beyond t = 0.1 report a recoverable error; CVODE shrinks the step and
  // goes on. The solution is unaffected.
  int refusals_left = 3;
  CvodeIntegrator integrator(
      [&](double t, std::span<const double> y, std::span<double> ydot) {
        if (t > 0.1 && refusals_left > 0) {
          --refusals_left;
          return 1;
        }
        return Diffusion{}.rhs(t, y, ydot);
      },
      [](double t, std::span<const double> y, std::span<const double> f, std::span<double> v) {
        return Diffusion{}.jacobian(t, y, f, v);
      },
      kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  EXPECT_DOUBLE_EQ(integrator.integrate_to(0.2), 0.2);
  EXPECT_EQ(refusals_left, 0);
  EXPECT_GE(integrator.statistics().convergence_failures, 1);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.2), kDiffusionErrorBound);
}

TEST(CvodeIntegrator, TooMuchWorkKeepsTheLastSuccessfulState) {
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.set_max_num_steps(5);
  try {
    integrator.integrate_to(0.2);
    ADD_FAILURE() << "no CvodeError";
  } catch (const CvodeError& e) {
    EXPECT_EQ(e.flag_name(), "CV_TOO_MUCH_WORK") << e.what();
    EXPECT_GT(e.time(), 0.0);
    EXPECT_LT(e.time(), 0.2);
    EXPECT_GE(e.worst_component(), 0);
    EXPECT_LT(e.worst_component(), 50);
    EXPECT_LT(mode_error(integrator.state(), 1, e.time()), kDiffusionErrorBound);
  }
  EXPECT_EQ(integrator.statistics().steps, 5);
}

TEST(CvodeIntegrator, BadTolerancesAreRejectedByName) {
  const auto rhs = [](double, std::span<const double>, std::span<double>) { return 0; };
  const auto jac = [](double, std::span<const double>, std::span<const double>, std::span<double>) {
    return 0;
  };
  for (const double bad : {0.0, -1e-6, kNaN, kInf}) {
    try {
      CvodeIntegrator(rhs, jac, {bad, 1e-8});
      ADD_FAILURE() << "relative = " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(contains(e.what(), "relative")) << e.what();
    }
    try {
      CvodeIntegrator(rhs, jac, {1e-6, bad});
      ADD_FAILURE() << "absolute = " << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(contains(e.what(), "absolute")) << e.what();
    }
  }
}

TEST(CvodeIntegrator, MalformedInputIsRejected) {
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  EXPECT_THROW(integrator.integrate_to(1.0), std::logic_error);  // before reset()
  EXPECT_THROW(integrator.set_stop_time(1.0), std::logic_error);

  const std::vector<double> y0(3, 1.0);
  const auto expect_rejected = [&](const SparsePattern& p, const std::string& reason) {
    try {
      integrator.reset(p, 0.0, y0);
      ADD_FAILURE() << "accepted: " << reason;
    } catch (const std::invalid_argument& e) {
      EXPECT_TRUE(contains(e.what(), reason)) << e.what();
    }
  };
  expect_rejected({3, {0, 1, 2, 3}, {0, 2, 2}}, "diagonal entry missing in row 1");
  expect_rejected({3, {0, 2, 3, 4}, {1, 0, 1, 2}}, "not sorted");
  expect_rejected({3, {0, 1, 2}, {0, 1}}, "row_ptr needs n + 1");
  expect_rejected({3, {0, 1, 2, 3}, {0, 1, 3}}, "out of range");
  EXPECT_THROW(integrator.reset(tridiagonal_pattern(4), 0.0, y0), std::invalid_argument);

  integrator.reset(tridiagonal_pattern(3), 0.0, y0);
  EXPECT_THROW(integrator.set_max_step(0.0), std::invalid_argument);
  EXPECT_THROW(integrator.set_max_num_steps(0), std::invalid_argument);
  EXPECT_THROW(integrator.integrate_to(kNaN), std::invalid_argument);
}

// ---- Each run after a reset is independent of the runs before it ------------------------------
// y' = -[[a, b], [-c, a]] y, decaying at rate a and turning at sqrt(b c). With b much larger than
// 1 + gamma a the Newton matrix I + gamma [[a, b], [-c, a]] has its largest entry in row 0 off the
// diagonal, and KLU (which factors the transpose of the CSR matrix) pivots across; with a large
// and b, c small, on the diagonal. A second problem with the first one's pattern must give the
// same bits whether the integrator ran the first before or is new (a run resumed from a
// checkpoint, docs/output.md): nothing of the first run (step size, order, Jacobian, the
// factorisation's values) may carry over. KLU refactors with the kept pivots, and KLU keeps a
// diagonal pivot whenever it is at least 1e-3 of its column's largest entry, so the pressure
// systems' diagonally dominant matrices pivot alike however they were reached.

struct Rotation {
  double a = 0.0, b = 0.0, c = 0.0;
};

std::vector<double> run_rotation(CvodeIntegrator& cvode, Rotation& problem, Rotation now) {
  problem = now;
  const SparsePattern full{2, {0, 2, 4}, {0, 1, 0, 1}};
  const std::vector<double> y0{1.0, 0.5};
  cvode.reset(full, 0.0, y0);
  cvode.integrate_to(1.0);
  return {cvode.state().begin(), cvode.state().end()};
}

TEST(CvodeIntegrator, ARunAfterAResetRepeatsTheSameRunOnAFreshIntegrator) {
  Rotation problem;
  const auto make = [&] {
    return CvodeIntegrator(
        [&](double, std::span<const double> y, std::span<double> ydot) {
          ydot[0] = -(problem.a * y[0] + problem.b * y[1]);
          ydot[1] = -(-problem.c * y[0] + problem.a * y[1]);
          return 0;
        },
        [&](double, std::span<const double>, std::span<const double>, std::span<double> v) {
          v[0] = -problem.a, v[1] = -problem.b, v[2] = problem.c, v[3] = -problem.a;
          return 0;
        },
        {1e-8, 1e-12});
  };
  CvodeIntegrator used = make(), fresh = make();
  run_rotation(used, problem, {1.0, 1e6, 0.0});  // pivots off the diagonal
  const auto after = run_rotation(used, problem, {50.0, 3.0, 2.0});
  const auto alone = run_rotation(fresh, problem, {50.0, 3.0, 2.0});
  EXPECT_EQ(used.statistics().klu_analyses, 1);  // the second run kept the analysis
  ASSERT_EQ(after.size(), alone.size());
  for (std::size_t i = 0; i < after.size(); ++i) EXPECT_EQ(after[i], alone[i]) << "y[" << i << "]";
}

}  // namespace test_cvode_integrator
}  // namespace unsatmpm::numerics
