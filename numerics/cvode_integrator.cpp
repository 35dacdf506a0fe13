// CVODE (BDF, Newton) + KLU or GMRES behind one RAII object: the only file that includes SUNDIALS.
//
// Ownership: Impl holds every SUNDIALS handle in a unique_ptr whose deleter is the matching
// SUNDIALS destructor (numerics/sundials_handles.hpp), declared in creation order so that they die
// in reverse (CVODE memory first, context last). Nothing else frees them. KLU sits behind a keeper
// that keeps its symbolic analysis across CVodeReInit (numerics/klu_keeper.hpp); GMRES with
// multigrid behind another (numerics/krylov_keeper.hpp).
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

namespace unsatmpm::numerics {

static_assert(std::is_same_v<sunindextype, std::int64_t>, "SparsePattern assumes 64-bit indices");
static_assert(std::is_same_v<realtype, double>, "the wrapper assumes double precision");

namespace {

using cvode_support::check_cvls;
using cvode_support::check_cvode;
using cvode_support::cvode_flag_name;
using cvode_support::CvodePtr;
using cvode_support::read_run_counters;
using cvode_support::RunCounters;
using cvode_support::view;
using cvode_support::worst_weighted_error;
using sundials::check_created;
using sundials::ContextPtr;
using sundials::MatrixPtr;
using sundials::VectorPtr;

void check_tolerance(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "CvodeTolerances." << name << " must be positive and finite, got " << value;
    throw std::invalid_argument(msg.str());
  }
}

}  // namespace

struct CvodeIntegrator::Impl {
  Rhs rhs;
  Jacobian jacobian;
  CvodeTolerances tolerances;
  double max_step = std::numeric_limits<double>::infinity();
  long max_num_steps = 500;  // CVODE's default
  int n_roots = 0;
  Roots roots;
  bool stop_time_pending = false;
  LinearSolverChoice choice = LinearSolverChoice::direct;
  std::int64_t iterative_from = 1;  // unknowns from which `automatic` is iterative

  SparsePattern pattern;   // of the live matrix; n = 0 until the first successful reset
  bool iterative = false;  // the live linear solver is GMRES with multigrid
  std::vector<double> y;   // the unknowns; y_vector wraps this buffer
  double t_reached = 0.0;

  std::exception_ptr callback_exception;  // thrown in a callback, rethrown after CVode
  std::string last_cvode_message;         // from CVODE's error handler
  long n_rhs = 0, n_jacobian = 0;
  KluCounters klu_counters;        // over every KLU solver of the object's life
  KrylovCounters krylov_counters;  // over every GMRES solver of the object's life
  RunCounters finished_runs;       // sums over CVODE runs ended by reset()
  CvodeStatistics statistics;

  // Creation order; destroyed in reverse.
  ContextPtr context;
  VectorPtr y_vector;
  MatrixPtr matrix;
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

  // ---- callbacks: no exception crosses into C -------------------------------------------------

  static int rhs_callback(realtype t, N_Vector y, N_Vector ydot, void* user_data) {
    auto& self = *static_cast<Impl*>(user_data);
    ++self.n_rhs;
    try {
      return self.rhs(t, view(y), view(ydot));
    } catch (...) {
      self.callback_exception = std::current_exception();
      return -1;
    }
  }

  static int jacobian_callback(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* user_data,
                               N_Vector, N_Vector, N_Vector) {
    auto& self = *static_cast<Impl*>(user_data);
    ++self.n_jacobian;
    try {
      // CVODE zeroes J (structure included) before this call: restore the pattern.
      const SparsePattern& p = self.pattern;
      const std::int64_t nnz = p.n_nonzeros();
      if (SUNSparseMatrix_NNZ(J) < nnz)
        throw std::logic_error("CvodeIntegrator: Jacobian storage smaller than the pattern");
      std::copy(p.row_ptr.begin(), p.row_ptr.end(), SUNSparseMatrix_IndexPointers(J));
      std::copy(p.col.begin(), p.col.end(), SUNSparseMatrix_IndexValues(J));
      const std::span<double> values(SUNSparseMatrix_Data(J), static_cast<std::size_t>(nnz));
      std::fill(values.begin(), values.end(), 0.0);
      return self.jacobian(t, view(y), view(fy), values);
    } catch (...) {
      self.callback_exception = std::current_exception();
      return -1;
    }
  }

  // The iterative solver's callbacks (numerics/krylov_keeper.hpp).
  static int preconditioner_setup(realtype t, N_Vector y, N_Vector fy, booleantype jok,
                                  booleantype* fresh, realtype gamma, void* user_data) {
    auto& self = *static_cast<Impl*>(user_data);
    try {
      bool evaluated = false;
      const int flag = self.krylov->setup(jok != 0, &evaluated, gamma, [&](std::span<double> j) {
        ++self.n_jacobian;
        return self.jacobian(t, view(y), view(fy), j);
      });
      *fresh = evaluated ? SUNTRUE : SUNFALSE;
      return flag;
    } catch (...) {
      self.callback_exception = std::current_exception();
      return -1;
    }
  }

  static int preconditioner_solve(realtype, N_Vector, N_Vector, N_Vector r, N_Vector z, realtype,
                                  realtype, int, void* user_data) {
    auto& self = *static_cast<Impl*>(user_data);
    try {
      self.krylov->precondition(view(r), view(z));
      return 0;
    } catch (...) {
      self.callback_exception = std::current_exception();
      return -1;
    }
  }

  static int jacobian_times(N_Vector v, N_Vector jv, realtype, N_Vector, N_Vector, void* user_data,
                            N_Vector) {
    static_cast<Impl*>(user_data)->krylov->multiply(view(v), view(jv));
    return 0;
  }

  static int roots_callback(realtype t, N_Vector y, realtype* g, void* user_data) {
    auto& self = *static_cast<Impl*>(user_data);
    try {
      return self.roots(t, view(y), std::span<double>(g, static_cast<std::size_t>(self.n_roots)));
    } catch (...) {
      self.callback_exception = std::current_exception();
      return -1;
    }
  }

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
                            void* user_data) {
    if (error_code >= 0) return;  // warnings (e.g. t + h == t) are not failures
    auto& self = *static_cast<Impl*>(user_data);
    self.last_cvode_message = std::string(module != nullptr ? module : "?") +
                              "::" + (function != nullptr ? function : "?") + ": " +
                              (msg != nullptr ? msg : "");
  }

  // ---- construction of the SUNDIALS objects ---------------------------------------------------

  void destroy_solver_objects() {
    cvode.reset();
    krylov.reset();
    klu.reset();
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
      krylov = std::make_unique<KrylovKeeper>(y_vector.get(), context.get(), p, krylov_counters);
    } else {
      matrix.reset(check_created(SUNSparseMatrix(p.n, p.n, p.n_nonzeros(), CSR_MAT, context.get()),
                                 "SUNSparseMatrix"));
      std::copy(p.row_ptr.begin(), p.row_ptr.end(), SUNSparseMatrix_IndexPointers(matrix.get()));
      std::copy(p.col.begin(), p.col.end(), SUNSparseMatrix_IndexValues(matrix.get()));
      std::fill_n(SUNSparseMatrix_Data(matrix.get()), p.n_nonzeros(), 0.0);
      klu = std::make_unique<KluKeeper>(y_vector.get(), matrix.get(), context.get(), klu_counters);
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
      check_cvls(CVodeSetLinearSolver(mem, klu->solver(), matrix.get()), "CVodeSetLinearSolver");
      check_cvls(CVodeSetJacFn(mem, jacobian_callback), "CVodeSetJacFn");
    }
    check_cvode(CVodeSetMaxStep(mem, std::isinf(max_step) ? 0.0 : max_step), "CVodeSetMaxStep");
    check_cvode(CVodeSetMaxNumSteps(mem, max_num_steps), "CVodeSetMaxNumSteps");
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
    statistics.klu_analyses = klu_counters.analyses;
    statistics.klu_seconds = klu_counters.seconds;
    statistics.klu_factorisations = klu_counters.setups;
    statistics.klu_setup_seconds = klu_counters.setup_seconds;
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

CvodeIntegrator::CvodeIntegrator(Rhs rhs, Jacobian jacobian, CvodeTolerances tolerances)
    : impl_(std::make_unique<Impl>(std::move(rhs), std::move(jacobian), tolerances)) {}

CvodeIntegrator::~CvodeIntegrator() = default;
CvodeIntegrator::CvodeIntegrator(CvodeIntegrator&&) noexcept = default;
CvodeIntegrator& CvodeIntegrator::operator=(CvodeIntegrator&&) noexcept = default;

void CvodeIntegrator::reset(const SparsePattern& pattern, double t0, std::span<const double> y0) {
  Impl& s = *impl_;
  pattern.validate();
  if (static_cast<std::int64_t>(y0.size()) != pattern.n)
    throw std::invalid_argument("CvodeIntegrator::reset: y0 has " + std::to_string(y0.size()) +
                                " entries, the pattern " + std::to_string(pattern.n));
  if (!std::isfinite(t0)) throw std::invalid_argument("CvodeIntegrator::reset: t0 not finite");

  // y0 may alias state() (the caller edits the unknowns and restarts from them).
  const std::vector<double> y_initial(y0.begin(), y0.end());

  if (s.cvode) s.finish_run();
  const bool iterative = s.resolve_iterative(pattern.n);
  if (s.ready() && pattern == s.pattern && iterative == s.iterative) {
    std::copy(y_initial.begin(), y_initial.end(), s.y.begin());
    check_cvode(CVodeReInit(s.cvode.get(), t0, s.y_vector.get()), "CVodeReInit");
    s.apply_roots();
    if (s.stop_time_pending) {
      // CVODE 6.4 has no CVodeClearStopTime; an infinite stop time never triggers.
      check_cvode(CVodeSetStopTime(s.cvode.get(), std::numeric_limits<double>::infinity()),
                  "CVodeSetStopTime");
    }
  } else {
    s.destroy_solver_objects();
    s.y = y_initial;
    s.pattern = pattern;
    s.iterative = iterative;
    try {
      s.create_solver_objects(t0);
    } catch (...) {
      s.destroy_solver_objects();
      throw;
    }
    s.apply_roots();
  }
  s.stop_time_pending = false;
  s.t_reached = t0;
  s.refresh_statistics();
}

double CvodeIntegrator::integrate_to(double t_out) {
  Impl& s = *impl_;
  if (!s.ready()) throw std::logic_error("CvodeIntegrator::integrate_to called before reset()");
  if (!std::isfinite(t_out))
    throw std::invalid_argument("CvodeIntegrator::integrate_to: t_out not finite");
  if (t_out == s.t_reached) return t_out;

  s.callback_exception = nullptr;
  s.last_cvode_message.clear();
  double t = s.t_reached;
  const int flag = CVode(s.cvode.get(), t_out, s.y_vector.get(), &t, CV_NORMAL);
  // On failure CVode has copied its last successful internal state (at t) into y.
  s.t_reached = t;
  if (flag == CV_TSTOP_RETURN) s.stop_time_pending = false;
  s.refresh_statistics();
  if (s.callback_exception) std::rethrow_exception(std::exchange(s.callback_exception, nullptr));
  if (flag < 0) throw s.make_error(flag, t);
  return t;
}

std::span<const double> CvodeIntegrator::state() const { return impl_->y; }
std::span<double> CvodeIntegrator::state() { return impl_->y; }

const CvodeStatistics& CvodeIntegrator::statistics() const { return impl_->statistics; }

void CvodeIntegrator::set_max_step(double max_step) {
  if (!(max_step > 0.0) || std::isnan(max_step))
    throw std::invalid_argument("CvodeIntegrator::set_max_step: must be > 0, got " +
                                std::to_string(max_step));
  impl_->max_step = max_step;
  if (impl_->cvode)
    check_cvode(CVodeSetMaxStep(impl_->cvode.get(), std::isinf(max_step) ? 0.0 : max_step),
                "CVodeSetMaxStep");
}

void CvodeIntegrator::set_roots(int n, Roots roots) {
  if (n < 0) throw std::invalid_argument("CvodeIntegrator::set_roots: n < 0");
  impl_->n_roots = roots ? n : 0;
  impl_->roots = std::move(roots);
}

std::vector<int> CvodeIntegrator::roots_found() const {
  const Impl& s = *impl_;
  std::vector<int> info(static_cast<std::size_t>(s.n_roots), 0), found;
  if (s.n_roots == 0 || !s.cvode) return found;
  check_cvode(CVodeGetRootInfo(s.cvode.get(), info.data()), "CVodeGetRootInfo");
  for (int k = 0; k < s.n_roots; ++k)
    if (info[static_cast<std::size_t>(k)] != 0) found.push_back(k);
  return found;
}

void CvodeIntegrator::set_linear_solver(LinearSolverChoice choice, std::int64_t iterative_from) {
  if (iterative_from < 1)
    throw std::invalid_argument("CvodeIntegrator::set_linear_solver: iterative_from must be > 0");
  impl_->choice = choice;
  impl_->iterative_from = iterative_from;
}

bool CvodeIntegrator::iterative() const { return impl_->ready() && impl_->iterative; }

void CvodeIntegrator::set_max_num_steps(long max_num_steps) {
  if (max_num_steps <= 0)
    throw std::invalid_argument("CvodeIntegrator::set_max_num_steps: must be > 0, got " +
                                std::to_string(max_num_steps));
  impl_->max_num_steps = max_num_steps;
  if (impl_->cvode)
    check_cvode(CVodeSetMaxNumSteps(impl_->cvode.get(), max_num_steps), "CVodeSetMaxNumSteps");
}

void CvodeIntegrator::set_stop_time(double t_stop) {
  Impl& s = *impl_;
  if (!s.ready()) throw std::logic_error("CvodeIntegrator::set_stop_time called before reset()");
  if (!std::isfinite(t_stop))
    throw std::invalid_argument("CvodeIntegrator::set_stop_time: t_stop not finite");
  check_cvode(CVodeSetStopTime(s.cvode.get(), t_stop), "CVodeSetStopTime");
  s.stop_time_pending = true;
}

}  // namespace unsatmpm::numerics
