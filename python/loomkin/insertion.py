"""Weft insertion beyond the shuttle (issue 30, docs/insertion.md): the time budget of any carrier,
the double rapier, torsion-bar projectile picking and the air jet — the numbers of
``loomkin insert budget|rapier|projectile|airjet --json``, keyed as there.

``loom`` is a loom file (TOML) with its ``[insertion] kind``; ``wif`` a WIF weave draft and
``lift_plan`` a lift plan (text files) whose every pick the clearance covers; without either,
plain weave over the loom's frames. ``speed_rpm`` overrides the file's speed.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Union

from . import _loomkin as _m
from ._inputs import bytes_of, required_text, text_of

__all__ = ["budget", "rapier", "projectile", "airjet"]

Path = Union[str, "os.PathLike[str]"]


def _opt(v: Optional[float]) -> Optional[float]:
    return None if v is None else float(v)


def budget(loom: Optional[Path] = None, wif: Optional[Path] = None, lift_plan: Optional[Path] = None, *,
           reed_width_mm: Optional[float] = None, carrier_length_mm: Optional[float] = None,
           window_deg: Optional[float] = None, speed_m_s: Optional[float] = None,
           speed_rpm: Optional[float] = None, carrier_mass_g: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin insert budget [LOOM.toml] --json``: the highest loom speed ``max_picks_per_min`` for
    the reed width (mm), carrier length (mm), window (deg) and mean carrier speed (m/s), the
    ``required_speed_m_s`` at the loom's speed (rpm), and with ``carrier_mass_g`` (g) the energy per
    pick (J) and drive power (W). Every keyword given replaces the loom file's; without a file the
    reed width, carrier length, window and speed are needed; with a pattern the window is its
    clear-shed window (``window_source``)."""
    return _m.insert_budget(text_of(loom), bytes_of(wif), text_of(lift_plan), _opt(reed_width_mm),
                            _opt(carrier_length_mm), _opt(window_deg), _opt(speed_m_s), _opt(speed_rpm),
                            _opt(carrier_mass_g))


def rapier(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
           speed_rpm: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin insert rapier LOOM.toml --json``: the transfer (``transfer_overlap_mm``,
    ``transfer_relative_speed_m_s``, …), each head's stroke, reversing point and peaks (``bringer``,
    ``taker``), ``peak_head_speed_m_s``, ``peak_head_acceleration_m_s2`` and the least clearance over
    every pick (``min_clearance_mm``, ``worst_pick``, ``worst_angle_deg``, ``worst_position_mm``)."""
    return _m.insert_rapier(required_text("loom", loom), bytes_of(wif), text_of(lift_plan), _opt(speed_rpm))


def projectile(loom: Path, wif: Optional[Path] = None, lift_plan: Optional[Path] = None,
               speed_rpm: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin insert projectile LOOM.toml --json``: the bar's energy (J), ``projectile_speed_m_s``,
    ``flight_time_ms``, ``arrival_deg``, the brake, the guide teeth's least clearance over every pick
    and, with a ``[sley]``, ``sley_back_dwell_deg`` and ``fits_sley_dwell``."""
    return _m.insert_projectile(required_text("loom", loom), bytes_of(wif), text_of(lift_plan), _opt(speed_rpm))


def airjet(loom: Path, speed_rpm: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin insert airjet LOOM.toml --json``: the yarn tip's ``arrival_deg``, ``flight_time_ms``,
    ``tip_speed_at_exit_m_s``, and ``relay_plan`` (a list of ``group``, ``open_deg``, ``close_deg``)
    with the air consumed, ``relay_open_ms``."""
    return _m.insert_airjet(required_text("loom", loom), _opt(speed_rpm))
