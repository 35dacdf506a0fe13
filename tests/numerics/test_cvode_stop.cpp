// The CVODE wrapper's stop check (CvodeIntegrator::set_stop_check): a request from outside ends
// an integration at the next evaluation, with the last successful state kept, and the object
// goes on once the request is withdrawn.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "numerics/cvode_integrator.hpp"

namespace unsatmpm::numerics {
namespace test_cvode_stop {

// y_i' = -(i + 1) y_i, y_i(0) = 1: y_i(t) = exp(-(i + 1) t); diagonal pattern.
constexpr int kN = 4;
constexpr CvodeTolerances kTolerances{1e-8, 1e-12};

SparsePattern diagonal_pattern() {
  SparsePattern p{kN, {0}, {}};
  for (int i = 0; i < kN; ++i) p.col.push_back(i), p.row_ptr.push_back(i + 1);
  return p;
}

struct Counts {
  long rhs = 0, jacobian = 0;
};

CvodeIntegrator decay_integrator(Counts& counts) {
  return CvodeIntegrator(
      [&counts](double, std::span<const double> y, std::span<double> ydot) {
        ++counts.rhs;
        for (int i = 0; i < kN; ++i) ydot[i] = -(i + 1.0) * y[i];
        return 0;
      },
      [&counts](double, std::span<const double>, std::span<const double>, std::span<double> v) {
        ++counts.jacobian;
        for (int i = 0; i < kN; ++i) v[i] = -(i + 1.0);
        return 0;
      },
      kTolerances);
}

// Largest error of the state against the exact decay at t, in CVODE's error weights
// 1 / (rtol |y| + atol). Each step keeps its local error's weighted RMS norm below 1, so each
// component's below sqrt(kN) = 2; a decay does not amplify earlier errors, so after n steps the
// global error is below 2 n.
double weighted_error(std::span<const double> y, double t) {
  double error = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double exact = std::exp(-(i + 1.0) * t);
    error = std::max(
        error, std::abs(y[i] - exact) / (kTolerances.relative * exact + kTolerances.absolute));
  }
  return error;
}

TEST(CvodeStop, ARequestEndsTheIntegrationAtTheNextEvaluationWithTheLastGoodState) {
  Counts counts;
  CvodeIntegrator integrator = decay_integrator(counts);
  long polls = 0;
  integrator.set_stop_check([&] { return ++polls > 30; });
  integrator.reset(diagonal_pattern(), 0.0, std::vector<double>(kN, 1.0));
  EXPECT_THROW(integrator.integrate_to(5.0), StopRequested);
  // Every evaluation polled first, and none ran once the request was made.
  EXPECT_EQ(counts.rhs + counts.jacobian, 30);
  EXPECT_EQ(polls, 31);
  const double reached = integrator.statistics().current_time;
  EXPECT_GT(reached, 0.0);
  EXPECT_LT(reached, 5.0);
  // The state is CVODE's last successful step, accurate to the tolerances, not a half-done
  // Newton iterate.
  const long steps = integrator.statistics().steps;
  EXPECT_GT(steps, 0);
  EXPECT_LT(weighted_error(integrator.state(), reached), 2.0 * steps);

  // Withdrawn, the object integrates on from where it stopped to the exact answer.
  integrator.set_stop_check({});
  const std::vector<double> y(integrator.state().begin(), integrator.state().end());
  integrator.reset(diagonal_pattern(), reached, y);
  EXPECT_DOUBLE_EQ(integrator.integrate_to(5.0), 5.0);
  EXPECT_LT(weighted_error(integrator.state(), 5.0), 2.0 * integrator.statistics().steps);
}

// A stop names the component that erred most in the last step attempt, or -1 where that attempt
// had no estimate yet (stopped at its first evaluation). Stopped at each of 40 evaluations in
// turn, it names one at least once, and never one out of range.
TEST(CvodeStop, ARequestNamesTheComponentThatErredMost) {
  int named = 0;
  for (long stop_at = 5; stop_at < 45; ++stop_at) {
    Counts counts;
    CvodeIntegrator integrator = decay_integrator(counts);
    long polls = 0;
    integrator.set_stop_check([&] { return ++polls > stop_at; });
    integrator.reset(diagonal_pattern(), 0.0, std::vector<double>(kN, 1.0));
    try {
      integrator.integrate_to(5.0);
      ADD_FAILURE() << "no stop at " << stop_at;
    } catch (const StopRequested& e) {
      EXPECT_GE(e.worst_component(), -1);
      EXPECT_LT(e.worst_component(), kN);
      named += e.worst_component() >= 0;
    }
  }
  EXPECT_GT(named, 0);
}

TEST(CvodeStop, ARequestBeforeTheFirstEvaluationLeavesTheStartState) {
  Counts counts;
  CvodeIntegrator integrator = decay_integrator(counts);
  integrator.set_stop_check([] { return true; });
  integrator.reset(diagonal_pattern(), 2.0, std::vector<double>(kN, 0.5));
  EXPECT_THROW(integrator.integrate_to(3.0), StopRequested);
  EXPECT_EQ(counts.rhs + counts.jacobian, 0);
  for (const double v : integrator.state()) EXPECT_EQ(v, 0.5);
}

TEST(CvodeStop, AStopCheckThatNeverFiresChangesNothing) {
  Counts watched_counts, plain_counts;
  CvodeIntegrator watched = decay_integrator(watched_counts),
                  plain = decay_integrator(plain_counts);
  long polls = 0;
  watched.set_stop_check([&] { return ++polls < 0; });
  watched.reset(diagonal_pattern(), 0.0, std::vector<double>(kN, 1.0));
  plain.reset(diagonal_pattern(), 0.0, std::vector<double>(kN, 1.0));
  watched.integrate_to(5.0), plain.integrate_to(5.0);
  for (int i = 0; i < kN; ++i) EXPECT_EQ(watched.state()[i], plain.state()[i]);
  EXPECT_EQ(polls, watched_counts.rhs + watched_counts.jacobian);
  EXPECT_GT(polls, 0);
}

}  // namespace test_cvode_stop
}  // namespace unsatmpm::numerics
