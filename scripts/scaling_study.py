#!/usr/bin/python3
"""The flow solvers' scaling study (docs/performance.md, "The flow's linear solvers").

A flow-only block -- rigid skeleton, rain-free infiltration from a wetted top face into a soil at
50 kPa suction, gravity, van Genuchten retention -- in 2D (1 m x 1 m) and 3D (1 m cube), 2 points
per cell in each direction, refined from about 1e3 to 1e6 pressure unknowns, run with
`implicit.linear_solver: direct` (the sparse LU: UMFPACK, or KLU with --direct-solver klu) and
`iterative` (GMRES with hypre's multigrid). For each
run: the pressure unknowns, the flow's wall time per simulated second (CVODE: right-hand sides,
Jacobians and the linear solver) and of it the linear solver's, CVODE's counts, and the process's
peak memory (/usr/bin/time). A run is skipped once the same solver took longer than --budget
seconds on a smaller size in the same dimension, and a run is stopped after --timeout seconds
(both are recorded as skipped, with the reason).

    /usr/bin/python3 scripts/scaling_study.py --unsatmpm build/bin/unsatmpm --out /tmp/scaling

writes scaling.csv and scaling.png in --out, and prints the table (Markdown) and the observed
exponents (least-squares slope of log time against log unknowns over the sizes from 5e3 on).
"""
import argparse
import csv
import json
import math
import pathlib
import subprocess
import sys

CASE = """name: scaling_block
dimension: {dim}
grid: {{origin: {origin}, size: {size}, cells: {cells}}}
shape_function: linear
gravity: {gravity}
phases: solid_liquid_gas
fluids:
  liquid: {{density: 1000, bulk_modulus: 2.0e+9, viscosity: 1.0e-3}}
  gas: {{model: ideal, density: 1.2, viscosity: 1.8e-5}}
mass_balance: full
pressure_update: nodal
skeleton: rigid
materials:
  - name: soil
    model: linear_elastic
    young_modulus: 1.0e+7
    poisson_ratio: 0.3
    solid_density: 2700
    porosity: 0.4
    intrinsic_permeability: 1.0e-12
    retention: {{model: van_genuchten, p0: 1.0e+4, lambda: 0.4, residual_saturation: 0, max_saturation: 1}}
    liquid_relative_permeability: {{model: mualem_van_genuchten, lambda: 0.4}}
    gas_relative_permeability: {{model: power, exponent: 3}}
bodies:
  - name: block
    material: soil
    points_per_cell: {ppc}
    box: {{min: {origin}, max: {size}}}
    initial_state: {{suction: 5.0e+4, gas_pressure: 0}}
boundaries:
  - name: top
    plane: {{axis: {up}, at: 1}}
    liquid: {{suction: 0}}
    gas: {{pressure: 0}}
solver:
  end_time: {end_time}
  damping: 0
  cycle: implicit
  implicit: {{linear_solver: {solver}, direct_solver: {direct}}}
output:
  history_interval: {history}
  write_grid: false
"""

# Target pressure unknowns (about 2 per node): 1e3 ... 1e6.
TARGETS = [1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6]
END_TIME = 100.0  # s: the wetting front moves about 0.2 m


def case_text(dim, unknowns, solver, direct="umfpack"):
    cells = max(2, round((unknowns / 2.0) ** (1.0 / dim) - 1.0))
    return CASE.format(
        dim=dim,
        origin=[0] * dim,
        size=[1] * dim,
        cells=[cells] * dim,
        gravity=[0] * (dim - 1) + [-9.81],
        ppc=2,
        up="y" if dim == 2 else "z",
        end_time=END_TIME,
        history=END_TIME / 10,
        solver=solver,
        direct=direct,
    )


def run(binary, folder, dim, target, solver, threads, timeout, max_memory, direct):
    folder.mkdir(parents=True, exist_ok=True)
    case = folder / "case.yaml"
    case.write_text(case_text(dim, target, solver, direct))
    out = folder / "out"
    time_log = folder / "time.txt"
    command = ["/usr/bin/time", "-f", "%M %e", "-o", str(time_log), str(binary), "run", "-q",
               "-t", str(threads), "-o", str(out), str(case)]
    if max_memory:
        command[-1:-1] = ["--max-memory", max_memory]
    try:
        done = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"dimension": dim, "solver": solver, "pressure_unknowns": target,
                "skipped": f"not finished in {timeout:.0f} s (stopped)"}
    if done.returncode != 0:
        last = done.stderr.strip().splitlines()[-1] if done.stderr.strip() else ""
        return {"dimension": dim, "solver": solver, "pressure_unknowns": target,
                "skipped": f"exit {done.returncode}: {last}"}
    summary = json.loads((out / "run_summary.json").read_text())
    s = summary["solver_statistics"]
    max_rss_kb, process_s = time_log.read_text().split()[-2:]
    simulated = summary["simulated_time_s"]
    linear_s = s["lu_wall_time_s"] if solver == "direct" else (
        s["flow_wall_time_s"] - s["rhs_wall_time_s"] - s["jacobian_wall_time_s"])
    return {
        "dimension": dim, "solver": solver, "pressure_unknowns": s["pressure_unknowns"],
        "points": summary["material_points"], "jacobian_nonzeros": s["jacobian_nonzeros"],
        "flow_s_per_simulated_s": s["flow_wall_time_s"] / simulated,
        "linear_s_per_simulated_s": linear_s / simulated,
        "rhs_s_per_simulated_s": s["rhs_wall_time_s"] / simulated,
        "cvode_steps": s["cvode_steps"], "newton_iterations": s["newton_iterations"],
        "setups": s["lu_factorisations"] if solver == "direct" else s["preconditioner_setups"],
        "linear_iterations": s["linear_iterations"],
        "max_rss_mb": int(max_rss_kb) / 1024.0, "process_s": float(process_s),
        "mismatch_liquid": summary["max_relative_mismatch_liquid"], "skipped": "",
        "direct_solver": s["direct_solver"] if solver == "direct" else "",
    }


def slope(rows, key):
    pts = [(math.log(r["pressure_unknowns"]), math.log(r[key])) for r in rows
           if not r["skipped"] and r["pressure_unknowns"] >= 5e3 and r[key] > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(x for x, _ in pts) / len(pts)
    my = sum(y for _, y in pts) / len(pts)
    return sum((x - mx) * (y - my) for x, y in pts) / sum((x - mx) ** 2 for x, _ in pts)


def plot(rows, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for dim, marker in ((2, "o"), (3, "s")):
        for solver, colour in (("direct", "tab:red"), ("iterative", "tab:blue")):
            sel = [r for r in rows if r["dimension"] == dim and r["solver"] == solver
                   and not r["skipped"]]
            if not sel:
                continue
            n = [r["pressure_unknowns"] for r in sel]
            label = f"{dim}D {solver}"
            axes[0].loglog(n, [r["linear_s_per_simulated_s"] for r in sel], marker=marker,
                           color=colour, ls="-" if dim == 2 else "--", label=label)
            axes[1].loglog(n, [r["max_rss_mb"] for r in sel], marker=marker, color=colour,
                           ls="-" if dim == 2 else "--", label=label)
    axes[0].set_ylabel("linear solver wall time per simulated second [s/s]")
    axes[1].set_ylabel("peak memory of the run [MB]")
    for ax in axes:
        ax.set_xlabel("pressure unknowns")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--unsatmpm", type=pathlib.Path)
    parser.add_argument("--out", required=True, type=pathlib.Path)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--budget", type=float, default=900.0,
                        help="skip larger sizes once a run's process took longer [s]")
    parser.add_argument("--budget-iterative", type=float, default=None,
                        help="the same for the iterative solver (default: --budget)")
    parser.add_argument("--timeout", type=float, default=1800.0,
                        help="stop a run after this long and record it as not finished [s]")
    parser.add_argument("--max-unknowns", type=float, default=1.1e6)
    parser.add_argument("--dimensions", default="2,3")
    parser.add_argument("--solvers", default="direct,iterative",
                        help="the linear solvers to run, of direct and iterative")
    parser.add_argument("--direct-solver", default="umfpack", choices=("umfpack", "klu"),
                        help="the sparse LU of the direct solver")
    parser.add_argument("--max-memory", default=None, help="passed to unsatmpm run")
    parser.add_argument("--rows", type=pathlib.Path, default=None,
                        help="run nothing: tabulate and plot the rows (JSON lines) of an earlier log")
    args = parser.parse_args()
    if not args.rows and not args.unsatmpm:
        parser.error("--unsatmpm is needed unless --rows is given")
    args.out.mkdir(parents=True, exist_ok=True)
    rows = []
    if args.rows:
        rows = [json.loads(line) for line in args.rows.read_text().splitlines()
                if line.startswith("{")]
    for dim in ([] if args.rows else (int(d) for d in args.dimensions.split(","))):
        for solver in args.solvers.split(","):
            if solver not in ("direct", "iterative"):
                parser.error(f"--solvers: unknown solver '{solver}'")
            over_budget = ""
            for target in (t for t in TARGETS if t <= args.max_unknowns):
                folder = args.out / f"{dim}d_{solver}_{int(target)}"
                if over_budget:
                    rows.append({"dimension": dim, "solver": solver, "pressure_unknowns": target,
                                 "skipped": over_budget})
                    continue
                row = run(args.unsatmpm, folder, dim, target, solver, args.threads, args.timeout,
                          args.max_memory, args.direct_solver)
                rows.append(row)
                print(json.dumps(row), flush=True)
                budget = (args.budget_iterative or args.budget) if solver == "iterative" \
                    else args.budget
                if row["skipped"]:
                    over_budget = row["skipped"]
                elif row["process_s"] > budget:
                    over_budget = (f"the {row['pressure_unknowns']}-unknown run took "
                                   f"{row['process_s']:.0f} s > {budget:.0f} s")
    keys = sorted({k for r in rows for k in r})
    with open(args.out / "scaling.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=keys)
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, args.out / "scaling.png")
    print("| dim | solver | unknowns | flow s/s | linear s/s | setups | GMRES its | peak MB |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        if r["skipped"]:
            print(f"| {r['dimension']}D | {r['solver']} | ~{r['pressure_unknowns']:.0e} | "
                  f"skipped: {r['skipped']} | | | | |")
            continue
        print(f"| {r['dimension']}D | {r['solver']} | {r['pressure_unknowns']} | "
              f"{r['flow_s_per_simulated_s']:.4g} | {r['linear_s_per_simulated_s']:.4g} | "
              f"{r['setups']} | {r['linear_iterations']} | {r['max_rss_mb']:.0f} |")
    for dim in (2, 3):
        for solver in ("direct", "iterative"):
            sel = [r for r in rows if r["dimension"] == dim and r["solver"] == solver]
            print(f"{dim}D {solver}: exponent of the linear solver's time "
                  f"{slope(sel, 'linear_s_per_simulated_s'):.2f}, of the flow's "
                  f"{slope(sel, 'flow_s_per_simulated_s'):.2f}, of memory "
                  f"{slope(sel, 'max_rss_mb'):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
