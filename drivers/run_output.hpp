// Everything a run writes into its output folder (SPEC §9), each file written atomically:
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

#include "drivers/case.hpp"
#include "drivers/vtk_output.hpp"
#include "numerics/grid.hpp"
#include "numerics/material_points.hpp"
#include "numerics/nodal_state.hpp"

namespace unsatmpm::drivers {

/// Empties `dir` if it holds an earlier unsatmpm run (it has a run_summary.json), creates it if
/// absent, and refuses a non-empty folder that is not ours, so no user file is ever deleted.
void prepare_output_folder(const std::filesystem::path& dir);

struct RunSummary {
  std::string status = "completed";  // completed | failed
  std::string message;
  std::int64_t steps = 0;
  double simulated_time = 0.0;  // [s]
  double wall_time = 0.0;       // [s]
  std::int64_t n_points = 0;
  std::int64_t n_nodes = 0;
  int n_threads = 1;
  double last_time_step = 0.0;  // [s]
};

template <int D>
class RunOutput {
 public:
  RunOutput(const Case& c, std::filesystem::path dir, const numerics::MaterialPoints<D>& mp,
            bool plastic_fields);

  /// Writes the fields of one output time (and the grid's, if the case asks for it).
  void write_fields(double t, const numerics::Grid<D>& grid, const numerics::NodalState<D>& nodes,
                    const numerics::MaterialPoints<D>& mp, const std::string& tag = "");
  /// Appends one row to the control-point and global histories (kept in memory).
  void record_history(double t, const numerics::MaterialPoints<D>& mp);
  /// Rewrites the CSV histories and the JSON summary.
  void flush(const RunSummary& summary) const;

 private:
  const Case& case_;
  std::filesystem::path dir_;
  PointFieldSelection selection_;
  std::vector<std::int64_t> control_index_;
  std::vector<std::vector<double>> control_rows_, global_rows_;
  PvdSeries points_series_, grid_series_;
  int frame_ = 0;
};

}  // namespace unsatmpm::drivers
