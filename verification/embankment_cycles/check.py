"""V5b: the embankment's rain in both cycles and both mass-balance forms (issue 17, item 2).

Five runs of verification/embankment/case.yaml: `solver.cycle` explicit (the paper's cycle) and
implicit (the main cycle), each with `mass_balance` full and simplified, and the main cycle's full
form once more with the face's penalty (`solver.implicit.surface_penalty: 16`), whose face takes in
the water the cells converge to where holding the surface node layer starves it (docs/input.md).
- Fast (CI, the default): 0.4 m cells (the grid widened to 25.2 m so that 63 x 20 cells are
  square), 2 x 2 points per cell, to t = 15 s: the wetting of the face, before any slide.
- Slow (EMBANKMENT_CYCLES_SLOW=1 in the environment, CTest label "slow"): the committed 0.2 m
  cells, each run to 400 s or until the slide has come to rest (../embankment/check.py REST),
  whichever is first (issue 17, item 4: no run had come to rest by 200 s, and the main cycle's
  slides again from about 210 s, ../embankment/README.md), with output frames every 50 s from
  200 s on as well.

Checks, set before the runs were looked at (pass: value <= tolerance):
- each cycle's full form closes both balances: largest |mismatch| of conservation.csv <= 1e-3
  (issue 14's bound for the liquid; the gas held to the same);
- the two cycles wet the face alike: their full forms' wetting depths at 15 s (../embankment/
  check.py: suction below 400 kPa, 90th percentile of the depth, mid-face) differ by at most one
  cell (the resolution of both: a front inside one cell is placed anywhere in it). The main
  cycle's run compared is the penalised one since 2026-11-30: the explicit cycle's nodes now
  take the mean of their conductivities (docs/balance_laws.md, "Wetting a dry soil through a
  face"), and on 0.4 m cells its face took in 3,608 kg/m by 15 s (1.06 m deep) against the
  penalised main cycle's 3,472 (1.03 m) and about 3,350 where the cells converge, while the main
  cycle holding its surface layer took in 1,373 (0.56 m). Before, the explicit cycle's 2,352 kg/m
  (0.58 m) had passed against the held layer's;
- in each cycle the simplified form holds less water at 15 s than the full form (value: the
  simplified form's water gained since t = 0 over the full form's, <= 1): the term it drops,
  -(v_l - v_s).grad(theta_l), is positive at a wetting front (docs/balance_laws.md), so dropping
  it stores less;
- fast variant, each cycle and form: no slide by 15 s, the largest kinetic energy to 15 s at
  most ../embankment/check.py's KE_FAILURE (1 J/m, its mark of a slide's start; on 0.2 m cells
  the slope first passes it at 43 s). Added for the main cycle 2026-11-28 after two forms of its
  offset relaxation tore a crest-corner point loose before 15 s (docs/balance_laws.md, "S1
  weighted by volume, and bounded"), which the checks above did not see. Asserted for the
  explicit cycle since 2026-11-30: before its nodes took the mean of their conductivities its
  surface points were loosened on 0.4 m cells from about 11.5 s (224-241 J/m at 15 s), the water
  piled up in the top point rows, which a layer of this soil deeper than about 0.25 m does not
  survive at zero suction (../embankment/investigations.md, "Which cycle's face is right").
Reported beside them: each run's measures as ../embankment/check.py takes them (initiation,
shear band, run-out, D2), its water held and counted as inflow, the face's median suction at
15 s in its top two 0.2 m bands (the main cycle's face stays drier: ../embankment/investigations.md,
"Which cycle's face is right"), and its wall time. Why the two
cycles' simplified forms report different mismatches: ../embankment/README.md.
"""
import importlib.util
import json
import os
from pathlib import Path

import numpy as np

from common import case_doc, read_csv, series

HERE = Path(__file__).resolve().parent
BASE = "../embankment/case.yaml"
SLOW = os.environ.get("EMBANKMENT_CYCLES_SLOW") == "1"
_spec = importlib.util.spec_from_file_location("embankment_check", HERE / "../embankment/check.py")
embankment = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(embankment)

_DOC = case_doc(HERE / BASE)
CELL = 0.2 if SLOW else 0.4  # m
END = 400.0 if SLOW else 15.0
MISMATCH = 1.0e-3
# This check's first run found the explicit cycle's simplified form gaining 1.41
# times its full form's water on 0.4 m cells (0.93 times on 0.2 m). The cause was the explicit
# cycle's surface, not the form: the node just inside the face counted as closed
# (numerics/pressure/free_surface.hpp). With the surface pressure acting there too the ratio is
# 0.90 on 0.4 m cells (2026-11-27), and the check blocks on both variants.
WET_TIME = 15.0


PENALTY = 16.0  # the face's penalty of the fifth run (docs/input.md: 16 to 64 measured)


def _solver(cycle, penalty=None):
    s = dict(_DOC["solver"])
    s["cycle"], s["end_time"] = cycle, END
    if cycle == "explicit":
        s.pop("implicit", None)  # the main cycle's coupling interval
    if penalty is not None:
        s["implicit"] = {**s.get("implicit", {}), "surface_penalty": penalty}
    if SLOW:
        s["stop_at_rest"] = dict(embankment.REST)
    return s


def _run(cycle, form, penalty=None):
    times = sorted(set(_DOC["output"]["times"]) | {200, 250, 300, 350})
    o = {"solver": _solver(cycle, penalty), "mass_balance": form,
         "output.times": [t for t in times if t < END] if SLOW else [5, 10]}
    if not SLOW:
        o["grid.size"] = [25.2, 8]
        o["grid.cells"] = [63, 20]
    return o


RUNS = {f"{c}_{f}": _run(c, f) for c in ("explicit", "implicit") for f in ("full", "simplified")}
RUNS["implicit_full_penalty"] = _run("implicit", "full", PENALTY)


def _water(run_dir, t):
    c = read_csv(run_dir / "conservation.csv")
    i = int(np.argmin(np.abs(c["time"] - t)))
    return {"held0": float(c["liquid_mass"][0]), "held": float(c["liquid_mass"][i]),
            "inflow": float(c["liquid_inflow"][i]),
            "mismatch_liquid": float(np.abs(c["liquid_mismatch"]).max()),
            "mismatch_gas": float(np.abs(c["gas_mismatch"]).max())}


def _face_suction(run_dir, t):
    """Median suction [kPa] at time t of the face band's points (../embankment/check.py BAND_X)
    within 0-0.2 m and 0.2-0.4 m of the face by their initial depth: the measure of
    ../embankment/investigations.md, "Which cycle's face is right" (reported, not asserted)."""
    s = embankment._snapshot(*embankment._nearest(series(run_dir), t))
    face = (s["x0"] >= embankment.BAND_X[0]) & (s["x0"] <= embankment.BAND_X[1])
    z = embankment.depth_below_surface(s["x0"][face], s["y0"][face])
    out = []
    for lo, hi in ((0.0, 0.2), (0.2, 0.4)):
        band = (z >= lo) & (z < hi)
        out.append(float(np.median(s["suction"][face][band])) / 1e3 if band.any() else np.nan)
    return out


def evaluate(run_dirs):
    data = {}
    for name, run in run_dirs.items():
        d, _ = embankment.evaluate({"rain": run, "dry": run})
        summary = json.loads((run / "run_summary.json").read_text())
        data[name] = {**d, **_water(run, WET_TIME), "wall_s": summary["wall_time_s"],
                      "status": summary["status"], "face_suction": _face_suction(run, WET_TIME)}
    checks = []
    for c in ("explicit", "implicit"):
        full, simp = data[f"{c}_full"], data[f"{c}_simplified"]
        checks.append((f"{c}, full: largest liquid mismatch", full["mismatch_liquid"], MISMATCH))
        checks.append((f"{c}, full: largest gas mismatch", full["mismatch_gas"], MISMATCH))
        gain_full, gain_simp = full["held"] - full["held0"], simp["held"] - simp["held0"]
        checks.append((f"{c}: water gained by 15 s, simplified / full", gain_simp / gain_full, 1.0))
    pen = data["implicit_full_penalty"]
    checks.append(("implicit, full, face penalty: largest liquid mismatch", pen["mismatch_liquid"],
                   MISMATCH))
    checks.append(("implicit, full, face penalty: largest gas mismatch", pen["mismatch_gas"],
                   MISMATCH))
    if not SLOW:
        for run in ("explicit_full", "explicit_simplified", "implicit_full",
                    "implicit_simplified", "implicit_full_penalty"):
            checks.append((f"{run.replace('_', ', ', 1)}: largest kinetic energy to {END:g} s "
                           "[J/m]", float(np.max(data[run]["ke"])), embankment.KE_FAILURE))
    checks.append(("wetting depth at 15 s, |explicit - implicit with the face's penalty| (full) "
                   "[m]", abs(data["explicit_full"]["wet_p90"] - pen["wet_p90"]), CELL))
    return data, checks


def _f(v, fmt="{:.2f}"):
    return "–" if v is None or not np.isfinite(v) else fmt.format(v)


def notes(data):
    rows = ["| run | reached [s] | wetting at 15 s [m] | water held at 15 s / counted inflow "
            "[kg/m] | KE > 1 J/m [s] | CP moves 0.1 m [s] | band at 15 s [m] | deepest plastic "
            "[m] | run-out [m] | D2 [m] | mismatch liquid / gas | face suction at 15 s, 0-0.2 / "
            "0.2-0.4 m deep [kPa] | wall [s] |",
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for name, d in data.items():
        rows.append(
            f"| {name} | {d['end_time']:g} | {d['wet_p90']:.2f} | {d['held']:.0f} / "
            f"{d['inflow']:.0f} | {_f(d['t_fail_ke'], '{:.1f}')} | "
            f"{_f(d['t_fail_cp'], '{:.1f}')} | {d['band_p90']:.2f} | {d['deepest_end']:.2f} | "
            f"{_f(d['runout'])} | {_f(d['d2_end'], '{:.3f}')} | "
            f"{d['mismatch_liquid']:.1e} / {d['mismatch_gas']:.1e} | "
            f"{_f(d['face_suction'][0], '{:.1f}')} / {_f(d['face_suction'][1], '{:.1f}')} | "
            f"{d['wall_s']:.0f} |")
    return (f"{'Slow' if SLOW else 'Fast'} variant: {CELL:g} m cells, to {END:g} s"
            + (" or rest" if SLOW else "") + ".\n\n" + "\n".join(rows))


def plot(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.5))
    for name, d in data.items():
        a1.semilogy(d["ke_time"], np.maximum(d["ke"], 1e-9), label=name)
        cp = np.max(list(d["cp"].values()), axis=0)
        a2.plot(d["cp_time"], cp, label=name)
    a1.set_xlabel("time [s]")
    a1.set_ylabel("kinetic energy [J/m]")
    a1.legend()
    a2.set_xlabel("time [s]")
    a2.set_ylabel("largest control-point displacement [m]")
    a2.legend()
    fig.suptitle(f"The embankment's rain in both cycles and both forms ({CELL:g} m cells)")
    fig.tight_layout()
    fig.savefig(out_dir / "embankment_cycles.png", dpi=100)
    plt.close(fig)
    return ["embankment_cycles.png"]
