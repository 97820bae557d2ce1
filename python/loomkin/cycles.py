"""Machine cycles (dwell, rise, return segments over one turn of the main shaft) in SI units.

A cycle comes from a TOML file (the format of ``loomkin cycle FILE.toml``) or from a dict with the
same keys. Positions are in m (``unit = "mm"``) or rad (``unit = "deg"``); velocities per second.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Union

from ._fields import default as _default
from ._inputs import required_text
from ._loomkin import Cycle
from ._table import Table

__all__ = ["Cycle", "load", "from_dict", "report", "sample"]


def load(path: Union[str, "os.PathLike[str]"]) -> Cycle:
    """Reads and checks a cycle TOML file."""
    return Cycle.from_toml(required_text("path", path))


def from_dict(spec: Mapping[str, Any]) -> Cycle:
    """A cycle from a dict with the file's keys: unit, stroke, speed_rpm, period_deg and
    segment (a list of dicts: kind, to_deg or length_deg, law, params, stroke)."""
    return Cycle.from_json(required_text("spec", spec))


def _cycle(source: Union[Cycle, str, "os.PathLike[str]", Mapping[str, Any]]) -> Cycle:
    if isinstance(source, Cycle):
        return source
    if isinstance(source, Mapping):
        return from_dict(source)
    return load(source)


def report(source: Union[Cycle, str, "os.PathLike[str]", Mapping[str, Any]],
           speed_rpm: Optional[float] = None, points: int = _default("Cycle::HELD_POINTS")) -> Dict[str, Any]:
    """``loomkin cycle FILE --json`` for a cycle, a path or a dict: segment peaks and samples.

    ``samples`` is a :class:`Table` (angle_deg, time_s, s_m, v_m_s, a_m_s2, j_m_s3, or the rad
    forms). speed_rpm: given here, else the file's, else 300 rpm.
    """
    r = _cycle(source).report(speed_rpm, points)
    r["samples"] = Table(r["samples"])
    return r


def sample(source: Union[Cycle, str, "os.PathLike[str]", Mapping[str, Any]],
           speed_rpm: Optional[float] = None, points: int = _default("Cycle::HELD_POINTS")) -> Table:
    """The samples of :func:`report` alone, as a :class:`Table` (the CLI's ``--csv`` columns),
    written straight into the arrays (no per-point objects: 10⁷ points are fine)."""
    return Table(_cycle(source).sample(speed_rpm, points))
