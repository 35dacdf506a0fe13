// Running a case: the time loop, output times, progress, and failure handling.
#pragma once

#include <filesystem>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "input/case.hpp"

namespace unsatmpm {

struct RunOptions {
  std::filesystem::path output_dir;
  int n_threads = 1;
  bool quiet = false;
  double checkpoint_every = 0.0;  // [s] of wall time between checkpoints; 0: output times only
  std::string program_version;    // written into the checkpoint
};

/// Runs the case to its end time. Returns the process exit code: 0 on success, 3 when the
/// simulation blew up (the last good state is written and the summary says where and when).
int run_case(const Case& c, const RunOptions& options);

/// Resumes the run whose checkpoint `checkpoint` is, its header read already, `c` the case it
/// holds; options.output_dir is the run's folder. Returns the exit code as run_case. Throws
/// CheckpointError when the checkpoint does not fit the case or is damaged.
int resume_case(const Case& c, CheckpointReader& checkpoint, const RunOptions& options);

}  // namespace unsatmpm
