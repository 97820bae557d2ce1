"""Reference for crates/dynamics/tests/cases/ode.rs `rise_residual_matches_quadrature`.

An undamped follower (199 Hz) under a poly4567 rise of 80 mm over 53 deg at 71 rpm (T = 53/426 s), from
rest: y'' + w^2 y = -a(t). Duhamel's integral at 40 digits gives the state at the end of the rise.
Run: python3 scripts/rise_residual_quadrature.py (needs mpmath).
"""
from mpmath import mp, mpf, quad, sin, cos, pi, linspace

mp.dps = 40
S = mpf("0.08")
T = mpf(53) / 426
w = 2 * pi * 199


def accel(t):
    x = t / T
    return S / T**2 * (420 * x**2 - 1680 * x**3 + 2100 * x**4 - 840 * x**5)


nodes = linspace(0, T, 200)
y_end = quad(lambda u: -accel(u) * sin(w * (T - u)) / w, nodes)
v_end = quad(lambda u: -accel(u) * cos(w * (T - u)), nodes)
print(mp.nstr(y_end, 20), mp.nstr(v_end, 20))
