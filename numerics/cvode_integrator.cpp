// CVODE (BDF, Newton) + a sparse LU or GMRES behind one RAII object; its state is
// numerics/cvode_impl.hpp and the functions CVODE calls back are in numerics/cvode_callbacks.cpp.
//
// Ownership: Impl holds every SUNDIALS handle in a unique_ptr whose deleter is the matching
// SUNDIALS destructor (numerics/sundials_handles.hpp), declared in creation order so that they die
// in reverse (CVODE memory first, context last). Nothing else frees them. The sparse LU sits behind
// a keeper that keeps its symbolic analysis across CVodeReInit (numerics/umfpack_keeper.hpp,
// numerics/klu_keeper.hpp); GMRES with multigrid behind another (numerics/krylov_keeper.hpp).
#include "numerics/cvode_integrator.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "numerics/cvode_impl.hpp"

namespace unsatmpm::numerics {

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
  if (s.ready() && pattern == s.pattern && iterative == s.iterative &&
      (iterative || s.direct == s.statistics.direct_solver)) {
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
  if (s.callback_exception) {
    try {
      std::rethrow_exception(std::exchange(s.callback_exception, nullptr));
    } catch (const StopRequested& stop) {  // with where the last step attempt erred most
      throw StopRequested(stop.what(), worst_weighted_error(s.cvode.get(), s.y_vector.get()));
    }
  }
  if (flag < 0) throw s.make_error(flag, t);
  return t;
}

std::span<const double> CvodeIntegrator::state() const { return impl_->y; }
std::span<double> CvodeIntegrator::state() { return impl_->y; }

const CvodeStatistics& CvodeIntegrator::statistics() const { return impl_->statistics; }

void CvodeIntegrator::set_lu_ordering(int ordering, long tried_on) {
  if (ordering < -1 || ordering > 1 || tried_on < 0)
    throw std::invalid_argument("CvodeIntegrator::set_lu_ordering: ordering " +
                                std::to_string(ordering) + " on " + std::to_string(tried_on) +
                                " unknowns");
  impl_->lu_ordering.ordering = ordering;
  impl_->lu_ordering.tried_on = tried_on;
  impl_->statistics.lu_ordering = ordering;
  impl_->statistics.lu_ordering_tried_on = tried_on;
}

void CvodeIntegrator::set_direct_solver(DirectSolverChoice choice) { impl_->direct = choice; }

std::pair<double, double> CvodeIntegrator::position() const {
  if (!impl_->cvode) return {0.0, 0.0};
  double t = 0.0, h = 0.0;
  check_cvode(CVodeGetCurrentTime(impl_->cvode.get(), &t), "CVodeGetCurrentTime");
  check_cvode(CVodeGetLastStep(impl_->cvode.get(), &h), "CVodeGetLastStep");
  return {t, h};
}

void CvodeIntegrator::set_max_step(double max_step) {
  if (!(max_step > 0.0) || std::isnan(max_step))
    throw std::invalid_argument("CvodeIntegrator::set_max_step: must be > 0, got " +
                                std::to_string(max_step));
  impl_->max_step = max_step;
  if (impl_->cvode)
    check_cvode(CVodeSetMaxStep(impl_->cvode.get(), std::isinf(max_step) ? 0.0 : max_step),
                "CVodeSetMaxStep");
}

void CvodeIntegrator::set_stop_check(StopCheck check) { impl_->stop_check = std::move(check); }

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
