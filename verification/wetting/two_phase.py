"""A reference for V15 with the gas: the column's liquid and gas mass balances together.

richards.py holds the gas at 0; with k_rg = 1 that is close (the runs' gas stays below 0.1 kPa).
With k_rg = (1 - S_e)^r the wet skin under the face closes the gas's way out: the gas below is
compressed by the water coming in, its pressure rises over the whole column, and the suction it
keeps at the skin slows the intake. This solves both balances,

    d/dt [n S_l(s) rho_l(P_l)]       + d/dz (rho_l q_l) = 0,
    d/dt [n (1 - S_l(s)) rho_g(P_g)] + d/dz (rho_g q_g) = 0,
    q_a = -kappa k_ra / mu_a (dP_a/dz + rho_a g),

with s = max(P_g - P_l, 0), over the whole column (the gas's pressure reaches its base within the
case's time): finite volumes, fine cells over the top FINE_DEPTH, where the front runs, coarser
ones below; each face's conductivity rho kappa k_r / mu the arithmetic mean of its two sides', the
top face's between the first cell's and the prescribed state's (half a cell apart), as in
richards.py; the densities and laws of the case (docs/models.md), the relative permeabilities
floored at 1e-12 as the program floors them. The unknowns are the cells' pressures, advanced by
BDF (SciPy, relative tolerance 1e-7) through each cell's 2 x 2 storage matrix; the water and gas
that enter through the top are integrated beside them, so that the reference reports how well it
keeps its own balances.
"""
import numpy as np

FINE_DEPTH = 0.2   # [m]
FINE_CELLS = 500   # 0.4 mm
COARSE_CELLS = 200  # 4 mm over the rest of the column
P_ATM = 101325.0   # [Pa], the ideal gas's (physics/fluids.hpp)


def _relperm(model, se):
    """k_r(S_e) of the case's law, floored at 1e-12 (physics/hydraulic_model.hpp)."""
    e = np.clip(se, 0.0, 1.0)
    kind = model["model"]
    if kind == "constant":
        k = np.ones_like(e)
    elif kind == "power":  # the gas's (1 - S_e)^r
        k = (1.0 - e) ** model["exponent"]
    elif kind == "mualem_van_genuchten":
        lam = model["lambda"]
        k = np.sqrt(e) * (1.0 - (1.0 - e ** (1.0 / lam)) ** lam) ** 2
    else:
        raise ValueError(f"two_phase.py: relative permeability model {kind!r} not covered")
    return np.maximum(k, 1e-12)


def solve(doc, times, fine=FINE_CELLS, coarse=COARSE_CELLS, fine_depth=FINE_DEPTH):
    """The column of `doc` (V15's case, 1D) to max(times). Returns a dict of lists, one entry
    per time: 'in' and 'gas_in' (water and gas taken in through the top since t = 0 [kg/m^2]),
    'held' and 'gas_held' (their gains in the column [kg/m^2]), and 'p_g_base' (the gas's
    pressure in the bottom cell [Pa])."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import coo_matrix

    mat = doc["materials"][0]
    liq, gas = doc["fluids"]["liquid"], doc["fluids"]["gas"]
    if gas.get("model") != "ideal":
        raise ValueError("two_phase.py: only the ideal gas is covered")
    ret = mat["retention"]
    if ret["model"] != "van_genuchten":
        raise ValueError("two_phase.py: only van Genuchten's retention is covered")
    n, kappa = mat["porosity"], mat["intrinsic_permeability"]
    p0, lam = ret["p0"], ret["lambda"]
    s_res, s_max = ret.get("residual_saturation", 0.0), ret.get("max_saturation", 1.0)
    m = 1.0 / (1.0 - lam)
    rho_l0, k_bulk, mu_l = liq["density"], liq["bulk_modulus"], liq["viscosity"]
    rho_g0, mu_g = gas["density"], gas["viscosity"]
    g = -doc["gravity"][0]
    length = doc["grid"]["size"][0]
    top = doc["boundaries"][1]
    ramp = top["liquid"]["suction"]["ramp"]
    p_g_top = float(top["gas"]["pressure"])
    init = doc["bodies"][0]["initial_state"]
    s0, p_g0 = float(init["suction"]), float(init["gas_pressure"])

    widths = np.concatenate([np.full(coarse, (length - fine_depth) / coarse),
                             np.full(fine, fine_depth / fine)])  # bottom (0) to top
    cells = widths.size
    gaps = 0.5 * (widths[1:] + widths[:-1])  # between neighbouring centres

    def saturation(s):  # S_l, dS_l/ds, S_e
        x = np.maximum(s, 0.0) / p0
        base = 1.0 + x ** m
        se = base ** (-lam)
        dse = -lam * base ** (-lam - 1.0) * m * x ** (m - 1.0) / p0
        return s_res + (s_max - s_res) * se, (s_max - s_res) * dse * (s > 0.0), se

    def rho_l(p):
        return rho_l0 * np.exp(p / k_bulk)

    def rho_g(p):
        return rho_g0 * (p + P_ATM) / P_ATM

    def conductivities(p_l, p_g):  # rho kappa k_r / mu of each fluid [s]
        se = saturation(p_g - p_l)[2]
        return (rho_l(p_l) * kappa * _relperm(mat["liquid_relative_permeability"], se) / mu_l,
                rho_g(p_g) * kappa * _relperm(mat["gas_relative_permeability"], se) / mu_g)

    def face_pressures(t):
        f = min(max((t - ramp["start"]) / (ramp["end"] - ramp["start"]), 0.0), 1.0)
        return p_g_top - (ramp["from"] + f * (ramp["to"] - ramp["from"])), p_g_top

    def fluxes(t, p_l, p_g):
        """Upward mass fluxes [kg/m^2/s] through the inner faces and the top, each fluid."""
        k_l, k_g = conductivities(p_l, p_g)
        tl, tg = face_pressures(t)
        ktl, ktg = conductivities(np.array([tl]), np.array([tg]))
        out = []
        for p, k, kt, pt, rho in ((p_l, k_l, ktl[0], tl, rho_l), (p_g, k_g, ktg[0], tg, rho_g)):
            r = rho(p)
            inner = -0.5 * (k[1:] + k[:-1]) * ((p[1:] - p[:-1]) / gaps
                                               + 0.5 * (r[1:] + r[:-1]) * g)
            r_top = 0.5 * (r[-1] + rho(np.array([pt]))[0])
            top_flux = -0.5 * (k[-1] + kt) * ((pt - p[-1]) / (0.5 * widths[-1]) + r_top * g)
            out.append((inner, top_flux))
        return out

    def rate(t, y):
        p_l, p_g = y[:cells], y[cells:2 * cells]
        gains, flux = [], fluxes(t, p_l, p_g)
        for inner, top_flux in flux:
            div = np.zeros(cells)
            div[:-1] += inner
            div[1:] -= inner
            div[-1] += top_flux
            gains.append(-div / widths)  # mass gained per unit volume and time
        s_l, ds, _ = saturation(p_g - p_l)
        rl, rg = rho_l(p_l), rho_g(p_g)
        # d[W_l, W_g]/d[P_l, P_g], with ds/dP_l = -1, ds/dP_g = 1.
        a11 = -n * ds * rl + n * s_l * rl / k_bulk
        a12 = n * ds * rl
        a21 = n * ds * rg
        a22 = -n * ds * rg + n * (1.0 - s_l) * rho_g0 / P_ATM
        det = a11 * a22 - a12 * a21
        out = np.empty_like(y)
        out[:cells] = (a22 * gains[0] - a12 * gains[1]) / det
        out[cells:2 * cells] = (-a21 * gains[0] + a11 * gains[1]) / det
        out[2 * cells:] = [-flux[0][1], -flux[1][1]]  # what enters through the top
        return out

    size = 2 * cells + 2

    def jacobian(t, y):
        # Each cell couples to its neighbours in both blocks: columns of one block j mod 3 apart
        # are perturbed together, six evaluations; the top cell also feeds the inflows.
        f0 = rate(t, y)
        h = 1e-6 * np.maximum(np.abs(y), 1.0)
        rows, cols, vals = [], [], []
        for block in (0, 1):
            for k in range(3):
                j = np.arange(k, cells, 3)
                c = j + block * cells
                z = y.copy()
                z[c] += h[c]
                df = rate(t, z) - f0
                for off in (-1, 0, 1):
                    i = j + off
                    ok = (i >= 0) & (i < cells)
                    for r in (i[ok], i[ok] + cells):
                        rows.append(r), cols.append(c[ok]), vals.append(df[r] / h[c[ok]])
                if j[-1] == cells - 1:
                    r = np.array([2 * cells, 2 * cells + 1])
                    rows.append(r), cols.append(np.full(2, c[-1])), vals.append(df[r] / h[c[-1]])
        return coo_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(size, size)).tocsc()

    y0 = np.concatenate([np.full(cells, p_g0 - s0), np.full(cells, p_g0), [0.0, 0.0]])
    atol = np.concatenate([np.full(2 * cells, 0.01), [1e-10, 1e-12]])
    sol = solve_ivp(rate, (0.0, max(times)), y0, method="BDF", jac=jacobian, rtol=1e-7,
                    atol=atol, t_eval=[0.0] + list(times))
    if not sol.success:
        raise RuntimeError(f"the two-phase reference failed: {sol.message}")

    def contents(y):
        p_l, p_g = y[:cells], y[cells:2 * cells]
        s_l = saturation(p_g - p_l)[0]
        return (np.sum(n * s_l * rho_l(p_l) * widths),
                np.sum(n * (1.0 - s_l) * rho_g(p_g) * widths))

    c0 = contents(sol.y[:, 0])
    out = {"in": [], "gas_in": [], "held": [], "gas_held": [], "p_g_base": []}
    for k in range(1, sol.y.shape[1]):
        y = sol.y[:, k]
        c = contents(y)
        out["in"].append(float(y[2 * cells])), out["gas_in"].append(float(y[2 * cells + 1]))
        out["held"].append(float(c[0] - c0[0])), out["gas_held"].append(float(c[1] - c0[1]))
        out["p_g_base"].append(float(y[cells]))
    return out


if __name__ == "__main__":
    import sys
    import time
    from pathlib import Path

    import yaml

    doc = yaml.safe_load((Path(__file__).parent / "case.yaml").read_text())
    if len(sys.argv) > 1:
        doc["materials"][0]["gas_relative_permeability"] = {"model": "power",
                                                            "exponent": float(sys.argv[1])}
    for f, c in ((250, 100), (500, 200), (1000, 400)):
        t0 = time.time()
        r = solve(doc, [1.0, 2.0], fine=f, coarse=c)
        print(f"{f}+{c} cells: water in {r['in']} held {r['held']}, gas in {r['gas_in']} held "
              f"{r['gas_held']}, gas at the base {r['p_g_base']} Pa ({time.time() - t0:.1f} s)")
