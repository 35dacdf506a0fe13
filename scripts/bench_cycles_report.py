"""The printed tables of scripts/bench_cycles.py: each part's runs, CVODE's counters and figures,
from the JSON the benchmark writes."""


def fmt_s(x):
    return f"{x:.3g}" if x < 1 else f"{x:.2f}" if x < 100 else f"{x:.0f}"


def table(header, rows):
    cols = [header] + rows
    w = [max(len(str(r[i])) for r in cols) for i in range(len(header))]
    line = lambda r: "| " + " | ".join(str(c).ljust(w[i]) for i, c in enumerate(r)) + " |"
    return "\n".join([line(header), "|" + "|".join("-" * (x + 2) for x in w) + "|"] +
                     [line(r) for r in rows])


CVODE_COLUMNS = ["cvode_steps", "rhs_evaluations", "newton_iterations", "jacobian_evaluations",
                 "error_test_failures", "convergence_failures", "lu_analyses",
                 "pressure_unknowns", "jacobian_nonzeros", "flow_wall_time_s", "lu_wall_time_s",
                 "rhs_wall_time_s", "jacobian_wall_time_s"]


def print_cvode(runs):
    """The implicit runs' CVODE counters, one row a run."""
    rows = [[r["name"]] + [r["solver_statistics"][k] for k in CVODE_COLUMNS]
            for r in runs if r.get("solver_statistics")]
    print(table(["run"] + CVODE_COLUMNS, rows))


def print_figures(figures):
    """name = value lines of a part's scalar figures (the JSON holds them all)."""
    for k, v in figures.items():
        print(f"  {k} = {v:.4g}" if isinstance(v, float) else f"  {k} = {v}")


def print_a(a, repeats):
    print(f"\n(a) {a['description']}")
    rows = [[cyc, fmt_s(r["wall_time_s"]), fmt_s(r["process_wall_time_s"]), r["steps"],
             f"{r['ns_per_mp_step']:.0f}", f"{r['worst_max']:.4f}", f"{r['worst_rms']:.4f}"]
            for cyc, r in a["runs"].items()]
    print(table(["cycle", f"wall_s (best of {repeats})", "process_s", "steps", "ns_per_mp_step",
                 "worst_max", "worst_rms"], rows))
    print_cvode([a["runs"]["implicit"]])
    print_figures({k: a[k] for k in ("wall_ratio_explicit_over_implicit",
                                     "process_wall_ratio_explicit_over_implicit")})


def print_b(b, repeats):
    ex, im = b["runs"]["explicit"], b["runs"]["implicit"]
    print(f"\n(b) {b['description']}")
    rows = [["explicit", f"{b['explicit_window_T']:g}", fmt_s(ex["wall_time_s"]), ex["steps"],
             "measured"],
            ["explicit", "1", fmt_s(b["explicit_extrapolated_linear_s"]),
             f"{b['explicit_extrapolated_steps_linear']:.3g}", "linear"],
            ["explicit", "1", fmt_s(b["explicit_extrapolated_by_count_s"]),
             f"{b['explicit_extrapolated_steps_by_count']:.3g}", "by_step_count"],
            ["implicit", "1", fmt_s(im["wall_time_s"]), im["steps"], "measured"]]
    print(table(["cycle", "to_T", f"wall_s (best of {repeats})", "steps", "how"], rows))
    print_cvode([im])
    rows = [[f"{c['T']:g}", f"{c['explicit_max']:.4f}", f"{c['explicit_rms']:.4f}",
             f"{c['implicit_max']:.4f}", f"{c['implicit_rms']:.4f}"] for c in b["common"]]
    e1 = b["implicit_error_T1"]
    rows.append([f"{e1['T']:g}", "-", "-", f"{e1['max']:.4f}", f"{e1['rms']:.4f}"])
    print(table(["T", "explicit_max", "explicit_rms", "implicit_max", "implicit_rms"], rows))
    print_figures({k: b[k] for k in ("explicit_step_mean_over_last",
                                     "explicit_window_steps_over_1000_v1",
                                     "wall_ratio_explicit_over_implicit", "wall_ratio_linear",
                                     "judged_T", "pass_error", "pass_ratio", "pass")})


def print_c(c, repeats):
    im, ex = c["runs"]["implicit"], c["runs"]["explicit"]
    print(f"\n(c) {c['description']}")
    rows = [[name, r["threads"], r["material_points"], f"{r['simulated_time_s']:g}", r["steps"],
             fmt_s(r["wall_time_s"]), fmt_s(r["wall_per_simulated_s"]),
             f"{r['ns_per_mp_step']:.0f}"] for name, r in c["runs"].items()]
    print(table(["cycle", "threads", "points", "window_s", "steps", f"wall_s (best of {repeats})",
                 "wall_per_simulated_s", "ns_per_mp_step"], rows))
    print_cvode([im])
    print_figures(dict(c["shares"], ratio_per_simulated_s=c["ratio_per_simulated_s"],
                       ratio_same_window=c["ratio_same_window"]))
    rows = [[f"{T:g}", f"{mx:.4f}", f"{rms:.4f}"] for T, mx, rms in im["errors_all_T"]]
    T, mx, rms = ex["errors_all_T"][-1]
    rows.append([f"{T:.3g} (explicit)", f"{mx:.4f}", f"{rms:.4f}"])
    print(table(["T", "max_error", "rms_error"], rows))
