"""V3b: first mode of an elastic bar fixed at x = 0 and free at x = L.

Closed form: u(x, t) = (v0 / omega) sin(beta x) sin(omega t), beta = pi / (2 L), omega = beta c,
c = sqrt(E / rho); period 4 L / c.

Tolerances, set from what the method can do before the runs were looked at: lumped-mass linear
elements shift the frequency by about (beta h)^2 / 24 (4e-5 here) and the symplectic Euler-Cromer
step by about (omega dt)^2 / 24 (1e-5), so the period is held to 0.5 %. Without damping the scheme
keeps the energy of a linear oscillator, so every period's amplitude is held to 1 % of the closed
form (material points sample the mode shape, and FLIP adds no dissipation).
"""
import numpy as np

from pathlib import Path

from common import body_height, case_doc, read_csv, read_points, series

_CASE = case_doc(Path(__file__).parent)
L = body_height(_CASE)
E = float(_CASE["materials"][0]["young_modulus"])
RHO = float(_CASE["materials"][0]["density"])
V0 = float(_CASE["bodies"][0]["initial_velocity"]["sine"]["amplitude"][0])
C = np.sqrt(E / RHO)
BETA = np.pi / (2 * L)
OMEGA = BETA * C


def upward_zero_crossings(t, u):
    i = np.where((u[:-1] < 0) & (u[1:] >= 0))[0]
    return t[i] - u[i] * (t[i + 1] - t[i]) / (u[i + 1] - u[i])


def evaluate(run_dirs):
    run_dir = run_dirs["run"]
    x0, a0 = read_points(series(run_dir)[0][1])
    h = read_csv(run_dir / "control_points.csv")
    t, u = h["time"], h["tip_displacement_x"]
    # The tracked point is the one nearest x = L at t = 0: the largest x of the bar.
    xp = float(x0[:, 0].max())
    amp_exact = V0 / OMEGA * np.sin(BETA * xp)
    period_exact = 2 * np.pi / OMEGA
    crossings = upward_zero_crossings(t, u)
    period = float(np.mean(np.diff(crossings)))
    amps = [np.abs(u[(t >= k * period_exact) & (t < (k + 1) * period_exact)]).max()
            for k in range(int(t[-1] / period_exact))]
    amp_err = float(np.max(np.abs(np.array(amps) / amp_exact - 1)))
    checks = [
        ("|period / (4 L / c) - 1|", abs(period / period_exact - 1), 0.005),
        ("max over periods |amplitude / closed form - 1|", amp_err, 0.01),
    ]
    return {"t": t, "u": u, "xp": xp, "amp": amp_exact, "period": period}, checks


def plot(data, out_dir):
    png = out_dir / "vibrating_bar.png"
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = data["t"]
    fig, ax = plt.subplots(figsize=(9, 4))
    ax.plot(t, data["amp"] * np.sin(OMEGA * t) * 1e3, "k-", lw=2, label="closed form")
    ax.plot(t, data["u"] * 1e3, "r--", label="MPM")
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"displacement at x = {data['xp']:.3f} m [mm]")
    ax.set_title(f"Vibrating bar, first mode: period {data['period']*1e3:.4f} ms "
                 f"(closed form {2e3*np.pi/OMEGA:.4f} ms)")
    ax.legend(loc="upper right")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)
    return [png.name]
