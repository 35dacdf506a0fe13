"""V5a: the embankment without rain stands (the fast part of V5, run in CI).

The embankment of verification/embankment/case.yaml with its surface suction held at 800 kPa,
to t = 30 s: the slope the paper's rain brings down must first stand, with its initial stresses
from gravity loading (solver.gravity_loading) and its strength from the suction (eqs. 13-14; at
800 kPa, c = 15.9 kPa and phi = 20.8 deg). The slow rain run is verification/embankment.

Checks, set from the issue's statement before the run was looked at (pass: value <= tolerance):
- max |displacement| of any point and of any control point up to t = 30 s <= 0.05 m;
- the gravity loading balanced: its final force ratio <= the case's tolerance (1e-3), read from
  the run summary;
- nothing yielded in the loading or the run: largest deviatoric plastic strain at 30 s <= 0.01
  (the slope is far from failure at 800 kPa: a plastic zone would mean a wrong initial state).
"""
import json

import numpy as np

from pathlib import Path

from common import case_doc, read_csv, read_points, series

BASE = "../embankment/case.yaml"
RUNS = {"dry": {"free_surface.liquid.suction": 8.0e5, "solver.end_time": 30,
                "output.times": [10, 20]}}
# solver.gravity_loading.tolerance of the case
TOLERANCE = float(case_doc(Path(__file__).parent / BASE)["solver"]["gravity_loading"]["tolerance"])


def evaluate(run_dirs):
    run = run_dirs["dry"]
    max_u, max_eps, snaps = 0.0, 0.0, []
    for t, path in series(run):
        x, a = read_points(path)
        u = np.linalg.norm(a["displacement"], axis=1)
        max_u = max(max_u, float(u.max()))
        max_eps = max(max_eps, float(a["deviatoric_plastic_strain"].max()))
        snaps.append((t, x, u))
    cp = read_csv(run / "control_points.csv")
    names = sorted({k.split("_")[0] for k in cp if k.endswith("_displacement_x")})
    hist = {n: np.hypot(cp[f"{n}_displacement_x"], cp[f"{n}_displacement_y"]) for n in names}
    for h in hist.values():
        max_u = max(max_u, float(h.max()))
    summary = json.loads((run / "run_summary.json").read_text())
    loading = summary["gravity_loading"]
    checks = [
        ("max displacement to t = 30 s [m]", max_u, 0.05),
        ("gravity loading: final force ratio", loading["force_ratio"], TOLERANCE),
        ("max deviatoric plastic strain at 30 s", max_eps, 0.01),
    ]
    return {"time": cp["time"], "hist": hist, "snaps": snaps, "loading": loading,
            "max_u": max_u}, checks


def plot(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.5))
    for n, h in data["hist"].items():
        a1.plot(data["time"], 1e3 * h, label=n)
    a1.set_xlabel("time [s]")
    a1.set_ylabel("displacement magnitude [mm]")
    a1.set_title("Control points, no rain (suction 800 kPa held)")
    a1.legend()
    t, x, u = data["snaps"][-1]
    sc = a2.scatter(x[:, 0], x[:, 1], c=1e3 * u, s=2, cmap="viridis")
    fig.colorbar(sc, ax=a2, label="displacement [mm]")
    a2.set_aspect("equal")
    a2.set_title(f"t = {t:g} s")
    a2.set_xlabel("x [m]")
    a2.set_ylabel("y [m]")
    fig.tight_layout()
    fig.savefig(out_dir / "embankment_dry.png", dpi=100)
    plt.close(fig)
    return ["embankment_dry.png"]


def notes(data):
    g = data["loading"]
    return (f"Gravity loading before t = 0: {g['steps']} steps, {g['time_s']:.3g} s of loading "
            f"time, force ratio {g['force_ratio']:.2e}; reset afterwards: largest displacement "
            f"{g['max_displacement_m']:.3e} m, largest plastic strain {g['max_plastic_strain']:.3e}.")
