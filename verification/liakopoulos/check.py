"""V8 (in progress): Liakopoulos's drainage test, the main cycle.

Reference: not yet in the repository (README.md): the published pressure profiles at 5, 10, 20,
30, 60 and 120 min and the outflow are still to be digitised with their uncertainty. Until then
this checker asserts what needs no reference, with tolerances set before the runs: each fluid's
mass balance closed to 1e-3 (the issue's bound for deforming cases), the base at the drained
boundary's pressure (|P_l| of the lowest points below rho_l g h = 490 Pa), and the column draining
monotonically (the outflow never decreasing). It plots the profiles for a visual check.
"""
from pathlib import Path

import numpy as np

from common import case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
H = float(_CASE["grid"]["size"][0])
CELL = H / int(_CASE["grid"]["cells"][0])
RHO_L = float(_CASE["fluids"]["liquid"]["density"])
G = abs(float(_CASE["gravity"][0]))


def evaluate(run_dirs):
    run_dir = run_dirs["run"]
    profiles = []
    base_p = 0.0
    for t, path in series(run_dir):
        x, a = read_points(path)
        z = x[:, 0]
        order = np.argsort(z)
        profiles.append((t, z[order], a["liquid_pressure"][order], a["gas_pressure"][order],
                         a["degree_of_saturation"][order]))
        base_p = max(base_p, float(np.abs(a["liquid_pressure"][z < CELL / 2]).max()))
    c = read_csv(run_dir / "conservation.csv")
    outflow = -c["liquid_inflow"]
    checks = [
        ("max |liquid mismatch|", float(np.abs(c["liquid_mismatch"]).max()), 1e-3),
        ("max |gas mismatch|", float(np.abs(c["gas_mismatch"]).max()), 1e-3),
        ("max |P_l| at the drained base / (rho_l g h)", base_p / (RHO_L * G * CELL), 1.0),
        ("largest decrease of the outflow [kg/m^2]", float(max(0.0, -np.diff(outflow).min())),
         1e-9),
    ]
    return {"profiles": profiles, "time": c["time"], "outflow": outflow}, checks


def plot(data, out_dir):
    png = out_dir / "liakopoulos.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(14, 5))
    for t, z, pl, pg, _ in data["profiles"][1:]:
        ax1.plot(pl / 1e3, z, "-o", ms=2, label=f"{t / 60:g} min")
        ax2.plot(pg / 1e3, z, "-o", ms=2, label=f"{t / 60:g} min")
    ax1.set_xlabel("liquid pressure [kPa]")
    ax2.set_xlabel("gas pressure [kPa]")
    for ax in (ax1, ax2):
        ax.set_ylabel("height [m]")
        ax.legend(fontsize=7)
    ax3.plot(data["time"] / 60, data["outflow"] / RHO_L * 1e3)
    ax3.set_xlabel("time [min]")
    ax3.set_ylabel("outflow [mm of water]")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
