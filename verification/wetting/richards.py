"""The reference of V15 and V16 (../rain): Richards' equation for the column's liquid, the gas at 0
throughout, its top held at a pressure (V15) or under rain that ponds (V16, solve(rain=...)).

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
    """The water taken in through the top by each of `times` [kg per m^2 of the section], the
    top held at V15's suction ramp (the case's second boundary)."""
    ramp = doc["boundaries"][1]["liquid"]["suction"]["ramp"]

    def face_pressure(t):
        f = min(max((t - ramp["start"]) / (ramp["end"] - ramp["start"]), 0.0), 1.0)
        return -(ramp["from"] + f * (ramp["to"] - ramp["from"]))

    return solve(doc, times, face_pressure=face_pressure, cells=cells, depth=depth)["in"]


def solve(doc, times, face_pressure=None, rain=None, cells=REFERENCE_CELLS, depth=REFERENCE_DEPTH):
    """Richards' equation on the top `depth` of the column of `doc` (its first material, its
    liquid, its body's initial suction, gravity along the column), the top either held at
    face_pressure(t) [Pa] or under rain [kg/(m^2 s)]: the rain enters while the soil takes it,
    and where it would take less the top ponds, held at zero suction (the flux through the top
    face the smaller of the rain and what that face takes at P_l = 0). Returns a dict of lists,
    one entry per time: 'in', the water the column gained since t = 0 [kg/m^2], 'counted', the
    water that entered through the top, integrated beside the pressures (the two agree to the
    integrator's tolerance), and 'ponded', whether the top takes less than the rain then (False
    without rain)."""
    from scipy.integrate import solve_ivp
    from scipy.sparse import bmat, csr_matrix, diags

    mat = doc["materials"][0]
    liquid = doc["fluids"]["liquid"]
    n, kappa = mat["porosity"], mat["intrinsic_permeability"]
    p0, lam = mat["retention"]["p0"], mat["retention"]["lambda"]
    rho0, k_l, mu = liquid["density"], liquid["bulk_modulus"], liquid["viscosity"]
    g = -doc["gravity"][-1]
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

    def top_inflow(t, p_top):
        """What enters through the top [kg/(m^2 s)], and whether the top is held there."""
        pf = face_pressure(t) if rain is None else 0.0
        k_top = 0.5 * (conductivity(np.array([p_top]))[0] + conductivity(np.array([pf]))[0])
        held = k_top * ((pf - p_top) / (dx / 2) + rho0 * g)
        if rain is None:
            return held, False
        return min(rain, held), held < rain

    def rate(t, y):  # cells bottom (0) to top, x upward; q: upward mass flux; y[-1]: water in
        p = y[:-1]
        k = conductivity(p)
        q = -0.5 * (k[1:] + k[:-1]) * ((p[1:] - p[:-1]) / dx + rho0 * g)
        q_in = top_inflow(t, p[-1])[0]
        div = np.zeros(cells)
        div[:-1] += q
        div[1:] -= q
        div[-1] -= q_in
        return np.append(-div / dx / storage(p), q_in)

    def jacobian(t, y):
        # Tridiagonal by finite differences, three column groups (j mod 3) per evaluation; the
        # last row and column (the water in) from the top cell alone.
        f0 = rate(t, y)
        h = 1e-6 * np.maximum(np.abs(y), 1.0)
        bands = np.zeros((3, cells))  # sub-, main and super-diagonal entries by column
        last = np.zeros(cells)        # d(water in rate)/dp
        for grp in range(3):
            z = y.copy()
            z[grp:cells:3] += h[grp:cells:3]
            df = rate(t, z) - f0
            for j in range(grp, cells, 3):
                for i in range(max(j - 1, 0), min(j + 2, cells)):
                    bands[i - j + 1, j] = df[i] / h[j]
                if j == cells - 1:
                    last[j] = df[-1] / h[j]
        inner = diags([bands[2, :-1], bands[1], bands[0, 1:]], [-1, 0, 1])
        return bmat([[inner, csr_matrix((cells, 1))],
                     [csr_matrix(last), csr_matrix((1, 1))]], format="csc")

    y0 = np.append(np.full(cells, -float(s0)), 0.0)
    atol = np.append(np.full(cells, 1.0), 1e-10)
    sol = solve_ivp(rate, (0.0, max(times)), y0, method="BDF", jac=jacobian, rtol=1e-7,
                    atol=atol, t_eval=[0.0] + list(times))
    if not sol.success:
        raise RuntimeError(f"the Richards reference failed: {sol.message}")
    held = [water(sol.y[:-1, k]).sum() * dx for k in range(sol.y.shape[1])]
    return {"in": [h - held[0] for h in held[1:]],
            "counted": [float(v) for v in sol.y[-1, 1:]],
            "ponded": [bool(top_inflow(t, sol.y[-2, k + 1])[1]) for k, t in enumerate(times)]}
