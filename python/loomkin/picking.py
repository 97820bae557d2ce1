"""Shuttle picking dynamics of an elastic under-pick mechanism (Jederán 1959).

Keywords (all optional, the CLI's flags with ``_``): the mechanism — ``mechanism`` (a TOML file
path; default: the paper's), ``law`` (a catalogue law for the cam instead of the compound law) and
``params`` (a dict of its parameters), ``velocity_m_s``, ``distance_m`` / ``distance_cm``,
``first_stage_m`` / ``first_stage_cm``, ``design_speed_rpm``, ``retardation_pct``, ``path_m``,
``free_shed_deg``; the loom settings — ``speed_rpm``, ``play_mm``, ``strap_cm``, ``shuttle_g``,
``checking_kgf``, ``start`` ("paper" or "equilibrium"); and ``method`` ("closed" or "ode").
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Tuple, Union

from . import _loomkin as _m
from ._fields import default as _default
from ._inputs import study_text, text_of
from ._table import Shard, Table, _draw_tables, _summary_texts

__all__ = ["design", "simulate", "history", "sweep", "montecarlo", "SETTINGS"]

#: Settings :func:`sweep` can vary (``loomkin pick sweep SETTING``).
SETTINGS = ("speed", "play", "strap", "shuttle", "checking")


def _kw(mechanism: Optional[Any], kw: Dict[str, Any]) -> Dict[str, Any]:
    if mechanism is not None:
        kw["mechanism_toml"] = text_of(mechanism)
    return kw


def design(mechanism: Optional[Any] = None, **kw: Any) -> Dict[str, Any]:
    """``loomkin pick design --json``: A (m/s²), μ (1/s), τ and T′ (s) of the compound law, the
    constants B (s²), C, D (m), natural_1_s, stroke_m, the design V, X, X1, speed and the cam."""
    return _m.pick_design(**_kw(mechanism, kw))


def simulate(mechanism: Optional[Any] = None, **kw: Any) -> Dict[str, Any]:
    """``loomkin pick simulate --json``: the shuttle's velocity (m/s) and travel (m) at the end of
    the pick, delays (s), accelerations (m/s²), the required velocity and the shortfall (%)."""
    return _m.pick_simulate(**_kw(mechanism, kw))


def history(points: int = _default("History::POINTS"), mechanism: Optional[Any] = None, **kw: Any) -> Tuple[Table, Dict[str, Any]]:
    """The pick over time (``loomkin pick simulate --csv``): a :class:`Table` of t_s, s_m, v_s_m_s,
    a_s_m_s2 (the picker's nominal motion) and x_m, v_m_s, a_m_s2 (the shuttle), and the outcome."""
    cols, outcome = _m.pick_history(points, **_kw(mechanism, kw))
    return Table(cols), outcome


def sweep(setting: str, start: float, stop: float, points: int, mechanism: Optional[Any] = None,
          shard: Shard = None, **kw: Any) -> Dict[str, Any]:
    """``loomkin pick sweep SETTING --from START --to STOP --points N --json``; ``rows`` is a
    :class:`Table` (one column per outcome key, the swept value under ``<setting>_<unit>``).
    ``shard=(i, n)`` computes only the rows of ``--shard i/n`` (:func:`loomkin.concat` of the
    n shards' ``rows`` is the unsharded ``rows``)."""
    r = _m.pick_sweep(setting, float(start), float(stop), points, shard, **_kw(mechanism, kw))
    r["rows"] = Table(r["rows"])
    return r


def montecarlo(study: Any, mechanism: Optional[Any] = None, *, shard: Shard = None,
               from_draws: Optional[Any] = None, summary: bool = False, from_summaries: Optional[Any] = None,
               **kw: Any) -> Any:
    """``loomkin pick montecarlo STUDY --json``: loom settings drawn from the study file's
    distributions (``study``: a TOML path or a dict with draws, seed, ``settings``, ``limits``), the
    end-of-pick results as distributions: draws, seed, method, failing and fail_share, ``inputs`` and
    ``results`` (per quantity, units in the name: mean, sd, percentiles, histogram, limit, count
    failing). ``per_draw`` is the per-draw :class:`Table` of ``--csv`` (draw, the settings drawn,
    simulated 1/0, velocity_m_s, distance_m, …). Mechanism keywords as :func:`design`. The draws run
    in parallel with the GIL released; Ctrl-C stops the study.

    For a cluster: ``shard=(i, n)`` runs only shard i of n of the draws and returns their per-draw
    :class:`Table` (``--shard i/n --csv``); ``from_draws=[table_1, …, table_n]`` (those tables in
    shard order, DataFrames, or paths of ``--parts`` directories or CSV files as ``--from-draws``
    takes) returns the report of the finished run, equal to the unsharded report (without
    ``per_draw``).

    Without moving the draws: ``summary=True`` (with ``shard``) returns the shard's mergeable
    summary, a small dict (the CLI's ``--summary``); ``from_summaries=[…]`` (those dicts, or files
    of ``--summary``) the report merged from them: counts, failing share, extremes bit for bit,
    mean and sd to rounding, no percentiles or histograms (docs/design/shards.md)."""
    return _m.pick_montecarlo(study_text(study), shard, _draw_tables(from_draws), summary,
                              _summary_texts(from_summaries), **_kw(mechanism, kw))

