"""The rotary-dobby modulator (Stäubli 2600 type): analysis of a given cam (task 1) and synthesis
of the conjugate cams for an output law with dwells (task 2).

Geometry keywords (the CLI's flags): ``alpha_deg`` (47), ``theta_deg`` (= alpha), ``l2_m`` (0.66),
``l3_m`` (0.36), ``l3p_m`` (0.36), ``l6_m`` (0.40), ``speed_rpm`` (None: values per rad/s of
input), ``pressure_limit_deg`` (60). Lengths in m, angles in deg.
"""

from __future__ import annotations

from typing import Any, Dict, Optional, Sequence, Tuple, Union

import numpy as np

from . import _loomkin as _m
from ._fields import default as _default
from ._inputs import study_text
from ._table import Shard, Table, _draw_tables, _summary_texts

__all__ = ["analyze", "synthesize", "tolerance", "sweep"]


def _wrap(r: Dict[str, Any]) -> Dict[str, Any]:
    r["rows"] = Table(r["rows"])
    return r


def _cam_args(cam: Union[str, Sequence[Sequence[float]], None]) -> Tuple[Optional[str], Optional[str]]:
    """The module's (cam_spec, cam_points_text) for ``cam``: a spec string, or an (N, 2) array of
    points in m written as the text of a point file (``--cam-file``); None for the paper's cam."""
    if isinstance(cam, str):
        return cam, None
    if cam is None:
        return None, None
    pts = np.asarray(cam, dtype=float)
    return None, "\n".join(f"{x!r},{y!r}" for x, y in pts.reshape(-1, 2).tolist())


def analyze(cam: Union[str, Sequence[Sequence[float]], None] = None, step_deg: float = _default("DobbyInputs::STEP_DEG"),
            roller_m: Optional[float] = None, **geometry: Any) -> Dict[str, Any]:
    """``loomkin dobby analyze --json``: summary (checks: output speed and acceleration range,
    pressure angles, curvature, closure; admissible α), warnings, and rows as a :class:`Table`.

    ``cam``: None (the paper's elliptic cam), ``"ellipse:a=A,b=B"`` (semi-axes in m) or an (N, 2)
    array of the cam's points in m (a closed curve, as ``--cam-file``)."""
    spec, text = _cam_args(cam)
    return _wrap(_m.dobby_analyze(cam_spec=spec, cam_points_text=text, step_deg=float(step_deg),
                                  roller_m=roller_m, **geometry))


def synthesize(dwell_deg: float = _default("OutputLawSpec::DWELL_DEG"),
               dwell_centre_deg: float = _default("OutputLawSpec::DWELL_CENTRE_DEG"),
               cycles: int = _default("OutputLawSpec::CYCLES"), law: str = "cycloidal",
               params: Optional[Dict[str, Any]] = None, roller_m: float = _default("DobbyInputs::ROLLER_M"), step_deg: float = _default("DobbyInputs::STEP_DEG"),
               **geometry: Any) -> Dict[str, Any]:
    """``loomkin dobby synthesize --json``: the cam Γ and counter-cam Γ′ for ``cycles`` output
    motions by the catalogue ``law`` with dwells of ``dwell_deg`` centred on ``dwell_centre_deg``.
    summary, warnings, rows (a :class:`Table`) and ``cam`` / ``counter_cam``: dicts of (N, 2)
    arrays centre_m, wall_left_m, wall_right_m (the roller-centre curve and the groove walls)."""
    return _wrap(_m.dobby_synthesize(float(dwell_deg), float(dwell_centre_deg), cycles, law, params, float(roller_m),
                                     float(step_deg), **geometry))


def tolerance(study: Any, *, shard: Shard = None, from_draws: Optional[Any] = None, summary: bool = False,
              from_summaries: Optional[Any] = None) -> Any:
    """``loomkin dobby tolerance STUDY --json``: the modulator's dimensions drawn from the study
    file's distributions (``study``: a TOML path or a dict with draws, seed, step_deg,
    ``dimensions`` in m and deg, ``limits``): draws, seed, step_deg, not_assembled, failing,
    fail_share, ``dimensions`` and ``results`` (output_angle_error_deg, pressure_angle_deg,
    dead_point_margin_deg: mean, sd, percentiles, histogram, limit, count failing). ``per_draw`` is the
    per-draw :class:`Table` of ``--csv``. The draws run in parallel with the GIL released; Ctrl-C
    stops the study.

    For a cluster: ``shard=(i, n)`` runs only shard i of n of the draws and returns their per-draw
    :class:`Table`; ``from_draws=[table_1, …, table_n]`` (or paths, as ``--from-draws`` takes)
    returns the report of the finished run, equal to the unsharded report (without ``per_draw``);
    ``summary=True`` and ``from_summaries`` as :func:`loomkin.picking.montecarlo`'s."""
    return _m.dobby_tolerance(study_text(study), shard, _draw_tables(from_draws), summary,
                              _summary_texts(from_summaries))


def sweep(alpha_deg: Any, cam: Union[str, Sequence[Sequence[float]], None] = None, shard: Shard = None,
          **kw: Any) -> Dict[str, Any]:
    """``loomkin dobby sweep --json`` (the paper's α sweep) at the lever angles ``alpha_deg`` (an
    array, deg; α = θ): ``rows``, a :class:`Table` with per α the analysis of ``cam`` (as
    :func:`analyze`) and the synthesis of the law (keywords of :func:`synthesize`: dwell_deg,
    dwell_centre_deg, cycles, law, params, roller_m, step_deg, and the geometry l2_m … in m,
    speed_rpm, pressure_limit_deg in deg); an_ok / syn_ok and the error texts as lists.
    ``shard=(i, n)`` computes only shard i of n of the angles (``--shard i/n``)."""
    spec, text = _cam_args(cam)
    alphas = [float(a) for a in np.atleast_1d(np.asarray(alpha_deg, dtype=float))]
    return _wrap(_m.dobby_sweep(alphas, cam_spec=spec, cam_points_text=text, shard=shard, **kw))
