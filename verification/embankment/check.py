"""V5: rain-induced failure of a 7 m, 32.5 degree embankment (the paper's section 5, figure 9).

Reference: the paper's description of its run, not an exact solution. With suction (800 kPa) the
slope stands; rain (the surface suction ramped to 0 over 10 s) removes the suction's strength near
the face and the slope fails a few seconds after t = 15 s along a shear band about 1.5 m deep,
runs out 2.5 m beyond the toe, and the deep control point D2 stays motionless.

Two runs: "rain" (case.yaml, to 200 s) and "dry" (the same slope with the surface suction held at
800 kPa, to 30 s). Checks, set from the paper's statements before the runs were looked at (a
check passes when value <= tolerance):
- dry slope stands: max |displacement| of any point or control point up to 30 s <= 0.05 m;
- rain slope fails: at least 5 % of the embankment's mass has moved 0.5 m or more by the end (a
  shallow slide 1.5 m deep along the 13 m face is about a quarter of it; a few points thrown off
  the toe are not a failure);
- run-out (toe at the end minus toe at t = 0) between 1 m and 5 m (the paper's 2.5 m within a
  factor of 2.5 either way). The toe is the largest x of the points that lie in grid cells
  holding at least 2 points (half the initial 4), so that an isolated point thrown ahead of the
  deposit does not count; the program's own front, globals.csv max_x (the largest x of any
  point), is reported beside it;
- D2 (10.5, 1.0), deep under the slope, moves less than 0.1 m by the end.
Reported, not checked: failure initiation (first time the kinetic energy exceeds 1 J/m, and first
time a control point moves 0.1 m), the wetting depth at 15 s (suction below 400 kPa), the
shear-band depth at 15 s and the deepest plastic point at the end (depth below the original
surface of the points with deviatoric plastic strain >= 0.05).
"""
import json

import numpy as np

from pathlib import Path

from common import case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
# The body's polygon runs (0, 0), (toe, 0), (crest, height), (0, height).
_VERTICES = _CASE["bodies"][0]["polygon"]["vertices"]
TOE, CREST, HEIGHT = float(_VERTICES[1][0]), float(_VERTICES[2][0]), float(_VERTICES[2][1])
OUTLINE = np.array([[0, 0], [TOE, 0], [CREST, HEIGHT], [0, HEIGHT], [0, 0]])
CONTROL = {cp["name"]: tuple(float(v) for v in cp["position"])
           for cp in _CASE["output"]["control_points"]}
PLASTIC = 0.05        # deviatoric plastic strain that marks a point as in the shear band
KE_FAILURE = 1.0      # J per metre of thickness: an order above anything before failure
CP_FAILURE = 0.1      # m
# A slide at rest (solver.stop_at_rest of the runs to rest, study.py and ../embankment_cycles):
# kinetic energy below 1 % of its peak for 5 s, once the peak passed 10 J/m (ten times
# KE_FAILURE, so that the loosening before a slide does not count as one).
REST = {"fraction": 0.01, "hold": 5.0, "min_peak": 10.0}
SLID_FRACTION = 0.05  # mass fraction moved >= 0.5 m that makes a failure
CELL = float(_CASE["grid"]["size"][0]) / int(_CASE["grid"]["cells"][0])  # grid cell [m]
BAND_X = (7.0, 14.0)  # initial x of the slope face away from crest and toe
SNAP_TIMES = (0.0, 15.0, 200.0)
WET_SUCTION = 4.0e5   # Pa: half the initial 800 kPa marks the wetted zone

RUNS = {
    "rain": {},
    "dry": {"free_surface.liquid.suction": 8.0e5, "solver.end_time": 30, "output.times": [10, 20]},
}


def depth_below_surface(x0, y0):
    """Distance of initial positions to the original surface (crest segment and slope face). For
    points under the face this is the depth normal to the slope line through (5, 7), (15.988, 0)."""
    p = np.column_stack([x0, y0])
    best = np.full(len(p), np.inf)
    for a, b in (((0.0, HEIGHT), (CREST, HEIGHT)), ((CREST, HEIGHT), (TOE, 0.0))):
        a, b = np.array(a), np.array(b)
        s = np.clip((p - a) @ (b - a) / ((b - a) @ (b - a)), 0.0, 1.0)
        best = np.minimum(best, np.linalg.norm(p - (a + s[:, None] * (b - a)), axis=1))
    return best


def _nearest(ser, t):
    return min(ser, key=lambda tp: abs(tp[0] - t))


def _snapshot(t, path):
    x, a = read_points(path)
    u = a["displacement"]
    x0 = x - u
    return {"time": t, "x": x[:, 0], "y": x[:, 1], "x0": x0[:, 0], "y0": x0[:, 1],
            "u": np.linalg.norm(u, axis=1), "suction": a["suction"], "mp_id": a["mp_id"],
            "eps": a["deviatoric_plastic_strain"], "mass": a["mass"]}


def _control(run_dir):
    c = read_csv(run_dir / "control_points.csv")
    return c["time"], {n: np.hypot(c[f"{n}_displacement_x"], c[f"{n}_displacement_y"])
                       for n in CONTROL if f"{n}_displacement_x" in c}


def deposit_toe(x, y, cell=CELL):
    """Largest x of the points in cells of size `cell` that hold at least 2 points."""
    cells = np.floor(np.column_stack([x, y]) / cell).astype(np.int64)
    _, inverse, counts = np.unique(cells, axis=0, return_inverse=True, return_counts=True)
    dense = counts[inverse.ravel()] >= 2
    return float(x[dense].max()) if dense.any() else float("nan")


def _cell(run_dir):
    """The grid cell [m] of the case a run was made from (the effective_case.yaml the program
    writes beside its output), so that a run on another grid than case.yaml's is measured on its
    own cells."""
    case = run_dir / "effective_case.yaml"
    if not case.is_file():
        return CELL
    grid = case_doc(case)["grid"]
    return float(grid["size"][0]) / int(grid["cells"][0])


def _first(times, mask):
    idx = np.flatnonzero(mask)
    return float(times[idx[0]]) if len(idx) else None


def _front(run_dir, ser):
    """Toe history: globals.csv max_x if written, else the largest x of each points file."""
    g = read_csv(run_dir / "globals.csv")
    if "max_x" in g:
        return g["time"], g["max_x"], "globals.csv max_x"
    return (np.array([t for t, _ in ser]),
            np.array([read_points(p)[0][:, 0].max() for _, p in ser]), "points files")


def evaluate(run_dirs):
    rain, dry = run_dirs["rain"], run_dirs["dry"]
    data = {}
    # Dry slope: every output to 30 s, and the control-point histories.
    dry_max = 0.0
    for t, p in series(dry):
        if t <= 30 + 1e-9:
            u = np.linalg.norm(read_points(p)[1]["displacement"], axis=1)
            dry_max = max(dry_max, float(u.max()))
    dt, dcp = _control(dry)
    for u in dcp.values():
        dry_max = max(dry_max, float(u[dt <= 30 + 1e-9].max()))
    data["dry"] = {"max_u": dry_max, "cp_time": dt, "cp": dcp}
    # Rain: snapshots at the output times nearest 0, 15 and 200 s (the run may have ended early).
    ser = series(rain)
    snaps = [_snapshot(*_nearest(ser, t)) for t in SNAP_TIMES]
    first, last = _snapshot(*ser[0]), _snapshot(*ser[-1])
    data["snaps"] = snaps
    data["end_time"] = last["time"]
    data["max_u_end"] = float(last["u"].max())
    slid = last["u"] >= 0.5
    data["slid_points"] = int(slid.sum())
    data["slid_mass_fraction"] = float(last["mass"][slid].sum() / last["mass"].sum())
    g = read_csv(rain / "globals.csv")
    data["ke_time"], data["ke"] = g["time"], g["kinetic_energy"]
    data["t_fail_ke"] = _first(g["time"], g["kinetic_energy"] > KE_FAILURE)
    ct, cp = _control(rain)
    data["cp_time"], data["cp"] = ct, cp
    data["t_fail_cp"] = _first(ct, np.max(list(cp.values()), axis=0) > CP_FAILURE)
    data["d2_end"] = float(cp["D2"][-1]) if "D2" in cp else float("nan")
    # Run-out from the points files; toe history from globals.csv or the points files.
    cell = _cell(rain)
    data["toe0"] = deposit_toe(first["x"], first["y"], cell)
    data["toe_end"] = deposit_toe(last["x"], last["y"], cell)
    data["runout"] = data["toe_end"] - data["toe0"]
    data["front_runout"] = float(last["x"].max() - first["x"].max())
    data["toe_time"], data["toe"], data["toe_source"] = _front(rain, ser)
    # Shear band at 15 s: depth of the plastic points of the face's middle part.
    s15 = snaps[1]
    face = (s15["x0"] >= BAND_X[0]) & (s15["x0"] <= BAND_X[1])
    band = face & (s15["eps"] >= PLASTIC)
    depth = depth_below_surface(s15["x0"][band], s15["y0"][band])
    data["band_time"], data["band_points"] = s15["time"], int(band.sum())
    data["band_p90"] = float(np.percentile(depth, 90)) if len(depth) else 0.0
    data["band_max"] = float(depth.max()) if len(depth) else 0.0
    # Wetting depth at 15 s: how deep under the face's middle part the suction has fallen below
    # half its initial value (WET_SUCTION).
    wet = face & (s15["suction"] < WET_SUCTION)
    wet_depth = depth_below_surface(s15["x0"][wet], s15["y0"][wet])
    data["wet_p90"] = float(np.percentile(wet_depth, 90)) if len(wet_depth) else 0.0
    plastic = last["eps"] >= PLASTIC
    deep = depth_below_surface(last["x0"][plastic], last["y0"][plastic])
    k = int(np.argmax(deep)) if len(deep) else None
    data["deepest_end"] = float(deep[k]) if k is not None else 0.0
    data["deepest_end_at"] = ((float(last["x0"][plastic][k]), float(last["y0"][plastic][k]))
                              if k is not None else None)
    data["cp_ids"] = json.loads((rain / "run_summary.json").read_text()).get(
        "control_point_mp_ids", {}) if (rain / "run_summary.json").exists() else {}
    checks = [
        ("dry slope: max displacement to t = 30 s [m]", dry_max, 0.05),
        ("rain: 0.05 / mass fraction moved >= 0.5 m (<= 1: it fails)",
         SLID_FRACTION / max(data["slid_mass_fraction"], 1e-12), 1.0),
        ("run-out [m] >= 1 (1 / run-out)", 1.0 / max(data["runout"], 1e-3), 1.0),
        ("run-out [m] <= 5", data["runout"], 5.0),
        ("D2 final displacement [m]", data["d2_end"], 0.1),
    ]
    return data, checks


def _fmt(v, f="{:.2f}", unit=""):
    return "n/a" if v is None or not np.isfinite(v) else f.format(v) + unit


def notes(data):
    at = data["deepest_end_at"]
    rows = [
        ("failure initiation: kinetic energy > 1 J/m", "a few seconds after t = 15 s",
         _fmt(data["t_fail_ke"], "{:.1f}", " s")),
        ("failure initiation: a control point moves 0.1 m", "",
         _fmt(data["t_fail_cp"], "{:.1f}", " s")),
        (f"wetting depth at t = {data['band_time']:g} s (90th pct of the depth of the points "
         f"with suction < {WET_SUCTION / 1e3:g} kPa, x0 in 7-14 m)",
         "not stated; >= 1.5 m (its band)", _fmt(data["wet_p90"], unit=" m")),
        (f"shear-band depth at t = {data['band_time']:g} s (90th pct / max, x0 in 7-14 m, "
         f"eps_p >= {PLASTIC})", "about 1.5 m",
         f"{data['band_p90']:.2f} / {data['band_max']:.2f} m ({data['band_points']} points)"),
        (f"deepest point with eps_p >= {PLASTIC} at t = {data['end_time']:g} s", "",
         f"{data['deepest_end']:.2f} m"
         + (f" (initially at {at[0]:.2f}, {at[1]:.2f})" if at else "")),
        (f"run-out at t = {data['end_time']:g} s (deposit toe)", "2.5 m",
         _fmt(data["runout"], unit=" m")),
        ("the same from globals.csv max_x (any point)", "", _fmt(data["front_runout"], unit=" m")),
        ("points moved >= 0.5 m at the end (mass fraction)", "",
         f"{data['slid_points']} ({100 * data['slid_mass_fraction']:.2f} %)"),
        ("D2 displacement at the end", "motionless", _fmt(data["d2_end"], "{:.4f}", " m")),
        ("dry slope: max displacement to 30 s", "(stands)",
         _fmt(data["dry"]["max_u"], "{:.4f}", " m")),
    ]
    lines = ["| measure | paper | this run |", "|---|---|---|"]
    lines += [f"| {a} | {b} | {c} |" for a, b, c in rows]
    lines += ["", f"Toe history from {data['toe_source']}. The rain run's last output is at "
              f"t = {data['end_time']:g} s; snapshots are the outputs nearest 0, 15 and 200 s."]
    return "\n".join(lines)


def plot(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm, Normalize

    names = []
    colors = dict(zip(CONTROL, ["C0", "C1", "C2", "C3"]))
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax in axes:
        for n, u in data["cp"].items():
            ax.plot(data["cp_time"], u, "-", color=colors[n], lw=1.8, label=f"{n} (rain)")
        for n, u in data["dry"]["cp"].items():
            ax.plot(data["dry"]["cp_time"], u, "--", color=colors[n], lw=0.8, label=f"{n} (dry)")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("displacement magnitude [m]")
    axes[1].set_yscale("log")
    axes[1].set_ylim(bottom=1e-6)
    axes[0].set_title("Control points (paper figure 9)")
    axes[1].set_title("the same, log scale")
    axes[0].legend(fontsize=8, ncol=2)
    fig.tight_layout()
    fig.savefig(out_dir / "embankment_control_points.png", dpi=100)
    plt.close(fig)
    names.append("embankment_control_points.png")

    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(data["toe_time"], data["toe"], "k-", lw=1.5,
            label=f"front (max x, {data['toe_source']})")
    ax.axhline(data["toe0"], color="gray", lw=1, ls="--", label=f"initial toe {data['toe0']:.2f} m")
    ax.axhline(data["toe0"] + 2.5, color="C3", lw=1, ls=":", label="paper: run-out 2.5 m")
    ax.annotate("", xy=(data["end_time"], data["toe_end"]), xytext=(data["end_time"], data["toe0"]),
                arrowprops=dict(arrowstyle="<->", color="C0"))
    ax.text(data["end_time"], 0.5 * (data["toe0"] + data["toe_end"]),
            f" run-out {data['runout']:.2f} m", color="C0", ha="right", va="center")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("toe position x [m]")
    ax.set_title("Toe of the rain run")
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(out_dir / "embankment_toe.png", dpi=100)
    plt.close(fig)
    names.append("embankment_toe.png")

    snaps = data["snaps"]
    umax = max(1e-3, max(s["u"].max() for s in snaps))
    rows = [("suction", "suction [kPa]", lambda s: s["suction"] / 1e3, Normalize(0, 800),
             "viridis"),
            ("eps", "dev. plastic strain", lambda s: s["eps"], Normalize(0, 0.5), "magma_r"),
            ("u", "|displacement| [m]", lambda s: np.maximum(s["u"], 1e-4), LogNorm(1e-4, umax),
             "plasma")]
    xmax = min(25.0, max(s["x"].max() for s in snaps) + 1.0)
    fig, axes = plt.subplots(3, 3, figsize=(16, 6.6), sharex=True, sharey=True,
                             layout="constrained")
    for r, (_, label, value, norm, cmap) in enumerate(rows):
        for c, s in enumerate(snaps):
            ax = axes[r, c]
            v = value(s)
            order = np.argsort(v)
            sc = ax.scatter(s["x"][order], s["y"][order], c=v[order], s=4, marker="s",
                            cmap=cmap, norm=norm, linewidths=0)
            ax.plot(OUTLINE[:, 0], OUTLINE[:, 1], "k-", lw=0.5, zorder=3)
            ax.set_aspect("equal")
            ax.set_xlim(0, xmax)
            ax.set_ylim(0, 7.6)
            if r == 0:
                ax.set_title(f"t = {s['time']:g} s")
            if c == 0:
                ax.set_ylabel("y [m]")
            if r == 2:
                ax.set_xlabel("x [m]")
        fig.colorbar(sc, ax=axes[r, :], shrink=0.95, pad=0.01, label=label)
    s0 = snaps[0]
    for n, xy in CONTROL.items():
        hit = np.flatnonzero(s0["mp_id"] == data["cp_ids"].get(n, -1))
        if len(hit):
            xy = (s0["x"][hit[0]], s0["y"][hit[0]])
        for r in range(3):
            axes[r, 0].plot(*xy, "o", ms=4, mfc="w", mec="k")
            axes[r, 0].annotate(n, xy, xytext=(3, 3), textcoords="offset points", fontsize=8,
                                bbox=dict(boxstyle="round,pad=0.1", fc="w", ec="none", alpha=0.8))
    fig.savefig(out_dir / "embankment_snapshots.png", dpi=110)
    plt.close(fig)
    names.append("embankment_snapshots.png")
    return names
