// unsatmpm's command line (app/command_line.hpp; app/main.cpp calls it).
//   unsatmpm run CASE [--output DIR] [--threads N] [--quiet] [--max-memory SIZE]
//                     [--checkpoint-every SECONDS]
//   unsatmpm resume DIR [--threads N] [--quiet] [--max-memory SIZE] [--checkpoint-every SECONDS]
//   unsatmpm check CASE [--threads N] [--max-memory SIZE]
//   unsatmpm bench NAME [--threads N] [--end-time SECONDS] [--direct-solver umfpack|klu]
// Exit codes: 0 success, 1 invalid input (case file, checkpoint), 2 command-line usage, 3 numerical
// failure, 4 other run-time error (e.g. an output file could not be written), 128 + the signal when
// SIGINT or SIGTERM ended a run (app/interrupt.hpp): 130, 143.
#include <fmt/core.h>
#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "app/bench.hpp"
#include "app/checkpoint.hpp"
#include "app/command_line.hpp"
#include "app/plausibility.hpp"
#include "app/run.hpp"
#include "cycles/resources.hpp"
#include "cycles/setup.hpp"
#include "cycles/tractions.hpp"
#include "input/case_parser.hpp"
#include "input/input_node.hpp"

#ifndef UNSATMPM_VERSION
#define UNSATMPM_VERSION "unknown"
#endif

namespace {

/// The liquid bulk modulus [Pa] up to which a saturated column at P_l = P_g was measured stable
/// in the main cycle's nodal pressure update (1 GPa was not; docs/balance_laws.md). The explicit
/// cycle's nodal update holds a closed column at 2.2 GPa, but a loaded column drained at its top
/// failed there at 1 and 2.2 GPa (0.2 GPa ran; its pointwise update ran at 2.2 GPa).
constexpr double stable_liquid_bulk_modulus = 5e8;

using namespace unsatmpm;

/// The case's points and surface loads set up as a run would (errors that need the points, such
/// as a traction on a plane no body touches, are found here); returns the point count.
template <int D>
std::int64_t set_up(const Case& c) {
  const auto grid = make_grid<D>(c);
  const auto points = fill_bodies<D>(c, grid);
  const BoundaryTractions<D> loads(c, grid, points.points);
  return static_cast<std::int64_t>(points.points.size());
}

/// Parses the case and checks its estimated memory against `max_memory` [bytes] before anything
/// is allocated (cycles/resources.hpp).
Case parse_within_limits(const std::string& file, int n_threads, double max_memory) {
  const Case c = parse_case_file(file);
  require_resources(c, InputNode::load_file(file), n_threads, max_memory);
  return c;
}

/// The most material points `check` sets up to find the errors that need them (about 200 MB);
/// a larger case is checked without them and says so (docs/input.md, "Resource limits").
constexpr double check_point_budget = 5e5;

int check(const std::string& file, int n_threads, double max_memory) {
  const Case c = parse_within_limits(file, n_threads, max_memory);
  const ResourceEstimate estimate = estimate_resources(c, n_threads);
  const bool set_up_points = estimate.points <= check_point_budget;
  std::int64_t n_points = 0;
  if (set_up_points)
    n_points = c.dimension == 1 ? set_up<1>(c) : (c.dimension == 2 ? set_up<2>(c) : set_up<3>(c));
  fmt::print("{}", effective_configuration(c));
  if (!set_up_points)
    fmt::print(
        "# {}: valid as far as checked; the surface loads' nodes are checked by run (the "
        "{:.0f} points exceed check's budget of {:.0f}); a run on {} thread(s) needs {}\n",
        file, estimate.points, check_point_budget, n_threads, describe_resources(estimate));
  else
    fmt::print("# {}: valid; {} material points; a run on {} thread(s) needs {}\n", file, n_points,
               n_threads, describe_resources(estimate));
  return 0;
}

int run(const std::string& file, const std::string& output, RunOptions options, double max_memory) {
  const Case c = parse_within_limits(file, options.n_threads, max_memory);
  const int n_threads = options.n_threads;
  const bool quiet = options.quiet;
  options.output_dir =
      output.empty() ? std::filesystem::path("output") / c.name : std::filesystem::path(output);
  if (!quiet) {
    spdlog::info("case {} ({}), effective configuration:\n{}", c.name, file,
                 effective_configuration(c));
    spdlog::info("output folder: {}", options.output_dir.string());
    spdlog::info("the run needs {}", describe_resources(estimate_resources(c, n_threads)));
  }
  // The step h / (c + |v|) is the 1D limit; in D dimensions about 1/sqrt(D) of it is stable
  // (docs/input.md, "What cfl_safety: 1 means").
  if (!c.solver.time_step.fixed &&
      c.solver.time_step.cfl_safety > 1.0 / std::sqrt(static_cast<double>(c.dimension)) + 1e-12) {
    spdlog::warn(
        "solver.time_step.cfl_safety = {} exceeds 1/sqrt({}) = {:.3f}, about the stable limit of "
        "the explicit step in {}D: the run may blow up (docs/input.md)",
        c.solver.time_step.cfl_safety, c.dimension, 1.0 / std::sqrt(c.dimension * 1.0),
        c.dimension);
  }
  // Water's own stiffness is not yet stable at the saturation kink in the main cycle's nodal
  // pressure updates (docs/balance_laws.md, "Saturated soil at the saturation kink"); the explicit
  // cycle's holds the closed and the drained columns and Mandel's slab at 2.2 GPa.
  if (c.fluids && c.skeleton == physics::Skeleton::deformable &&
      c.fluids->liquid.bulk_modulus > stable_liquid_bulk_modulus &&
      c.solver.cycle == Cycle::implicit_pressure) {
    spdlog::warn(
        "fluids.liquid.bulk_modulus = {:g} Pa exceeds {:g} Pa: in the main cycle a closed "
        "saturated column at P_l ~ P_g went unstable at 1 and 2.2 GPa (0.5 GPa held); the run may "
        "go unstable (docs/balance_laws.md, \"Saturated soil at the saturation kink\")",
        c.fluids->liquid.bulk_modulus, stable_liquid_bulk_modulus);
  }
  for (const std::string& w : implausible_parameters(c)) spdlog::warn("{}", w);
  return run_case(c, options);
}

/// Continues the run in `dir` from its checkpoint (app/checkpoint.hpp), with the case it holds.
int resume(const std::string& dir, RunOptions options, double max_memory) {
  options.output_dir = dir;
  CheckpointReader checkpoint(options.output_dir / checkpoint_file_name);
  const CheckpointHeader h = read_checkpoint_header(checkpoint);
  const Case c = parse_case_text(h.case_text, h.case_file);
  if (c.dimension != h.dimension) checkpoint.fail("its dimension differs from its case's");
  require_resources(c, InputNode::load_text(h.case_text, h.case_file), options.n_threads,
                    max_memory);
  if (h.program_version != options.program_version)
    spdlog::warn(
        "the checkpoint was written by unsatmpm {}, this is {}: the resumed part may differ from "
        "what the first would have computed",
        h.program_version, options.program_version);
  if (!options.quiet)
    spdlog::info("resuming case {} ({}, {} cycle) in {}", c.name, h.case_file, h.cycle, dir);
  return resume_case(c, checkpoint, options);
}

}  // namespace

int unsatmpm::run_command_line(int argc, char** argv) {
  CLI::App app{"unsatmpm: three-phase Material Point Method for unsaturated soils"};
  app.set_version_flag("--version", std::string("unsatmpm ") + UNSATMPM_VERSION);
  app.require_subcommand(1);

  std::string case_file, output_dir, bench_name;
  int n_threads = 1;
  bool quiet = false;
  double max_memory = default_memory_limit(), checkpoint_every = 0.0;
  const auto add_memory_option = [&](CLI::App* cmd) {
    cmd->add_option("--max-memory", max_memory,
                    "Largest estimated memory a case may need, e.g. 16GB (default: 80 % of this "
                    "machine's memory)")
        ->transform(CLI::AsSizeValue(true))
        ->check(CLI::PositiveNumber);
  };
  auto* run_cmd = app.add_subcommand("run", "Run a case to its end time");
  // The case file's existence is the parser's to check: its message and exit code 1 are those
  // of every input error (docs/input.md, "Error messages").
  run_cmd->add_option("CASE", case_file, "Case file (YAML)")->required();
  run_cmd->add_option("--output,-o", output_dir, "Output folder (default: output/<case name>)");
  const auto add_run_options = [&](CLI::App* cmd) {
    cmd->add_option("--threads,-t", n_threads, "OpenMP threads")->check(CLI::Range(1, 256));
    cmd->add_flag("--quiet,-q", quiet, "No progress or configuration echo");
    cmd->add_option("--checkpoint-every", checkpoint_every,
                    "Also write the checkpoint after this many seconds of wall time (default: at "
                    "output times only)")
        ->check(CLI::PositiveNumber);
    add_memory_option(cmd);
  };
  add_run_options(run_cmd);
  auto* resume_cmd =
      app.add_subcommand("resume", "Continue a run from the checkpoint in its output folder");
  resume_cmd->add_option("DIR", output_dir, "The run's output folder")->required();
  add_run_options(resume_cmd);
  auto* check_cmd = app.add_subcommand("check", "Validate a case without running it");
  check_cmd->add_option("CASE", case_file, "Case file (YAML)")->required();
  check_cmd->add_option("--threads,-t", n_threads, "Threads a run would use (for the estimate)")
      ->check(CLI::Range(1, 256));
  add_memory_option(check_cmd);
  auto* bench_cmd = app.add_subcommand("bench", "Run a built-in benchmark");
  bench_cmd
      ->add_option("NAME", bench_name,
                   "column2d | column3d | column2d_gimp_mc | column2d_three_phase | embankment")
      ->required();
  bench_cmd->add_option("--threads,-t", n_threads, "OpenMP threads")->check(CLI::Range(1, 256));
  double bench_end_time = 0.0;
  bench_cmd
      ->add_option("--end-time", bench_end_time, "embankment only: simulated time [s] (default 30)")
      ->check(CLI::PositiveNumber);
  std::string bench_direct_solver;
  bench_cmd
      ->add_option("--direct-solver", bench_direct_solver,
                   "embankment only: the flow's sparse LU (default: the case's, umfpack)")
      ->check(CLI::IsMember({"umfpack", "klu"}));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  try {
    RunOptions options;
    options.n_threads = n_threads, options.quiet = quiet;
    options.checkpoint_every = checkpoint_every, options.program_version = UNSATMPM_VERSION;
    if (run_cmd->parsed()) return run(case_file, output_dir, options, max_memory);
    if (resume_cmd->parsed()) return resume(output_dir, options, max_memory);
    if (check_cmd->parsed()) return check(case_file, n_threads, max_memory);
    if ((bench_end_time > 0.0 || !bench_direct_solver.empty()) && bench_name != "embankment") {
      fmt::print(stderr,
                 "error: --end-time and --direct-solver apply to the embankment benchmark "
                 "only\n");
      return 2;
    }
    run_benchmark(bench_name, n_threads, bench_end_time, bench_direct_solver);
    return 0;
  } catch (const InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (const CheckpointError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (const std::invalid_argument& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 4;
  }
}
