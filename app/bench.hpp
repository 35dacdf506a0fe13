// Built-in benchmarks: `unsatmpm bench NAME`. Each prints one line of key=value figures
// (docs/performance.md says what each figure is and how to reproduce the published ones).
#pragma once

#include <string>
#include <vector>

namespace unsatmpm {

std::vector<std::string> benchmark_names();
/// Runs the named benchmark with n_threads; `end_time` [s] is the embankment's simulated time (0:
/// its default, 30 s) and `direct_solver` its flow's sparse LU (`umfpack` or `klu`; empty: the
/// case's). Throws std::invalid_argument for an unknown name or sparse LU.
void run_benchmark(const std::string& name, int n_threads, double end_time = 0.0,
                   const std::string& direct_solver = "");

/// The column2d benchmark's elastic kernel [ns per point-step] on n_threads, best of 3: the
/// yardstick of the embankment's kernel_ratio.
double column2d_kernel_ns(int n_threads);

/// The verification embankment (verification/embankment/case.yaml, built in) from its gravity
/// loading to `end_time` [s] on the main cycle, without output, its flow's sparse LU as
/// run_benchmark says (app/bench_embankment.cpp).
void bench_embankment(int n_threads, double end_time, const std::string& direct_solver);

}  // namespace unsatmpm
