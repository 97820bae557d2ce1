"""The elastic follower: a cycle driven through a spring-mass-damper (natural frequency f_n in Hz,
damping ratio ζ) at a speed — the tracking error and the residual vibration in the dwells.
"""

from __future__ import annotations

from typing import Any, Dict

from . import _loomkin as _m
from ._table import Table
from .cycles import _cycle

__all__ = ["response", "sweep"]


def response(cycle: Any, natural_hz: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn response FILE --natural-hz F --json`` for a cycle (a :class:`loomkin.Cycle`,
    a TOML path or a dict). Keywords: damping_ratio, mass_kg, return_spring_n_m (N/m), preload_n,
    weight (bool), force_n (N), speed_rpm, cycles (from rest), steady (bool), points (per cycle).

    The report (summary, units, speed_rpm, natural_hz, damping_ratio, start, cycles) and
    ``samples``, a :class:`Table` of angle_deg, s_mm, x_mm, error_mm, a_m_s2 (or the deg and
    rad/s² forms for a swinging follower)."""
    r = _m.dyn_response(_cycle(cycle), float(natural_hz), **kw)
    r["samples"] = Table(r["samples"])
    return r


def sweep(cycle: Any, speed_rpm: Any, natural_hz: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn sweep FILE --speed-rpm … --natural-hz F --json`` at the speeds of an array
    (rpm): natural_hz, damping_ratio, start and ``points``, a :class:`Table` with the CLI's
    columns (speed_rpm, the residual vibration and peak error in the cycle's units, …).
    Keywords as :func:`response` (without speed_rpm, cycles, points)."""
    r = _m.dyn_sweep(_cycle(cycle), speed_rpm, float(natural_hz), **kw)
    r["points"] = Table(r["points"])
    return r
