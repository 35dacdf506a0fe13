#!/usr/bin/python3
"""What reproduces the paper (issue 17, item 3): the embankment case run over the choices the paper
leaves open, each run measured as check.py measures the committed one.

Each variant is the committed case.yaml with a few keys changed (dotted paths, as check.RUNS).
The study's grid and why each value is in it: README.md, "What reproduces the paper"; the
published ranges: hydraulic_ranges.md.

Usage:
  study.py --unsatmpm build/bin/unsatmpm --output DIR [--end-time T] [--jobs J] [--threads N]
           [--rest] [--surface-penalty G | --cycle explicit] [--flip-fraction F]
           [--relative-permeability nodes] [--only NAME ...]
  study.py --list                      # the variants and what each changes
  study.py --output DIR --remeasure    # measure DIR's runs again (after check.py changed)

Writes DIR/<variant>.yaml, DIR/<variant>/ (the run), and DIR/study.json and DIR/study.md: one row
per variant run so far (a rerun replaces its row). A variant whose run fails is reported with the
program's message; the others go on. With --rest each run stops once the slide has come to rest
(check.REST) or at the end time, whichever comes first. With --surface-penalty every variant
takes the free surface's liquid condition as a penalty on the face's trace with factor G
(solver.implicit.surface_penalty, docs/input.md) instead of holding the surface node layer. With
--cycle explicit every variant runs on the paper's explicit cycle (its face takes the suction
through the boundary term, docs/cycles.md) instead of the main cycle. With --flip-fraction every
variant blends its points' velocity update with that FLIP fraction (solver.flip_fraction,
docs/input.md; the case's 1, pure FLIP, otherwise). With --relative-permeability nodes the main
cycle's flow takes each point's relative permeabilities from its stencil nodes
(solver.implicit.relative_permeability, docs/balance_laws.md). A folder holds runs of one setting
only.
"""
import argparse
import concurrent.futures
import fcntl
import json
import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import yaml

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))
sys.path.insert(0, str(HERE))
import check  # noqa: E402  (this folder's checker: its measures are the study's)
from run_verification import apply_overrides  # noqa: E402
from common import read_csv  # noqa: E402

MAT = "materials[0]."


def _retention(p0, lam, s_res=0.0, s_max=0.95, occluded=0.0):
    law = {"model": "van_genuchten", "p0": p0, "lambda": lam, "residual_saturation": s_res,
           "max_saturation": s_max}
    if occluded > 0.0:
        law["occluded_gas_scale"] = occluded
    return {MAT + "retention": law}


def _mualem(lam):
    return {MAT + "liquid_relative_permeability": {"model": "mualem_van_genuchten", "lambda": lam}}


def _power(r):
    return {MAT + "liquid_relative_permeability": {"model": "power", "exponent": r}}


def _curve(p0, lam, krl=3, note="", s_res=0.0, s_max=0.95, occluded=0.0):
    """A retention curve with k_rl = S_e^krl, or Mualem's with the same lambda (krl "mualem"),
    its occluded gas giving way over `occluded` Pa (0: flat at S_max): (what it varies,
    overrides)."""
    what = f"P0 {p0 / 1e3:g} kPa, lambda {lam:g}"
    what += f", S_max {s_max:g}" if s_max != 0.95 else ""
    what += f", S_res {s_res:g}" if s_res != 0.0 else ""
    what += ", Mualem" if krl == "mualem" else f", k_rl = S_e^{krl}"
    what += f", occluded gas {occluded:g} Pa" if occluded > 0.0 else ""
    perm = _mualem(lam) if krl == "mualem" else _power(krl)
    return what + note, {**_retention(p0, lam, s_res, s_max, occluded), **perm}


# The suction at the crest stays 800 kPa; below it the liquid is at rest (731 kPa at the base).
_HYDROSTATIC = {"bodies[0].initial_state": {
    "water_table": {"elevation": 7.0 - 8.0e5 / (1000 * 9.81), "max_suction": 8.0e5},
    "gas_pressure": 0}}

# name -> (what it varies, overrides of case.yaml). The committed case is P0 = 400 kPa, lambda =
# 0.5, S_max = 0.95, Mualem k_rl with the retention's lambda, k_rg = 1, a uniform 800 kPa, 0.2 m
# cells with 2 x 2 points.
VARIANTS = {
    "committed": ("the committed case", {}),
    # liquid relative permeability, the committed retention
    "se3": ("k_rl = S_e^3", _power(3)),
    "se4": ("k_rl = S_e^4", _power(4)),
    "se2": ("k_rl = S_e^2", _power(2)),
    # retention within the published ranges (hydraulic_ranges.md, sections 1-3), with S_e^3 and
    # with Mualem
    "p50_l03_se3": _curve(5e4, 0.3),
    "p20_l03_se3": _curve(2e4, 0.3),
    "p150_l03_se3": _curve(1.5e5, 0.3),
    "p150_l04_se3": _curve(1.5e5, 0.4),
    "p50_l04_se3": _curve(5e4, 0.4),
    "p150_l04_mvg": _curve(1.5e5, 0.4, "mualem"),
    "p50_l04_mvg": _curve(5e4, 0.4, "mualem"),
    "p50_l04_mvg_occ": _curve(5e4, 0.4, "mualem", occluded=1e3),
    "p150_l04_mvg_occ": _curve(1.5e5, 0.4, "mualem", occluded=1e3),
    "committed_occ": _curve(4e5, 0.5, "mualem", occluded=1e3),
    "p400_l03_se3": _curve(4e5, 0.3),
    "p5_l02_se3": _curve(5e3, 0.2, note=" (the CL/SC class means)"),
    "p5_l03_se3": _curve(5e3, 0.3),
    "p20_l03_mvg": _curve(2e4, 0.3, "mualem"),
    "p20_l03_mvg_occ": _curve(2e4, 0.3, "mualem", occluded=1e3),
    "p400_l02_se3": _curve(4e5, 0.2),
    "p400_l03_se2": _curve(4e5, 0.3, 2),
    "p400_l03_mvg": _curve(4e5, 0.3, "mualem"),
    "p200_l02_se3": _curve(2e5, 0.2),
    "p400_l015_se3": _curve(4e5, 0.15),
    "p1000_l03_se3": _curve(1e6, 0.3, note=" (out of range: what it takes)"),
    "p150_l03_smax09_se3": _curve(1.5e5, 0.3, s_max=0.9),
    "p150_l03_sres015_se3": _curve(1.5e5, 0.3, s_res=0.15),
    # the choices the paper leaves open besides the curves
    "hydrostatic": ("initial suction at rest below 800 kPa at the crest", _HYDROSTATIC),
    "krg_power1": ("k_rg = 1 - S_e", {MAT + "gas_relative_permeability":
                                      {"model": "power", "exponent": 1}}),
    "ppc3": ("3 x 3 points per cell", {"bodies[0].points_per_cell": 3}),
    "cells01": ("0.1 m cells", {"grid.cells": [250, 80]}),
    "cells04": ("0.4 m cells", {"grid.size": [25.2, 8], "grid.cells": [63, 20]}),
    "cells08": ("0.8 m cells", {"grid.size": [25.6, 8], "grid.cells": [32, 10]}),
    "cells04_se2": ("0.4 m cells, k_rl = S_e^2",
                    {"grid.size": [25.2, 8], "grid.cells": [63, 20], **_power(2)}),
}

def case_for(name, end_time, rest, penalty=0.0, cycle="implicit", flip=None, relperm=None):
    doc = check.case_doc(HERE)
    apply_overrides(doc, VARIANTS[name][1])
    if flip is not None:
        doc["solver"]["flip_fraction"] = flip
    if relperm is not None:
        doc["solver"].setdefault("implicit", {})["relative_permeability"] = relperm
    if penalty > 0.0:
        doc["solver"].setdefault("implicit", {})["surface_penalty"] = penalty
    if cycle == "explicit":
        doc["solver"]["cycle"] = "explicit"
        doc["solver"].pop("implicit", None)
    doc["name"] = f"embankment_{name}"
    doc["solver"]["end_time"] = end_time
    doc["output"]["times"] = [t for t in doc["output"]["times"] if t < end_time]
    if rest:
        doc["solver"]["stop_at_rest"] = dict(check.REST)
    return doc


# The suction below which the outer 1.5 m of the face, as an infinite slope (32.5 degrees, unit
# weight 20.5 kN/m3 wet, phi' = 20 degrees, net stress with P_g = 0), is at limit equilibrium:
# the cohesion needed is gamma z (sin b cos b - cos^2 b tan phi') = 5.9 kPa at z = 1.5 m, which
# eq. 13 (c' = 1 kPa, dc_max = 15 kPa, B = 0.7 per atmosphere) gives at 57 kPa. The depth above
# which the suction has fallen below it at 15 s is how deep the paper's band could be by then.
SOFT_SUCTION = 5.7e4


def softened_depth(snap):
    face = (snap["x0"] >= check.BAND_X[0]) & (snap["x0"] <= check.BAND_X[1])
    soft = face & (snap["suction"] < SOFT_SUCTION)
    depth = check.depth_below_surface(snap["x0"][soft], snap["y0"][soft])
    return float(np.percentile(depth, 90)) if len(depth) else 0.0


def measure(run_dir):
    data, _ = check.evaluate({"rain": run_dir, "dry": run_dir})
    summary = json.loads((run_dir / "run_summary.json").read_text())
    cons = read_csv(run_dir / "conservation.csv")
    ke = data["ke"]
    # check.py takes the output nearest 15 s; a run that ended before has none at 15 s.
    at_15 = abs(data["band_time"] - 15.0) < 1e-6
    row = {
        "status": summary["status"], "message": summary.get("message", ""),
        "reached_s": float(summary["simulated_time_s"]), "wall_s": float(summary["wall_time_s"]),
        "wet_depth_15": data["wet_p90"], "soft_depth_15": softened_depth(data["snaps"][1]),
        "band_p90_15": data["band_p90"],
        "band_points_15": data["band_points"], "t_ke_1": data["t_fail_ke"],
        "t_cp_01": data["t_fail_cp"], "deepest_plastic_end": data["deepest_end"],
        "runout_end": data["runout"], "moved_fraction_end": data["slid_mass_fraction"],
        "d2_end": data["d2_end"], "ke_end": float(ke[-1]), "ke_peak": float(ke.max()),
        "mismatch_liquid": float(np.abs(cons["liquid_mismatch"]).max()),
        "mismatch_gas": float(np.abs(cons["gas_mismatch"]).max()),
    }
    if not at_15:
        for k in ("wet_depth_15", "soft_depth_15", "band_p90_15", "band_points_15"):
            row[k] = None
    return row


def run(name, exe, out, end_time, threads, rest, penalty, cycle, flip, relperm):
    case_file = out / f"{name}.yaml"
    case_file.write_text(yaml.safe_dump(
        case_for(name, end_time, rest, penalty, cycle, flip, relperm), sort_keys=False))
    run_dir = out / name
    summary = run_dir / "run_summary.json"
    before = summary.stat().st_mtime_ns if summary.exists() else None
    t0 = time.monotonic()
    proc = subprocess.run([exe, "run", str(case_file), "--output", str(run_dir), "--threads",
                           str(threads), "--quiet"], capture_output=True, text=True)
    row = {"name": name, "varies": VARIANTS[name][0], "end_time": end_time, "rest": rest,
           "surface_penalty": penalty, "cycle": cycle, "flip_fraction": flip,
           "relative_permeability": relperm, "threads": threads,
           "elapsed_s": time.monotonic() - t0}
    if not summary.exists() or summary.stat().st_mtime_ns == before:  # none, or an old run's
        return {**row, "status": "no output", "message": proc.stderr.strip()[-400:]}
    try:
        return {**row, **measure(run_dir)}
    except Exception as e:  # a run that ended before 15 s has no 15 s snapshot to measure
        return {**row, "status": "not measured", "message": f"{type(e).__name__}: {e}"}


def _f(v, fmt):
    return "–" if v is None or (isinstance(v, float) and not np.isfinite(v)) else fmt.format(v)


def write_table(out, rows):
    head = ("| run | varies | reached [s] | wetting at 15 s [m] | s < 57 kPa at 15 s [m] | band at 15 s [m] (points) | "
            "KE > 1 J/m [s] | CP moves 0.1 m [s] | deepest plastic [m] | run-out [m] | "
            "moved ≥ 0.5 m | D2 [m] | KE end / peak [J/m] | mismatch l / g | wall [s] |")
    lines = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        if "wet_depth_15" not in r:
            lines.append(f"| {r['name']} | {r['varies']} | {r['status']}: {r['message']} |"
                         + " |" * 12)
            continue
        lines.append(
            f"| {r['name']} | {r['varies']} | {_f(r['reached_s'], '{:g}')} | "
            f"{_f(r['wet_depth_15'], '{:.2f}')} | {_f(r.get('soft_depth_15'), '{:.2f}')} | "
            f"{_f(r['band_p90_15'], '{:.2f}')} ({_f(r['band_points_15'], '{}')}) | "
            f"{_f(r['t_ke_1'], '{:.1f}')} | {_f(r['t_cp_01'], '{:.1f}')} | "
            f"{r['deepest_plastic_end']:.2f} | {_f(r['runout_end'], '{:.2f}')} | "
            f"{100 * r['moved_fraction_end']:.1f} % | {_f(r['d2_end'], '{:.3f}')} | "
            f"{r['ke_end']:.3g} / {r['ke_peak']:.3g} | "
            f"{r['mismatch_liquid']:.1e} / {r['mismatch_gas']:.1e} | {r['wall_s']:.0f} |")
    (out / "study.md").write_text("\n".join(lines) + "\n")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unsatmpm")
    ap.add_argument("--output", type=Path)
    ap.add_argument("--end-time", type=float, default=25.0)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rest", action="store_true")
    ap.add_argument("--surface-penalty", type=float, default=0.0,
                    help="the face's liquid condition as a penalty with this factor (0: held layer)")
    ap.add_argument("--cycle", choices=["implicit", "explicit"], default="implicit",
                    help="the main cycle (the committed case's) or the paper's explicit cycle")
    ap.add_argument("--flip-fraction", type=float, default=None,
                    help="the points' FLIP/PIC blend (solver.flip_fraction; the case's 1 if absent)")
    ap.add_argument("--relative-permeability", choices=["points", "nodes"], default=None,
                    help="the main cycle's flow's k_r at the points (the case's) or from the nodes")
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--list", action="store_true")
    ap.add_argument("--remeasure", action="store_true",
                    help="measure again the runs already in DIR (no run)")
    a = ap.parse_args()
    if a.list:
        for name, (what, _) in VARIANTS.items():
            print(f"{name}: {what}")
        return 0
    if a.remeasure:
        for row in json.loads((a.output / "study.json").read_text()):
            if (a.output / row["name"] / "run_summary.json").exists():
                row.update(measure(a.output / row["name"]))
            record(a.output, row)
        return 0
    if not a.unsatmpm or not a.output:
        ap.error("--unsatmpm and --output are required")
    if a.surface_penalty < 0.0:
        ap.error("--surface-penalty must be >= 0")
    if a.surface_penalty > 0.0 and a.cycle == "explicit":
        ap.error("--surface-penalty is the main cycle's; the explicit cycle has its boundary term")
    if a.flip_fraction is not None and not 0.0 <= a.flip_fraction <= 1.0:
        ap.error("--flip-fraction must be in [0, 1]")
    if a.relative_permeability is not None and a.cycle == "explicit":
        ap.error("--relative-permeability is the main cycle's flow's")
    names = a.only or list(VARIANTS)
    unknown = [n for n in names if n not in VARIANTS]
    if unknown:
        ap.error(f"unknown variant(s) {unknown}; --list shows them")
    store = a.output / "study.json"
    if store.exists():  # one folder, one setting: its table does not say which each row had
        mixed = [r["name"] for r in json.loads(store.read_text())
                 if (r.get("surface_penalty", 0.0), r.get("cycle", "implicit"),
                     r.get("flip_fraction"), r.get("relative_permeability"))
                 != (a.surface_penalty, a.cycle, a.flip_fraction, a.relative_permeability)]
        if mixed:
            ap.error(f"{a.output} holds runs {mixed} made with another --surface-penalty, "
                     "--cycle, --flip-fraction or --relative-permeability; use another folder")
    a.output.mkdir(parents=True, exist_ok=True)
    with concurrent.futures.ThreadPoolExecutor(max_workers=a.jobs) as pool:
        futures = [pool.submit(run, n, a.unsatmpm, a.output, a.end_time, a.threads, a.rest,
                               a.surface_penalty, a.cycle, a.flip_fraction,
                               a.relative_permeability) for n in names]
        for fut in concurrent.futures.as_completed(futures):
            row = fut.result()
            record(a.output, row)
            print(f"{row['name']}: {row.get('status')} in {row['elapsed_s']:.0f} s", flush=True)
    return 0


def record(out, row):
    """Adds a row to DIR/study.json (replacing the variant's earlier row) and rewrites study.md,
    under a lock, so that several study processes may share one folder."""
    with open(out / "study.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        store = out / "study.json"
        rows = json.loads(store.read_text()) if store.exists() else []
        rows = [r for r in rows if r["name"] != row["name"]] + [row]
        order = list(VARIANTS)
        rows.sort(key=lambda r: order.index(r["name"]) if r["name"] in order else len(order))
        tmp = out / "study.json.tmp"
        tmp.write_text(json.dumps(rows, indent=2))
        os.replace(tmp, store)
        write_table(out, rows)


if __name__ == "__main__":
    sys.exit(main())
