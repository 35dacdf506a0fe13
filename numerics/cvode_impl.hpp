// The CVODE wrapper's state (numerics/cvode_integrator.hpp), private to the wrapper's files:
// cvode_integrator.cpp (the public calls, the solver objects' construction, the statistics) and
// cvode_callbacks.cpp (the functions CVODE calls back, which let no exception cross into C).
#pragma once

#include "numerics/cvode_integrator.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <limits>
#include <sstream>
#include <utility>

#include "numerics/cvode_support.hpp"
#include "numerics/klu_keeper.hpp"
#include "numerics/krylov_keeper.hpp"
#include "numerics/sundials_handles.hpp"
#include "numerics/umfpack_keeper.hpp"

namespace unsatmpm::numerics {

static_assert(std::is_same_v<sunindextype, std::int64_t>, "SparsePattern assumes 64-bit indices");
static_assert(std::is_same_v<realtype, double>, "the wrapper assumes double precision");

// The wrapper's own helpers, for its two files.
using cvode_support::check_cvls;
using cvode_support::check_cvode;
using cvode_support::check_tolerance;
using cvode_support::cvode_flag_name;
using cvode_support::CvodePtr;
using cvode_support::read_run_counters;
using cvode_support::RunCounters;
using cvode_support::view;

/// The relative change of gamma past which CVODE renews the Newton matrix (create_solver_objects).
inline constexpr double newton_matrix_gamma_change = 1.0;
using cvode_support::worst_weighted_error;
using sundials::check_created;
using sundials::ContextPtr;
using sundials::MatrixPtr;
using sundials::VectorPtr;

struct CvodeIntegrator::Impl {
  Rhs rhs;
  Jacobian jacobian;
  CvodeTolerances tolerances;
  double max_step = std::numeric_limits<double>::infinity();
  long max_num_steps = 500;  // CVODE's default
  int n_roots = 0;
  Roots roots;
  StopCheck stop_check;
  bool stop_time_pending = false;
  LinearSolverChoice choice = LinearSolverChoice::direct;
  DirectSolverChoice direct = DirectSolverChoice::umfpack;  // for the next solver objects
  std::int64_t iterative_from = 1;  // unknowns from which `automatic` is iterative

  SparsePattern pattern;   // of the live matrix; n = 0 until the first successful reset
  bool iterative = false;  // the live linear solver is GMRES with multigrid
  std::vector<double> y;   // the unknowns; y_vector wraps this buffer
  double t_reached = 0.0;

  std::exception_ptr callback_exception;  // thrown in a callback, rethrown after CVode
  std::string last_cvode_message;         // from CVODE's error handler
  long n_rhs = 0, n_jacobian = 0;
  LuCounters lu_counters;          // over every sparse LU of the object's life
  LuOrdering lu_ordering;          // chosen by the first sparse LU's trial, kept by the later ones
  KrylovCounters krylov_counters;  // over every GMRES solver of the object's life
  RunCounters finished_runs;       // sums over CVODE runs ended by reset()
  CvodeStatistics statistics;

  // Creation order; destroyed in reverse.
  ContextPtr context;
  VectorPtr y_vector;
  MatrixPtr matrix;
  std::unique_ptr<UmfpackKeeper> umfpack;  // or:
  std::unique_ptr<KluKeeper> klu;
  std::unique_ptr<KrylovKeeper> krylov;
  CvodePtr cvode;

  Impl(Rhs rhs_, Jacobian jacobian_, CvodeTolerances tolerances_)
      : rhs(std::move(rhs_)), jacobian(std::move(jacobian_)), tolerances(tolerances_) {
    check_tolerance(tolerances.relative, "relative");
    check_tolerance(tolerances.absolute, "absolute");
    if (!rhs) throw std::invalid_argument("CvodeIntegrator: the rhs callback is empty");
    if (!jacobian) throw std::invalid_argument("CvodeIntegrator: the Jacobian callback is empty");
    SUNContext raw = nullptr;
    const int flag = SUNContext_Create(nullptr, &raw);
    if (flag != 0 || raw == nullptr)
      throw std::runtime_error("SUNContext_Create failed with " + std::to_string(flag));
    context.reset(raw);
  }

  bool ready() const { return cvode != nullptr && pattern.n > 0; }

  /// Throws StopRequested if the stop check asks to end the integration (in a callback's try).
  void throw_if_stop_requested() const {
    if (stop_check && stop_check())
      throw StopRequested("the integration was asked to stop (CvodeIntegrator::set_stop_check)");
  }

  // ---- callbacks: no exception crosses into C -------------------------------------------------

  static int rhs_callback(realtype t, N_Vector y, N_Vector ydot, void* user_data);

  static int jacobian_callback(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user_data,
                               N_Vector, N_Vector, N_Vector);

  // The iterative solver's callbacks (numerics/krylov_keeper.hpp).
  static int preconditioner_setup(realtype t, N_Vector y, N_Vector fy, booleantype jok,
                                  booleantype* fresh, realtype gamma, void* user_data);

  static int preconditioner_solve(realtype, N_Vector, N_Vector, N_Vector r, N_Vector z, realtype,
                                  realtype, int, void* user_data);

  static int jacobian_times(N_Vector v, N_Vector jv, realtype, N_Vector, N_Vector, void* user_data,
                            N_Vector);

  static int roots_callback(realtype t, N_Vector y, realtype* g, void* user_data);

  /// Rootfinding as set_roots asked, for the run that starts now.
  void apply_roots() {
    void* mem = cvode.get();
    if (n_roots == 0) {
      check_cvode(CVodeRootInit(mem, 0, nullptr), "CVodeRootInit");
      return;
    }
    check_cvode(CVodeRootInit(mem, n_roots, roots_callback), "CVodeRootInit");
    std::vector<int> falling(static_cast<std::size_t>(n_roots), -1);
    check_cvode(CVodeSetRootDirection(mem, falling.data()), "CVodeSetRootDirection");
    // A function that starts at zero is not a root (the caller decides at the restart).
    check_cvode(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
  }

  static void error_handler(int error_code, const char* module, const char* function, char* msg,
                            void* user_data);

  // ---- construction of the SUNDIALS objects ---------------------------------------------------

  void destroy_solver_objects() {
    cvode.reset();
    krylov.reset();
    klu.reset();
    umfpack.reset();
    matrix.reset();
    y_vector.reset();
    pattern = SparsePattern{};
  }

  bool resolve_iterative(std::int64_t n) const {
    return choice == LinearSolverChoice::iterative ||
           (choice == LinearSolverChoice::automatic && n >= iterative_from);
  }

  // Objects for `pattern` (already stored) with the linear solver `iterative` says.
  void create_solver_objects(double t0) {
    const SparsePattern& p = pattern;
    y_vector.reset(check_created(
        N_VMake_Serial(static_cast<sunindextype>(p.n), y.data(), context.get()), "N_VMake_Serial"));
    if (iterative) {
      sundials::use_blocked_dot(y_vector.get());  // for SPGMR's Gram-Schmidt, cloned from y
      krylov = std::make_unique<KrylovKeeper>(y_vector.get(), context.get(), p, krylov_counters);
    } else {
      matrix.reset(check_created(SUNSparseMatrix(p.n, p.n, p.n_nonzeros(), CSR_MAT, context.get()),
                                 "SUNSparseMatrix"));
      std::copy(p.row_ptr.begin(), p.row_ptr.end(), SUNSparseMatrix_IndexPointers(matrix.get()));
      std::copy(p.col.begin(), p.col.end(), SUNSparseMatrix_IndexValues(matrix.get()));
      std::fill_n(SUNSparseMatrix_Data(matrix.get()), p.n_nonzeros(), 0.0);
      if (direct == DirectSolverChoice::klu)
        klu = std::make_unique<KluKeeper>(y_vector.get(), matrix.get(), context.get(), lu_counters,
                                          lu_ordering);
      else
        umfpack = std::make_unique<UmfpackKeeper>(context.get(), lu_counters, lu_ordering);
      statistics.direct_solver = direct;
    }

    cvode.reset(check_created(CVodeCreate(CV_BDF, context.get()), "CVodeCreate"));
    void* mem = cvode.get();
    check_cvode(CVodeInit(mem, rhs_callback, t0, y_vector.get()), "CVodeInit");
    check_cvode(CVodeSetUserData(mem, this), "CVodeSetUserData");
    check_cvode(CVodeSetErrHandlerFn(mem, error_handler, this), "CVodeSetErrHandlerFn");
    check_cvode(CVodeSStolerances(mem, tolerances.relative, tolerances.absolute),
                "CVodeSStolerances");
    if (iterative) {
      check_cvls(CVodeSetLinearSolver(mem, krylov->solver(), nullptr), "CVodeSetLinearSolver");
      check_cvls(CVodeSetPreconditioner(mem, preconditioner_setup, preconditioner_solve),
                 "CVodeSetPreconditioner");
      check_cvls(CVodeSetJacTimes(mem, nullptr, jacobian_times), "CVodeSetJacTimes");
    } else {
      check_cvls(CVodeSetLinearSolver(mem, klu ? klu->solver() : umfpack->solver(), matrix.get()),
                 "CVodeSetLinearSolver");
      check_cvls(CVodeSetJacFn(mem, jacobian_callback), "CVodeSetJacFn");
    }
    check_cvode(CVodeSetMaxStep(mem, std::isinf(max_step) ? 0.0 : max_step), "CVodeSetMaxStep");
    check_cvode(CVodeSetMaxNumSteps(mem, max_num_steps), "CVodeSetMaxNumSteps");
    // The Newton matrix I - gamma J is renewed when gamma has moved by more than this fraction
    // since it was formed (CVODE's default 0.3). Every coupling interval restarts CVODE at order
    // 1 with a small step that then grows, each growth past 30 % a new factorisation. With the
    // matrix of gamma_old and r = gamma / gamma_old, CVODE scales each Newton update by
    // 2 / (1 + r); for an eigenvalue z = gamma_old lambda <= 0 of gamma_old J (diffusion) the
    // error then shrinks by 1 - (2 / (1 + r)) (1 - r z) / (1 - z), at most |r - 1| / (r + 1) in
    // size: 1/3 for r = 2, 0.6 for r = 4. Up to r = 2 the iteration converges about as fast as
    // CVODE's three-iteration test needs; a convergence failure renews the matrix anyway. (With
    // GMRES only the preconditioner ages: its products use the current gamma.)
    // Measured on the embankment to 4 s: 24 factorisations in 8 intervals against 32, 72 Newton
    // iterations against 75 (10 gave 19 but 101). docs/performance.md, also for 2 (not kept).
    check_cvode(CVodeSetDeltaGammaMaxLSetup(mem, newton_matrix_gamma_change),
                "CVodeSetDeltaGammaMaxLSetup");
  }

  // ---- statistics and failures ----------------------------------------------------------------

  void refresh_statistics() {
    const RunCounters run = read_run_counters(cvode.get());
    statistics.steps = finished_runs.steps + run.steps;
    statistics.newton_iterations = finished_runs.newton_iterations + run.newton_iterations;
    statistics.error_test_failures = finished_runs.error_test_failures + run.error_test_failures;
    statistics.convergence_failures = finished_runs.convergence_failures + run.convergence_failures;
    statistics.linear_iterations = finished_runs.linear_iterations + run.linear_iterations;
    statistics.linear_failures = finished_runs.linear_failures + run.linear_failures;
    statistics.preconditioner_setups = krylov_counters.setups;
    statistics.preconditioner_seconds =
        krylov_counters.setup_seconds + krylov_counters.apply_seconds;
    statistics.rhs_evaluations = n_rhs;
    statistics.jacobian_evaluations = n_jacobian;
    statistics.lu_analyses = lu_counters.analyses;
    statistics.lu_seconds = lu_counters.seconds;
    statistics.lu_factorisations = lu_counters.setups;
    statistics.lu_setup_seconds = lu_counters.setup_seconds;
    statistics.lu_ordering_trials = lu_ordering.trials;
    statistics.lu_ordering = lu_ordering.ordering;
    statistics.lu_ordering_tried_on = lu_ordering.tried_on;
    check_cvode(CVodeGetLastStep(cvode.get(), &statistics.last_step), "CVodeGetLastStep");
    check_cvode(CVodeGetCurrentTime(cvode.get(), &statistics.current_time), "CVodeGetCurrentTime");
  }

  void finish_run() {
    const RunCounters run = read_run_counters(cvode.get());
    finished_runs.steps += run.steps;
    finished_runs.newton_iterations += run.newton_iterations;
    finished_runs.error_test_failures += run.error_test_failures;
    finished_runs.convergence_failures += run.convergence_failures;
    finished_runs.linear_iterations += run.linear_iterations;
    finished_runs.linear_failures += run.linear_failures;
  }

  CvodeError make_error(int flag, double t) const {
    const std::string name = cvode_flag_name(flag);
    const std::int64_t worst = worst_weighted_error(cvode.get(), y_vector.get());
    std::ostringstream msg;
    msg.precision(10);
    msg << "CVode failed with " << name << " (" << flag << ") at t = " << t;
    if (worst >= 0)
      msg << ", worst component " << worst << " (y = " << y[static_cast<std::size_t>(worst)] << ")";
    else
      msg << ", no error estimate yet";
    if (!last_cvode_message.empty()) msg << "; " << last_cvode_message;
    return CvodeError(msg.str(), flag, name, t, worst);
  }
};

}  // namespace unsatmpm::numerics
