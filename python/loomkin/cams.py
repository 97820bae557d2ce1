"""From a law to a part: controller cam tables (``loomkin cam table``) and disc cam profiles
(``loomkin cam profile``) of a machine cycle, or of a single catalogue law.

Lengths are in mm, angles in degrees (main-shaft angle for the points), curvatures in 1/mm
(positive where convex), as the CLI's JSON keys say.
"""

from __future__ import annotations

import os
import warnings
from typing import Any, Dict, Mapping, Optional, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._table import Table
from .cycles import _cycle

__all__ = ["table", "profile", "rise_return", "FORMATS", "FOLLOWERS", "CLOSURES"]

#: The formats of :func:`table`.
FORMATS = ("xyvaj", "poly5", "csv", "twincat", "st", "xyva")
#: The followers of :func:`profile`.
FOLLOWERS = ("translating", "oscillating", "flat")
#: The closures of :func:`profile`.
CLOSURES = ("single", "conjugate", "groove")

CycleLike = Union["_m.Cycle", str, "os.PathLike[str]", Mapping[str, Any]]


def _usage(field: str, reason: str) -> Exception:
    e = _m.LoomkinError(f"{field}: {reason}")
    e.field, e.allowed = field, None
    return e


def _no_rise_with(params: Any, stroke_mm: Any, stroke_deg: Any, motion_deg: Any) -> None:
    """With a cycle the single-rise arguments have nothing to act on: refused, not ignored (as the
    CLI refuses ``--stroke-mm`` with a cycle file)."""
    for name, v in (("params", params), ("stroke_mm", stroke_mm), ("stroke_deg", stroke_deg),
                    ("motion_deg", motion_deg)):
        if v is not None:
            raise _usage(name, f"{name} describes a single rise (with law=…) and cannot be combined with a cycle "
                               "(the cycle sets the laws, strokes and angles)")


def _source(cycle: CycleLike) -> str:
    return "" if isinstance(cycle, (Mapping, _m.Cycle)) else os.fspath(cycle)


def rise_return(law: str = "cycloidal", params: Optional[Dict[str, Union[float, str]]] = None, *,
                stroke_mm: Optional[float] = None, stroke_deg: Optional[float] = None,
                motion_deg: Optional[float] = None) -> "_m.Cycle":
    """The cycle ``loomkin cam profile --law LAW --stroke-mm H --motion-deg B`` makes of a law: the
    rise over ``motion_deg`` (deg, at most 180), a dwell, the return by the same law and a dwell,
    over one turn. The stroke in mm (translating follower) or ``stroke_deg`` in deg (swinging)."""
    return _m.rise_return_cycle(law, params, stroke_mm, stroke_deg, motion_deg)


def table(cycle: Optional[CycleLike], format: str, step_deg: Optional[float] = None,
          tolerance: Optional[float] = None, *, law: Optional[str] = None,
          params: Optional[Dict[str, Union[float, str]]] = None, stroke_mm: Optional[float] = None,
          stroke_deg: Optional[float] = None, motion_deg: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin cam table CYCLE --format F --json`` and its file: ``text`` (the table as the CLI
    writes it), points, unit, spacing, the exact re-interpolation errors (slave unit per deg^k)
    and the decimals written. ``step_deg`` (default 1°) or ``tolerance`` (slave unit: mm or deg).

    With ``cycle=None`` and ``law`` (a catalogue name, ``params`` its parameters): a single rise of
    ``stroke_mm`` (mm) or ``stroke_deg`` (deg) over ``motion_deg`` (deg), as
    ``loomkin cam table --law LAW --stroke-mm H --motion-deg B``."""
    if cycle is None:
        name = law if law is not None else "cycloidal"
        return _m.cam_table(None, format, step_deg, tolerance, f"law {name}", name, params, stroke_mm,
                            stroke_deg, motion_deg)
    if law is not None:
        raise _usage("law", "give a cycle or a law, not both")
    _no_rise_with(params, stroke_mm, stroke_deg, motion_deg)
    return _m.cam_table(_cycle(cycle), format, step_deg, tolerance, _source(cycle))


def _points(r: Dict[str, Any]) -> Dict[str, Any]:
    r["points"] = Table(r["points"])
    if "counter_points" in r:
        r["counter_points"] = Table(r["counter_points"])
    return r


def profile(cycle: Optional[CycleLike] = None, follower: str = "translating", *,
            prime_radius_mm: Optional[float] = None, max_pressure_deg: Optional[float] = None,
            roller_radius_mm: float = _default("CamDesign::ROLLER_RADIUS_MM"),
            offset_mm: float = _default("CamDesign::OFFSET_MM"), arm_mm: Optional[float] = None,
            pivot_mm: Optional[float] = None, closure: str = "single",
            step_deg: float = _default("CamProfile::STEP_DEG"), dxf: bool = False,
            chord_tol_mm: float = _default("CamProfile::CHORD_TOL_MM"), bore_mm: Optional[float] = None,
            law: Optional[str] = None, params: Optional[Dict[str, Union[float, str]]] = None,
            stroke_mm: Optional[float] = None, stroke_deg: Optional[float] = None,
            motion_deg: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin cam profile CYCLE --follower F … --json``: a disc cam for the cycle.

    ``follower``: ``"translating"`` (roller; ``offset_mm`` the offset of its line of motion, mm),
    ``"oscillating"`` (roller on an arm of ``arm_mm`` pivoted ``pivot_mm`` from the cam centre;
    the cycle in deg) or ``"flat"`` (flat face). ``closure``: ``"single"``, ``"conjugate"`` (a
    counter-cam and second roller) or ``"groove"``. Size: ``prime_radius_mm`` (mm), or the least
    prime circle whose pressure angle stays within ``max_pressure_deg`` (deg; default 30 for a
    roller). ``roller_radius_mm`` (mm; 0 is a knife edge).

    Returns the report (prime and base radius in mm, max pressure angle in deg and where, least
    convex radius of the pitch curve in mm and where, ``undercut`` and the keys of the follower
    kind) with ``points`` (and ``counter_points`` for a conjugate pair), a :class:`Table` every
    ``step_deg`` of main-shaft angle: angle_deg, x_mm, y_mm (pitch curve), pressure_angle_deg,
    curvature_pitch_per_mm, profile_x_mm, profile_y_mm, curvature_profile_per_mm (1/mm). An
    undercut cam gives a :class:`UserWarning`. ``dxf=True`` adds ``dxf``, the drawing ``--dxf``
    writes (mm; chord tolerance ``chord_tol_mm``, bore ``bore_mm``); an undercut cam is never
    drawn (:class:`loomkin.LoomkinError` naming the roller).

    With ``cycle=None``, ``law`` (and ``params``), ``stroke_mm`` or ``stroke_deg`` and
    ``motion_deg`` give the cycle of :func:`rise_return`, as ``--law`` does."""
    if cycle is None:
        name = law if law is not None else "cycloidal"
        c = rise_return(name, params, stroke_mm=stroke_mm, stroke_deg=stroke_deg, motion_deg=motion_deg)
        source = f"law {name} (rise, dwell, return, dwell)"
    elif law is not None:
        raise _usage("law", "give a cycle or a law, not both")
    else:
        _no_rise_with(params, stroke_mm, stroke_deg, motion_deg)
        c, source = _cycle(cycle), _source(cycle)
    r = _points(_m.cam_profile(c, follower, prime_radius_mm, max_pressure_deg, roller_radius_mm, offset_mm,
                               arm_mm, pivot_mm, closure, step_deg, source, dxf, chord_tol_mm, bore_mm))
    if r["undercut"]:
        at = r.get("undercut_at_deg")
        largest = r.get("roller_max_mm")
        msg = f"the cam is undercut at {at} deg"
        if largest is not None:
            msg += f"; the largest roller without undercut is {largest} mm"
        warnings.warn(msg, UserWarning, stacklevel=2)
    return r
