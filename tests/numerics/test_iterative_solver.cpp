// Tests of the flow's iterative linear solver: hypre's multigrid V-cycles as a preconditioner
// (numerics/amg_preconditioner.hpp) and CVODE with GMRES and that preconditioner
// (numerics/krylov_keeper.hpp) against an exact solution, against KLU, and on its error paths.
// In their own executable (tests/CMakeLists.txt): hypre initialises MPI, whose runtime keeps
// allocations to the end of the process that the leak checker must be told about.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "numerics/amg_preconditioner.hpp"
#include "numerics/cvode_integrator.hpp"

namespace unsatmpm::numerics {
namespace test_iterative_solver {

// ---- 2D diffusion y' = A y on the unit square, zero Dirichlet edges, m x m interior nodes ------
// A is the 5-point Laplacian with h = 1 / (m + 1). The sampled product of sine modes
// sin(k pi x) sin(l pi y) is an eigenvector with eigenvalue -(lambda_k + lambda_l),
// lambda_k = 4 / h^2 sin^2(k pi h / 2), so y(t) decays exactly as exp(-(lambda_k + lambda_l) t).

struct Diffusion2d {
  std::int64_t m;
  double inv_h2() const { return static_cast<double>((m + 1) * (m + 1)); }
  std::int64_t n() const { return m * m; }

  SparsePattern pattern() const {
    SparsePattern p{n(), {0}, {}};
    for (std::int64_t j = 0; j < m; ++j)
      for (std::int64_t i = 0; i < m; ++i) {
        if (j > 0) p.col.push_back((j - 1) * m + i);
        if (i > 0) p.col.push_back(j * m + i - 1);
        p.col.push_back(j * m + i);
        if (i + 1 < m) p.col.push_back(j * m + i + 1);
        if (j + 1 < m) p.col.push_back((j + 1) * m + i);
        p.row_ptr.push_back(static_cast<std::int64_t>(p.col.size()));
      }
    return p;
  }
  int rhs(std::span<const double> y, std::span<double> ydot) const {
    for (std::int64_t j = 0; j < m; ++j)
      for (std::int64_t i = 0; i < m; ++i) {
        const std::int64_t k = j * m + i;
        double sum = -4.0 * y[k];
        if (j > 0) sum += y[k - m];
        if (i > 0) sum += y[k - 1];
        if (i + 1 < m) sum += y[k + 1];
        if (j + 1 < m) sum += y[k + m];
        ydot[k] = sum * inv_h2();
      }
    return 0;
  }
  // Values in the pattern's order: -4/h^2 on the diagonal, 1/h^2 off it.
  void jacobian(std::span<double> values) const {
    const SparsePattern p = pattern();
    for (std::int64_t r = 0; r < p.n; ++r)
      for (std::int64_t k = p.row_ptr[r]; k < p.row_ptr[r + 1]; ++k)
        values[k] = (p.col[k] == r ? -4.0 : 1.0) * inv_h2();
  }
  std::vector<double> mode(int k, int l) const {
    std::vector<double> y(static_cast<std::size_t>(n()));
    const double h = 1.0 / static_cast<double>(m + 1);
    for (std::int64_t j = 0; j < m; ++j)
      for (std::int64_t i = 0; i < m; ++i)
        y[j * m + i] = std::sin(k * std::numbers::pi * (i + 1) * h) *
                       std::sin(l * std::numbers::pi * (j + 1) * h);
    return y;
  }
  double rate(int k) const {
    const double h = 1.0 / static_cast<double>(m + 1), s = std::sin(k * std::numbers::pi * h / 2.0);
    return 4.0 / (h * h) * s * s;
  }
};

// The grid's size is read from y's length (m x m unknowns), so that one integrator can be reset
// to grids of several sizes.
Diffusion2d grid_of(std::span<const double> y) {
  return {static_cast<std::int64_t>(std::lround(std::sqrt(static_cast<double>(y.size()))))};
}

CvodeIntegrator diffusion_integrator(CvodeTolerances tolerances) {
  return CvodeIntegrator(
      [](double, std::span<const double> y, std::span<double> ydot) {
        return grid_of(y).rhs(y, ydot);
      },
      [](double, std::span<const double> y, std::span<const double>, std::span<double> v) {
        grid_of(y).jacobian(v);
        return 0;
      },
      tolerances);
}

double max_difference(std::span<const double> a, std::span<const double> b) {
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

// The same bound as the direct solver's 1D test (test_cvode_integrator.cpp): rtol 1e-6 on a unit
// amplitude, 10 rtol of global error over some tens of steps. GMRES is asked for a residual of
// 0.05 of the Newton tolerance (CVODE's default), so it adds no error of a larger order.
constexpr CvodeTolerances kTolerances{1e-6, 1e-10};
constexpr double kErrorBound = 10.0 * 1e-6;

TEST(IterativeSolver, DiffusionMatchesExactModalDecayAndKlu) {
  const Diffusion2d problem{40};
  const std::vector<double> y0 = problem.mode(1, 2);
  const double t_end = 0.01;
  CvodeIntegrator iterative = diffusion_integrator(kTolerances);
  iterative.set_linear_solver(LinearSolverChoice::iterative);
  iterative.reset(problem.pattern(), 0.0, y0);
  EXPECT_TRUE(iterative.iterative());
  EXPECT_DOUBLE_EQ(iterative.integrate_to(t_end), t_end);

  std::vector<double> exact = y0;
  const double decay = std::exp(-(problem.rate(1) + problem.rate(2)) * t_end);
  for (double& v : exact) v *= decay;
  const double error = max_difference(iterative.state(), exact);
  EXPECT_LT(error, kErrorBound);
  EXPECT_GT(error, 0.0);

  CvodeIntegrator direct = diffusion_integrator(kTolerances);
  direct.set_linear_solver(LinearSolverChoice::direct);
  direct.reset(problem.pattern(), 0.0, y0);
  EXPECT_FALSE(direct.iterative());
  direct.integrate_to(t_end);
  EXPECT_LT(max_difference(iterative.state(), direct.state()), kErrorBound);

  const CvodeStatistics& s = iterative.statistics();
  EXPECT_EQ(s.lu_factorisations, 0);
  EXPECT_GT(s.preconditioner_setups, 0);
  EXPECT_GT(s.linear_iterations, 0);
  // A V-cycle of a 2D Laplacian-like matrix leaves GMRES a few iterations per Newton iteration.
  EXPECT_LE(s.linear_iterations, 10 * s.newton_iterations);
  EXPECT_GT(s.preconditioner_seconds, 0.0);
  EXPECT_EQ(direct.statistics().linear_iterations, 0);
  EXPECT_EQ(direct.statistics().preconditioner_setups, 0);
}

TEST(IterativeSolver, AutomaticChoiceFollowsTheSize) {
  const Diffusion2d small{10}, large{15};  // 100 and 225 unknowns
  CvodeIntegrator integrator = diffusion_integrator(kTolerances);
  integrator.reset(small.pattern(), 0.0, small.mode(1, 1));
  EXPECT_FALSE(integrator.iterative());  // the default: direct
  integrator.set_linear_solver(LinearSolverChoice::automatic, 200);
  integrator.reset(small.pattern(), 0.0, small.mode(1, 1));
  EXPECT_FALSE(integrator.iterative());  // below the threshold
  integrator.integrate_to(1e-3);
  integrator.reset(large.pattern(), 0.0, large.mode(1, 1));
  EXPECT_TRUE(integrator.iterative());  // above it
  integrator.integrate_to(1e-3);
  integrator.set_linear_solver(LinearSolverChoice::direct);
  integrator.reset(large.pattern(), 0.0, large.mode(1, 1));  // same pattern, another solver
  EXPECT_FALSE(integrator.iterative());
  EXPECT_THROW(integrator.set_linear_solver(LinearSolverChoice::automatic, 0),
               std::invalid_argument);
}

TEST(IterativeSolver, ExceptionInJacobianReachesTheCaller) {
  const Diffusion2d problem{10};
  CvodeIntegrator integrator(
      [problem](double, std::span<const double> y, std::span<double> ydot) {
        return problem.rhs(y, ydot);
      },
      [](double, std::span<const double>, std::span<const double>, std::span<double>) -> int {
        throw std::domain_error("jacobian model failure");
      },
      kTolerances);
  integrator.set_linear_solver(LinearSolverChoice::iterative);
  integrator.reset(problem.pattern(), 0.0, problem.mode(1, 1));
  EXPECT_THROW(integrator.integrate_to(0.01), std::domain_error);
}

// The preconditioner's V-cycles on the 2D Poisson matrix reduce the residual of any right-hand
// side by a large factor (multigrid's h-independent contraction, about 0.1 per V-cycle for a
// 5-point Laplacian); 0.5 would already be a poor multigrid, and no cycle at all leaves it at 1.
TEST(AmgPreconditioner, VCyclesContractThePoissonResidual) {
  for (const std::int64_t m : {16, 64}) {
    const Diffusion2d problem{m};
    const SparsePattern p = problem.pattern();
    std::vector<double> values(static_cast<std::size_t>(p.n_nonzeros()));
    problem.jacobian(values);
    for (double& v : values) v = -v;  // the SPD Laplacian
    AmgPreconditioner amg;
    amg.setup(p, values);
    std::vector<double> r(static_cast<std::size_t>(p.n)), z(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = std::sin(0.37 * static_cast<double>(i)) + 1;
    amg.apply(r, z);
    double residual = 0.0, norm = 0.0;
    for (std::int64_t row = 0; row < p.n; ++row) {
      double az = 0.0;
      for (std::int64_t k = p.row_ptr[row]; k < p.row_ptr[row + 1]; ++k)
        az += values[k] * z[p.col[k]];
      residual += (r[row] - az) * (r[row] - az);
      norm += r[row] * r[row];
    }
    EXPECT_LT(std::sqrt(residual / norm), 0.5) << "m = " << m;
  }
}

TEST(AmgPreconditioner, MisuseIsRejected) {
  AmgPreconditioner amg;
  std::vector<double> r(4, 1.0), z(4, 0.0);
  EXPECT_THROW(amg.apply(r, z), std::logic_error);
  const Diffusion2d problem{2};
  std::vector<double> too_few(3, 1.0);
  EXPECT_THROW(amg.setup(problem.pattern(), too_few), std::invalid_argument);
  std::vector<double> values(static_cast<std::size_t>(problem.pattern().n_nonzeros()));
  problem.jacobian(values);
  amg.setup(problem.pattern(), values);
  std::vector<double> short_z(3, 0.0);
  EXPECT_THROW(amg.apply(r, short_z), std::invalid_argument);
}

}  // namespace test_iterative_solver
}  // namespace unsatmpm::numerics
