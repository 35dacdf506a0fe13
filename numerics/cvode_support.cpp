#include "numerics/cvode_support.hpp"

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "numerics/cvode_integrator.hpp"
#include "numerics/sundials_handles.hpp"

namespace unsatmpm::numerics {

CvodeError::CvodeError(const std::string& message, int flag, std::string flag_name, double time,
                       std::int64_t worst_component)
    : std::runtime_error(message),
      flag_(flag),
      flag_name_(std::move(flag_name)),
      time_(time),
      worst_component_(worst_component) {}

namespace cvode_support {

void CvodeDeleter::operator()(void* cvode_mem) const { CVodeFree(&cvode_mem); }

namespace {
// CVodeGetReturnFlagName / CVodeGetLinReturnFlagName return a malloc'ed string the caller frees.
std::string take_c_string(char* name) {
  std::string s = name != nullptr ? name : "unknown flag";
  std::free(name);
  return s;
}
}  // namespace

std::string cvode_flag_name(int flag) { return take_c_string(CVodeGetReturnFlagName(flag)); }
std::string cvls_flag_name(int flag) { return take_c_string(CVodeGetLinReturnFlagName(flag)); }

void check_cvode(int flag, const char* call) {
  if (flag < 0)
    throw std::runtime_error(std::string(call) + " failed: " + cvode_flag_name(flag) + " (" +
                             std::to_string(flag) + ")");
}
void check_cvls(int flag, const char* call) {
  if (flag < 0)
    throw std::runtime_error(std::string(call) + " failed: " + cvls_flag_name(flag) + " (" +
                             std::to_string(flag) + ")");
}

void check_tolerance(double value, const char* name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream msg;
    msg << "CvodeTolerances." << name << " must be positive and finite, got " << value;
    throw std::invalid_argument(msg.str());
  }
}

RunCounters read_run_counters(void* mem) {
  RunCounters c;
  check_cvode(CVodeGetNumSteps(mem, &c.steps), "CVodeGetNumSteps");
  check_cvode(CVodeGetNumNonlinSolvIters(mem, &c.newton_iterations), "CVodeGetNumNonlinSolvIters");
  check_cvode(CVodeGetNumErrTestFails(mem, &c.error_test_failures), "CVodeGetNumErrTestFails");
  check_cvode(CVodeGetNumStepSolveFails(mem, &c.convergence_failures), "CVodeGetNumStepSolveFails");
  check_cvls(CVodeGetNumLinIters(mem, &c.linear_iterations), "CVodeGetNumLinIters");
  check_cvls(CVodeGetNumLinConvFails(mem, &c.linear_failures), "CVodeGetNumLinConvFails");
  return c;
}

std::int64_t worst_weighted_error(void* mem, N_Vector y) {
  const RunCounters run = read_run_counters(mem);
  if (run.steps + run.error_test_failures + run.convergence_failures == 0) return -1;
  const sundials::VectorPtr errors(N_VClone(y)), weights(N_VClone(y));
  if (!errors || !weights || CVodeGetEstLocalErrors(mem, errors.get()) < 0 ||
      CVodeGetErrWeights(mem, weights.get()) < 0)
    return -1;
  const std::span<double> e = view(errors.get()), w = view(weights.get());
  std::int64_t worst = -1;
  double worst_value = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    double value = std::abs(e[i]) * w[i];
    if (std::isnan(value)) value = std::numeric_limits<double>::infinity();
    if (value > worst_value) {
      worst_value = value;
      worst = static_cast<std::int64_t>(i);
    }
  }
  return worst;
}

}  // namespace cvode_support
}  // namespace unsatmpm::numerics
