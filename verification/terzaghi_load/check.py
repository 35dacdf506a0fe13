"""V9: Terzaghi's consolidation under a surface load, saturated at gas pressure 0, both cycles.

Reference: one-dimensional consolidation of a column of height H drained at its top (P_l = 0) and
impervious at its fixed base, under a total vertical stress q(t) applied at the top. A unit step
of q raises the pore pressure at once by Skempton's B = 1 / (1 + n M / K_l) (grains
incompressible, M the constrained modulus), which then dissipates as
    u_step(d, t) = B sum_m 4 / (pi (2m + 1)) sin(M_m d / H) exp(-M_m^2 T),  M_m = pi (2m + 1) / 2,
T = c_v t / H^2, c_v = (kappa / mu) / (1/M + n / K_l), d the depth. The case ramps q linearly over
t_r (case.yaml), so the reference is the superposition u(d, t) = int_0^min(t, t_r) q' u_step(d,
t - tau) dtau. A point initially at height z settles by the strain of
the soil below it, s(z, t) = int_0^z (q(t) - u(H - z', t)) / M dz'. Both integrals are taken in
closed form, mode by mode (400 modes).

Tolerances (issue 14, set before the runs): the undrained start, u at the base point at the end of
the ramp, within 2 % of the reference's; u/q0 at T = 0.05, 0.2, 0.5 and 1 with RMS over the
points <= 0.02; the settlement of the top control point within 2 % of the reference's at every
history time with T >= 0.1; each fluid's mass mismatch <= 1e-3. In both cycles.
"""
import math
from pathlib import Path

import numpy as np

from common import case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
_MAT = _CASE["materials"][0]
_LIQ = _CASE["fluids"]["liquid"]
_TOP = next(b for b in _CASE["boundaries"] if "traction" in b)
_RAMP = _TOP["traction"]["normal"]["ramp"]
H = float(_CASE["grid"]["size"][0])
N = float(_MAT["porosity"])
E, NU = float(_MAT["young_modulus"]), float(_MAT["poisson_ratio"])
M_OED = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))
K_L, MU = float(_LIQ["bulk_modulus"]), float(_LIQ["viscosity"])
KAPPA = float(_MAT["intrinsic_permeability"])
Q0, T_RAMP = float(_RAMP["to"]), float(_RAMP["end"])
B = 1.0 / (1.0 + N * M_OED / K_L)
C_V = (KAPPA / MU) / (1.0 / M_OED + N / K_L)
TOP_Z = float(next(c for c in _CASE["output"]["control_points"] if c["name"] == "top")["position"][0])
PROFILE_T = [0.05, 0.2, 0.5, 1.0]

RUNS = {"implicit": {}, "explicit": {"solver.cycle": "explicit"}}


def _series(t, terms=400):
    """The ramp's superposition in closed form: for each mode m, its coefficient times
    int_0^te (q0 / t_r) exp(-a_m (t - tau)) dtau = (q0 / t_r) (exp(-a_m (t - te)) - exp(-a_m t)) / a_m,
    a_m = M_m^2 c_v / H^2, te = min(t, t_r). Returns (M_m, weights) with u = sum w_m sin(M_m d / H)."""
    m = np.arange(terms)
    mm = math.pi * (2 * m + 1) / 2
    a = mm ** 2 * C_V / H ** 2
    te = min(max(t, 0.0), T_RAMP)
    time_part = (Q0 / T_RAMP) * (np.exp(-a * (t - te)) - np.exp(-a * t)) / a
    return mm, B * 4.0 / (math.pi * (2 * m + 1)) * time_part


def load(t):
    return Q0 * min(max(t, 0.0), T_RAMP) / T_RAMP


def u_ref(d, t):
    d = np.atleast_1d(np.asarray(d, dtype=float))
    mm, w = _series(t)
    return np.sin(np.outer(d / H, mm)) @ w


def settlement_ref(z, t):
    """int_0^z (q - u(H - z')) / M dz', with int_0^z sin(M_m (H - z') / H) dz' =
    (H / M_m) cos(M_m (H - z) / H) (cos M_m = 0)."""
    mm, w = _series(t)
    return float((load(t) * z - np.sum(w * H / mm * np.cos(mm * (H - z) / H))) / M_OED)


def evaluate(run_dirs):
    data, checks = {}, []
    for cycle, run_dir in run_dirs.items():
        profiles, rms_at = [], {}
        start_error = None
        for t, path in series(run_dir)[1:]:
            x, a = read_points(path)
            z0 = x[:, 0] - a["displacement"][:, 0]
            d = H - z0
            u = a["liquid_pressure"]
            ref = u_ref(d, t)
            if abs(t - T_RAMP) < 1e-9:
                base = int(np.argmin(z0))
                start_error = abs(u[base] - ref[base]) / ref[base]
            T = C_V * t / H ** 2
            nearest = min(PROFILE_T, key=lambda x: abs(x - T))
            if abs(nearest - T) < 0.01:
                rms_at[nearest] = float(np.sqrt(np.mean(((u - ref) / Q0) ** 2)))
            profiles.append((T, d, u))
        h = read_csv(run_dir / "control_points.csv")
        T_h = C_V * h["time"] / H ** 2
        s_num = -h["top_displacement_x"]
        late = T_h >= 0.1
        s_ref = np.array([settlement_ref(TOP_Z, t) for t in h["time"][late]])
        s_err = float(np.max(np.abs(s_num[late] - s_ref) / s_ref))
        c = read_csv(run_dir / "conservation.csv")
        data[cycle] = {"profiles": profiles, "T": T_h, "settlement": s_num, "rms": rms_at,
                       "start": start_error}
        checks.append((f"{cycle}: undrained start, |u - u_ref| / u_ref at the base at the ramp's "
                       f"end (u_ref = {u_ref([H - 0.0125], T_RAMP)[0] / Q0:.4f} q0)",
                       start_error if start_error is not None else float("inf"), 0.02))
        for T in PROFILE_T:
            checks.append((f"{cycle}: RMS (u - u_ref) / q0 at T = {T:g}",
                           rms_at.get(T, float("inf")), 0.02))
        checks += [
            (f"{cycle}: max |s - s_ref| / s_ref of the top point, T >= 0.1", s_err, 0.02),
            (f"{cycle}: max |liquid mismatch|", float(np.abs(c["liquid_mismatch"]).max()), 1e-3),
            (f"{cycle}: max |gas mismatch|", float(np.abs(c["gas_mismatch"]).max()), 1e-3),
        ]
    return data, checks


def notes(data):
    lines = [f"Skempton's B = {B:.4f}, c_v = {C_V:.4f} m^2/s; RMS of (u - u_ref)/q0 by T:", ""]
    for cycle, d in data.items():
        lines.append(f"- {cycle}: " + ", ".join(f"T = {T:g}: {v:.2e}" for T, v in sorted(
            d["rms"].items())) + f"; undrained start off by {d['start']:.2e}")
    return "\n".join(lines)


def plot(data, out_dir):
    png = out_dir / "terzaghi_load.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 5))
    d = np.linspace(0, H, 200)
    for cycle, mark in (("implicit", "o"), ("explicit", "s")):
        for T, dd, u in data[cycle]["profiles"]:
            ax1.plot(u / Q0, dd / H, mark, ms=3, mfc="none")
    for T, _, _ in data["implicit"]["profiles"]:
        ax1.plot(u_ref(d, T * H ** 2 / C_V) / Q0, d / H, "k-", lw=0.8)
    ax1.invert_yaxis()
    ax1.set_xlabel("pore pressure / q0")
    ax1.set_ylabel("depth / H")
    ax1.set_title("Reference (lines); implicit (o), explicit (s)")
    s_final = Q0 * TOP_Z / M_OED
    ts = np.linspace(0.0, H ** 2 / C_V, 120)
    ax2.plot(C_V * ts / H ** 2, [settlement_ref(TOP_Z, t) / s_final for t in ts], "k-",
             label="reference")
    for cycle in ("implicit", "explicit"):
        ax2.plot(data[cycle]["T"], data[cycle]["settlement"] / s_final, "--", label=cycle)
    ax2.set_xlabel("T = c_v t / H^2")
    ax2.set_ylabel("settlement of the top point / final")
    ax2.legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
