// CVODE's flags, counters and error estimates as the CVODE wrapper reads them (part of the wrapper:
// included through its private state, numerics/cvode_impl.hpp).
#pragma once

#include <nvector/nvector_serial.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>

namespace unsatmpm::numerics::cvode_support {

struct CvodeDeleter {
  void operator()(void* cvode_mem) const;
};
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

/// CVODE's and its linear-solver interface's names of a return flag.
std::string cvode_flag_name(int flag);
std::string cvls_flag_name(int flag);
/// Throw std::runtime_error naming the call, the flag's name and value when flag < 0.
void check_cvode(int flag, const char* call);
void check_cvls(int flag, const char* call);
/// Throw std::invalid_argument naming CvodeTolerances.`name` unless value is positive and finite.
void check_tolerance(double value, const char* name);

/// A serial N_Vector's data.
inline std::span<double> view(N_Vector v) {
  return {N_VGetArrayPointer(v), static_cast<std::size_t>(N_VGetLength(v))};
}

/// CVODE's own counters of the current run, which CVodeReInit and a re-creation reset to zero.
struct RunCounters {
  long steps = 0, newton_iterations = 0, error_test_failures = 0, convergence_failures = 0;
  long linear_iterations = 0, linear_failures = 0;
};
RunCounters read_run_counters(void* cvode_mem);

/// Index of max |e_i| w_i over CVODE's local error estimates e and weights w (a NaN counts as
/// infinite), for vectors like `y`; -1 before any attempted step, or if all estimates are zero.
std::int64_t worst_weighted_error(void* cvode_mem, N_Vector y);

}  // namespace unsatmpm::numerics::cvode_support
