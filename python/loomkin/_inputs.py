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


def required_text(field: str, source: PathOrDict) -> str:
    """:func:`text_of` of an input that must be given: None raises :class:`loomkin.LoomkinError`
    naming ``field``."""
    text = text_of(source)
    if text is None:
        from ._loomkin import LoomkinError

        err = LoomkinError(f"{field}: give a file path or a dict")
        err.field, err.allowed = field, "a file path or a dict"
        raise err
    return text


def bytes_of(source: Optional[Union[str, "os.PathLike[str]"]]) -> Optional[bytes]:
    """None stays None; a path is read as bytes (a file whose encoding the library decides)."""
    if source is None:
        return None
    with open(os.fspath(source), "rb") as f:
        return f.read()


def study_text(study: Any) -> str:
    """A TOML file's text (a study, a servo axis): a path is read, a dict written as TOML."""
    from collections.abc import Mapping

    if isinstance(study, Mapping):
        return _toml_of(study)
    return required_text("study", study)


def _toml_of(d: Any, prefix: str = "") -> str:
    """A dict of a study file (numbers, strings, lists of numbers, inline tables of numbers and
    strings, one level of tables) as TOML text."""
    import json
    from collections.abc import Mapping

    def value(v: Any) -> str:
        if isinstance(v, Mapping):
            return "{ " + ", ".join(f"{k} = {value(x)}" for k, x in v.items()) + " }"
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, (list, tuple)):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, str):
            return json.dumps(v)
        return repr(float(v)) if isinstance(v, float) else str(v)

    top = [f"{k} = {value(v)}" for k, v in d.items() if not isinstance(v, Mapping)]
    tables = [f"\n[{k}]\n" + "\n".join(f"{kk} = {value(vv)}" for kk, vv in v.items())
              for k, v in d.items() if isinstance(v, Mapping)]
    return "\n".join(top) + "\n" + "\n".join(tables) + "\n"
