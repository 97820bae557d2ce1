"""Servo motion functions from definition points (Sivčák 2017): the spline law, motor torque of a
drive, optimisation of the points and the controller exports.

``def_points`` is ``"X:Y,X:Y,…"`` or a sequence of (x, y) pairs (None: the CLI's default, the
sine-shaped start). ``drive`` is None (the built-in needle-rack drive), a path to a drive file
(TOML or JSON) or a dict with the drive's keys. Speeds in rpm of the main shaft; torque in N·m,
power in W, rack motion in m, m/s, m/s².
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, Optional, Sequence, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._fields import speeds as _default_speeds
from ._inputs import PathOrDict, study_text, text_of
from ._loomkin import Law
from ._table import Table

__all__ = ["spline_law", "law", "torque", "torque_curve", "optimize", "export", "check", "EXPORT_FORMATS"]

if TYPE_CHECKING:
    from .cams import CycleLike

DefPoints = Union[str, Sequence[Sequence[float]], None]

#: The formats of :func:`export` (``loomkin servo export --format``).
EXPORT_FORMATS = ("coeffs", "json", "csv", "xyva", "poly5", "cycle")


def _drive(drive: Optional[PathOrDict]) -> Optional[str]:
    # A dict of the drive's keys is the file's [drive] table.
    if isinstance(drive, dict) and "drive" not in drive:
        drive = {"drive": drive}
    return text_of(drive)


def _speeds(speed_rpm: Union[float, Sequence[float]]) -> list:
    if isinstance(speed_rpm, (int, float)):
        return [float(speed_rpm)]
    return [float(s) for s in speed_rpm]


def spline_law(def_points: DefPoints = None, end: str = "natural") -> Law:
    """The servo law through the definition points as a :class:`loomkin.Law` (unit stroke on
    x = 0…1): metrics, continuity, samples. ``end``: "natural" or "clamped"."""
    return _m.servo_spline_law(def_points, end)


def law(def_points: DefPoints = None, end: str = "natural") -> Dict[str, Any]:
    """``loomkin servo law --json``: def_points, d, d_unit, scale, metrics (dimensionless),
    continuity_class, intervals, spline_b."""
    return _m.servo_law(def_points, end)


def torque(speed_rpm: Union[float, Sequence[float]] = tuple(_default_speeds("TORQUE")), def_points: DefPoints = None,
           end: str = "natural", drive: Optional[PathOrDict] = None) -> Dict[str, Any]:
    """``loomkin servo torque --json``: def_points, drive (with layout_deg) and per speed the peak
    and RMS motor torque (N·m), the angle of the peak (deg), peak power (W), peak rack velocity
    (m/s) and acceleration (m/s²), peak motor speed (rpm), rise and cycle time (s)."""
    return _m.servo_torque(_speeds(speed_rpm), def_points, end, _drive(drive))


def torque_curve(speed_rpm: float = _default_speeds("DESIGN")[0], points: int = _default("ServoInputs::CURVE_POINTS"), def_points: DefPoints = None,
                 end: str = "natural", drive: Optional[PathOrDict] = None) -> Table:
    """The drive over one turn: angle_deg, time_s, u_m, v_m_s, a_m_s2, torque_nm, power_w (arrays)
    and phase (a list of rise / dwell-after-rise / return / dwell-after-return)."""
    return Table(_m.servo_torque_curve(float(speed_rpm), points, def_points, end, _drive(drive)))


def optimize(speed_rpm: Union[float, Sequence[float]] = tuple(_default_speeds("DESIGN")), objective: str = "peak",
             starts: int = _default("ServoInputs::STARTS"),
             fixed_x: bool = False, def_points: DefPoints = None, end: str = "natural",
             drive: Optional[PathOrDict] = None) -> Dict[str, Any]:
    """``loomkin servo optimize --json``: least worst peak (or "rms") motor torque over the
    speeds; before, after (N·m), the optimised def_points and def text, evaluations. Deterministic.
    The GIL is released while it runs; Ctrl-C (a notebook's interrupt) stops it with KeyboardInterrupt."""
    return _m.servo_optimize(_speeds(speed_rpm), objective, starts, fixed_x, def_points, end, _drive(drive))


def export(format: str, step_deg: float = _default("ServoInputs::EXPORT_STEP_DEG"), def_points: DefPoints = None, end: str = "natural",
           drive: Optional[PathOrDict] = None) -> Dict[str, Any]:
    """``loomkin servo export --format F``: text (the file's content; the cam tables csv, xyva and
    poly5 are those of :func:`loomkin.cams.table` on the drive's turn, in mm), filename, media_type; for
    the cam tables (csv, xyva) also points, step_deg (deg) and reinterpolation (worst errors of
    linear, cubic-spline and quintic-Hermite re-interpolation: m, m/deg, m/deg², relative; the
    same rows also as interpolation, the workbench API's key, each row naming its mode as
    interpolation and as mode)."""
    return _m.servo_export(format, float(step_deg), def_points, end, _drive(drive))


def check(axis: PathOrDict, cycle: Optional["CycleLike"] = None, *, speed_rpm: Optional[float] = None,
          law: Optional[str] = None, params: Optional[Dict[str, Union[float, str]]] = None,
          stroke_mm: Optional[float] = None, stroke_deg: Optional[float] = None,
          motion_deg: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin servo check AXIS --cycle CYCLE --json``: a servo axis moving a cycle.

    ``axis``: the axis file (a path, or a dict of its tables: ``motor`` with rated_torque_nm,
    peak_torque_nm, rated_speed_rpm, max_speed_rpm, rotor_inertia_kg_m2; ``load`` with
    moving_mass_kg and travel_mm_per_rev, or load_inertia_kg_m2 and gear_ratio, and the friction,
    spring and force keys; optional ``limits`` with max_inertia_ratio). ``cycle``: a
    :class:`loomkin.Cycle`, a path or a dict; or ``cycle=None`` and ``law`` (``params``),
    ``stroke_mm`` or ``stroke_deg`` and ``motion_deg``: the rise, dwell, return, dwell of
    :func:`loomkin.cams.rise_return`, as ``--law`` does. ``speed_rpm``: given here, else the
    cycle's, else 300 rpm.

    Returns speed_rpm, cycle_time_s, the peak motor torque (N·m) and where (deg), the RMS torque,
    the peak motor speed (rpm) and where, the envelope ratio (|T| over the peak-torque line) and
    where, the inertia ratio, ``checks`` (name, value, limit, unit, margin, pass) and ``pass``."""
    from .cams import _usage, rise_return
    from .cycles import _cycle

    if cycle is None:
        c = rise_return(law if law is not None else "cycloidal", params, stroke_mm=stroke_mm,
                        stroke_deg=stroke_deg, motion_deg=motion_deg)
    elif law is not None:
        raise _usage("law", "give a cycle or a law, not both")
    else:
        c = _cycle(cycle)
    return _m.servo_check(study_text(axis), c, None if speed_rpm is None else float(speed_rpm))
