// Tests of the CVODE wrapper: accuracy on problems with known solutions (linear diffusion against
// its exact modal decay, Robertson's kinetics against literature values), the sparse LU's symbolic
// analyses kept or redone on reset() and its ordering's trial, stop times and roots, and a reset
// run repeating a fresh one; the direct solver's tests for both sparse LUs (UMFPACK, KLU). The
// error paths: test_cvode_integrator_errors.cpp.

#include "cvode_test_problems.hpp"

namespace unsatmpm::numerics::test_cvode_integrator {

/// The direct solver's tests, run with each sparse LU.
class DirectSolver : public ::testing::TestWithParam<DirectSolverChoice> {
 protected:
  CvodeIntegrator integrator(CvodeIntegrator cvode) const {
    cvode.set_direct_solver(GetParam());
    return cvode;
  }
};

INSTANTIATE_TEST_SUITE_P(BothLus, DirectSolver,
                         ::testing::Values(DirectSolverChoice::umfpack, DirectSolverChoice::klu),
                         [](const auto& info) {
                           return info.param == DirectSolverChoice::klu ? "Klu" : "Umfpack";
                         });

TEST_P(DirectSolver, DiffusionMatchesExactModalDecay) {
  const std::int64_t n = 50;
  const int k = 1;
  CvodeIntegrator integrator = this->integrator(diffusion_integrator(kDiffusionTolerances));
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
  EXPECT_EQ(s.lu_analyses, 1);
  // Every Jacobian is factorised; CVODE also refactorises I - gamma J when gamma changes.
  EXPECT_GE(s.lu_factorisations, s.jacobian_evaluations);
  EXPECT_LE(s.lu_factorisations, s.steps);
  EXPECT_GT(s.lu_setup_seconds, 0.0);
  EXPECT_LE(s.lu_setup_seconds, s.lu_seconds);
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

TEST_P(DirectSolver, ResetKeepsAnalysisOnlyForTheSamePattern) {
  CvodeIntegrator integrator = this->integrator(diffusion_integrator(kDiffusionTolerances));
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.1);
  const CvodeStatistics first = integrator.statistics();
  ASSERT_EQ(first.lu_analyses, 1);

  // Same pattern, new initial condition (mode 2) and start time: CVodeReInit only.
  const double* buffer = integrator.state().data();
  integrator.reset(tridiagonal_pattern(50), 1.0, sine_mode(50, 2));
  EXPECT_EQ(integrator.state().data(), buffer);
  EXPECT_EQ(integrator.statistics().steps, first.steps);  // cumulative, nothing lost at reset
  EXPECT_DOUBLE_EQ(integrator.integrate_to(1.05), 1.05);
  EXPECT_LT(mode_error(integrator.state(), 2, 0.05), kDiffusionErrorBound);
  const CvodeStatistics second = integrator.statistics();
  EXPECT_EQ(second.lu_analyses, 1);
  EXPECT_GT(second.steps, first.steps);
  EXPECT_GT(second.jacobian_evaluations, first.jacobian_evaluations);  // new values, same analysis

  // A different size: new matrix, new sparse LU, one more symbolic analysis.
  integrator.reset(tridiagonal_pattern(40), 0.0, sine_mode(40, 1));
  ASSERT_EQ(integrator.state().size(), 40u);
  integrator.integrate_to(0.2);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.2), kDiffusionErrorBound);
  const CvodeStatistics third = integrator.statistics();
  EXPECT_EQ(third.lu_analyses, 2);
  EXPECT_GT(third.steps, second.steps);

  // Restart from the current state itself (y0 aliasing state()), as the coupling does.
  integrator.reset(tridiagonal_pattern(40), 0.2, integrator.state());
  integrator.integrate_to(0.3);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.3), kDiffusionErrorBound);
  EXPECT_EQ(integrator.statistics().lu_analyses, 2);

  // Back to 50 nodes: a pattern change again.
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.01);
  EXPECT_EQ(integrator.statistics().lu_analyses, 3);
}

TEST_P(DirectSolver, TriesItsOrderingsOncePerSizeClass) {
  CvodeIntegrator integrator = this->integrator(diffusion_integrator(kDiffusionTolerances));
  EXPECT_EQ(integrator.statistics().lu_ordering, -1);
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.1);
  EXPECT_EQ(integrator.statistics().lu_ordering_trials, 1);
  // A tridiagonal matrix fills in with neither ordering: equal flops keep AMD.
  EXPECT_EQ(integrator.statistics().lu_ordering, 0);
  // Within a fifth of the size tried on: a new analysis, no new trial.
  integrator.reset(tridiagonal_pattern(41), 0.0, sine_mode(41, 1));
  integrator.integrate_to(0.1);
  EXPECT_EQ(integrator.statistics().lu_analyses, 2);
  EXPECT_EQ(integrator.statistics().lu_ordering_trials, 1);
  // Beyond it: tried again, and the answer is still right.
  integrator.reset(tridiagonal_pattern(39), 0.0, sine_mode(39, 1));
  integrator.integrate_to(0.1);
  EXPECT_EQ(integrator.statistics().lu_ordering_trials, 2);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.1), kDiffusionErrorBound);
}

TEST_P(DirectSolver, AGivenOrderingIsKeptAsATrialsWouldBe) {
  // As a resumed run hands over the saved run's choice: COLAMD chosen on 50 unknowns.
  CvodeIntegrator integrator = this->integrator(diffusion_integrator(kDiffusionTolerances));
  integrator.set_lu_ordering(1, 50);
  integrator.reset(tridiagonal_pattern(45), 0.0, sine_mode(45, 1));
  integrator.integrate_to(0.1);
  EXPECT_EQ(integrator.statistics().lu_ordering_trials, 0);
  EXPECT_EQ(integrator.statistics().lu_ordering, 1);
  EXPECT_EQ(integrator.statistics().lu_ordering_tried_on, 50);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.1), kDiffusionErrorBound);
  EXPECT_THROW(integrator.set_lu_ordering(2, 50), std::invalid_argument);
  EXPECT_THROW(integrator.set_lu_ordering(0, -1), std::invalid_argument);
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

TEST_P(DirectSolver, RobertsonKineticsMatchesLiteratureAtT40) {
  const SparsePattern full{3, {0, 3, 6, 9}, {0, 1, 2, 0, 1, 2, 0, 1, 2}};
  CvodeIntegrator integrator = this->integrator(CvodeIntegrator(
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
      {1e-8, 1e-14}));
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
  EXPECT_EQ(integrator.statistics().lu_analyses, 1);
  EXPECT_GT(integrator.statistics().steps, 0);
}

// ---- Each run after a reset is independent of the runs before it ------------------------------
// y' = -[[a, b], [-c, a]] y, decaying at rate a and turning at sqrt(b c). With b much larger than
// 1 + gamma a the Newton matrix I + gamma [[a, b], [-c, a]] has its largest entry in row 0 off the
// diagonal, and the sparse LU (which factors the transpose of the CSR matrix) pivots across; with a
// large and b, c small, on the diagonal. A second problem with the first one's pattern must give
// the same bits whether the integrator ran the first before or is new (a run resumed from a
// checkpoint, docs/output.md): nothing of the first run (step size, order, Jacobian, the
// factorisation's values) may carry over. UMFPACK pivots afresh at every factorisation; KLU
// refactors with the kept pivots, and keeps a diagonal pivot whenever it is at least 1e-3 of its
// column's largest entry, so the pressure systems' diagonally dominant matrices pivot alike
// however they were reached.

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

TEST_P(DirectSolver, ARunAfterAResetRepeatsTheSameRunOnAFreshIntegrator) {
  Rotation problem;
  const auto make = [&] {
    return this->integrator(CvodeIntegrator(
        [&](double, std::span<const double> y, std::span<double> ydot) {
          ydot[0] = -(problem.a * y[0] + problem.b * y[1]);
          ydot[1] = -(-problem.c * y[0] + problem.a * y[1]);
          return 0;
        },
        [&](double, std::span<const double>, std::span<const double>, std::span<double> v) {
          v[0] = -problem.a, v[1] = -problem.b, v[2] = problem.c, v[3] = -problem.a;
          return 0;
        },
        {1e-8, 1e-12}));
  };
  CvodeIntegrator used = make(), fresh = make();
  run_rotation(used, problem, {1.0, 1e6, 0.0});  // pivots off the diagonal
  const auto after = run_rotation(used, problem, {50.0, 3.0, 2.0});
  const auto alone = run_rotation(fresh, problem, {50.0, 3.0, 2.0});
  EXPECT_EQ(used.statistics().lu_analyses, 1);  // the second run kept the analysis
  ASSERT_EQ(after.size(), alone.size());
  for (std::size_t i = 0; i < after.size(); ++i) EXPECT_EQ(after[i], alone[i]) << "y[" << i << "]";
}

TEST(CvodeIntegrator, TheSparseLuIsUmfpackUnlessKluIsAsked) {
  CvodeIntegrator integrator = diffusion_integrator(kDiffusionTolerances);
  integrator.reset(tridiagonal_pattern(50), 0.0, sine_mode(50, 1));
  integrator.integrate_to(0.05);
  EXPECT_EQ(integrator.statistics().direct_solver, DirectSolverChoice::umfpack);
  EXPECT_EQ(integrator.statistics().lu_analyses, 1);
  // Another sparse LU on the same pattern: new solver objects, a new analysis, the same answer.
  integrator.set_direct_solver(DirectSolverChoice::klu);
  integrator.reset(tridiagonal_pattern(50), 0.05, integrator.state());
  integrator.integrate_to(0.2);
  EXPECT_EQ(integrator.statistics().direct_solver, DirectSolverChoice::klu);
  EXPECT_EQ(integrator.statistics().lu_analyses, 2);
  EXPECT_LT(mode_error(integrator.state(), 1, 0.2), kDiffusionErrorBound);
  // The same one again: CVodeReInit only.
  integrator.reset(tridiagonal_pattern(50), 0.2, integrator.state());
  integrator.integrate_to(0.3);
  EXPECT_EQ(integrator.statistics().lu_analyses, 2);
}

}  // namespace unsatmpm::numerics::test_cvode_integrator
