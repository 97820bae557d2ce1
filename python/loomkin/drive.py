"""The loom's main shaft: the reduced moment of inertia J(φ) of its mechanisms over the pattern
repeat, its periodic speed under a motor (speed ripple, energy swing, motor torque, flywheel) and
the time-true cams that move the frames in time at that speed (issue 29, docs/drive.md).

``loom`` is a loom file (TOML, as ``loomkin drive ripple LOOM.toml``); ``wif`` a WIF weave draft
and ``lift_plan`` a lift plan (text files); without either, plain weave over the loom's frames.
The motor is the loom file's ``[drive]`` motor, with any of the keywords ``motor`` ("constant",
"induction" or "servo"), ``motor_curve`` ("linear" or "kloss"), ``synchronous_rpm``,
``rated_rpm``, ``rated_power_kw``, ``breakdown_ratio``, ``gear_ratio``, ``servo_gain_n_m_s``,
``servo_integral_s``, ``servo_torque_limit_n_m`` over it (the CLI's motor flags).
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._inputs import bytes_of, required_text, text_of
from ._table import Table

__all__ = ["inertia", "ripple", "correct"]

Path = Union[str, "os.PathLike[str]"]


def inertia(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
            step_deg: float = _default("Drive::STEP_DEG")) -> Dict[str, Any]:
    """``loomkin drive inertia --json``: the total reduced inertia's least, largest and mean (kg·m²)
    and where (deg of the repeat), each mechanism's under ``mechanisms``; and ``curve``, a
    :class:`Table` of the ``--csv`` columns: angle_deg, then ``j_NAME_kg_m2`` (J) and
    ``dj_NAME_kg_m2_per_rad`` (dJ/dφ) for every mechanism (frame1 …, sley, rotating) and the total."""
    r = _m.drive_inertia(required_text("loom", loom), bytes_of(wif), text_of(lift_plan), float(step_deg))
    r["curve"] = Table(r["curve"])
    return r


def ripple(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None, *,
           motor: Optional[str] = None, motor_curve: Optional[str] = None,
           synchronous_rpm: Optional[float] = None, rated_rpm: Optional[float] = None,
           rated_power_kw: Optional[float] = None, breakdown_ratio: Optional[float] = None,
           gear_ratio: Optional[float] = None, servo_gain_n_m_s: Optional[float] = None,
           servo_integral_s: Optional[float] = None, servo_torque_limit_n_m: Optional[float] = None,
           flywheel_kg_m2: Optional[float] = None, target_ripple_pct: Optional[float] = None,
           step_deg: float = _default("ripple::STEP_DEG")) -> Dict[str, Any]:
    """``loomkin drive ripple --json``: the shaft's steady running — mean, least and largest speed
    (rpm), speed_ripple_pct, energy_swing_j, peak and RMS motor torque (N·m), works (J) and
    flywheel_kg_m2 (the file's, the given one, or with ``target_ripple_pct`` the least that holds
    the ripple there); and ``curve``, a :class:`Table` of the ``--csv`` columns: angle_deg,
    speed_rpm (ω), motor_torque_n_m, load_torque_n_m, energy_j."""
    r = _m.drive_ripple(required_text("loom", loom), bytes_of(wif), text_of(lift_plan), flywheel_kg_m2,
                        target_ripple_pct, float(step_deg),
                        **_motor(motor, motor_curve, synchronous_rpm, rated_rpm, rated_power_kw, breakdown_ratio,
                                 gear_ratio, servo_gain_n_m_s, servo_integral_s, servo_torque_limit_n_m))
    r["curve"] = Table(r["curve"])
    return r


def correct(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None, *,
            output: Optional[Path] = None,
            motor: Optional[str] = None, motor_curve: Optional[str] = None,
            synchronous_rpm: Optional[float] = None, rated_rpm: Optional[float] = None,
            rated_power_kw: Optional[float] = None, breakdown_ratio: Optional[float] = None,
            gear_ratio: Optional[float] = None, servo_gain_n_m_s: Optional[float] = None,
            servo_integral_s: Optional[float] = None, servo_torque_limit_n_m: Optional[float] = None,
            flywheel_kg_m2: Optional[float] = None, step_deg: float = _default("ripple::STEP_DEG"),
            natural_hz: Optional[float] = None,
            damping_ratio: float = _default("Follower::DAMPING_RATIO")) -> Dict[str, Any]:
    """``loomkin drive correct --json``: time-true cams — the frames' laws corrected for the shaft's
    speed ripple; timing errors before and after (deg), the ripple with the design and corrected
    cams (%), rounds, per frame the errors and, with ``natural_hz`` (Hz), the residual vibrations
    (mm). ``cycles`` maps each cycle file's name (frame-01.toml …) to its text, as ``-o DIR``
    writes it (read it with :class:`loomkin.Cycle`); with ``output`` the files are written there
    too and ``files`` lists their paths, as the CLI's."""
    title = os.path.basename(os.fspath(loom)) if isinstance(loom, (str, os.PathLike)) else "loom"
    r = _m.drive_correct(required_text("loom", loom), bytes_of(wif), text_of(lift_plan), title, flywheel_kg_m2,
                         float(step_deg), natural_hz, float(damping_ratio),
                         **_motor(motor, motor_curve, synchronous_rpm, rated_rpm, rated_power_kw, breakdown_ratio,
                                  gear_ratio, servo_gain_n_m_s, servo_integral_s, servo_torque_limit_n_m))
    if output is not None:
        out = os.fspath(output)
        os.makedirs(out, exist_ok=True)
        files = []
        for name, text in r["cycles"].items():
            path = os.path.join(out, name)
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            files.append(path)
        r["files"] = files
    return r


def _motor(motor: Optional[str], motor_curve: Optional[str], synchronous_rpm: Optional[float],
           rated_rpm: Optional[float], rated_power_kw: Optional[float], breakdown_ratio: Optional[float],
           gear_ratio: Optional[float], servo_gain_n_m_s: Optional[float], servo_integral_s: Optional[float],
           servo_torque_limit_n_m: Optional[float]) -> Dict[str, Any]:
    """The motor keywords given (the ones left None come from the loom file)."""
    kw = dict(motor=motor, motor_curve=motor_curve, synchronous_rpm=synchronous_rpm, rated_rpm=rated_rpm,
              rated_power_kw=rated_power_kw, breakdown_ratio=breakdown_ratio, gear_ratio=gear_ratio,
              servo_gain_n_m_s=servo_gain_n_m_s, servo_integral_s=servo_integral_s,
              servo_torque_limit_n_m=servo_torque_limit_n_m)
    return {k: v for k, v in kw.items() if v is not None}
