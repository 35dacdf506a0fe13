"""V1: one-dimensional infiltration into an unsaturated column (the paper's section 4).

Reference (Terzaghi-type series of the linearised problem, README.md): with C = kappa / (mu_l n a_s)
and T = C t / h^2, s / s0 = sum_m (2 / M) sin(M z) exp(-M^2 T), M = pi (2m + 1) / 2, z = depth / h.

Tolerances and expectations, set from the issue and the paper before the runs were looked at:
full form, 4 points per element, alpha = 0: RMS of (s - s_ref)/s0 <= 0.01 and max <= 0.03 at
every T >= 0.05; alpha = 0.75 has at least three times the error of alpha = 0.05; the simplified
form errs more than the full form at a_s = 1e-3 1/kPa, and more at 1e-3 than at 1e-4; the full
form's liquid-mass mismatch stays below 1e-3.

alpha = 0.05 (decided in issue 14, item 6): damping the fluids' driving force scales the flow by
1 - alpha (README.md, "Damping"; docs/balance_laws.md), so a damped run is the undamped one at
(1 - alpha) T. The issue's first tolerance, RMS <= 0.01 against the series at T, was set without
knowing that; it is replaced by the two checks measured since: alpha = 0.05 within max 0.03 of
the series at T, and within RMS 0.01 of the series at (1 - alpha) T. alpha = 0.75's checks stay.
"""
import json
from pathlib import Path

import numpy as np

from common import Column, infiltration_series, read_csv, read_points, series, suction_profiles

COLUMN = Column.from_case(Path(__file__).parent)  # case.yaml
H, N, KAPPA, MU, S0, K_L = COLUMN.h, COLUMN.n, COLUMN.kappa, COLUMN.mu, COLUMN.s0, COLUMN.k_l
T_LIST = [0.05, 0.1, 0.2, 0.5, 0.7, 1.0]
DEPTH_HISTORY = 0.49


def diffusivity(a_s):
    return COLUMN.diffusivity(a_s)


def run_overrides(a_s, **extra):
    times = [T * H ** 2 / diffusivity(a_s) for T in T_LIST]
    out = {"solver.end_time": times[-1], "output.times": times,
           "output.history_interval": times[-1] / 1000,
           "output.control_points": [{"name": "z049", "position": [H - DEPTH_HISTORY]}],
           "materials[0].retention.a_s": a_s}
    out.update(extra)
    return out


# case.yaml solves the mass balances at the nodes (pressure_update: nodal; README.md, "Points per
# element"); the two pointwise runs are the paper's own update, kept to show what that changes.
RUNS = {
    "mp1": run_overrides(1e-6, **{"bodies[0].points_per_cell": 1}),
    "mp4": run_overrides(1e-6),
    "mp1_pointwise": run_overrides(1e-6, pressure_update="pointwise",
                                   **{"bodies[0].points_per_cell": 1}),
    "mp4_pointwise": run_overrides(1e-6, pressure_update="pointwise"),
    "alpha005": run_overrides(1e-6, **{"solver.damping": 0.05}),
    "alpha075": run_overrides(1e-6, **{"solver.damping": 0.75}),
    "simplified_as1e-3": run_overrides(1e-6, mass_balance="simplified"),
    "full_as1e-4": run_overrides(1e-7),
    "simplified_as1e-4": run_overrides(1e-7, mass_balance="simplified"),
}
# The implicit cycle (docs/cycles.md) on every run that applies. Damping acts on its mechanics only, and
# the skeleton is rigid here, so the alpha runs would repeat implicit_mp4: they are left out.
IMPLICIT = {"mp1": "implicit_mp1", "mp4": "implicit_mp4",
            "simplified_as1e-3": "implicit_simplified_as1e-3",
            "full_as1e-4": "implicit_full_as1e-4", "simplified_as1e-4": "implicit_simplified_as1e-4"}
for _explicit, _implicit in IMPLICIT.items():
    RUNS[_implicit] = dict(RUNS[_explicit], **{"solver.cycle": "implicit"})
# implicit_mp4 with the iterative linear solver (GMRES with multigrid) instead of KLU: the same ODE
# to the same CVODE tolerances, so the same checks hold, and the two solutions differ by no more
# than a small multiple of CVODE's global error (below).
RUNS["implicit_mp4_iterative"] = dict(RUNS["implicit_mp4"],
                                      **{"solver.implicit": {"linear_solver": "iterative"}})
A_S = {name: (1e-7 if "1e-4" in name else 1e-6) for name in RUNS}
DAMPING = {"alpha005": 0.05, "alpha075": 0.75}

def profiles(run_dir, a_s):
    """[(T, depth, s/s0 numerical, s/s0 analytical)] at the output times after t = 0."""
    return [(T, d, s, r) for T, d, s, r, _ in suction_profiles(run_dir, COLUMN, diffusivity(a_s))]


def errors(prof, time_factor=1.0):
    """Per T: (T, max |e|, RMS e), against the series at time_factor * T."""
    out = []
    for T, depth, s, r in prof:
        if time_factor != 1.0:
            r = infiltration_series(depth / H, time_factor * T)
        out.append((T, float(np.max(np.abs(s - r))), float(np.sqrt(np.mean((s - r) ** 2)))))
    return out


def largest_reversal(prof):
    """Largest decrease of s/s0 from one point to the next deeper one, over all T. The reference
    increases monotonically with depth, so any decrease is a spurious oscillation."""
    return max(max(0.0, float(-np.min(np.diff(s)))) for _, _, s, _ in prof)


def compressible_factor(a_s):
    """Time factor of the series once the liquid's compressibility is in the storage:
    C = kappa / (mu n (a_s + S/K_l)), with S = 1 (the wetted region that carries the flow)."""
    return a_s / (a_s + 1.0 / K_L)


def evaluate(run_dirs):
    data = {}
    for name, d in run_dirs.items():
        prof = profiles(d, A_S[name])
        cons = read_csv(d / "conservation.csv")
        hist = read_csv(d / "control_points.csv")
        summary = json.loads((d / "run_summary.json").read_text())
        data[name] = {"profiles": prof, "errors": errors(prof), "wall_time": summary["wall_time_s"],
                      "rms_all": float(np.sqrt(np.mean([e[2] ** 2 for e in errors(prof)]))),
                      "mismatch": float(np.max(np.abs(cons["liquid_mismatch"]))),
                      "gas_mismatch": float(np.max(np.abs(cons["gas_mismatch"]))),
                      "gas_pressure_max": max(float(np.max(np.abs(read_points(f)[1]["gas_pressure"])))
                                              for _, f in series(d)),
                      "reversal": largest_reversal(prof), "history": hist}
        if name in DAMPING:
            data[name]["errors_shifted"] = errors(prof, 1.0 - DAMPING[name])
        if not name.startswith("simplified"):
            data[name]["errors_compressible"] = errors(prof, compressible_factor(A_S[name]))
    worst = lambda name, k, key="errors": max(e[k] for e in data[name][key])
    checks = []
    checks.append(("full, 4 MPs, alpha = 0: max over T of RMS error", worst("mp4", 2), 0.01))
    checks.append(("full, 4 MPs, alpha = 0: max over T of max error", worst("mp4", 1), 0.03))
    checks.append(("full, 4 MPs, alpha = 0.05: max over T of max error against the series at T",
                   worst("alpha005", 1), 0.03))
    for name in DAMPING:
        f = 1.0 - DAMPING[name]
        checks.append((f"{name} against the series at {f:g} T (damping scales the flow by "
                       f"1 - alpha): max over T of RMS error", worst(name, 2, "errors_shifted"),
                       0.01))
    checks += [
        ("3 x RMS(alpha = 0.05) / RMS(alpha = 0.75)  [alpha = 0.75 errs 3x more]",
         3 * data["alpha005"]["rms_all"] / data["alpha075"]["rms_all"], 1.0),
        ("RMS(full) / RMS(simplified) at a_s = 1e-3 1/kPa  [simplified errs more]",
         data["mp4"]["rms_all"] / data["simplified_as1e-3"]["rms_all"], 1.0),
        ("RMS(simplified, 1e-4) / RMS(simplified, 1e-3)  [more error at 1e-3]",
         data["simplified_as1e-4"]["rms_all"] / data["simplified_as1e-3"]["rms_all"], 1.0),
        ("full, 4 MPs: max relative liquid-mass mismatch", data["mp4"]["mismatch"], 1e-3),
    ]
    # The same assertions for the implicit cycle, where they apply (no alpha runs).
    checks += [
        ("implicit, full, 4 MPs: max over T of RMS error", worst("implicit_mp4", 2), 0.01),
        ("implicit, full, 4 MPs: max over T of max error", worst("implicit_mp4", 1), 0.03),
        ("implicit: RMS(full) / RMS(simplified) at a_s = 1e-3 1/kPa  [simplified errs more]",
         data["implicit_mp4"]["rms_all"] / data["implicit_simplified_as1e-3"]["rms_all"], 1.0),
        ("implicit: RMS(simplified, 1e-4) / RMS(simplified, 1e-3)  [more error at 1e-3]",
         data["implicit_simplified_as1e-4"]["rms_all"] /
         data["implicit_simplified_as1e-3"]["rms_all"], 1.0),
        ("implicit, full, 4 MPs: max relative liquid-mass mismatch",
         data["implicit_mp4"]["mismatch"], 1e-3),
        ("implicit, iterative solver: max over T of RMS error", worst("implicit_mp4_iterative", 2),
         0.01),
        ("implicit, iterative solver: max over T of max error", worst("implicit_mp4_iterative", 1),
         0.03),
        ("implicit, iterative solver: max relative liquid-mass mismatch",
         data["implicit_mp4_iterative"]["mismatch"], 1e-3),
        # Both runs hold CVODE's local error near rtol = 1e-6 per step; their difference is of the
        # order of the global error, bounded here by 100 rtol of s0.
        ("implicit: max |s/s0 (iterative) - s/s0 (direct)| over T and depth",
         max(float(np.max(np.abs(a[2] - b[2]))) for a, b in
             zip(data["implicit_mp4_iterative"]["profiles"], data["implicit_mp4"]["profiles"])),
         1e-4),
    ]
    return data, checks


def _table(data, key, title):
    lines = [title, "", "| run | " + " | ".join(f"T = {T}" for T in T_LIST) + " |",
             "|---" * (len(T_LIST) + 1) + "|"]
    for name, d in data.items():
        if key in d:
            lines.append(f"| {name} | " +
                         " | ".join(f"{mx:.4f} / {rms:.4f}" for _, mx, rms in d[key]) + " |")
    return lines


def _worst(d, key="errors"):
    return max(e[1] for e in d[key]), max(e[2] for e in d[key])


def observations(data):
    """The paper's observations (section 4, figures 2-6), run by run, with our numbers."""
    mx = {name: _worst(d) for name, d in data.items()}
    rms_t = lambda name: {T: rms for T, _, rms in data[name]["errors"]}
    out = []
    m4, m1 = data["mp4"], data["mp1"]
    out.append(
        f"- **mp4** (full, 4 MPs, alpha = 0). Paper: fits the analytical solution. Ours: max "
        f"{mx['mp4'][0]:.4f}, RMS at most {mx['mp4'][1]:.4f} of s0 over the six T; liquid-mass "
        f"mismatch {m4['mismatch']:.1e}. **Holds.** What is left is mostly the liquid's "
        f"compressibility, which the series ignores: against the series with n S/K_l added to the "
        f"storage the RMS is at most {_worst(m4, 'errors_compressible')[1]:.4f}.")
    out.append(
        f"- **mp4_pointwise** (the paper's pointwise update). Max "
        f"{mx['mp4_pointwise'][0]:.4f}, RMS at most {mx['mp4_pointwise'][1]:.4f}: with linear "
        f"shape functions every point of a cell gets the same increment, so the pressure is "
        f"constant per cell and points off the centre err by the slope times their offset. "
        f"The paper's 'fits perfectly' holds to the eye; solving the mass balances at the nodes "
        f"(pressure_update: nodal, the mp4 run) removes this error.")
    osc = {n: data[n]["reversal"] for n in ("mp1", "mp1_pointwise", "mp4", "mp4_pointwise")}
    out.append(
        f"- **mp1, mp1_pointwise** (1 MP per element). Paper: numerical oscillations. Ours: "
        f"none worth the name: the largest decrease of s/s0 from a point to the next deeper one "
        f"is {osc['mp1']:.1e} (nodal update) and {osc['mp1_pointwise']:.1e} (pointwise), against "
        f"{osc['mp4']:.1e} and {osc['mp4_pointwise']:.1e} with 4 MPs; errors max "
        f"{mx['mp1'][0]:.4f} / {mx['mp1_pointwise'][0]:.4f}. **Does not hold** for the suction "
        f"profiles. Why: the skeleton is rigid, so no point crosses a cell boundary (the usual "
        f"source of MPM oscillations), and one point at each cell centre makes the pointwise "
        f"scheme the cell-centred finite-volume scheme for diffusion, which is monotone at a "
        f"stable step. One artefact of 1 point per element does show, in the gas: with the "
        f"pointwise update, as the cells below the surface approach saturation (T -> 1) and their "
        f"gas storage vanishes, the gas pressure reaches "
        f"{data['mp1_pointwise']['gas_pressure_max'] / 1e3:.1f} kPa (mp4_pointwise: "
        f"{data['mp4_pointwise']['gas_pressure_max'] / 1e3:.1f} kPa) and the gas-mass mismatch "
        f"{data['mp1_pointwise']['gas_mismatch']:.3f} (mp4_pointwise: "
        f"{data['mp4_pointwise']['gas_mismatch']:.1e}); the nodal update keeps them at "
        f"{data['mp1']['gas_pressure_max'] / 1e3:.1f} kPa and {data['mp1']['gas_mismatch']:.1e}.")
    a05, a75 = data["alpha005"], data["alpha075"]
    sh05, sh75 = _worst(a05, "errors_shifted"), _worst(a75, "errors_shifted")
    out.append(
        f"- **alpha005**. Paper: fits the analytical solution. Ours: max {mx['alpha005'][0]:.4f}, "
        f"RMS up to {mx['alpha005'][1]:.4f} (largest at T = "
        f"{max(rms_t('alpha005'), key=rms_t('alpha005').get)}): **holds to the eye of a figure "
        f"(at most {mx['alpha005'][0]:.3f} of s0); issue 3's RMS <= 0.01 at T was replaced by the "
        f"check at (1 - alpha) T (issue 14)**. Why: "
        f"damping acts on the driving force, so the flux is (1 - alpha) times Darcy's and the run "
        f"is the undamped one at 0.95 T: against the series at 0.95 T the errors are max "
        f"{sh05[0]:.4f}, RMS {sh05[1]:.4f}, as small as alpha = 0's.")
    out.append(
        f"- **alpha075**. Paper: visibly slows infiltration (a gross error). Ours: RMS up to "
        f"{mx['alpha075'][1]:.3f}, {a75['rms_all'] / a05['rms_all']:.1f} times alpha = 0.05's "
        f"(over all T). **Holds**, and for the same reason: against the series at 0.25 T the "
        f"errors are max {sh75[0]:.4f}, RMS {sh75[1]:.4f}.")
    r3 = rms_t("simplified_as1e-3")
    top = sorted(r3, key=r3.get, reverse=True)[:2]
    out.append(
        f"- **simplified_as1e-3**. Paper: the simplified form deviates, most at T = 0.2 and 0.7. "
        f"Ours: RMS {', '.join(f'{r3[T]:.3f} (T = {T})' for T in T_LIST)}, against at most "
        f"{mx['mp4'][1]:.4f} for the full form; the two largest at T = {top[0]} and {top[1]}. "
        + ("**Holds.** " if set(top) == {0.2, 0.7} else
           f"**Holds in part:** it deviates at every T from 0.05 to 0.7, most at T = {top[0]} "
           f"and {top[1]} rather than 0.2 and 0.7 (the paper gives no numbers, only curves). ")
        + f"Its liquid-mass mismatch is "
        f"{data['simplified_as1e-3']['mismatch']:.2f}: dropping the advective term loses mass "
        f"where saturation changes steeply, which is why it lags.")
    r4s, r4f = rms_t("simplified_as1e-4"), rms_t("full_as1e-4")
    out.append(
        f"- **full_as1e-4, simplified_as1e-4**. Paper: the simplified form deviates less at "
        f"a_s = 1e-4 than at 1e-3. Ours: the simplified form's RMS is {max(r4s.values()):.3f} at "
        f"most (1e-3: {max(r3.values()):.3f}), and only {max(r4s[T] - r4f[T] for T in T_LIST):.3f} "
        f"above the full form's at the same a_s (1e-3: "
        f"{max(r3[T] - rms_t('mp4')[T] for T in T_LIST):.3f}). **Holds.** The full form's own error "
        f"at 1e-4 (RMS up to {max(r4f.values()):.3f}) is the liquid's compressibility: n S/K_l is "
        f"12 % of the storage n a_s at this a_s; with it in the series the RMS is at most "
        f"{_worst(data['full_as1e-4'], 'errors_compressible')[1]:.4f}.")
    return out


def notes(data):
    lines = _table(data, "errors", "Errors of s/s0 against the series, per run and T (max / RMS):")
    lines += ["", "| run | largest reversal of s/s0 with depth | max liquid-mass mismatch | "
              "max gas-mass mismatch | max abs gas pressure [kPa] |", "|---|---|---|---|---|"]
    for name, d in data.items():
        lines.append(f"| {name} | {d['reversal']:.2e} | {d['mismatch']:.2e} | "
                     f"{d['gas_mismatch']:.2e} | {d['gas_pressure_max'] / 1e3:.2f} |")
    lines += [""] + _table(data, "errors_shifted",
                           "Damped runs against the series at (1 - alpha) T (max / RMS):")
    lines += [""] + _table(data, "errors_compressible",
                           "Full-form runs against the series with the liquid's compressibility "
                           "in the storage, C = kappa / (mu n (a_s + 1/K_l)) (max / RMS):")
    lines += ["", "The two cycles side by side (worst over T of max / RMS error; wall time of the "
              "run, output included):", "",
              "| run | explicit max / RMS | implicit max / RMS | explicit wall [s] | "
              "implicit wall [s] | ratio |", "|---|---|---|---|---|---|"]
    for explicit, implicit in IMPLICIT.items():
        e, i = data[explicit], data[implicit]
        (emx, erms), (imx, irms) = _worst(e), _worst(i)
        lines.append(f"| {explicit} | {emx:.4f} / {erms:.4f} | {imx:.4f} / {irms:.4f} | "
                     f"{e['wall_time']:.2f} | {i['wall_time']:.3f} | "
                     f"{e['wall_time'] / i['wall_time']:.0f} |")
    lines += ["", "The alpha runs do not apply to the implicit cycle: its fluids have no inertia "
              "(Darcy form), damping acts on the mechanics only, and the skeleton is rigid here."]
    lines += ["", "The paper's observations, run by run (explicit cycle):", ""] + observations(data)
    return "\n".join(lines)


def plot(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    groups = {
        "infiltration_points_per_element.png": (["mp1", "mp4"], "1 vs 4 MPs per element (alpha = 0)"),
        "infiltration_pointwise_update.png": (["mp1_pointwise", "mp4_pointwise"],
                                              "the paper's pointwise update, 1 vs 4 MPs"),
        "infiltration_damping.png": (["mp4", "alpha005", "alpha075"], "local damping alpha"),
        "infiltration_mass_balance_as1e-3.png": (["mp4", "simplified_as1e-3"],
                                                 "full vs simplified, a_s = 1e-3 1/kPa"),
        "infiltration_mass_balance_as1e-4.png": (["full_as1e-4", "simplified_as1e-4"],
                                                 "full vs simplified, a_s = 1e-4 1/kPa"),
        "infiltration_implicit_points_per_element.png": (
            ["implicit_mp1", "implicit_mp4"], "implicit cycle: 1 vs 4 MPs per element"),
        "infiltration_implicit_mass_balance_as1e-3.png": (
            ["implicit_mp4", "implicit_simplified_as1e-3"],
            "implicit cycle: full vs simplified, a_s = 1e-3 1/kPa"),
        "infiltration_implicit_mass_balance_as1e-4.png": (
            ["implicit_full_as1e-4", "implicit_simplified_as1e-4"],
            "implicit cycle: full vs simplified, a_s = 1e-4 1/kPa"),
    }
    styles = ["o", "s", "^"]
    colors = plt.cm.viridis(np.linspace(0, 0.9, len(T_LIST)))
    names = []
    for png, (runs, title) in groups.items():
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5.5))
        z = np.linspace(0, H, 201)
        for c, T in zip(colors, T_LIST):
            ax1.plot(infiltration_series(z / H, T), z, "-", color=c, lw=1.5, label=f"T = {T}")
        for k, run in enumerate(runs):
            for c, (T, depth, s, _) in zip(colors, data[run]["profiles"]):
                ax1.plot(s, depth, styles[k], ms=2.5, color=c, mfc="none" if k else c,
                         label=run if T == T_LIST[0] else None)
            h = data[run]["history"]
            a_s = A_S[run]
            T_h = diffusivity(a_s) * h["time"] / H ** 2
            ax2.plot(T_h, h["z049_suction"] / S0, "--", label=run)
        T_fine = np.linspace(1e-4, 1.0, 400)
        ax2.plot(T_fine, [infiltration_series(np.array([DEPTH_HISTORY / H]), T)[0] for T in T_fine], "k-",
                 lw=2, label="analytical")
        ax1.invert_yaxis()
        ax1.set_xlabel("s / s0")
        ax1.set_ylabel("depth [m]")
        ax1.set_title(f"Suction profiles: {title}")
        ax1.legend(fontsize=7, loc="lower left")
        ax2.set_xlabel("T = C t / h^2")
        ax2.set_ylabel(f"s / s0 at depth {DEPTH_HISTORY} m")
        ax2.set_title("History of the point nearest z = 0.49 m")
        ax2.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(out_dir / png, dpi=100)
        plt.close(fig)
        names.append(png)
    return names
