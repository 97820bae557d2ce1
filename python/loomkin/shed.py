"""Shedding laws of the heald frames: dwell and window criteria, experiment tables, Pareto fronts
and the best law for a required window.

Common keywords: ``threshold`` (the fraction of the stroke within which the frame counts as at
rest, default 0.95), ``stroke_mm`` (100), ``speed_rpm`` (300). Design keywords: ``design``
("presets", "table1", "fig1", "grid"), ``family`` ("trapezoid", "lead-trapezoid",
"linear-trapezoid") or ``shapes``, ``step``, ``min_k``, ``max_k``, ``motion_deg`` ("FROM:TO:STEP"
or "A,B,…" in deg).
"""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._inputs import text_of
from ._table import Table

__all__ = ["presets", "law", "table", "pareto", "best", "window"]


def presets() -> List[Dict[str, Any]]:
    """``loomkin shed list --json``'s laws: name, name_ru, motion_deg, dwell_deg, table_shape, positive."""
    return _m.shed_presets()


def law(name: Optional[str] = None, spec: Union[str, "os.PathLike[str]", None] = None,
        motion_deg: Optional[float] = None, **conditions: Any) -> Dict[str, Any]:
    """``loomkin shed law NAME --json`` (or ``--spec FILE.toml``): window_deg, dwell_deg,
    conditional_dwell_deg, cv, ca, cj, cm, ca_rms, peak_velocity_m_s, peak_accel_m_s2,
    peak_jerk_m_s3, … and the law's definition."""
    text = text_of(spec) if spec is not None else None
    label = os.fspath(spec) if spec is not None else None
    return _m.shed_law(name, text, motion_deg, label=label, **conditions)


def table(**kw: Any) -> Table:
    """``loomkin shed table --json``'s rows as a :class:`Table` (``.frame()`` for pandas);
    ``shard=(i, n)`` gives only the rows of ``--shard i/n``."""
    return Table(_m.shed_table(**kw))


def pareto(**kw: Any) -> Table:
    """``loomkin shed pareto --json``'s rows: the front of largest window and least peak
    acceleration, as a :class:`Table`."""
    return Table(_m.shed_pareto(**kw))


def best(window_deg: float, **kw: Any) -> Dict[str, Any]:
    """``loomkin shed best --window-deg W --json``: the law with the least peak acceleration
    among those with a window ≥ window_deg."""
    return _m.shed_best(float(window_deg), **kw)


def window(carrier_speed_m_s: float, reed_width_m: float, *, cloth_width_m: Optional[float] = None,
           carrier_length_m: float = _default("LoomRequirement::CARRIER_LENGTH_M"),
           crossing_range_deg: float = _default("LoomRequirement::CROSSING_RANGE_DEG"),
           shed_excess: float = _default("LoomRequirement::SHED_EXCESS"),
           speed_rpm: float = _default("ShaftSpeed::SPEED")) -> Dict[str, Any]:
    """``loomkin shed window --carrier-speed-m-s V --reed-width-m L --json``: the window a loom
    needs. The loom data (the weft carrier's mean speed in m/s; reed width, cloth width (default:
    the reed's) and carrier length in m; the crossing-point range in deg; the shed-height excess as
    a fraction; the main-shaft speed in rpm) with flight_deg (the carrier's flight through the
    warp), required_window_deg (flight plus crossing range, deg of the main shaft), threshold
    (T = 1/(1 + excess)) and threshold_both_sheets."""
    return _m.shed_window(float(carrier_speed_m_s), float(reed_width_m),
                          None if cloth_width_m is None else float(cloth_width_m), float(carrier_length_m),
                          float(crossing_range_deg), float(shed_excess), float(speed_rpm))
