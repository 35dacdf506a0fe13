"""V3a: elastic column under self-weight, damped to rest.

Reference (exact for a laterally confined linear elastic column at rest): the vertical stress of a
point is the weight of the material above it, sigma_yy = -rho g (H - Y), with Y its initial height
(the mass above a material point does not change as the column compresses), and the lateral stress
is sigma_xx = sigma_zz = nu / (1 - nu) sigma_yy.

Tolerances, set from what the method can do before the runs were looked at:
- With linear shape functions the strain is uniform in a cell, so both points of a cell carry the
  stress of the cell's mid-depth: each point is off by rho g h / 4. A point's error may be up to
  rho g h / 2 (twice that): max |error| / (rho g H) <= h / (2 H).
- The mean of a cell row's points has no such error (the field is linear): its error is what is
  left of the dynamics and of the damping, 0.5 % of rho g H.
- The lateral ratio sigma_xx / sigma_yy below the top two cells: within 0.01 of nu / (1 - nu).
- At rest: final kinetic energy below 1e-6 of the largest kinetic energy of the run.
"""
import numpy as np

from pathlib import Path

from common import body_height, case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
RHO = float(_CASE["materials"][0]["density"])
G = abs(float(_CASE["gravity"][1]))
H = body_height(_CASE)
NU = float(_CASE["materials"][0]["poisson_ratio"])
CELL = float(_CASE["grid"]["size"][1]) / int(_CASE["grid"]["cells"][1])


def evaluate(run_dirs):
    run_dir = run_dirs["run"]
    t, last = series(run_dir)[-1]
    x, a = read_points(last)
    y0 = x[:, 1] - a["displacement"][:, 1]
    s = a["net_stress"]
    scale = RHO * G * H
    ref_yy = -RHO * G * (H - y0)
    err = (s[:, 1] - ref_yy) / scale
    rows = np.floor(y0 / CELL).astype(int)
    row_err = [abs(np.mean(s[rows == r, 1]) - np.mean(ref_yy[rows == r])) / scale
               for r in np.unique(rows)]
    deep = (H - y0) > 2 * CELL
    k0 = NU / (1 - NU)
    ratio_err = np.abs(s[deep, 0] / s[deep, 1] - k0)
    g = read_csv(run_dir / "globals.csv")
    ek_ratio = g["kinetic_energy"][-1] / g["kinetic_energy"].max()
    checks = [
        ("max point error of sigma_yy / (rho g H)", float(np.abs(err).max()), CELL / (2 * H)),
        ("max cell-row mean error of sigma_yy / (rho g H)", float(max(row_err)), 0.005),
        ("max |sigma_xx/sigma_yy - nu/(1-nu)| below 2 cells", float(ratio_err.max()), 0.01),
        ("final / peak kinetic energy", float(ek_ratio), 1e-6),
    ]
    return {"time": t, "depth": H - y0, "s": s, "ref_yy": ref_yy, "globals": g}, checks


def plot(data, out_dir):
    png = out_dir / "column_selfweight.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 5))
    d = data["depth"]
    order = np.argsort(d)
    ax1.plot(-data["ref_yy"][order] / 1e3, d[order], "k-", label=r"$\rho g (H-Y)$")
    ax1.plot(-NU / (1 - NU) * data["ref_yy"][order] / 1e3, d[order], "k--",
             label=r"$\nu/(1-\nu)\,\rho g (H-Y)$")
    ax1.plot(-data["s"][:, 1] / 1e3, d, "o", ms=3, label=r"MPM $-\sigma_{yy}$")
    ax1.plot(-data["s"][:, 0] / 1e3, d, "s", ms=3, mfc="none", label=r"MPM $-\sigma_{xx}$")
    ax1.invert_yaxis()
    ax1.set_xlabel("compressive stress [kPa]")
    ax1.set_ylabel("depth below the top [m]")
    ax1.set_title(f"Stresses at t = {data['time']:.2f} s")
    ax1.legend()
    g = data["globals"]
    ax2.semilogy(g["time"][1:], g["kinetic_energy"][1:])
    ax2.set_xlabel("time [s]")
    ax2.set_ylabel("kinetic energy [J/m]")
    ax2.set_title("Damped to rest (alpha = 0.3)")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
