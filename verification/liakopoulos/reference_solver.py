#!/usr/bin/python3
"""Independent reference solutions of Liakopoulos's drainage test (README.md, reference/SOURCES.md).

A 1 m column, initially saturated at P = 0 (gauge), drains through its base (P = 0 there from
t = 0+); no water flux through the top. z upward from the base, gravity g downward. Pressures are
gauge, compression positive (suction s = max(-P, 0)). The curves are the exact closed forms of
make_curves.py, not the case's tables:
    S(P)  = max(1 - 1.9722e-11 s^2.4279, 0.2),       k_rw(S) = max(1 - 2.207 (1 - S)^1.0121, 0).

Model (a), `rigid`: Richards' equation on a rigid skeleton, gas at atmospheric pressure (what the
main cycle solves with `skeleton: rigid`), in mass form with the program's liquid density law
rho(P) = rho_0 exp(P / K_l) (physics/fluids.hpp) in the storage and in the flux:
    d(n S rho)/dt = n (rho' S + rho S') dP/dt = -dJ/dz,   J = -rho (kappa k_rw / mu) (dP/dz + rho g).
Model (b), `mechanics`: OpenGeoSys's RICHARDS_MECHANICS as its liakopoulos_QN.prj sets it up:
Biot coefficient 1, incompressible grains, Bishop's chi = S, porosity constant in the storage,
rho(P) = rho_0 (1 + P / K_l) (OGS's linear law), an oedometric linear-elastic skeleton of
constrained modulus M = E (1 - nu) / ((1 + nu)(1 - 2 nu)) under a total vertical stress constant
in time. The compressive vertical strain is then eps = -(S P) / M (Bishop's effective stress
sigma' = sigma + S P, tension positive), and the mass balance rho [n (S/K + S') dP/dt - S deps/dt]
= -dJ/dz becomes
    rho [n (S / K_l + S') + S (S + P S') / M] dP/dt = -dJ/dz.
Left out of (b), as in the brief: the change of the total stress as the column's water weight
drops (OGS's body force follows n S rho), and the grains' bulk modulus of 1e12 Pa.

Space: vertex-centred finite volumes (lumped linear elements), nodes z_i = i h, i = 0..N, node 0
held at P = 0, the top node's control volume h / 2; face values of rho and k_rw are the means of
the two nodes. Time: scipy's BDF (method of lines), rtol 1e-8, the tridiagonal sparsity given.
The cumulative outflow through the base, integral of -J(z = h/2) dt [kg/m^2], is integrated as an
extra unknown; the mass balance compares it with the loss of stored water (`--check`).

Usage: reference_solver.py            write reference/*.csv (both K_l of (a), and (b))
       reference_solver.py --check    also: convergence (2N cells, rtol / 2) and mass balance
"""
import argparse
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import yaml
from scipy.integrate import solve_ivp
from scipy.sparse import diags

HERE = Path(__file__).resolve().parent
CASE = yaml.safe_load((HERE / "case.yaml").read_text())
MAT, LIQ = CASE["materials"][0], CASE["fluids"]["liquid"]
N_POR = float(MAT["porosity"])
KAPPA = float(MAT["intrinsic_permeability"])
MU = float(LIQ["viscosity"])
RHO0 = float(LIQ["density"])
K_CASE = float(LIQ["bulk_modulus"])
G = abs(float(CASE["gravity"][0]))
H = float(CASE["grid"]["size"][0])
E, NU = float(MAT["young_modulus"]), float(MAT["poisson_ratio"])
M_OED = E * (1 - NU) / ((1 + NU) * (1 - 2 * NU))
A_RET, B_RET, S_RES = 1.9722e-11, 2.4279, 0.2
S_CAP = ((1 - S_RES) / A_RET) ** (1 / B_RET)  # suction where S reaches 0.2

PROFILE_TIMES = [300.0, 600.0, 1200.0, 1800.0, 3600.0, 7200.0]  # 5, 10, 20, 30, 60, 120 min
OGS_TIMES = [300.0, 600.0, 1200.0, 2400.0, 4800.0, 7200.0]      # OGS RM's stored results
HISTORY = np.arange(0.0, 7200.0 + 1e-9, 60.0)


def saturation(p):
    s = np.clip(-p, 0.0, S_CAP)
    return 1.0 - A_RET * s ** B_RET


def d_saturation(p):
    """dS/dP (= -dS/ds), >= 0."""
    s = -p
    inside = (s > 0) & (s < S_CAP)
    return np.where(inside, A_RET * B_RET * np.abs(s) ** (B_RET - 1), 0.0)


def k_rel(sat):
    return np.clip(1.0 - 2.207 * np.clip(1.0 - sat, 0.0, None) ** 1.0121, 0.0, 1.0)


class Column:
    """The discrete column of one model: `rigid` (a) or `mechanics` (b), N cells, K_l."""

    def __init__(self, model, cells, k_l):
        self.model, self.n, self.k_l = model, cells, k_l
        self.h = H / cells
        self.z = np.linspace(0.0, H, cells + 1)
        self.vol = np.full(cells, self.h)  # control volumes of nodes 1..N
        self.vol[-1] = self.h / 2

    def rho(self, p):
        if self.model == "rigid":
            return RHO0 * np.exp(p / self.k_l)
        return RHO0 * (1.0 + p / self.k_l)

    def storage(self, p):
        """d(stored mass)/dP per unit volume [kg/m^3/Pa]."""
        rho, sat, ds = self.rho(p), saturation(p), d_saturation(p)
        d_rho = rho / self.k_l if self.model == "rigid" else RHO0 / self.k_l
        c = N_POR * (d_rho * sat + rho * ds)
        if self.model == "mechanics":
            c = c + rho * sat * (sat + p * ds) / M_OED
        return c

    def fluxes(self, p_nodes):
        """Upward mass flux J at the N faces i + 1/2, i = 0..N-1 [kg/m^2/s]."""
        rho = self.rho(p_nodes)
        kr = k_rel(saturation(p_nodes))
        rho_f = 0.5 * (rho[1:] + rho[:-1])
        kr_f = 0.5 * (kr[1:] + kr[:-1])
        return -rho_f * KAPPA * kr_f / MU * (np.diff(p_nodes) / self.h + rho_f * G)

    def rhs(self, _t, y):
        p = np.concatenate([[0.0], y[:-1]])
        j = self.fluxes(p)
        div = j - np.concatenate([j[1:], [0.0]])  # in at i - 1/2 minus out at i + 1/2
        dp = div / (self.vol * self.storage(p[1:]))
        return np.concatenate([dp, [-j[0]]])

    def stored_change(self, p):
        """Stored water (per m^2) minus its initial value, exactly for the storage above."""
        if self.model == "rigid":
            w = N_POR * (saturation(p) * self.rho(p) - RHO0)
        else:  # integral of the storage from 0 to P, Gauss-Legendre (smooth integrand)
            x, wq = np.polynomial.legendre.leggauss(64)
            pq = 0.5 * p[:, None] * (x[None, :] + 1.0)
            w = 0.5 * p * (self.storage(pq) * wq[None, :]).sum(axis=1)
        return float(np.sum(self.vol * w))

    def solve(self, rtol=1e-8, times=PROFILE_TIMES):
        sparsity = diags([1, 1, 1], [-1, 0, 1], shape=(self.n + 1, self.n + 1)).tolil()
        sparsity[self.n, 0] = 1
        y0 = np.zeros(self.n + 1)
        t_eval = np.union1d(HISTORY, times)
        with warnings.catch_warnings():  # scipy's difference quotients of the outflow's
            warnings.simplefilter("ignore", RuntimeWarning)  # empty column overflow harmlessly
            sol = solve_ivp(self.rhs, (0.0, 7200.0), y0, method="BDF", t_eval=t_eval, rtol=rtol,
                            atol=np.concatenate([np.full(self.n, 1e-6), [1e-10]]),
                            jac_sparsity=sparsity.tocsr(), first_step=1e-6)
        if not sol.success:
            raise RuntimeError(sol.message)
        p = np.vstack([np.zeros(len(sol.t)), sol.y[:-1]])
        return {"t": sol.t, "p": p, "outflow": sol.y[-1], "nfev": sol.nfev}


def profiles_at(result, times):
    idx = [int(np.argmin(np.abs(result["t"] - t))) for t in times]
    return result["p"][:, idx]


def write_profiles(path, z, times, p):
    cols = ["height_m"] + [f"p_l_{t:04.0f}s_Pa" for t in times] + [f"s_l_{t:04.0f}s" for t in times]
    data = np.column_stack([z, p, saturation(p)])
    fmt = ["%.5f"] + ["%.4f"] * len(times) + ["%.10f"] * len(times)
    np.savetxt(path, data, delimiter=",", header=",".join(cols), comments="", fmt=fmt)


def write_outflow(path, result):
    keep = np.isin(result["t"], HISTORY)
    np.savetxt(path, np.column_stack([result["t"][keep], result["outflow"][keep]]), delimiter=",",
               header="time_s,outflow_kg_per_m2", comments="", fmt=["%.1f", "%.9f"])


def k_label(k_l):
    mant, exp = f"{k_l:.0e}".split("e")
    return f"K{mant}e{int(exp)}"


def generate(cells=400, rtol=1e-8):
    runs = {}
    for k_l in (K_CASE, 2.0e7):
        t0 = time.time()
        col = Column("rigid", cells, k_l)
        res = col.solve(rtol)
        name = f"richards_rigid_{k_label(k_l)}"
        write_profiles(HERE / "reference" / f"{name}.csv", col.z, PROFILE_TIMES,
                       profiles_at(res, PROFILE_TIMES))
        write_outflow(HERE / "reference" / f"{name}_outflow.csv", res)
        print(f"{name}: {time.time() - t0:.1f} s, {res['nfev']} rhs evaluations")
        runs[name] = (col, res)
    t0 = time.time()
    col = Column("mechanics", cells, K_CASE)
    res = col.solve(rtol, OGS_TIMES)
    write_profiles(HERE / "reference" / "richards_mechanics.csv", col.z, OGS_TIMES,
                   profiles_at(res, OGS_TIMES))
    write_outflow(HERE / "reference" / "richards_mechanics_outflow.csv", res)
    print(f"richards_mechanics: {time.time() - t0:.1f} s, {res['nfev']} rhs evaluations")
    runs["richards_mechanics"] = (col, res)
    return runs


def check(runs, cells=400, rtol=1e-8):
    """Convergence: the same model on 2N cells with rtol / 2, compared at the common nodes;
    mass balance: outflow + change of stored water, relative to the outflow."""
    for name, (col, res) in runs.items():
        times = OGS_TIMES if col.model == "mechanics" else PROFILE_TIMES
        fine_col = Column(col.model, 2 * cells, col.k_l)
        fine = fine_col.solve(rtol / 2, times)
        pc, pf = profiles_at(res, times), profiles_at(fine, times)[::2]
        top = np.abs(pc[-1])
        dp = np.abs(pc - pf).max(axis=0) / top
        q_c, q_f = res["outflow"][np.isin(res["t"], times)], fine["outflow"][np.isin(fine["t"], times)]
        print(f"{name}: N = {cells} vs {2 * cells}, rtol {rtol:g} vs {rtol / 2:g}:")
        print("  max |dP| / |P_top| at " + ", ".join(f"{t:g} s: {d:.1e}" for t, d in zip(times, dp)))
        print("  |d outflow| / outflow: " + ", ".join(f"{abs(a - b) / b:.1e}" for a, b in zip(q_c, q_f)))
        worst = max(abs(q + col.stored_change(res["p"][1:, k])) / q
                    for k, q in enumerate(res["outflow"]) if res["t"][k] >= 60.0)
        print(f"  mass balance: max |outflow + change of stored water| / outflow = {worst:.1e}")
        print(f"  outflow at 7200 s: {res['outflow'][-1]:.6f} kg/m^2, P_top: "
              + ", ".join(f"{p:.1f}" for p in pc[-1]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cells", type=int, default=400)
    ap.add_argument("--check", action="store_true", help="convergence and mass balance")
    args = ap.parse_args()
    runs = generate(args.cells)
    if args.check:
        check(runs, args.cells)
    return 0


if __name__ == "__main__":
    sys.exit(main())
