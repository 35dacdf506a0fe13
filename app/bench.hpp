// Built-in benchmarks: `unsatmpm bench NAME`. Each prints one line of key=value figures
// (docs/performance.md says what each figure is and how to reproduce the published ones).
#pragma once

#include <string>
#include <vector>

namespace unsatmpm {

std::vector<std::string> benchmark_names();
/// Runs the named benchmark with n_threads; `end_time` [s] is the embankment's simulated time (0:
/// its default, 30 s). Throws std::invalid_argument for an unknown name.
void run_benchmark(const std::string& name, int n_threads, double end_time = 0.0);

/// The column2d benchmark's elastic kernel [ns per point-step] on n_threads, best of 3: the
/// yardstick of the embankment's kernel_ratio.
double column2d_kernel_ns(int n_threads);

/// The verification embankment (verification/embankment/case.yaml, built in) from its gravity
/// loading to `end_time` [s] on the main cycle, without output (app/bench_embankment.cpp).
void bench_embankment(int n_threads, double end_time);

}  // namespace unsatmpm
