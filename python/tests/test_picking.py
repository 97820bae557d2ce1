"""Picking: parity with `loomkin pick … --json`, histories, errors."""

import numpy as np
import pytest

import loomkin
from conftest import records, same


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
