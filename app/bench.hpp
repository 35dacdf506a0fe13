// Built-in benchmarks: `unsatmpm bench NAME`. Each prints one line of key=value figures.
#pragma once

#include <string>
#include <vector>

namespace unsatmpm {

std::vector<std::string> benchmark_names();
/// Runs the named benchmark with n_threads; throws std::invalid_argument for an unknown name.
void run_benchmark(const std::string& name, int n_threads);

}  // namespace unsatmpm
