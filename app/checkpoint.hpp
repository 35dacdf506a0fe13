// The run's checkpoint (docs/output.md, "Checkpoints and resume"): written atomically into the
// output folder as checkpoint.bin at every output time, at most every --checkpoint-every seconds
// of wall time, and when a signal ends the run; `unsatmpm resume DIR` reads it back.
//
// Sections, in order (checkpoint/checkpoint_file.hpp): the header (program version, the case as
// run, its file, dimension, cycle), the loop's state (time, step, output schedule, the rest
// monitor, last good state, gravity loading report), the outputs' state (writers/run_output.hpp)
// and the cycle's own (each solver's save()). The case is the effective configuration, which
// reads back exactly (input/case_parser.hpp): a resumed run does not depend on the case file still
// being there, or unchanged.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "app/cycle_adapters.hpp"
#include "app/output_schedule.hpp"
#include "app/rest_monitor.hpp"
#include "checkpoint/checkpoint_file.hpp"
#include "input/case_parser.hpp"
#include "writers/atomic_file.hpp"
#include "writers/output_folder.hpp"
#include "writers/run_output.hpp"

namespace unsatmpm {

inline constexpr const char* checkpoint_file_name = "checkpoint.bin";

/// What the header says: enough to set up the solver the rest of the checkpoint belongs to.
struct CheckpointHeader {
  std::string program_version, case_text, case_file, cycle;
  int dimension = 0;
};

/// The run loop's position and what its summary has counted so far.
struct LoopPosition {
  double time = 0.0;  // [s]
  std::int64_t step = 0;
  double last_time_step = 0.0;  // [s]
  double wall_time = 0.0;       // [s] of every part of the run so far
  std::int64_t resumes = 0;     // how often the run was resumed before
};

inline CheckpointHeader read_checkpoint_header(CheckpointReader& r) {
  CheckpointHeader h;
  h.program_version = r.text("program_version");
  h.case_text = r.text("case");
  h.case_file = r.text("case_file");
  h.cycle = r.text("cycle");
  h.dimension = static_cast<int>(r.value<std::int64_t>("dimension"));
  return h;
}

/// Writes the whole checkpoint into `folder` atomically: a kill during the write leaves the
/// previous one.
template <int D, class Solver>
void write_checkpoint(OutputFolder& folder, const Case& c, const std::string& program_version,
                      const LoopPosition& at, const OutputSchedule& schedule,
                      const RestMonitor& rest, const LastGoodState<D>& last_good,
                      const std::string& gravity_loading, const RunOutput<D>& out,
                      const Solver& solver) {
  const std::filesystem::path file = folder.file(checkpoint_file_name);
  write_file_atomically(file, [&](const std::filesystem::path& tmp) {
    CheckpointWriter w(tmp, quoted_path(file));
    w.text("program_version", program_version);
    w.text("case", effective_configuration(c));
    w.text("case_file", c.file);
    w.text("cycle", cycle_name(solver));
    w.value("dimension", std::int64_t{D});
    w.value("loop.time", at.time);
    w.value("loop.step", at.step);
    w.value("loop.last_time_step", at.last_time_step);
    w.value("loop.wall_time", at.wall_time);
    w.value("loop.resumes", at.resumes);
    schedule.save(w);
    rest.save(w);
    last_good.save(w);
    w.text("gravity_loading", gravity_loading);
    out.save(w);
    solver.save(w);
    w.finish();
  });
}

/// Reads what write_checkpoint wrote after the header into the loop's, the outputs' and the
/// solver's state, and checks that nothing is left and the hash matches.
template <int D, class Solver>
LoopPosition read_checkpoint(CheckpointReader& r, OutputSchedule& schedule, RestMonitor& rest,
                             LastGoodState<D>& last_good, std::string& gravity_loading,
                             RunOutput<D>& out, Solver& solver) {
  LoopPosition at;
  at.time = r.value<double>("loop.time");
  at.step = r.value<std::int64_t>("loop.step");
  at.last_time_step = r.value<double>("loop.last_time_step");
  at.wall_time = r.value<double>("loop.wall_time");
  at.resumes = r.value<std::int64_t>("loop.resumes");
  schedule.restore(r, at.time);
  rest.restore(r);
  last_good.restore(r, solver.points().size(), solver.fluids().size());
  gravity_loading = r.text("gravity_loading");
  out.restore(r);
  solver.restore(r);
  r.finish();
  return at;
}

}  // namespace unsatmpm
