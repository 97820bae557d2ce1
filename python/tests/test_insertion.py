"""Insertion: parity with `loomkin insert budget|rapier|projectile|airjet --json`, an independent
reading of each result, errors."""

import math

import pytest

import loomkin
from conftest import REPO, same

EX = REPO / "examples"


def test_budget_matches_insert_budget(cli):
    # From the flags alone: the textbook case, and the formula read independently here.
    args = dict(reed_width_mm=1150, carrier_length_mm=300, window_deg=135, speed_m_s=13.75)
    ref = cli("insert", "budget", "--reed-width-mm", "1150", "--carrier-length-mm", "300", "--window-deg", "135",
              "--speed-m-s", "13.75", "--json")
    r = loomkin.insertion.budget(**args)
    same(r, ref)
    assert r["max_picks_per_min"] == pytest.approx(13.75 * 135 / (6 * (1.15 + 0.30)), rel=1e-15)
    assert math.floor(r["max_picks_per_min"]) == 213
    # A loom file with its clear-shed window, keywords over it.
    ref = cli("insert", "budget", "examples/rapier-loom.toml", "--wif", "examples/point-24.wif", "--carrier-mass-g",
              "300", "--speed-rpm", "400", "--json")
    r = loomkin.insertion.budget(EX / "rapier-loom.toml", wif=EX / "point-24.wif", carrier_mass_g=300, speed_rpm=400)
    same(r, ref)
    assert r["window_source"] == "clear_shed"
    # The energy and power read independently: ½·m·v̄², and that times the picks per second.
    assert r["energy_per_pick_j"] == pytest.approx(0.5 * 0.3 * r["speed_m_s"] ** 2, rel=1e-14)
    assert r["drive_power_w"] == pytest.approx(r["energy_per_pick_j"] * 400 / 60, rel=1e-14)
    same(loomkin.insertion.budget(EX / "rapier-loom.toml", window_deg=200),
         cli("insert", "budget", "examples/rapier-loom.toml", "--window-deg", "200", "--json"))


def test_budget_errors():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.insertion.budget(reed_width_mm=1150, carrier_length_mm=300, speed_m_s=13.75)
    assert e.value.field == "window_deg" and "required without a loom file" in str(e.value)
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.insertion.budget(reed_width_mm=-1, carrier_length_mm=300, window_deg=135, speed_m_s=13.75)
    # PickBudget::REED_WIDTH_MM: at least 1 mm (1340aaf: a width of 5e-324 mm gave inf).
    assert e.value.field == "reed_width_mm" and e.value.low == 1
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.insertion.budget(wif=EX / "point-24.wif", reed_width_mm=1150, carrier_length_mm=300, window_deg=135,
                                 speed_m_s=13.75)
    assert e.value.field == "wif"


def test_rapier_matches_insert_rapier(cli):
    ref = cli("insert", "rapier", "examples/rapier-loom.toml", "--wif", "examples/point-24.wif", "--json")
    r = loomkin.insertion.rapier(EX / "rapier-loom.toml", wif=EX / "point-24.wif")
    same(r, ref)
    for key in ("transfer_overlap_mm", "transfer_relative_speed_m_s", "peak_head_speed_m_s",
                "peak_head_acceleration_m_s2", "min_clearance_mm", "worst_pick", "worst_angle_deg",
                "worst_position_mm"):
        assert key in r
    # Independent reading: the heads' path is fixed on the shaft angle, so their speeds scale as the
    # loom speed and their accelerations as its square.
    slow = loomkin.insertion.rapier(EX / "rapier-loom.toml", wif=EX / "point-24.wif", speed_rpm=r["speed_rpm"] / 2)
    assert slow["peak_head_speed_m_s"] == pytest.approx(r["peak_head_speed_m_s"] / 2, rel=1e-12)
    assert slow["peak_head_acceleration_m_s2"] == pytest.approx(r["peak_head_acceleration_m_s2"] / 4, rel=1e-12)
    assert slow["transfer_overlap_mm"] == r["transfer_overlap_mm"]


def test_projectile_matches_insert_projectile(cli):
    ref = cli("insert", "projectile", "examples/projectile-loom.toml", "--wif", "examples/point-24.wif",
              "--speed-rpm", "350", "--json")
    r = loomkin.insertion.projectile(EX / "projectile-loom.toml", wif=EX / "point-24.wif", speed_rpm=350)
    same(r, ref)
    # Independent reading: the arrival is the launch plus 6·n degrees a second of flight.
    assert r["arrival_deg"] == pytest.approx(r["launch_deg"] + 6 * 350 * r["flight_time_ms"] * 1e-3, rel=1e-14)
    # The launch speed does not depend on the loom speed.
    assert loomkin.insertion.projectile(EX / "projectile-loom.toml")["projectile_speed_m_s"] == r["projectile_speed_m_s"]


def test_airjet_matches_insert_airjet(cli):
    ref = cli("insert", "airjet", "examples/airjet-loom.toml", "--json")
    r = loomkin.insertion.airjet(EX / "airjet-loom.toml")
    same(r, ref)
    plan = r["relay_plan"]
    assert [g["group"] for g in plan] == sorted(g["group"] for g in plan)
    # Independent reading: the air consumed is the sum of the groups' open angles, in time at the speed.
    open_deg = sum(g["close_deg"] - g["open_deg"] for g in plan)
    assert r["relay_open_deg"] == pytest.approx(open_deg, rel=1e-12)
    assert r["relay_open_ms"] == pytest.approx(open_deg / (6 * r["speed_rpm"]) * 1e3, rel=1e-12)
    same(loomkin.insertion.airjet(EX / "airjet-loom.toml", speed_rpm=600),
         cli("insert", "airjet", "examples/airjet-loom.toml", "--speed-rpm", "600", "--json"))


def test_carrier_errors():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.insertion.rapier(EX / "shuttle-loom.toml")
    assert e.value.field == "insertion.kind"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.insertion.airjet(EX / "rapier-loom.toml")
    assert e.value.field == "insertion.kind"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.insertion.projectile(EX / "projectile-loom.toml", speed_rpm=-5)
    assert e.value.field == "speed_rpm"
