#!/usr/bin/python3
"""Prints the Del Monte sand's curves of Liakopoulos's test as the case file's tables (README.md).

Retention (Liakopoulos 1965, as fitted in Lewis & Schrefler 1998 and Schrefler & Scotta 2001):
    S_w = 1 - 1.9722e-11 s^2.4279        (s the suction [Pa])
down to S_w = 0.2 (s = 23.4 kPa), held below; relative permeabilities against
S_e = (S_w - 0.2) / 0.8 (S_res = 0.2, so S_e is the program's effective saturation):
    k_rw = max(1 - 2.207 (1 - S_w)^1.0121, 0)
    k_rg = max((1 - S_e)^2 (1 - S_e^(5/3)), 1e-4)   (Brooks-Corey with lambda = 3, floored)
Suctions are sampled geometrically (the retention curve is flat near 0 and steep beyond 5 kPa).
"""
import numpy as np

S_END = (0.8 / 1.9722e-11) ** (1 / 2.4279)


def rows(x, y):
    return ", ".join(f"[{a:.6g}, {b:.6g}]" for a, b in zip(x, y))


s = np.concatenate([[0.0], np.geomspace(500.0, S_END, 30)])
sw = np.maximum(1.0 - 1.9722e-11 * s ** 2.4279, 0.2)
sw[-1] = 0.2
se = np.linspace(0.0, 1.0, 26)
krw = np.clip(1.0 - 2.207 * (1.0 - (0.2 + 0.8 * se)) ** 1.0121, 0.0, 1.0)
krg = np.maximum((1.0 - se) ** 2 * (1.0 - se ** (5.0 / 3.0)), 1e-4)
print("    retention: {model: table, points: [" + rows(s, sw) + "]}")
print("    liquid_relative_permeability: {model: table, points: [" + rows(se, krw) + "]}")
print("    gas_relative_permeability: {model: table, points: [" + rows(se, krg) + "]}")
