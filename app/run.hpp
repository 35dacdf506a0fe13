// Running a case: the time loop, output times, progress, and failure handling.
#pragma once

#include <filesystem>

#include "input/case.hpp"

namespace unsatmpm {

struct RunOptions {
  std::filesystem::path output_dir;
  int n_threads = 1;
  bool quiet = false;
};

/// Runs the case to its end time. Returns the process exit code: 0 on success, 3 when the
/// simulation blew up (the last good state is written and the summary says where and when).
int run_case(const Case& c, const RunOptions& options);

}  // namespace unsatmpm
