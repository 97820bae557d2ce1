"""The whole loom: every frame's motion from a weave pattern, shed geometry, the shedding torque
over the repeat and the stagger of the frames' crossings.

``loom`` is a loom file (TOML, as ``loomkin loom check LOOM.toml``); ``wif`` a WIF weave draft
and ``lift_plan`` a lift plan (text files); without either, plain weave over the loom's frames.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Tuple, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._inputs import bytes_of, required_text, text_of
from ._table import Table

__all__ = ["check", "torque", "stagger", "servo", "sley", "sley_synthesize"]

Path = Union[str, "os.PathLike[str]"]


def _texts(loom: Path, wif: Optional[Path], lift_plan: Optional[Path]) -> Tuple[str, Optional[bytes], Optional[str]]:
    # The WIF goes as its bytes: the library decodes it (UTF-8, else the Windows code page with a
    # UserWarning), as the CLI and the workbench do.
    return required_text("loom", loom), bytes_of(wif), text_of(lift_plan)


def check(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None) -> Dict[str, Any]:
    """``loomkin loom check --json``: per frame stroke (mm), shed angle (deg), warp strain; peak
    and RMS shedding torque (N·m), the insertion window (deg), the least clearance (mm)."""
    loom_toml, wif_bytes, plan = _texts(loom, wif, lift_plan)
    return _m.loom_check(loom_toml, wif_bytes, plan)


def torque(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
           step_deg: float = _default("Drive::STEP_DEG")) -> Dict[str, Any]:
    """``loomkin loom torque --json``: peak and RMS shedding torque (N·m) over the repeat and
    ``points``, a :class:`Table` of angle_deg and torque_n_m."""
    loom_toml, wif_bytes, plan = _texts(loom, wif, lift_plan)
    r = _m.loom_torque(loom_toml, wif_bytes, plan, float(step_deg))
    r["points"] = Table(r["points"])
    return r


def stagger(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
            objective: str = "peak") -> Dict[str, Any]:
    """``loomkin loom stagger --json``: crossing offsets (deg) that least the peak (or "rms")
    shedding torque with the window kept, against no stagger and two groups."""
    loom_toml, wif_bytes, plan = _texts(loom, wif, lift_plan)
    return _m.loom_stagger(loom_toml, wif_bytes, plan, objective)


def servo(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
          optimize: bool = False, objective: str = "peak",
          min_clearance_mm: float = _default("StaggerOptions::MIN_CLEARANCE_MM")) -> Dict[str, Any]:
    """``loomkin loom servo --json`` (a loom file with ``[shedding] drive = "servo"``): the shared
    DC bus (peak and mean power in W, regenerated and braking energy in J per repeat), the shed the
    carrier passes (window in deg, least clearance in mm) and ``frames`` in shaft order (torques in
    N·m, speeds in rpm, powers in W, motor checks; ``rise_law``, ``fall_law`` and, where the file
    gives one, ``through_law``: each kind of move's law as the loom file names it). With ``optimize`` (``--optimize``): every
    frame's stagger and motion angle (deg) for the least peak bus power (or "rms": the worst
    frame's RMS torque), the ``_before``/``_after`` keys and the study of the optimum; the search
    keeps at least ``min_clearance_mm`` (mm, ``--min-clearance-mm``; the design's own when it keeps
    less) of clearance to the carrier in every pick, reported as ``min_clearance_kept_mm``."""
    loom_toml, wif_bytes, plan = _texts(loom, wif, lift_plan)
    return _m.loom_servo(loom_toml, wif_bytes, plan, bool(optimize), objective, float(min_clearance_mm))


def sley(loom: Path, speed_rpm: Optional[float] = None,
         dwell_tolerance_mm: float = _default("SleyAnalysis::DWELL_TOLERANCE_MM"),
         points: int = _default("SleyAnalysis::POINTS")) -> Dict[str, Any]:
    """``loomkin sley analyze LOOM.toml --json``: the loom file's ``[sley]`` four-bar at speed_rpm
    (rpm; the file's when None): reed stroke (mm), back dwell (deg) within dwell_tolerance_mm (mm),
    peak reed velocity, acceleration, jerk (m/s, m/s², m/s³), forces (N), crank torque (N·m) with
    their angles (deg), and ``curve``, a :class:`Table` of the ``--csv`` rows at ``points`` angles."""
    return _m.loom_sley(required_text("loom", loom), speed_rpm, float(dwell_tolerance_mm), points)


def sley_synthesize(stroke_mm: float, back_dwell_deg: float,
                    dwell_tolerance_mm: float = _default("SleyAnalysis::DWELL_TOLERANCE_MM"),
                    reed_height_mm: float = _default("SleyTarget::REED_HEIGHT_MM"),
                    sword_mm: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin sley synthesize --reed-stroke-mm S --back-dwell-deg D --json``: the crank-rocker
    sley (its ``[sley]`` dimensions in mm) for a reed stroke (mm) and back dwell (deg of main
    shaft, within dwell_tolerance_mm) with the largest least transmission angle (deg)."""
    return _m.loom_sley_synthesize(float(stroke_mm), float(back_dwell_deg), float(dwell_tolerance_mm),
                                   float(reed_height_mm), None if sword_mm is None else float(sword_mm))
