"""V15: a dry sand wetted through its top: both cycles over the cells against Richards' equation.

The reference is richards.py: the column's liquid by finite volumes on 0.4 mm cells, the gas
at 0 (the case's gas is free to leave, k_rg = 1; its pressure is about 0.1 kPa at 2 s in the
runs). What is checked is the water taken in by 2 s, W, in the main cycle on 128, 256 and 512
cells and in the explicit cycle on 64, 128 and 256: the front is a few millimetres sharp where
k_rl changes by four orders of magnitude, so coarse cells are far off (README.md gives the
figures); the checks are the convergence a consistent discretisation must show.

Tolerances (from the method's order, not fitted to the runs): the distance |W - W_ref| falls by at
least 2 per halving of the cells (first order) over the main cycle's two halvings and the explicit
cycle's last; each run keeps its water and gas to the project's mismatch bounds of V11 (1e-3
liquid, 1e-2 gas).
"""
from pathlib import Path

import numpy as np

from common import case_doc, read_csv

HERE = Path(__file__).parent
_CASE = case_doc(HERE)
MAIN_CELLS = [128, 256, 512]
EXPLICIT_CELLS = [64, 128, 256]
T_READ = float(_CASE["solver"]["end_time"])
T_EARLY = 1.0

RUNS = {f"main_{n}": {"grid.cells": [n]} for n in MAIN_CELLS}
RUNS.update({f"explicit_{n}": {"grid.cells": [n], "solver.cycle": "explicit"}
             for n in EXPLICIT_CELLS})


def _reference():
    import sys
    sys.path.insert(0, str(HERE))
    import richards
    return richards.intake(_CASE, [T_EARLY, T_READ])


def _water_in(c, t):
    """The water taken in by t [kg per m^2 of the column's section]."""
    return float(np.interp(t, c["time"], c["liquid_inflow"]))


def evaluate(run_dirs):
    data, checks = {}, []
    for run, run_dir in run_dirs.items():
        c = read_csv(run_dir / "conservation.csv")
        data[run] = {"conservation": c, "in": _water_in(c, T_READ),
                     "in_early": _water_in(c, T_EARLY)}
        checks += [(f"{run}: max |liquid mismatch|", float(np.abs(c["liquid_mismatch"]).max()),
                    1e-3),
                   (f"{run}: max |gas mismatch|", float(np.abs(c["gas_mismatch"]).max()), 1e-2)]
    early, ref = _reference()
    data["reference"] = {"in": ref, "in_early": early}
    for cycle, cells, halvings in (("main", MAIN_CELLS, 2), ("explicit", EXPLICIT_CELLS, 1)):
        err = [abs(data[f"{cycle}_{n}"]["in"] - ref) for n in cells]
        for k in range(len(cells) - halvings, len(cells)):
            checks.append((f"{cycle} cycle: |W({cells[k]}) - W_ref| / |W({cells[k - 1]}) - W_ref|"
                           f" (first order: at most 1/2)", err[k] / err[k - 1], 0.5))
    return data, checks


def notes(data):
    ref = data["reference"]
    lines = [f"Water in by {T_READ:g} s and by {T_EARLY:g} s [kg/m^2]; Richards' equation "
             f"(richards.py): {ref['in']:.3f} and {ref['in_early']:.3f}.", ""]
    for run, d in data.items():
        if run != "reference":
            lines.append(f"- {run}: {d['in']:.3f} ({d['in'] / ref['in']:.2f} of the reference); "
                         f"by {T_EARLY:g} s {d['in_early']:.3f} "
                         f"({d['in_early'] / ref['in_early']:.2f})")
    return "\n".join(lines)


def plot(data, out_dir):
    png = out_dir / "wetting.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.5))
    ref = data["reference"]
    for run, d in data.items():
        if run == "reference":
            continue
        c = d["conservation"]
        ax.plot(c["time"], c["liquid_inflow"], "-" if run.startswith("main") else "--",
                label=run.replace("_", ", ") + " cells")
    ax.plot([T_EARLY, T_READ], [ref["in_early"], ref["in"]], "k*", ms=10,
            label="Richards' equation")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("water in [kg/m²]")
    ax.set_title("The water the wetted face takes in")
    ax.legend(fontsize=8)
    for cycle, cells, style in (("main", MAIN_CELLS, "o-"), ("explicit", EXPLICIT_CELLS, "s--")):
        err = [abs(data[f"{cycle}_{n}"]["in"] / ref["in"] - 1.0) for n in cells]
        bx.loglog([1.0 / n for n in cells], err, style, label=f"{cycle} cycle")
    bx.set_xlabel("cell size [m]")
    bx.set_ylabel(f"|W / W_ref - 1| at {T_READ:g} s")
    bx.set_title("Against Richards' equation")
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
