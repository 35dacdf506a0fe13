"""V8: Liakopoulos's drainage test against independent Richards solutions and OpenGeoSys.

References (README.md, reference/SOURCES.md). No experimental data: Liakopoulos's measurements
are published only as figures, and none was digitised.
- (a) reference_solver.py's method-of-lines solution of Richards' equation on a rigid skeleton
  (gas at atmospheric pressure, the program's liquid density law, the closed-form curves of
  make_curves.py; 400 cells, BDF at rtol 1e-8, converged to 5e-6 of |P_top|), for the case's
  K_l = 2 GPa and for the explicit run's K_l = 20 MPa: profiles at 5, 10, 20, 30, 60, 120 min
  and the cumulative outflow.
- (b) the same solver with OpenGeoSys's RICHARDS_MECHANICS model (Bishop chi = S, oedometric
  skeleton), checked against OGS's committed RM results at 300 to 7200 s: this validates the
  solver and its reading of the problem, independently of our program.
- OGS's TH2M results (two-phase, deformable, Bishop) beside our deformable run: report only,
  the models differ (our skeleton follows net stress; OGS starts at 100 Pa of capillary pressure
  and holds the base at -100 Pa).

Tolerances, fixed before any comparison (issue 13): for the main cycle with a rigid skeleton
against (a) at K_l = 2 GPa, and the explicit cycle (rigid, undamped, K_l = 20 MPa; the `slow`
run) against (a) at 20 MPa: at each of the six times, RMS over the points of P_l - P_ref(z)
<= 0.01 |P_ref(top)| and max <= 0.03 |P_ref(top)| (as V1 and V7 ask of a diffusion on this
mesh), cumulative outflow within 2 % of the reference; solver (b) against OGS RM: RMS over OGS's
nodes <= 0.02 |P_OGS(top)| at each stored time; each fluid's mass balance of every run within
1e-3. The deformable run also keeps the checks that need no reference: the drained base at its
pressure (|P_l| of the lowest points below rho_l g h) and the outflow never decreasing.

The explicit runs (about 6 min each on one core) are added to RUNS only with
LIAKOPOULOS_SLOW=1 in the environment (README.md), with the deformable run. The checked one makes Richards' assumption
explicit, k_rg = 1 (the gas moves freely and stays atmospheric); the run with the measured k_rg,
floored at 1e-4, is reported: the explicit cycle treats the gas of a desaturating node as an
unknown, so that run is a two-phase problem, not Richards', and (a) is not its reference. This
assignment was decided after the first explicit runs (README.md gives both); the tolerances were
not changed.
"""
import os
from pathlib import Path

import numpy as np

from common import case_doc, read_csv, read_points, series

HERE = Path(__file__).parent
REF = HERE / "reference"
_CASE = case_doc(HERE)
H = float(_CASE["grid"]["size"][0])
CELL = H / int(_CASE["grid"]["cells"][0])
RHO_L = float(_CASE["fluids"]["liquid"]["density"])
G = abs(float(_CASE["gravity"][0]))
TIMES = [300.0, 600.0, 1200.0, 1800.0, 3600.0, 7200.0]  # the reference's profiles
OGS_RM_TIMES = [300, 600, 1200, 2400, 4800, 7200]
OGS_TH2M_TIMES = [300, 4800, 7200]
K_EXPLICIT = 2.0e7

RUNS = {"rigid": {"skeleton": "rigid"}}
if os.environ.get("LIAKOPOULOS_SLOW") == "1":
    # The deformable main cycle feels the nearly saturated column's undrained stiffness (its
    # two-way coupling, docs/balance_laws.md): with K_l = 2 GPa its explicit step is ~1e-5 s and
    # the run hours long, so it takes the explicit runs' liquid, K_l = 20 MPa (report only).
    RUNS["deformable"] = {"fluids.liquid.bulk_modulus": K_EXPLICIT}
    # Damping would slow the drag-dominated flow by 1 - alpha (docs/balance_laws.md), and the
    # implicit cycle's settings are refused with the explicit cycle, so `solver` is replaced.
    RUNS["explicit"] = {"skeleton": "rigid", "fluids.liquid.bulk_modulus": K_EXPLICIT,
                        "solver": {"end_time": _CASE["solver"]["end_time"], "damping": 0,
                                   "cycle": "explicit"}}
    # Checked against (a): the same run with k_rg = 1, so that air enters freely and the gas stays
    # atmospheric, as Richards assumes. The run with the measured k_rg is reported (docstring).
    RUNS["explicit_krg1"] = dict(RUNS["explicit"], **{
        "materials[0].gas_relative_permeability": {"model": "constant"}})
REFERENCE = {"rigid": "richards_rigid_K2e9", "explicit_krg1": "richards_rigid_K2e7"}
REPORT_ONLY = {"explicit": "richards_rigid_K2e7"}
TOL_RMS, TOL_MAX, TOL_OUTFLOW, TOL_OGS, TOL_MASS = 0.01, 0.03, 0.02, 0.02, 1e-3


def _csv(name):
    return read_csv(REF / f"{name}.csv")


def _key(t):
    return f"{t:04.0f}s"


def frames(run_dir):
    """[(t, z0, P_l, P_g, S_l)] of the run's output after t = 0, points by initial height."""
    out = []
    for t, path in series(run_dir)[1:]:
        x, a = read_points(path)
        z0 = x[:, 0] - a["displacement"][:, 0]
        o = np.argsort(z0)
        out.append((t, z0[o], a["liquid_pressure"][o], a["gas_pressure"][o],
                    a["degree_of_saturation"][o]))
    return out


def at_time(frame_list, t):
    for f in frame_list:
        if abs(f[0] - t) < 1e-6 * max(t, 1.0):
            return f
    raise RuntimeError(f"no output at t = {t:g} s")


def frame_outflow(run_dir, t):
    """Initial liquid mass minus the points' liquid mass sum n S rho V at the output t [kg/m^2]."""
    doc = case_doc(run_dir / "effective_case.yaml")
    liq = doc["fluids"]["liquid"]
    mass = []
    for tt, path in (series(run_dir)[0], [f for f in series(run_dir) if abs(f[0] - t) < 1e-6][0]):
        _, a = read_points(path)
        rho = float(liq["density"]) * np.exp(a["liquid_pressure"] / float(liq["bulk_modulus"]))
        mass.append(float(np.sum(a["porosity"] * a["degree_of_saturation"] * rho * a["volume"])))
    return mass[0] - mass[1]


def outflow_at(hist, t, run_dir=None):
    """Linear in time between history rows (the explicit cycle's rows fall a step after each
    multiple of the interval: 60.00004 s, ...); past the last row (the explicit cycle writes none
    at the end time), from the points' liquid mass at the output t."""
    if hist["time"][-1] + 1.0 < t and run_dir is not None:
        return frame_outflow(run_dir, t)
    if not hist["time"][0] <= t <= hist["time"][-1] + 1.0:
        raise RuntimeError(f"no history at t = {t:g} s")
    return float(np.interp(t, hist["time"], hist["outflow"]))


def compare_richards(run_dir, ref_name):
    """Per reference time: (t, RMS, max of |P_l - P_ref| / |P_ref(top)|, outflow error)."""
    prof, flow = _csv(ref_name), _csv(f"{ref_name}_outflow")
    c = read_csv(run_dir / "conservation.csv")
    hist = {"time": c["time"], "outflow": -c["liquid_inflow"]}
    ref_hist = {"time": flow["time_s"], "outflow": flow["outflow_kg_per_m2"]}
    fl, rows = frames(run_dir), []
    for t in TIMES:
        _, z, p, _, _ = at_time(fl, t)
        p_ref = prof[f"p_l_{_key(t)}_Pa"]
        e = (p - np.interp(z, prof["height_m"], p_ref)) / abs(p_ref[-1])
        q, q_ref = outflow_at(hist, t, run_dir), outflow_at(ref_hist, t)
        rows.append((t, float(np.sqrt(np.mean(e ** 2))), float(np.abs(e).max()),
                     float((q - q_ref) / q_ref)))
    return rows, fl, hist, c


def solver_vs_ogs_rm():
    """(t, RMS / |P_OGS(top)|, max / |P_OGS(top)|) of solver (b) at OGS's nodes."""
    b, rows = _csv("richards_mechanics"), []
    for t in OGS_RM_TIMES:
        o = _csv(f"ogs_richards_mechanics_t{t:04d}s")
        p_o = o["liquid_pressure_gauge_Pa"]
        e = (np.interp(o["height_m"], b["height_m"], b[f"p_l_{_key(t)}_Pa"]) - p_o) / abs(p_o[-1])
        rows.append((t, float(np.sqrt(np.mean(e ** 2))), float(np.abs(e).max())))
    return rows


def deformable_vs_ogs(fl):
    """Report only: RMS of our deformable run's P_l (and P_g) minus OGS's at OGS's times that we
    output, over our points (OGS interpolated), relative to |P_l,OGS(top)|."""
    rows = []
    for model, times, col in (("TH2M", OGS_TH2M_TIMES, "ogs_th2m_t{:04d}s"),
                              ("RM", OGS_RM_TIMES, "ogs_richards_mechanics_t{:04d}s")):
        for t in times:
            try:
                _, z, pl, pg, _ = at_time(fl, t)
            except RuntimeError:
                continue
            o = _csv(col.format(t))
            top = abs(o["liquid_pressure_gauge_Pa"][-1])
            el = pl - np.interp(z, o["height_m"], o["liquid_pressure_gauge_Pa"])
            eg = pg - (np.interp(z, o["height_m"], o["gas_pressure_gauge_Pa"])
                       if "gas_pressure_gauge_Pa" in o else 0.0)
            rows.append((model, t, float(np.sqrt(np.mean(el ** 2)) / top),
                         float(np.sqrt(np.mean(eg ** 2)) / top)))
    return rows


def evaluate(run_dirs):
    data, checks = {"runs": {}}, []
    for name, run_dir in run_dirs.items():
        if name in REPORT_ONLY:
            rows, fl, hist, c = compare_richards(run_dir, REPORT_ONLY[name])
            data["runs"][name] = {"rows": rows, "frames": fl, "hist": hist}
        elif name in REFERENCE:
            rows, fl, hist, c = compare_richards(run_dir, REFERENCE[name])
            data["runs"][name] = {"rows": rows, "frames": fl, "hist": hist}
            worst_rms = max(rows, key=lambda r: r[1])
            worst_max = max(rows, key=lambda r: r[2])
            worst_q = max(rows, key=lambda r: abs(r[3]))
            checks += [
                (f"{name}: max over the 6 times of RMS (P_l - P_ref) / |P_ref(top)| "
                 f"(worst {worst_rms[0] / 60:g} min)", worst_rms[1], TOL_RMS),
                (f"{name}: max over the 6 times of max |P_l - P_ref| / |P_ref(top)| "
                 f"(worst {worst_max[0] / 60:g} min)", worst_max[2], TOL_MAX),
                (f"{name}: max over the 6 times of |outflow - ref| / ref "
                 f"(worst {worst_q[0] / 60:g} min)", abs(worst_q[3]), TOL_OUTFLOW),
            ]
        else:  # deformable, with gas: no reference of the same model
            c = read_csv(run_dir / "conservation.csv")
            fl = frames(run_dir)
            hist = {"time": c["time"], "outflow": -c["liquid_inflow"]}
            base_p = max(float(np.abs(f[2][f[1] < CELL / 2]).max()) for f in fl)
            data["runs"][name] = {"frames": fl, "hist": hist, "ogs": deformable_vs_ogs(fl)}
            checks += [
                (f"{name}: max |P_l| at the drained base / (rho_l g h)",
                 base_p / (RHO_L * G * CELL), 1.0),
                (f"{name}: largest decrease of the outflow [kg/m^2]",
                 float(max(0.0, -np.diff(hist["outflow"]).min())), 1e-9),
            ]
        checks += [
            (f"{name}: max |liquid mismatch|", float(np.abs(c["liquid_mismatch"]).max()), TOL_MASS),
            (f"{name}: max |gas mismatch|", float(np.abs(c["gas_mismatch"]).max()), TOL_MASS),
        ]
    for d in data["runs"].values():
        d["pg_min"] = min(float(f[3].min()) for f in d["frames"])
    rm = solver_vs_ogs_rm()
    data["solver_vs_ogs"] = rm
    worst = max(rm, key=lambda r: r[1])
    checks.append((f"reference solver (b) vs OGS RICHARDS_MECHANICS: max over {len(rm)} times of "
                   f"RMS / |P_OGS(top)| (worst {worst[0]} s)", worst[1], TOL_OGS))
    return data, checks


def notes(data):
    lines = ["Per time (RMS and max of (P_l - P_ref) / |P_ref(top)| over the points; outflow "
             "error against the reference's; explicit_krg1 is reported, not checked):", "",
             "| run | time [min] | RMS | max | outflow error |", "|---|---|---|---|---|"]
    for name, d in data["runs"].items():
        for t, rms, mx, dq in d.get("rows", []):
            lines.append(f"| {name} | {t / 60:g} | {rms:.2e} | {mx:.2e} | {100 * dq:+.3f} % |")
    lines += ["", "Lowest gas pressure over the points and outputs (Richards' equation, the "
              "references (a) and (b), holds it at 0): " + ", ".join(
                  f"{name} {d['pg_min']:.0f} Pa" for name, d in data["runs"].items()) + ". The "
              "main cycle with a rigid skeleton holds the gas of every node that starts free of "
              "gas for the whole run (docs/balance_laws.md); the explicit cycle makes the gas an "
              "unknown again once a node holds more than 1e-4 of gas, and air then enters the "
              "column only through k_rg's floor of 1e-4, so its run is not Richards' problem "
              "(README.md)."]
    lines += ["", "Reference solver (b) against OGS RICHARDS_MECHANICS (at OGS's 81 nodes, "
              "relative to |P_OGS(top)|):", "", "| time [s] | RMS | max |", "|---|---|---|"]
    lines += [f"| {t} | {rms:.2e} | {mx:.2e} |" for t, rms, mx in data["solver_vs_ogs"]]
    if "deformable" in data["runs"]:
        d = data["runs"]["deformable"]
        lines += ["", "Report only: our deformable run (gas phase, skeleton on net stress) minus "
                  "OGS (TH2M: two-phase; RM: Richards with Bishop's stress), RMS over our points "
                  "relative to |P_l,OGS(top)|; OGS's TH2M starts at -100 Pa and holds its base at "
                  "-100 Pa:", "", "| OGS model | time [s] | RMS of P_l | RMS of P_g (RM: against 0) |",
                  "|---|---|---|---|"]
        lines += [f"| {m} | {t} | {a:.3f} | {b:.3f} |" for m, t, a, b in d["ogs"]]
        q = d["hist"]["outflow"][-1]
        lines += ["", f"Deformable run: outflow {q:.3f} kg/m^2 at {d['hist']['time'][-1]:g} s "
                  f"(rigid reference (a): {_csv(REFERENCE['rigid'] + '_outflow')['outflow_kg_per_m2'][-1]:.3f}; "
                  f"solver (b), Bishop skeleton: "
                  f"{_csv('richards_mechanics_outflow')['outflow_kg_per_m2'][-1]:.3f})."]
    return "\n".join(lines)


def plot(data, out_dir):
    png = out_dir / "liakopoulos.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(13, 10))
    ax1, ax2, ax3, ax4 = axes.ravel()
    colours = dict(zip(TIMES, [f"C{i}" for i in range(len(TIMES))]))
    ref = _csv(REFERENCE["rigid"])
    for t in TIMES:
        ax1.plot(ref[f"p_l_{_key(t)}_Pa"] / 1e3, ref["height_m"], "-", color=colours[t], lw=1,
                 label=f"{t / 60:g} min, reference (a)")
    marks = {"rigid": ("o", "main cycle, rigid"), "explicit": ("x", "explicit, rigid, K_l = 20 MPa"),
             "explicit_krg1": ("+", "the same with k_rg = 1 (report only)")}
    for name, (m, label) in marks.items():
        if name in data["runs"]:
            for t, z, p, _, _ in data["runs"][name]["frames"]:
                if t in colours:
                    ax1.plot(p / 1e3, z, m, ms=4, mfc="none", color=colours[t],
                             label=label if t == TIMES[0] else None)
    ax1.set_title("Rigid skeleton: P_l against Richards (a)")
    ax1.set_xlabel("liquid pressure [kPa]")
    ax1.legend(fontsize=7)
    for name, style in (("richards_rigid_K2e9", "k-"), ("richards_rigid_K2e7", "k:"),
                        ("richards_mechanics", "k--")):
        f = _csv(f"{name}_outflow")
        ax2.plot(f["time_s"] / 60, f["outflow_kg_per_m2"], style, lw=1, label=f"solver: {name}")
    for name, d in data["runs"].items():
        ax2.plot(d["hist"]["time"] / 60, d["hist"]["outflow"], "o", ms=3, mfc="none",
                 label=f"ours: {name}")
    ax2.set_xlabel("time [min]")
    ax2.set_ylabel("cumulative outflow [kg/m^2]")
    ax2.set_title("Outflow through the base")
    ax2.legend(fontsize=7)
    b = _csv("richards_mechanics")
    for i, t in enumerate(OGS_RM_TIMES):
        o = _csv(f"ogs_richards_mechanics_t{t:04d}s")
        ax3.plot(b[f"p_l_{_key(t)}_Pa"] / 1e3, b["height_m"], "-", color=f"C{i}", lw=1,
                 label=f"{t} s, solver (b)")
        ax3.plot(o["liquid_pressure_gauge_Pa"] / 1e3, o["height_m"], "s", ms=3, mfc="none",
                 color=f"C{i}", label="OGS RM" if i == 0 else None)
    ax3.set_title("Richards-Bishop skeleton: solver (b) vs OGS RICHARDS_MECHANICS")
    ax3.set_xlabel("liquid pressure [kPa]")
    ax3.legend(fontsize=7)
    if "deformable" in data["runs"]:
        fl = data["runs"]["deformable"]["frames"]
        for i, t in enumerate(OGS_TH2M_TIMES):
            o = _csv(f"ogs_th2m_t{t:04d}s")
            ax4.plot(o["liquid_pressure_gauge_Pa"] / 1e3, o["height_m"], "-", color=f"C{i}",
                     lw=1, label=f"{t} s, OGS TH2M P_l")
            ax4.plot(o["gas_pressure_gauge_Pa"] / 1e3, o["height_m"], ":", color=f"C{i}", lw=1)
            try:
                _, z, pl, pg, _ = at_time(fl, t)
            except RuntimeError:
                continue
            ax4.plot(pl / 1e3, z, "o", ms=3, mfc="none", color=f"C{i}",
                     label="ours, deformable: P_l (o), P_g (+)" if i == 0 else None)
            ax4.plot(pg / 1e3, z, "+", ms=4, color=f"C{i}")
    ax4.set_title("Deformable with gas: ours vs OGS TH2M (report only; P_g dotted)")
    ax4.set_xlabel("pressure [kPa]")
    ax4.legend(fontsize=7)
    for ax in (ax1, ax3, ax4):
        ax.set_ylabel("height [m]")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
