"""The elastic follower: a cycle driven through a spring-mass-damper (natural frequency f_n in Hz,
damping ratio ζ) at a speed — the tracking error and the residual vibration in the dwells.
"""

from __future__ import annotations

from os import PathLike
from pathlib import Path
from typing import Any, Dict

from . import _loomkin as _m
from ._fields import default as _default
from ._table import Shard, Table
from .cycles import _cycle

__all__ = ["response", "sweep", "spectrum", "compensate", "optimize", "two_mass"]


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


def sweep(cycle: Any, speed_rpm: Any, natural_hz: float, shard: Shard = None, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn sweep FILE --speed-rpm … --natural-hz F --json`` at the speeds of an array
    (rpm): natural_hz, damping_ratio, start and ``points``, a :class:`Table` with the CLI's
    columns (speed_rpm, the residual vibration and peak error in the cycle's units, …).
    Keywords as :func:`response` (without speed_rpm, cycles, points). ``shard=(i, n)`` computes
    only shard i of n of the speeds (``--shard i/n``)."""
    r = _m.dyn_sweep(_cycle(cycle), speed_rpm, float(natural_hz), shard=shard, **kw)
    r["points"] = Table(r["points"])
    return r


def spectrum(laws: Any, ratio: Any = None, damping_ratio: Any = _default("Follower::DAMPING_RATIO")) -> Table:
    """``loomkin dyn spectrum LAW … --csv``: the residual vibration a rise leaves, in % of the
    stroke, against the ratio of motion time to natural period T·f_n (dimensionless).

    ``laws``: one or a list of catalogue names (``"cycloidal"``, ``"NAME:KEY=VALUE"`` as the CLI
    takes them), :class:`loomkin.Law` objects, or cycles (a :class:`loomkin.Cycle`, a TOML path
    ending in ``.toml`` or a dict: each of its rises and returns). ``ratio``: an array of ratios
    (each 0 < r < 1e4; default the CLI's 0.5:10:0.01). ``damping_ratio``: one ζ or a list
    (0 ≤ ζ < 1). Returns a :class:`Table`: ``motion_time_over_natural_period`` and one column
    ``residual_pct_of_stroke_<key>_zeta_<ζ>`` per law and ζ, the key the law's name with the parameters
    given (``modified-trapezoid_ramp_0.2``) or, for a cycle, ``<file stem>_<law>_seg<i>`` (``cycle_…`` for a
    Cycle object or a dict); a key
    given twice gets ``_2``, ``_3``, … (the CLI's ``--csv`` columns).
    Runs with the GIL released; Ctrl-C stops it."""
    import numpy as np

    from ._loomkin import Law

    if ratio is None:
        ratio = _m.dyn_default_ratios()
    ratio = np.ascontiguousarray(ratio, dtype=np.float64)
    zetas = list(damping_ratio) if isinstance(damping_ratio, (list, tuple, np.ndarray)) else [damping_ratio]
    items = laws if isinstance(laws, (list, tuple)) else [laws]
    # The CLI's column keys: the law's name with the parameters given (`modified-trapezoid_ramp_0.2`),
    # or the cycle file's name and the segment (`sley-cycle_cycloidal_seg1`); a key given twice gets
    # `_2`, `_3`, … (`loomkin dyn spectrum --csv`).
    named = []
    for item in items:
        if isinstance(item, Law):
            named.append((item.name, item))
        elif isinstance(item, str) and not item.endswith(".toml"):
            name, _, kv = item.partition(":")
            params = {}
            if kv:
                k, _, v = kv.partition("=")
                params[k.strip()] = v.strip()
            law = Law(name, **params)
            named.append((law.name + "".join(f"_{k}_{v}" for k, v in params.items()), law))
        else:
            # A cycle given as an object or a dict has no file name: `cycle`.
            stem = Path(item).stem if isinstance(item, (str, PathLike)) else "cycle"
            for i, law in _cycle(item).laws():
                named.append((f"{stem}_{law.name}_seg{i}", law))
    seen: Dict[str, int] = {}
    for j, (key, law) in enumerate(named):
        seen[key] = seen.get(key, 0) + 1
        if seen[key] > 1:
            named[j] = (f"{key}_{seen[key]}", law)
    cols = {"motion_time_over_natural_period": ratio}
    for key, law in named:
        for z in zetas:
            cols[f"residual_pct_of_stroke_{key}_zeta_{_compact(float(z))}"] = _m.dyn_spectrum(law, ratio, float(z))
    return Table(cols)


def _compact(x: float) -> str:
    """A number as the CLI names it in a column (shortest round-trip form, no trailing .0)."""
    r = float(f"{x:.11e}") + 0.0
    s = repr(r)
    return s[:-2] if s.endswith(".0") else s


def compensate(cycle: Any, natural_hz: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn compensate FILE --natural-hz F``: the input law (polydyne) that makes the
    follower (natural_hz in Hz, damping_ratio, optional mass_kg …) follow the cycle exactly.

    designed_class, input_class (continuity: the highest continuous derivative), period_s (s),
    speed_rpm, ``pieces`` (the ``.toml`` output: t0 and duration in s, from_deg, to_deg, poly: SI
    coefficients of t^k, t in s from the piece's start; sine [b_s, b_c, Ω in rad/s] or None; exp
    [C, a in 1/s] or None) and ``samples`` (the ``.csv`` output, a :class:`Table`): angle_deg,
    x_mm (designed), s_mm (input), s_velocity_m_s, s_acceleration_m_s2 (or the deg, rad/s forms).
    Keywords: damping_ratio, mass_kg, return_spring_n_m, preload_n, weight, force_n, speed_rpm,
    points. A cycle whose input would jump raises :class:`loomkin.LoomkinError` (field cycle)."""
    r = _m.dyn_compensate(_cycle(cycle), float(natural_hz), **kw)
    r["samples"] = Table(r["samples"])
    return r


def optimize(cycle: Any, natural_hz: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn optimize FILE --natural-hz F --json``: every rise and return reshaped for the
    least residual vibration across ``speed_rpm·(1 ± band_pct/100)`` (rpm, %), peak acceleration
    at most 110 % of the modified sine's. The report (residual amplitudes in the cycle's unit,
    improvement_factor, peak_acceleration_ratio, per-segment figures) and ``cycle_toml``, the
    optimised cycle file (``loomkin.cycles.Cycle.from_toml`` reads it). Keywords as
    :func:`response` plus band_pct (default 10). Takes seconds with the GIL released; Ctrl-C
    returns at once."""
    return _m.dyn_optimize(_cycle(cycle), float(natural_hz), **kw)


def two_mass(cycle: Any, drive_mass_kg: float, drive_stiffness_n_m: float, frame_mass_kg: float,
             frame_stiffness_n_m: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin dyn two-mass FILE --json``: the cycle drives the drive's output mass (kg) through
    a stiffness (N/m), which drives the heald frame (kg) through the frame stiffness (N/m).
    natural_hz (both modes, Hz), peak_drive_error and peak_frame_error in the cycle's unit with
    where (deg), frame_residual_bound (dwells), rigidity_ratio (f₁/f_shaft). Keywords:
    damping_ratio (both modes), speed_rpm, steady."""
    return _m.dyn_two_mass(_cycle(cycle), float(drive_mass_kg), float(drive_stiffness_n_m), float(frame_mass_kg),
                           float(frame_stiffness_n_m), **kw)
