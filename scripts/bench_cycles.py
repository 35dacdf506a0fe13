#!/usr/bin/python3
"""Benchmark of the two computational cycles (solver.cycle: explicit | implicit), side by side.

Three parts, all on the V1 infiltration column (verification/infiltration) or a variant of it:

  (a) V1 as it is (40 elements, 4 MPs per element, full form, to T = 1): wall time of each cycle,
      the errors (max and RMS of (s - s_ref)/s0 against the series at T = 0.05, 0.2, 1.0, worst
      over T) and the wall-time ratio explicit / implicit.
  (b) The same column with kappa 1000 times smaller (a clay, 5e-14 m^2; T = 1 at t = 6000 s).
      The implicit cycle runs to T = 1; the explicit cycle, whose step is set by the wave speeds
      and not by kappa, runs over a short window and its wall time is extrapolated to T = 1:
      linearly in simulated time (from the window's step rate), and by step count (the explicit
      step depends only on the state, which is a function of T alone, so the clay run takes 1000
      times the steps V1 takes to reach the same T; V1's steps up to each T are counted in an
      untimed calibration run). The errors are compared at the common output times.
      Requirement: implicit error <= explicit error at the common T, and ratio >= 100.
  (c) A 2D variant: 1 m x 1 m, 100 x 100 cells, 2 x 2 MPs per cell, the same one-dimensional
      boundary conditions (the side faces impervious), checked against the 1D series along the
      height. Implicit: wall time per simulated second and the share of KLU, rhs and Jacobian in
      the flow time. Explicit over a short window (1 thread, and 2 threads for reference).

Wall times are the program's own (run_summary.json, wall_time_s), best (minimum) of --repeats
runs; the process wall time is kept in the JSON too. Implicit settings are the case defaults
(relative_tolerance 1e-6, absolute_tolerance 1 Pa, coupling_interval auto = history_interval for
a rigid skeleton), read back from each run's effective_case.yaml.

Usage: bench_cycles.py --unsatmpm PATH [--output DIR] [--repeats N] [--quick]
"""
import argparse
import json
import math
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import yaml

ROOT = Path(__file__).resolve().parent.parent
VERIFICATION = ROOT / "verification"
sys.path.insert(0, str(VERIFICATION))

from common import Column, infiltration_series, read_csv, read_points, series  # noqa: E402
from run_verification import apply_overrides  # noqa: E402

from bench_cycles_report import print_a, print_b, print_c, print_figures  # noqa: E402

CASE_YAML = VERIFICATION / "infiltration" / "case.yaml"
COLUMN = Column.from_case(CASE_YAML)
H, N, MU, S0 = COLUMN.h, COLUMN.n, COLUMN.mu, COLUMN.s0
A_S = COLUMN.a_s
KAPPA_V1, KAPPA_CLAY = COLUMN.kappa, COLUMN.kappa / 1000.0
# The V1 control point's height [m] (case.yaml)
CONTROL_HEIGHT = float(yaml.safe_load(CASE_YAML.read_text())["output"]["control_points"][0]["position"][0])
T_ERR = [0.05, 0.2, 1.0]  # part (a): error times


def diffusivity(kappa, a_s=A_S):
    return kappa / (MU * N * a_s)


def t_of(T, kappa):
    """Simulated time [s] of time factor T."""
    return T * H ** 2 / diffusivity(kappa)


# ---------------------------------------------------------------------------------------------
# running


class RunFailed(RuntimeError):
    pass


def base_doc():
    return yaml.safe_load(CASE_YAML.read_text())


def write_case(doc, path):
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    return path


def run_case(exe, doc, name, out_root, threads=1, repeats=1):
    """Runs a case `repeats` times; returns the summary of the fastest run (by the program's
    wall_time_s) with every repeat's wall times, and the run folder (of the last repeat)."""
    case_file = write_case(doc, out_root / f"{name}.yaml")
    run_dir = out_root / name
    walls, procs, best = [], [], None
    for _ in range(repeats):
        if run_dir.exists():
            shutil.rmtree(run_dir)
        t0 = time.monotonic()
        proc = subprocess.run([str(exe), "run", str(case_file), "--output", str(run_dir),
                               "--threads", str(threads), "--quiet"],
                              capture_output=True, text=True)
        wall = time.monotonic() - t0
        summary_file = run_dir / "run_summary.json"
        summary = json.loads(summary_file.read_text()) if summary_file.exists() else {}
        if proc.returncode != 0 or summary.get("status") not in (None, "completed"):
            raise RunFailed(f"{name}: unsatmpm exited with {proc.returncode}; status "
                            f"{summary.get('status')!r}; message {summary.get('message')!r}\n"
                            f"stderr: {proc.stderr.strip()[-2000:]}\n"
                            f"solver_statistics: {summary.get('solver_statistics')}")
        walls.append(summary["wall_time_s"])
        procs.append(wall)
        if best is None or summary["wall_time_s"] < best["wall_time_s"]:
            best = summary
    eff = yaml.safe_load((run_dir / "effective_case.yaml").read_text())
    return {"name": name, "dir": str(run_dir), "threads": threads, "repeats": repeats,
            "wall_time_s": best["wall_time_s"], "wall_time_s_all": walls,
            "process_wall_time_s": min(procs), "process_wall_time_s_all": procs,
            "steps": best["steps"], "simulated_time_s": best["simulated_time_s"],
            "last_time_step_s": best["last_time_step_s"],
            "mean_time_step_s": best["simulated_time_s"] / best["steps"],
            "material_points": best["material_points"], "ns_per_mp_step": best["ns_per_mp_step"],
            "max_relative_mismatch_liquid": best.get("max_relative_mismatch_liquid"),
            "max_relative_mismatch_gas": best.get("max_relative_mismatch_gas"),
            "cycle": best["cycle"], "solver_statistics": best.get("solver_statistics"),
            "implicit_settings": eff["solver"].get("implicit")}


def profile_errors(run_dir, kappa, axis):
    """[(T, max |e|, RMS e)] at every output time after t = 0; e = (s - s_ref)/s0 against the 1D
    series, depth = H - coordinate along `axis` (every point of a 2D block counts)."""
    out = []
    for t, f in series(run_dir)[1:]:
        x, a = read_points(f)
        depth = H - x[:, axis]
        T = diffusivity(kappa) * t / H ** 2
        e = a["suction"] / S0 - infiltration_series(depth / H, T)
        out.append((T, float(np.max(np.abs(e))), float(np.sqrt(np.mean(e ** 2)))))
    return out


def at_T(errs, T, rel=1e-6):
    for e in errs:
        if abs(e[0] - T) <= rel * max(T, 1e-12):
            return e
    raise KeyError(f"no output at T = {T}: {[e[0] for e in errs]}")


def calibration_steps(exe, out_root):
    """Untimed V1 explicit run with the control-point history written every step: the explicit
    step count up to each time factor T (the step depends on the state only)."""
    doc = base_doc()
    apply_overrides(doc, {"solver.cycle": "explicit", "output.history_interval": 0,
                          "output.times": [], "output.write_grid": False})
    doc["name"] = "calibration_v1_explicit"
    run = run_case(exe, doc, "calibration_v1_explicit", out_root)
    times = read_csv(Path(run["dir"]) / "control_points.csv")["time"][1:]
    C = diffusivity(KAPPA_V1)
    return np.asarray(times) * C / H ** 2, run


def steps_to(T_steps, T):
    """Number of V1 explicit steps up to time factor T (calibration)."""
    return int(np.searchsorted(T_steps, T * (1 + 1e-9), side="right"))


# ---------------------------------------------------------------------------------------------
# parts


def part_a(exe, out, repeats):
    res = {"description": "V1 as it is (40 elements, 4 MPs, full form, T = 1 at t = 6 s)",
           "runs": {}}
    for cyc in ("explicit", "implicit"):
        doc = base_doc()
        apply_overrides(doc, {"solver.cycle": cyc})
        doc["name"] = f"a_v1_{cyc}"
        run = run_case(exe, doc, f"a_v1_{cyc}", out, repeats=repeats)
        errs = profile_errors(run["dir"], KAPPA_V1, 0)
        sel = [at_T(errs, T) for T in T_ERR]
        run["errors_all_T"] = errs
        run["errors"] = {f"{T:g}": {"max": e[1], "rms": e[2]} for T, e in zip(T_ERR, sel)}
        run["worst_max"] = max(e[1] for e in sel)
        run["worst_rms"] = max(e[2] for e in sel)
        res["runs"][cyc] = run
    r = res["runs"]
    res["wall_ratio_explicit_over_implicit"] = r["explicit"]["wall_time_s"] / r["implicit"]["wall_time_s"]
    res["process_wall_ratio_explicit_over_implicit"] = (r["explicit"]["process_wall_time_s"] /
                                                        r["implicit"]["process_wall_time_s"])
    return res


def part_b(exe, out, repeats, T_window, T_steps):
    C = diffusivity(KAPPA_CLAY)
    t_end = t_of(1.0, KAPPA_CLAY)
    T_out_imp = sorted({0.0025, 0.005, 0.01, 0.02, 0.05, 0.2, T_window} - {1.0})
    T_out_exp = [T for T in (0.0025, 0.005, 0.01, 0.02) if T < T_window * (1 - 1e-9)]
    res = {"description": f"clay: intrinsic_permeability {KAPPA_CLAY:g} m^2 (V1's / 1000), "
                          f"C = {C:.4g} m^2/s, T = 1 at t = {t_end:g} s",
           "explicit_window_T": T_window, "explicit_window_t_s": t_of(T_window, KAPPA_CLAY)}
    runs = {}
    # implicit to T = 1, history (coupling) interval end/1000 as in V1
    doc = base_doc()
    apply_overrides(doc, {"solver.cycle": "implicit",
                          "materials[0].intrinsic_permeability": KAPPA_CLAY,
                          "solver.end_time": t_end,
                          "output.times": [t_of(T, KAPPA_CLAY) for T in T_out_imp],
                          "output.history_interval": t_end / 1000})
    doc["name"] = "b_clay_implicit"
    runs["implicit"] = run_case(exe, doc, "b_clay_implicit", out, repeats=repeats)
    # explicit over the window
    t_w = t_of(T_window, KAPPA_CLAY)
    doc = base_doc()
    apply_overrides(doc, {"solver.cycle": "explicit",
                          "materials[0].intrinsic_permeability": KAPPA_CLAY,
                          "solver.end_time": t_w,
                          "output.times": [t_of(T, KAPPA_CLAY) for T in T_out_exp],
                          "output.history_interval": t_w / 100})
    doc["name"] = "b_clay_explicit_window"
    runs["explicit"] = run_case(exe, doc, "b_clay_explicit_window", out, repeats=repeats)
    for cyc in runs:
        runs[cyc]["errors_all_T"] = profile_errors(runs[cyc]["dir"], KAPPA_CLAY, 0)
    res["runs"] = runs
    ex, im = runs["explicit"], runs["implicit"]
    # step constancy within the window, and extrapolation to T = 1
    res["explicit_step_mean_over_last"] = ex["mean_time_step_s"] / ex["last_time_step_s"]
    res["explicit_extrapolated_linear_s"] = ex["wall_time_s"] * t_end / ex["simulated_time_s"]
    n_w, n_1 = steps_to(T_steps, T_window), steps_to(T_steps, 1.0)
    res["v1_calibration_steps"] = {"to_window_T": n_w, "to_T1": n_1}
    res["explicit_extrapolated_steps_linear"] = ex["steps"] * t_end / ex["simulated_time_s"]
    res["explicit_window_steps_over_1000_v1"] = ex["steps"] / (1000 * n_w)  # similarity check
    res["explicit_extrapolated_steps_by_count"] = 1000 * n_1
    res["explicit_extrapolated_by_count_s"] = ex["wall_time_s"] / ex["steps"] * 1000 * n_1
    res["explicit_extrapolated_s"] = min(res["explicit_extrapolated_linear_s"],
                                         res["explicit_extrapolated_by_count_s"])
    res["wall_ratio_explicit_over_implicit"] = res["explicit_extrapolated_s"] / im["wall_time_s"]
    res["wall_ratio_linear"] = res["explicit_extrapolated_linear_s"] / im["wall_time_s"]
    # errors at the common output times
    common = []
    for T, mx, rms in ex["errors_all_T"]:
        try:
            _, imx, irms = at_T(im["errors_all_T"], T)
        except KeyError:
            continue
        common.append({"T": T, "explicit_max": mx, "explicit_rms": rms,
                       "implicit_max": imx, "implicit_rms": irms})
    res["common"] = common
    judged = max(common, key=lambda c: c["T"])
    res["judged_T"] = judged["T"]
    res["implicit_error_T1"] = dict(zip(("T", "max", "rms"), im["errors_all_T"][-1]))
    res["pass_error"] = bool(judged["implicit_max"] <= judged["explicit_max"] and
                             judged["implicit_rms"] <= judged["explicit_rms"])
    res["pass_ratio"] = bool(res["wall_ratio_explicit_over_implicit"] >= 100)
    res["pass"] = res["pass_error"] and res["pass_ratio"]
    return res


def block_2d_doc(cycle, end_time, times, history_interval):
    doc = base_doc()
    doc["name"] = f"block2d_{cycle}"
    doc["dimension"] = 2
    doc["grid"] = {"origin": [0, 0], "size": [1, 1], "cells": [100, 100]}
    doc["gravity"] = [0, 0]
    body = doc["bodies"][0]
    body["points_per_cell"] = 2  # 2 x 2 per cell
    body["box"] = {"min": [0, 0], "max": [1, 1]}
    planes = {"top": {"axis": "y", "at": 1}, "bottom": {"axis": "y", "at": 0}}
    for b in doc["boundaries"]:
        b["plane"] = planes[b["name"]]
    doc["solver"]["end_time"] = end_time
    doc["solver"]["cycle"] = cycle
    doc["output"] = {"times": times, "history_interval": history_interval,
                     "control_points": [{"name": "z049", "position": [0.5, CONTROL_HEIGHT]}]}
    return doc


def part_c(exe, out, repeats, T_imp, t_exp, T_steps, two_threads):
    t_imp = t_of(T_imp, KAPPA_V1)
    res = {"description": "2D block 1 m x 1 m, 100 x 100 cells, 2 x 2 MPs per cell, V1's "
                          "boundary conditions on y = 1 (suction 0, gas 0) and y = 0 (gas 0), "
                          "side faces impervious",
           "implicit_window_T": T_imp, "implicit_window_t_s": t_imp,
           "explicit_window_t_s": t_exp,
           "explicit_window_T": t_exp * diffusivity(KAPPA_V1) / H ** 2}
    runs = {}
    times = [t_of(T, KAPPA_V1) for T in (0.05,) if T < T_imp * (1 - 1e-9)]
    runs["implicit"] = run_case(exe, block_2d_doc("implicit", t_imp, times, 0.006),
                                "c_block2d_implicit", out, repeats=repeats)
    runs["implicit"]["errors_all_T"] = profile_errors(runs["implicit"]["dir"], KAPPA_V1, 1)
    exp_doc = block_2d_doc("explicit", t_exp, [], t_exp / 10)
    runs["explicit"] = run_case(exe, exp_doc, "c_block2d_explicit", out, repeats=repeats)
    runs["explicit"]["errors_all_T"] = profile_errors(runs["explicit"]["dir"], KAPPA_V1, 1)
    if two_threads:
        runs["explicit_2threads"] = run_case(exe, exp_doc, "c_block2d_explicit_2threads", out,
                                             threads=2, repeats=repeats)
    for r in runs.values():
        r["wall_per_simulated_s"] = r["wall_time_s"] / r["simulated_time_s"]
    res["runs"] = runs
    im, ex = runs["implicit"], runs["explicit"]
    st = im["solver_statistics"]
    res["shares"] = {"lu_over_wall": st["lu_wall_time_s"] / im["wall_time_s"],
                     "lu_over_flow": st["lu_wall_time_s"] / st["flow_wall_time_s"],
                     "rhs_over_flow": st["rhs_wall_time_s"] / st["flow_wall_time_s"],
                     "jacobian_over_flow": st["jacobian_wall_time_s"] / st["flow_wall_time_s"],
                     "flow_over_wall": st["flow_wall_time_s"] / im["wall_time_s"]}
    res["ratio_per_simulated_s"] = ex["wall_per_simulated_s"] / im["wall_per_simulated_s"]
    # explicit to the implicit window: linear, and by the V1 step count
    T_w = res["explicit_window_T"]
    n_w, n_i = steps_to(T_steps, T_w), steps_to(T_steps, T_imp)
    res["v1_calibration_steps"] = {"to_explicit_window_T": n_w, "to_implicit_window_T": n_i}
    res["explicit_to_implicit_window_linear_s"] = ex["wall_time_s"] * t_imp / ex["simulated_time_s"]
    res["explicit_to_implicit_window_by_count_s"] = ex["wall_time_s"] * n_i / n_w if n_w else None
    est = [v for v in (res["explicit_to_implicit_window_linear_s"],
                       res["explicit_to_implicit_window_by_count_s"]) if v]
    res["ratio_same_window"] = min(est) / im["wall_time_s"]
    res["implicit_error_end"] = dict(zip(("T", "max", "rms"), im["errors_all_T"][-1]))
    return res


# ---------------------------------------------------------------------------------------------
# printing


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unsatmpm", required=True, help="path of the unsatmpm program")
    ap.add_argument("--output", default="/tmp/bench_cycles", help="output folder")
    ap.add_argument("--repeats", type=int, default=None,
                    help="runs per figure, the fastest kept (default 3; 1 with --quick)")
    ap.add_argument("--quick", action="store_true", help="short windows, a smoke test (~1 min)")
    ap.add_argument("--no-two-threads", action="store_true",
                    help="skip the 2D explicit run on 2 threads")
    args = ap.parse_args()
    exe = Path(args.unsatmpm).resolve()
    out = Path(args.output).resolve()
    out.mkdir(parents=True, exist_ok=True)
    repeats = args.repeats or (1 if args.quick else 3)
    windows = ({"b_T": 0.002, "c_T": 0.02, "c_t_exp": 0.002} if args.quick else
               {"b_T": 0.01, "c_T": 0.2, "c_t_exp": 0.01})
    t_start = time.monotonic()
    print_figures({"unsatmpm": str(exe), "output": str(out), "repeats": repeats,
                   "quick": args.quick})
    result = {"unsatmpm": str(exe), "repeats": repeats, "quick": args.quick, "windows": windows}
    failed = []
    try:
        T_steps, cal = calibration_steps(exe, out)
        result["calibration"] = {"run": cal["dir"], "steps_to_T1": int(len(T_steps)),
                                 "steps_in_summary": cal["steps"]}
        print_figures({"calibration_steps_to_T1": int(len(T_steps))})
    except RunFailed as e:
        print(f"calibration run failed: {e}")
        return 1
    parts = [("a", lambda: part_a(exe, out, repeats), print_a),
             ("b", lambda: part_b(exe, out, repeats, windows["b_T"], T_steps), print_b),
             ("c", lambda: part_c(exe, out, repeats, windows["c_T"], windows["c_t_exp"], T_steps,
                                  not args.no_two_threads), print_c)]
    for key, run, show in parts:
        try:
            result[key] = run()
            show(result[key], repeats)
        except RunFailed as e:
            print(f"\n({key}) FAILED: {e}")
            result[key] = {"failed": str(e)}
            failed.append(key)
        sys.stdout.flush()
    result["total_wall_time_s"] = time.monotonic() - t_start
    ok = "b" in result and result["b"].get("pass")
    print("\nsummary")
    print_figures({
        "a_wall_ratio": result.get("a", {}).get("wall_ratio_explicit_over_implicit", math.nan),
        "b_pass": ok,
        "b_wall_ratio": result.get("b", {}).get("wall_ratio_explicit_over_implicit", math.nan),
        "c_implicit_wall_per_simulated_s":
            result.get("c", {}).get("runs", {}).get("implicit", {}).get("wall_per_simulated_s",
                                                                        math.nan),
        "c_lu_over_flow": result.get("c", {}).get("shares", {}).get("lu_over_flow", math.nan),
        "total_wall_time_s": result["total_wall_time_s"]})
    (out / "bench_cycles.json").write_text(json.dumps(result, indent=2))
    print(f"figures: {out / 'bench_cycles.json'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
