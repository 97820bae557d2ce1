"""Inputs given as a file path, a dict or text, turned into the text the Rust side reads."""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Optional, Union

PathOrDict = Union[str, "os.PathLike[str]", Mapping[str, Any]]


def text_of(source: Optional[PathOrDict]) -> Optional[str]:
    """None stays None; a mapping becomes JSON text; a path is read (UTF-8)."""
    if source is None:
        return None
    if isinstance(source, Mapping):
        return json.dumps(source)
    with open(os.fspath(source), encoding="utf-8") as f:
        return f.read()
