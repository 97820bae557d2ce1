"""The libraries' field descriptors (``_loomkin.FIELDS``): keyword defaults are read from them, so a
default lives once, on the library type that owns it (see docs/reference/fields.md)."""

from __future__ import annotations

from typing import Any, Dict

from . import _loomkin as _m


def field(path: str) -> Dict[str, Any]:
    """The descriptor declared at ``path`` (e.g. ``"ShaftSpeed::SPEED"``): name, range, default, count, doc."""
    return _m.FIELDS[path]


def default(path: str) -> Any:
    """The default of the descriptor at ``path``: an int for a count, else a float."""
    f = field(path)
    v = f["default"]
    if v is None:
        raise KeyError(f"{path} has no default")
    return int(v) if f["count"] else float(v)


def speeds(kind: str) -> list:
    """The servo commands' default speeds (rpm): ``"TORQUE"`` (servo torque) or ``"DESIGN"``."""
    return list(_m.SERVO_DEFAULT_SPEEDS[kind])
