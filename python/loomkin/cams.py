"""From a law to a part: controller cam tables of a machine cycle (``loomkin cam table``).

Disc cam profiles (``loomkin cam profile``) are not in the package yet.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Mapping, Optional, Union

from . import _loomkin as _m
from .cycles import _cycle

__all__ = ["table", "FORMATS"]

#: The formats of :func:`table`.
FORMATS = ("xyvaj", "poly5", "csv", "twincat", "st")


def table(cycle: Union["_m.Cycle", str, "os.PathLike[str]", Mapping[str, Any]], format: str,
          step_deg: Optional[float] = None, tolerance: Optional[float] = None) -> Dict[str, Any]:
    """``loomkin cam table CYCLE --format F --json`` and its file: ``text`` (the table as the CLI
    writes it), points, unit, spacing, the exact re-interpolation errors (slave unit per deg^k)
    and the decimals written. ``step_deg`` (default 1°) or ``tolerance`` (slave unit)."""
    source = "" if isinstance(cycle, (Mapping, _m.Cycle)) else os.fspath(cycle)
    return _m.cam_table(_cycle(cycle), format, step_deg, tolerance, source)
