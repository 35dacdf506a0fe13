"""The reference of V15: Richards' equation for the column's liquid, the gas at 0 throughout.

Finite volumes on the top REFERENCE_DEPTH of the column (the front stays within its top tenth by
the case's end; the cells below keep their initial state), cells of 0.4 mm, each face's
conductivity the arithmetic mean of its two sides', the top face's between the prescribed state
and the first cell's (half a cell apart); integrated in time by SciPy's BDF to a relative
tolerance of 1e-7, with the tridiagonal Jacobian by finite differences (SciPy's own sparse
differencing took 20 s of its 21, this 1 s). The water per unit volume is n S_l(s) rho_l(P_l)
with s = -P_l and the liquid's compressibility of the case. On 250, 500, 1000 and 2000 cells over
0.2 m the intake by 2 s is 5.163, 5.126, 5.113 and 5.108 kg/m^2 (2026-11-30), first order, so the
500 cells that check.py uses are within 0.4 % of the converged value (about 5.105).
"""
import numpy as np

REFERENCE_DEPTH = 0.2  # [m]
REFERENCE_CELLS = 500


def intake(doc, times, cells=REFERENCE_CELLS, depth=REFERENCE_DEPTH):
    """The water taken in through the top by each of `times` [kg per m^2 of the section]."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import diags

    mat = doc["materials"][0]
    liquid = doc["fluids"]["liquid"]
    n, kappa = mat["porosity"], mat["intrinsic_permeability"]
    p0, lam = mat["retention"]["p0"], mat["retention"]["lambda"]
    rho0, k_l, mu = liquid["density"], liquid["bulk_modulus"], liquid["viscosity"]
    g = -doc["gravity"][0]
    ramp = doc["boundaries"][1]["liquid"]["suction"]["ramp"]
    s0 = doc["bodies"][0]["initial_state"]["suction"]
    m = 1.0 / (1.0 - lam)
    dx = depth / cells

    def se(p):
        return (1.0 + (np.maximum(-p, 0.0) / p0) ** m) ** (-lam)

    def conductivity(p):  # rho kappa k_rl / mu, Mualem's k_rl
        e = np.clip(se(p), 0.0, 1.0)
        return rho0 * kappa * np.maximum(np.sqrt(e) * (1 - (1 - e ** (1 / lam)) ** lam) ** 2,
                                         1e-12) / mu

    def water(p):
        return n * se(p) * rho0 * np.exp(p / k_l)

    def storage(p):
        h = 1e-3 * np.maximum(1.0, 1e-4 * np.abs(p))
        return (water(p + h) - water(p - h)) / (2 * h)

    def face_pressure(t):
        f = min(max((t - ramp["start"]) / (ramp["end"] - ramp["start"]), 0.0), 1.0)
        return -(ramp["from"] + f * (ramp["to"] - ramp["from"]))

    def rate(t, p):  # cells bottom (0) to top, x upward; q: upward mass flux
        k = conductivity(p)
        q = -0.5 * (k[1:] + k[:-1]) * ((p[1:] - p[:-1]) / dx + rho0 * g)
        pf = face_pressure(t)
        k_top = 0.5 * (k[-1] + conductivity(np.array([pf]))[0])
        q_top = -k_top * ((pf - p[-1]) / (dx / 2) + rho0 * g)
        div = np.zeros(cells)
        div[:-1] += q
        div[1:] -= q
        div[-1] += q_top
        return -div / dx / storage(p)

    def jacobian(t, p):
        # Tridiagonal by finite differences, three columns groups (j mod 3) per evaluation.
        f0 = rate(t, p)
        h = 1e-6 * np.maximum(np.abs(p), 1.0)
        bands = np.zeros((3, cells))  # sub-, main and super-diagonal entries by column
        for g in range(3):
            q = p.copy()
            q[g::3] += h[g::3]
            df = (rate(t, q) - f0)
            for j in range(g, cells, 3):
                lo, hi = max(j - 1, 0), min(j + 2, cells)
                bands[:, j] = 0.0
                for i in range(lo, hi):
                    bands[i - j + 1, j] = df[i] / h[j]
        return diags([bands[2, :-1], bands[1], bands[0, 1:]], [-1, 0, 1], format="csc")

    sol = solve_ivp(rate, (0.0, max(times)), np.full(cells, -float(s0)), method="BDF",
                    jac=jacobian, rtol=1e-7, atol=1.0, t_eval=[0.0] + list(times))
    if not sol.success:
        raise RuntimeError(f"the Richards reference failed: {sol.message}")
    held = [water(sol.y[:, k]).sum() * dx for k in range(sol.y.shape[1])]
    return [h - held[0] for h in held[1:]]
