// The CVODE/KLU wrapper's error paths: callback exceptions, non-finite and recoverable right-hand
// sides, too much work (the last good state kept), bad tolerances and malformed input.

#include "cvode_test_problems.hpp"

namespace unsatmpm::numerics::test_cvode_integrator {

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

}  // namespace unsatmpm::numerics::test_cvode_integrator
