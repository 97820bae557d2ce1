"""Normalised rise laws: the catalogue, metrics, continuity and samples as numpy arrays.

A law maps x in [0, 1] (fraction of the motion angle) to s in [0, 1] (fraction of the stroke);
v = ds/dx, a = d²s/dx², j = d³s/dx³ are dimensionless. Every law is exact in closed form.
"""

from __future__ import annotations

from typing import Any, Dict, List

from ._loomkin import Law, law_catalogue
from ._table import Shard, Table

__all__ = ["Law", "catalogue", "names", "info", "sample"]


def catalogue() -> List[Dict[str, Any]]:
    """The laws that need no parameters given, as ``loomkin law list --json``'s ``laws``.

    Each: name, description, params and the metrics cv, ca, cj, cm, ca_rms (dimensionless) with
    their positions x_* (fraction of the motion angle), continuity_class.
    """
    return law_catalogue()


def names() -> List[str]:
    """Names accepted by :class:`Law` (the catalogue, then ``piecewise`` and ``polynomial``)."""
    return [e["name"] for e in law_catalogue()] + ["piecewise", "polynomial"]


def info(name: str, **params: Any) -> Dict[str, Any]:
    """``loomkin law info NAME --param K=V --json``: law, params, metrics, segments, continuity."""
    return Law(name, **params).info()


def sample(name: str, points: int, shard: Shard = None, **params: Any) -> Table:
    """``loomkin law sample NAME --points N``: a :class:`Table` of arrays x, s, v, a, j
    (dimensionless), both ends included (as ``Law(name, **params).sample(points)``); ``shard=(i,
    n)`` gives only the rows of ``--shard i/n``."""
    return Law(name, **params).sample(points, shard)
