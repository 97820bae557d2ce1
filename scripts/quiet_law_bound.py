"""What a quiet law can achieve at all: an independent bound for `loomkin dyn optimize`.

Issue 13 asks for a rise whose residual vibration, across +-10 % of the design speed, is at least ten
times below the modified sine's, with a peak acceleration within 10 % of the modified sine's. This script
finds the best any rise can do under that acceleration bound (and optionally a jerk bound), by linear
programming over piecewise-linear accelerations, so that the optimiser's figures can be read against
what is possible.

Model (normalised: stroke 1, motion time 1, natural frequency r = f_n * T): the relative coordinate
d = x - s obeys d'' + 2 z w d' + w^2 d = -a(u), w = 2 pi r, from rest at u = 0. After the rise the
residual amplitude is |D| with D = d(1) + i (d'(1) + z w d(1)) / w_d, linear in a. The LP minimises t
subject to Re(exp(i phi_k) D(r_j)) <= t for 24 directions phi_k (a 24-gon inside the circle, so t is
within cos(pi/24) of the modulus) and every band ratio r_j, |a| <= 1.1 * Ca(modified sine), a = 0 at
both ends, integral(a) = 0 (rest at the end) and integral((1 - u) a) = 1 (unit stroke).

Run: python3 scripts/quiet_law_bound.py   (needs numpy and scipy; not part of CI)
"""

import numpy as np
from scipy.optimize import linprog

N = 400  # fine quadrature grid
u = np.linspace(0.0, 1.0, N + 1)
du = 1.0 / N
wq = np.full(N + 1, du)
wq[0] = wq[-1] = du / 2


def modified_sine(x):
    if x <= 1 / 8:
        return np.sin(4 * np.pi * x)
    if x <= 7 / 8:
        return np.sin(4 * np.pi / 3 * (x - 1 / 8) + np.pi / 2)
    return -np.sin(4 * np.pi * (1 - x))


A_MS = np.array([modified_sine(x) for x in u])
A_MS /= np.sum(wq * (1 - u) * A_MS)  # unit stroke: Ca = 5.528


def residual_rows(r, z):
    w = 2 * np.pi * r
    wd = w * np.sqrt(1 - z * z)
    tau = 1 - u
    e = np.exp(-z * w * tau)
    h = e * np.sin(wd * tau) / wd
    hp = e * (wd * np.cos(wd * tau) - z * w * np.sin(wd * tau)) / wd
    d, dp = -(wq * h), -(wq * hp)
    return d, (dp + z * w * d) / wd


def residual(a, r, z):
    re, im = residual_rows(r, z)
    return np.hypot(re @ a, im @ a)


def best_ratio(lo, hi, z, pieces, jerk_factor=None):
    knots = np.linspace(0, 1, pieces + 1)
    interp = np.array([np.interp(u, knots, np.eye(pieces + 1)[k]) for k in range(pieces + 1)]).T
    band = np.linspace(lo, hi, 41)
    a_max = 1.1 * A_MS.max()
    nv = pieces + 2
    a_ub, b_ub = [], []
    for r in band:
        re, im = residual_rows(r, z)
        for phi in np.arange(24) * 2 * np.pi / 24:
            row = np.zeros(nv)
            row[:-1] = (np.cos(phi) * re + np.sin(phi) * im) @ interp
            row[-1] = -1
            a_ub.append(row)
            b_ub.append(0.0)
    if jerk_factor is not None:
        j_max = jerk_factor * np.max(np.abs(np.diff(A_MS) / du))
        for i in range(pieces):
            row = np.zeros(nv)
            row[i], row[i + 1] = -pieces, pieces
            a_ub += [row, -row]
            b_ub += [j_max, j_max]
    e0, e1 = np.zeros(nv), np.zeros(nv)
    e0[0], e1[pieces] = 1, 1
    a_eq = [np.r_[wq @ interp, 0], np.r_[(wq * (1 - u)) @ interp, 0], e0, e1]
    res = linprog(np.r_[np.zeros(pieces + 1), 1], A_ub=np.array(a_ub), b_ub=b_ub, A_eq=np.array(a_eq),
                  b_eq=[0, 1, 0, 0], bounds=[(-a_max, a_max)] * (pieces + 1) + [(0, None)], method="highs")
    a = interp @ res.x[:-1]
    ms = max(residual(A_MS, r, z) for r in band)
    best = max(residual(a, r, z) for r in band)
    return ms, best


if __name__ == "__main__":
    # The heald-frame example (f_n 54 Hz, 120 degree rise): T*f_n over +-10 % of 300, 450, 600 rpm.
    for rpm, lo, hi in [(600, 1.64, 2.0), (450, 2.18, 2.67), (300, 3.27, 4.0)]:
        for z in (0.05, 0.0):
            ms, best = best_ratio(lo, hi, z, 400)
            _, best16 = best_ratio(lo, hi, z, 16, 1.0)
            print(f"{rpm} rpm, zeta {z}: modified sine {ms:.4e}, best possible {best:.4e} "
                  f"(ratio {ms / best:.1f}); 16 pieces with jerk <= the modified sine's: ratio {ms / best16:.1f}")
