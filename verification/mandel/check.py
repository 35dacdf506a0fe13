"""V10: Mandel's problem, saturated at gas pressure 0, both cycles.

Reference: Abousleiman, Cheng, Cui, Detournay & Roegiers (1996), "Mandel's problem revisited",
Geotechnique 46(2), 187-195, eqs. for the pore pressure and the vertical displacement of a slab
-a <= x <= a between rigid frictionless plates loaded by a force 2F per unit length (here
F = q0 a, q0 the plate's mean pressure), drained at x = +-a, in plane strain, for a step load:
    p(x, t) = (2 F B (1 + nu_u) / (3 a)) sum_n sin(al_n) / (al_n - sin(al_n) cos(al_n))
              (cos(al_n x / a) - cos(al_n)) exp(-al_n^2 c t / a^2),
    u_y(y, t) = (-F (1 - nu) / (2 G a)
                 + F (1 - nu_u) / (G a) sum_n sin(al_n) cos(al_n) / (al_n - sin(al_n) cos(al_n))
                   exp(-al_n^2 c t / a^2)) y,
with tan(al_n) = (1 - nu) / (nu_u - nu) al_n and c = 2 kappa B^2 G (1 - nu) (1 + nu_u)^2 /
(9 (1 - nu_u) (nu_u - nu)), kappa = k / mu. Grains incompressible (Biot alpha = 1), the liquid's
bulk modulus K_l: Biot's modulus K_l / n, K_u = K + K_l / n, Skempton's B = K_l / (K_l + n K),
nu_u = (3 K_u - 2 G) / (2 (3 K_u + G)). The case raises the load smoothly over t_r (case.yaml's
table, piecewise linear); the reference
is the superposition over the load's table, mode by mode in closed form (2000 modes). The series is
checked against the undrained start (sum = 1/2 in p at t = 0, the undrained strain in u_y) and c
against the one-dimensional kappa M (K + 4G/3) / (K_u + 4G/3), before any run is compared.

Tolerances (issue 14, set before the runs): the centre's pore pressure over the whole history
with RMS <= 0.03 p0 (p0 the undrained start B (1 + nu_u) q0 / 3); the Mandel-Cryer rise: the
computed maximum above the value at the ramp's end, and the peak within 0.03 p0 of the
reference's; the plate's settlement within 2 % of the reference for c t / a^2 >= 0.1; each
fluid's mass mismatch <= 1e-3.
"""
import json
import math
import os
from pathlib import Path

import numpy as np

from common import case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
_MAT = _CASE["materials"][0]
_LIQ = _CASE["fluids"]["liquid"]
_PLATE = next(b for b in _CASE["boundaries"] if "traction" in b)
_LOAD = np.array(_PLATE["traction"]["normal"]["table"], dtype=float)  # [[t, q], ...]
_BOX = _CASE["bodies"][0]["box"]
A = float(_BOX["max"][0]) - float(_BOX["min"][0])
E, NU = float(_MAT["young_modulus"]), float(_MAT["poisson_ratio"])
N = float(_MAT["porosity"])
K_L, MU = float(_LIQ["bulk_modulus"]), float(_LIQ["viscosity"])
KAPPA = float(_MAT["intrinsic_permeability"]) / MU
Q0, T_RAMP = float(_LOAD[-1, 1]), float(_LOAD[-1, 0])
G = E / (2 * (1 + NU))
K = E / (3 * (1 - 2 * NU))
K_U = K + K_L / N
B = K_L / (K_L + N * K)
NU_U = (3 * K_U - 2 * G) / (2 * (3 * K_U + G))
C = 2 * KAPPA * B ** 2 * G * (1 - NU) * (1 + NU_U) ** 2 / (9 * (1 - NU_U) * (NU_U - NU))
P0 = B * (1 + NU_U) * Q0 / 3
_CP = {c["name"]: c["position"] for c in _CASE["output"]["control_points"]}
CENTRE_X = float(_CP["centre"][0])  # for the plot; evaluate() takes each run's own points
PLATE_Y = float(_CP["plate"][1])

# In CI both cycles run on a grid of 10 x 5 cells (12 s and 3 s on one core); MANDEL_SLOW=1
# (label "slow") runs the case's 20 x 10 (the main cycle about 3 min: its coupling interval is
# bounded here by the permeable soil's undrained stiffness, one or two mechanics steps each).
_COARSE = {"grid.cells": [10, 5]}
RUNS = {"implicit": dict(_COARSE), "explicit": {"solver.cycle": "explicit", **_COARSE}}
if os.environ.get("MANDEL_SLOW") == "1":
    RUNS = {"implicit": {}, "explicit": {"solver.cycle": "explicit"}}


def _roots(terms=2000):
    """al_n in ((n - 1) pi, (n - 1) pi + pi / 2) with tan(al) = k al, k = (1 - nu)/(nu_u - nu) > 1,
    by bisection."""
    k = (1 - NU) / (NU_U - NU)
    roots = []
    for n in range(terms):
        lo, hi = n * math.pi + 1e-12, n * math.pi + math.pi / 2 - 1e-12
        f = lambda x: math.sin(x) - k * x * math.cos(x)  # same roots, no pole
        flo = f(lo)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if (f(mid) > 0) == (flo > 0):
                lo, flo = mid, f(mid)
            else:
                hi = mid
        roots.append(0.5 * (lo + hi))
    return np.array(roots)


AL = _roots()
_DEN = AL - np.sin(AL) * np.cos(AL)


def _time_part(t):
    """The load history q(tau) / q0 (case.yaml's table: piecewise linear from q(0) = 0, constant
    after its last point) superposed on each mode's decay exp(-l (t - tau)), l = al^2 c / a^2:
    segment k of slope s_k adds s_k (exp(-l (t - te)) - exp(-l (t - t_k))) / l, te =
    min(t, t_k+1), for t > t_k."""
    lam = AL ** 2 * C / A ** 2
    out = np.zeros_like(AL)
    for (t0, q0), (t1, q1) in zip(_LOAD[:-1], _LOAD[1:]):
        if t <= t0:
            break
        te = min(t, t1)
        out += (q1 - q0) / (t1 - t0) / Q0 * (np.exp(-lam * (t - te)) - np.exp(-lam * (t - t0))) / lam
    return out


def load(t):
    return float(np.interp(t, _LOAD[:, 0], _LOAD[:, 1]))


def p_ref(x, t):
    w = np.sin(AL) / _DEN * _time_part(t)
    return 2 * Q0 * B * (1 + NU_U) / 3 * float(np.sum(w * (np.cos(AL * x / A) - np.cos(AL))))


def uy_ref(y, t):
    series = float(np.sum(np.sin(AL) * np.cos(AL) / _DEN * _time_part(t)))
    return (-load(t) * (1 - NU) / (2 * G) + Q0 * (1 - NU_U) / G * series) * y


def _self_check():
    """The series at t = 0 gives the undrained state, and c the one-dimensional coefficient."""
    s_p = float(np.sum(np.sin(AL) / _DEN * (1 - np.cos(AL))))  # at x = 0
    s_u = float(np.sum(np.sin(AL) * np.cos(AL) / _DEN))
    c_1d = KAPPA * (K_L / N) * (K + 4 * G / 3) / (K_U + 4 * G / 3)
    for what, got, want in (("p series at x = 0", s_p, 0.5),
                            ("u series", s_u, (NU_U - NU) / (2 * (1 - NU_U))),
                            ("c", C, c_1d)):
        if abs(got - want) > 1e-3 * abs(want):
            raise AssertionError(f"Mandel reference: {what} = {got}, expected {want}")


_self_check()


def evaluate(run_dirs):
    data, checks = {}, []
    t_peak = np.linspace(T_RAMP, 0.3 * A ** 2 / C, 400)
    for cycle, run_dir in run_dirs.items():
        # The control points' material points at t = 0 (a run may use another grid).
        ids = json.loads((run_dir / "run_summary.json").read_text())["control_point_mp_ids"]
        x0, _ = read_points(series(run_dir)[0][1])
        centre_x, plate_y = float(x0[ids["centre"], 0]), float(x0[ids["plate"], 1])
        h = read_csv(run_dir / "control_points.csv")
        t = h["time"]
        p = h["centre_liquid_pressure"]
        ref = np.array([p_ref(centre_x, s) for s in t])
        rms = float(np.sqrt(np.mean(((p - ref) / P0) ** 2)))
        after = t >= T_RAMP - 1e-12
        p_peak_ref = max(p_ref(centre_x, s) for s in t_peak)
        p_end_ramp = float(p[after][0])
        rise = float(p[after].max() - p_end_ramp) / P0
        peak_err = abs(float(p[after].max()) - p_peak_ref) / P0
        tstar = C * t / A ** 2
        late = tstar >= 0.1
        u = -h["plate_displacement_y"]
        u_ref = np.array([-uy_ref(plate_y, s) for s in t])
        s_err = float(np.max(np.abs(u[late] - u_ref[late]) / u_ref[late]))
        c = read_csv(run_dir / "conservation.csv")
        data[cycle] = {"tstar": tstar, "p": p, "u": u * PLATE_Y / plate_y, "rms": rms,
                       "rise": rise, "peak_err": peak_err}
        checks += [
            (f"{cycle}: RMS (p - p_ref) / p0 at the centre over the history", rms, 0.03),
            (f"{cycle}: Mandel-Cryer rise, -(max p - p(t_r)) / p0 (negative: a rise)", -rise, 0.0),
            (f"{cycle}: |max p - max p_ref| / p0 (reference peak {p_peak_ref / P0:.4f} p0)",
             peak_err, 0.03),
            (f"{cycle}: max |u - u_ref| / u_ref of the plate, c t / a^2 >= 0.1", s_err, 0.02),
            (f"{cycle}: max |liquid mismatch|", float(np.abs(c["liquid_mismatch"]).max()), 1e-3),
            (f"{cycle}: max |gas mismatch|", float(np.abs(c["gas_mismatch"]).max()), 1e-3),
        ]
    return data, checks


def notes(data):
    lines = [f"B = {B:.4f}, nu_u = {NU_U:.4f}, c = {C:.4f} m^2/s, p0 = {P0:.1f} Pa; the "
             f"reference's peak at the centre is {max(p_ref(CENTRE_X, s) for s in np.linspace(T_RAMP, 0.3 * A ** 2 / C, 400)) / P0:.4f} p0.", ""]
    for cycle, d in data.items():
        lines.append(f"- {cycle}: RMS {d['rms']:.2e} p0, rise {d['rise']:.3f} p0, peak off by "
                     f"{d['peak_err']:.2e} p0")
    return "\n".join(lines)


def plot(data, out_dir):
    png = out_dir / "mandel.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4.5))
    ts = np.linspace(0.0, 1.0 * A ** 2 / C, 300)
    ax1.plot(C * ts / A ** 2, [p_ref(CENTRE_X, s) / P0 for s in ts], "k-", label="reference")
    ax2.plot(C * ts / A ** 2, [-uy_ref(PLATE_Y, s) * 1e3 for s in ts], "k-", label="reference")
    for cycle, style in (("implicit", "--"), ("explicit", ":")):
        if cycle in data:
            ax1.plot(data[cycle]["tstar"], data[cycle]["p"] / P0, style, label=cycle)
            ax2.plot(data[cycle]["tstar"], data[cycle]["u"] * 1e3, style, label=cycle)  # at y
    ax1.set_xlabel("c t / a^2")
    ax1.set_ylabel("pore pressure at the centre / p0")
    ax1.set_title("Mandel-Cryer: the centre's pressure rises first")
    ax1.legend()
    ax2.set_xlabel("c t / a^2")
    ax2.set_ylabel("settlement of the plate point [mm]")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
