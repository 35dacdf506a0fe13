// Everything a run writes into its output folder (docs/output.md), each file written atomically:
//   points_NNNN.vtu / grid_NNNN.vtu and points.pvd / grid.pvd   fields at the output times
//   control_points.csv   history of the points nearest each control point at t = 0
//   globals.csv          kinetic energy, mass and momentum of the whole body over time
//   effective_case.yaml  the case as run, defaults included
//   run_summary.json     steps, times, cost per MP-step, status
// The folder is prepared only after the case has been validated and the points generated.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_file.hpp"
#include "input/case.hpp"
#include "numerics/fluid_points.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/nodal_state.hpp"
#include "writers/output_folder.hpp"
#include "writers/vtk_output.hpp"

#include <span>

namespace unsatmpm {

struct RunSummary {
  std::string cycle;               // which computational cycle ran
  std::string status = "running";  // running (written at each output) | completed | failed
  std::string message;
  std::int64_t steps = 0;
  double simulated_time = 0.0;  // [s]
  double wall_time = 0.0;       // [s]
  std::int64_t n_points = 0;
  std::int64_t n_nodes = 0;
  int n_threads = 1;
  double last_time_step = 0.0;    // [s]
  std::string solver_statistics;  // a JSON object of the cycle's own counters, or empty
  std::string gravity_loading;    // a JSON object of the loading before t = 0, or empty
  // A failed run: the step that failed (1-based) and the time it started from [s], and the time
  // of the last good state written as points_last_good.vtu [s]; failure_step 0 otherwise.
  std::int64_t failure_step = 0;
  double failure_time = 0.0, last_good_time = 0.0;
  // A resumed run: how often it was resumed, and the time of the checkpoint it last went on
  // from [s].
  std::int64_t resumes = 0;
  double resumed_from = 0.0;
};

template <int D>
class RunOutput {
 public:
  RunOutput(const Case& c, OutputFolder& folder, const numerics::MaterialPoints<D>& mp,
            bool plastic_fields);

  /// Writes the points' fields of one output time (with the cycle's extra point fields) and,
  /// if the case asks for it and `nodal` is not empty, the active grid's. With a `tag` the points
  /// go to points_<tag>.vtu alone, outside the .pvd series (the last good state of a failure).
  void write_fields(double t, const numerics::Grid<D>& grid, std::span<const VtkField> nodal,
                    const numerics::MaterialPoints<D>& mp, std::span<const VtkField> extra,
                    const std::string& tag = "");
  /// Appends one row to the conservation report (three-phase cases).
  void record_balance(double t, const numerics::FluidBalance& balance);
  /// Appends one row to the control-point and global histories (kept in memory); the fluid
  /// columns only when `fp` holds the points' fluids.
  void record_history(double t, const numerics::MaterialPoints<D>& mp,
                      const numerics::FluidPoints<D>& fp);
  /// Rewrites the CSV histories and the JSON summary.
  void flush(const RunSummary& summary) const;

  /// What a resumed run continues from (a checkpoint keeps it): the control points' indices, the
  /// histories' rows, the conservation report's reference and maxima, the series' frames.
  void save(CheckpointWriter& w) const;
  /// Reads what save() wrote, replacing what the constructor set up.
  void restore(CheckpointReader& r);

 private:
  const Case& case_;
  OutputFolder& folder_;
  PointFieldSelection selection_;
  std::vector<std::int64_t> control_index_;
  std::vector<std::vector<double>> control_rows_, global_rows_, balance_rows_;
  bool fluid_columns_ = false;
  numerics::FluidBalance initial_{};
  double max_mismatch_[2] = {0.0, 0.0};
  PvdSeries points_series_, grid_series_;
  int frame_ = 0;
};

}  // namespace unsatmpm
