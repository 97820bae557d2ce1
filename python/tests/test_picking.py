"""Picking: parity with `loomkin pick … --json`, histories, errors."""

import csv
import io

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same


def test_design_matches_pick_design(cli):
    same(loomkin.picking.design(), cli("pick", "design", "--json"))
    same(
        loomkin.picking.design(velocity_m_s=11, distance_cm=20, law="modified-trapezoid", params={"ramp": 0.1}),
        cli("pick", "design", "--velocity-m-s", "11", "--distance-cm", "20", "--law", "modified-trapezoid",
            "--param", "ramp=0.1", "--json"),
    )


@pytest.mark.parametrize("method", ["closed", "ode"])
def test_simulate_matches_pick_simulate(cli, method):
    same(
        loomkin.picking.simulate(play_mm=15.5, speed_rpm=220, method=method),
        cli("pick", "simulate", "--play-mm", "15.5", "--speed-rpm", "220", "--method", method, "--json"),
    )


def test_sweep_matches_pick_sweep(cli):
    ref = cli("pick", "sweep", "speed", "--from", "160", "--to", "240", "--points", "9", "--json")
    r = loomkin.picking.sweep("speed", 160, 240, 9)
    rows = [{k: v for k, v in row.items() if v is not None} for row in records(r.pop("rows"))]
    same(rows, ref.pop("rows"))
    same(r, ref)


def test_history_ends_at_the_outcome():
    t, outcome = loomkin.picking.history(points=401, play_mm=15.5, speed_rpm=220)
    assert t["t_s"].shape == (401,)
    assert t["t_s"][-1] == pytest.approx(outcome["t_end_s"], rel=1e-12)
    # Independent route: the shuttle's velocity integrated over time (trapezoids) gives its travel.
    travel = np.trapezoid(t["v_m_s"], t["t_s"]) if hasattr(np, "trapezoid") else np.trapz(t["v_m_s"], t["t_s"])
    assert travel == pytest.approx(t["x_m"][-1] - t["x_m"][0], rel=1e-4)
    assert t["v_m_s"][-1] == pytest.approx(outcome["velocity_m_s"], rel=1e-9)


def test_picking_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.picking.simulate(play_mm=-5)
    assert e.value.field is not None and e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.sweep("colour", 0, 1, 3)
    assert e.value.field is not None
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.simulate(method="euler")
    assert e.value.field == "method"


def _study(tmp_path, name, draws):
    """The example study with fewer draws: as a dict (the package's input) and as a file (the CLI's)."""
    tomllib = pytest.importorskip("tomllib")

    from loomkin._inputs import study_text

    d = tomllib.loads((REPO / "examples" / name).read_text())
    d["draws"] = draws
    path = tmp_path / name
    path.write_text(study_text(d))
    return d, path


def test_montecarlo_matches_pick_montecarlo(cli, tmp_path):
    d, path = _study(tmp_path, "pick-montecarlo.toml", 300)
    ref = cli("pick", "montecarlo", path, "--json")
    text = cli("pick", "montecarlo", path, "--csv", text=True)
    r = loomkin.picking.montecarlo(d)
    draws = r.pop("per_draw")
    same(r, ref)
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(draws) == list(rows[0])
    for k in draws:
        np.testing.assert_array_equal(draws[k], [float(row[k]) for row in rows])
    # The file gives the same study as the dict; the report's mean is the draws' mean.
    same(loomkin.picking.montecarlo(path)["results"], ref["results"])
    ok = draws["simulated"] == 1
    v = next(q for q in r["results"] if q["name"] == "velocity_m_s")
    assert v["mean"] == pytest.approx(draws["velocity_m_s"][ok].mean(), rel=1e-12)
    assert r["failing"] == int(((draws["velocity_m_s"] < 16.5) | (draws["velocity_m_s"] > 19.5)
                                | (draws["distance_m"] < 0.2) | ~ok).sum())


def test_montecarlo_errors(tmp_path):
    d, _ = _study(tmp_path, "pick-montecarlo.toml", 0)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d)
    assert e.value.field is not None
    d["draws"] = 10
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.picking.montecarlo(d, speed_rpm=210)
    assert e.value.field == "speed" and "settings" in e.value.allowed
