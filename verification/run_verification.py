#!/usr/bin/python3
"""Runs the verification cases, checks them against their references, plots, and writes a report.

Each case lives in verification/<case>/: case.yaml (the input, as users write it), check.py (the
reference, the tolerances and the plot) and README.md. For every case this runs
`unsatmpm run`, evaluates the checks, saves <output>/<case>/result.json and a PNG, and rebuilds
<output>/report.md from every result present. Exit status 1 if any check of the cases run fails.

With --resume, a run whose folder already holds a completed run of the same effective case (as
`unsatmpm check` gives it) made by the same program (the executable's SHA-256, which the runner
keeps beside the folder as <run>.program) is taken as it is, and one that stopped before its end
with its checkpoint (interrupted, or killed while `running`) goes on with `unsatmpm resume`; the
others run from the start. So a slow case of several runs (hours each) can be run in pieces.

Usage: run_verification.py --unsatmpm PATH [--output DIR] [--case NAME ...] [--threads N] [--resume]
"""
import argparse
import hashlib
import importlib.util
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import yaml

HERE = Path(__file__).resolve().parent
CASES = ["infiltration", "grid_convergence", "column_selfweight", "vibrating_bar", "embankment_dry",
         "water_table", "terzaghi", "liakopoulos", "terzaghi_load", "mandel", "loaded_wetting",
         "collapse", "embankment_cycles", "occluded_gas", "drying", "wetting", "rain"]
# Run only when named with --case: slow (CTest label "slow"), or still in progress (README.md).
SLOW = ["embankment"]
IN_PROGRESS = []


def load_check(case):
    spec = importlib.util.spec_from_file_location(f"check_{case}", HERE / case / "check.py")
    module = importlib.util.module_from_spec(spec)
    sys.path.insert(0, str(HERE))
    spec.loader.exec_module(module)
    return module


def apply_overrides(doc, overrides):
    """Sets dotted keys with list indices, e.g. {"bodies[0].points_per_cell": 1}, in a YAML doc."""
    for path, value in overrides.items():
        node, parts = doc, re.findall(r"[^.\[\]]+", path)
        keys = [int(k) if k.isdigit() else k for k in parts]
        for k in keys[:-1]:
            node = node[k]
        node[keys[-1]] = value


def _effective(lines):
    """A case's effective configuration without its comment lines (which name the file)."""
    return [line for line in lines if not line.startswith("#")]


def program_id(exe):
    """The executable's SHA-256: what a kept run must have been made by."""
    return hashlib.sha256(Path(exe).read_bytes()).hexdigest()


def previous_run(exe, case_file, run_dir):
    """What run_dir holds of this case: "completed" (a finished run of the same effective case by
    the same program), "unfinished" (one that stopped before its end, with its checkpoint) or None
    (nothing to keep: no run, another case or program, or a failed run)."""
    summary, effective = run_dir / "run_summary.json", run_dir / "effective_case.yaml"
    made_by = run_dir.with_name(run_dir.name + ".program")
    if not (summary.exists() and effective.exists() and made_by.exists()) or \
            made_by.read_text().strip() != program_id(exe):
        return None
    proc = subprocess.run([exe, "check", str(case_file)], capture_output=True, text=True)
    if proc.returncode != 0 or \
            _effective(proc.stdout.splitlines()) != _effective(effective.read_text().splitlines()):
        return None
    status = json.loads(summary.read_text()).get("status")
    if status == "completed":
        return "completed"
    if status in ("running", "interrupted") and (run_dir / "checkpoint.bin").exists():
        return "unfinished"
    return None


def run_one(exe, case_file, run_dir, threads, resume=False):
    previous = previous_run(exe, case_file, run_dir) if resume else None
    t0 = time.monotonic()
    if previous is None:
        run_dir.with_name(run_dir.name + ".program").write_text(program_id(exe) + "\n")
    if previous != "completed":
        command = [exe, "resume", str(run_dir)] if previous == "unfinished" else \
            [exe, "run", str(case_file), "--output", str(run_dir)]
        proc = subprocess.run(command + ["--threads", str(threads), "--quiet"],
                              capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"{case_file}: unsatmpm exited with {proc.returncode}:\n{proc.stderr}")
    wall = time.monotonic() - t0
    summary = json.loads((run_dir / "run_summary.json").read_text())
    return {"wall_time_s": wall if previous is None else summary["wall_time_s"],
            "steps": summary["steps"], "material_points": summary["material_points"],
            "ns_per_mp_step": summary["ns_per_mp_step"],
            **({"reused": previous} if previous else {})}


def check_entry(name, value, tolerance, known=None):
    """A check passes when value <= tolerance. `known` names a documented discrepancy: the check
    still shows FAIL in the report, with the reason, but does not make the run fail."""
    entry = {"name": name, "value": value, "tolerance": tolerance, "passed": bool(value <= tolerance)}
    if known:
        entry["known_discrepancy"] = known
    return entry


def status(check):
    if check["passed"]:
        return "pass"
    return "FAIL (known discrepancy: " + check["known_discrepancy"] + ")" \
        if "known_discrepancy" in check else "FAIL"


def blocking(check):
    return not check["passed"] and "known_discrepancy" not in check


def run_case(case, exe, out_root, threads, resume=False):
    """Runs every run of a case (check.RUNS: name -> overrides of case.yaml; default one run)."""
    check = load_check(case)
    case_dir = out_root / case
    case_dir.mkdir(parents=True, exist_ok=True)
    base = (HERE / case / getattr(check, "BASE", "case.yaml")).resolve()  # BASE: another case's
    runs = getattr(check, "RUNS", {"run": {}})
    run_dirs, info = {}, {}
    for name, overrides in runs.items():
        case_file = base
        if overrides:
            doc = yaml.safe_load(base.read_text())
            apply_overrides(doc, overrides)
            doc["name"] = f"{doc['name']}_{name}"
            case_file = case_dir / f"{name}.yaml"
            case_file.write_text(yaml.safe_dump(doc, sort_keys=False))
        run_dirs[name] = case_dir / name
        info[name] = run_one(exe, case_file, run_dirs[name], threads, resume)
    data, checks = check.evaluate(run_dirs)
    plots = check.plot(data, case_dir)
    result = {
        "case": case,
        "title": (check.__doc__ or case).strip().splitlines()[0],
        "checks": [check_entry(*c) for c in checks],
        "runs": info,
        "plots": plots,
        "notes": check.notes(data) if hasattr(check, "notes") else "",
    }
    tmp = case_dir / f"result.json.{os.getpid()}.tmp"
    tmp.write_text(json.dumps(result, indent=2))
    os.replace(tmp, case_dir / "result.json")
    return result


def write_report(out_root):
    lines = ["# unsatmpm verification report", "",
             "Generated by `verification/run_verification.py`. Each case: its input "
             "(`verification/<case>/case.yaml`), its reference and tolerances "
             "(`verification/<case>/check.py`, README.md), the checks, and a plot.", ""]
    lines += ["| case | result | runs | material points | steps | wall time [s] |",
              "|---|---|---|---|---|---|"]
    results = []
    for case in CASES + SLOW + IN_PROGRESS:
        f = out_root / case / "result.json"
        if f.exists():
            r = json.loads(f.read_text())
            if "runs" in r:  # results of an older runner version are left out
                results.append(r)
    for r in results:
        known = sum(1 for c in r["checks"] if not c["passed"] and not blocking(c))
        result = "FAIL" if any(blocking(c) for c in r["checks"]) else "pass"
        if known:
            result += f", {known} known discrepanc{'y' if known == 1 else 'ies'} (FAIL, explained)"
        runs = r["runs"].values()
        lines.append(f"| {r['case']} | {result} | {len(r['runs'])} | "
                     f"{max(x['material_points'] for x in runs)} | "
                     f"{sum(x['steps'] for x in runs)} | {sum(x['wall_time_s'] for x in runs):.2f} |")
    for r in results:
        lines += ["", f"## {r['case']}: {r['title']}", "", "| check | value | tolerance | result |",
                  "|---|---|---|---|"]
        for c in r["checks"]:
            name = c["name"].replace("|", "\\|")
            lines.append(f"| {name} | {c['value']:.3e} | {c['tolerance']:.3e} | {status(c)} |")
        if len(r["runs"]) > 1:
            lines += ["", "| run | material points | steps | wall time [s] | ns per MP-step |",
                      "|---|---|---|---|---|"]
            for name, x in r["runs"].items():
                kept = {"completed": " (kept)", "unfinished": " (resumed)"}.get(x.get("reused"), "")
                lines.append(f"| {name}{kept} | {x['material_points']} | {x['steps']} | "
                             f"{x['wall_time_s']:.2f} | {x['ns_per_mp_step']:.0f} |")
        if r["notes"]:
            lines += ["", r["notes"]]
        for png in r["plots"]:
            lines += ["", f"![{png}]({r['case']}/{png})"]
    tmp = out_root / f"report.md.{os.getpid()}.tmp"
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, out_root / "report.md")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--unsatmpm", required=True, help="path of the unsatmpm program")
    ap.add_argument("--output", default=str(HERE / "output"), help="output folder")
    ap.add_argument("--case", action="append", choices=CASES + SLOW + IN_PROGRESS,
                    help="case to run (default: all but the slow ones and those in progress)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--resume", action="store_true",
                    help="keep the runs already completed and resume those stopped with their "
                         "checkpoint (see above)")
    args = ap.parse_args()
    out_root = Path(args.output).resolve()
    out_root.mkdir(parents=True, exist_ok=True)
    failed, known = [], []
    for case in args.case or CASES:
        r = run_case(case, args.unsatmpm, out_root, args.threads, args.resume)
        for c in r["checks"]:
            print(f"{case}: {c['name']}: {c['value']:.3e} (tolerance {c['tolerance']:.3e}) "
                  f"{status(c)}")
            if blocking(c):
                failed.append(f"{case}: {c['name']}")
            elif not c["passed"]:
                known.append(f"{case}: {c['name']}")
    write_report(out_root)
    print(f"report: {out_root / 'report.md'}")
    if known:
        print("failed checks with a documented, explained discrepancy (not resolved):\n  " +
              "\n  ".join(known))
    if failed:
        print("failed checks:\n  " + "\n  ".join(failed))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
