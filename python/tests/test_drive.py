"""The main shaft: parity with `loomkin drive inertia|ripple|correct --json` and `--csv` (bit for
bit), an independent check of the curves, and the bad arguments' errors naming their field."""

import csv
import io
import pathlib

import numpy as np
import pytest

import loomkin
from conftest import REPO, same

EX = REPO / "examples"
SHUTTLE, TWILL = EX / "shuttle-loom.toml", EX / "twill-2-2.wif"
RAPIER = EX / "rapier-loom.toml"


def _csv(cli, *args):
    rows = list(csv.DictReader(io.StringIO(cli(*args, "--csv", text=True))))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def _same_table(curve, ref):
    assert type(curve) is loomkin.Table and list(curve) == list(ref)
    for k in ref:
        np.testing.assert_array_equal(curve[k], ref[k], err_msg=k)


def test_inertia_matches_drive_inertia(cli):
    args = ("drive", "inertia", "examples/shuttle-loom.toml", "--wif", "examples/twill-2-2.wif", "--step-deg", "0.5")
    r = loomkin.drive.inertia(SHUTTLE, wif=TWILL, step_deg=0.5)
    curve = r.pop("curve")
    same(r, cli(*args, "--json"))
    _same_table(curve, _csv(cli, *args))
    # Independent route: the total is the sum of the mechanisms' J and dJ/dφ, and dJ/dφ is the
    # derivative of J (central differences of the columns, away from the laws' joints).
    js = [k for k in curve if k.startswith("j_") and k != "j_total_kg_m2"]
    np.testing.assert_allclose(sum(curve[k] for k in js), curve["j_total_kg_m2"], rtol=1e-12)
    h = np.radians(0.5)
    fd = (curve["j_total_kg_m2"][2:] - curve["j_total_kg_m2"][:-2]) / (2 * h)
    dj = curve["dj_total_kg_m2_per_rad"][1:-1]
    smooth = np.abs(np.diff(curve["dj_total_kg_m2_per_rad"], 2)) < 1e-3 * np.abs(dj).max()
    assert smooth.sum() > len(dj) // 2
    np.testing.assert_allclose(fd[smooth], dj[smooth], atol=2e-4 * np.abs(dj).max())
    # The mean over the grid approaches the exact mean.
    assert curve["j_total_kg_m2"].mean() == pytest.approx(r["j_mean_kg_m2"], rel=1e-6)


def test_ripple_matches_drive_ripple(cli):
    args = ("drive", "ripple", "examples/rapier-loom.toml", "--wif", "examples/point-24.wif", "--motor", "servo",
            "--servo-gain-n-m-s", "40", "--servo-torque-limit-n-m", "300", "--flywheel-kg-m2", "0.5",
            "--step-deg", "0.5")
    r = loomkin.drive.ripple(RAPIER, wif=EX / "point-24.wif", motor="servo", servo_gain_n_m_s=40,
                             servo_torque_limit_n_m=300, flywheel_kg_m2=0.5, step_deg=0.5)
    curve = r.pop("curve")
    same(r, cli(*args, "--json"))
    _same_table(curve, _csv(cli, *args))
    assert r["motor"] == "servo" and r["flywheel_kg_m2"] == 0.5
    # Independent route: the speed's extremes on the grid lie within the located extremes, and the
    # energy balance over the repeat closes (the motor's work is the load's).
    w = curve["speed_rpm"]
    assert r["min_speed_rpm"] <= w.min() + 1e-9 and w.max() <= r["max_speed_rpm"] + 1e-9
    assert curve["energy_j"][0] == pytest.approx(curve["energy_j"][-1], rel=1e-9)
    assert r["motor_work_j"] == pytest.approx(r["load_work_j"], rel=1e-9)


def test_ripple_from_the_file_and_the_flywheel_for_a_target(cli):
    args = ("drive", "ripple", "examples/shuttle-loom.toml", "--wif", "examples/twill-2-2.wif")
    r = loomkin.drive.ripple(SHUTTLE, wif=TWILL)
    r.pop("curve")
    same(r, cli(*args, "--json"))
    t = loomkin.drive.ripple(SHUTTLE, wif=TWILL, target_ripple_pct=r["speed_ripple_pct"] / 2)
    t.pop("curve")
    same(t, cli(*args, "--target-ripple-pct", repr(r["speed_ripple_pct"] / 2), "--json"))
    assert t["flywheel_kg_m2"] > 0 and t["speed_ripple_pct"] == pytest.approx(r["speed_ripple_pct"] / 2, rel=1e-6)


def test_correct_matches_drive_correct(cli, tmp_path):
    out = tmp_path / "cli"
    ref = cli("drive", "correct", "examples/shuttle-loom.toml", "--wif", "examples/twill-2-2.wif", "--natural-hz", "60",
              "--damping-ratio", "0.05", "-o", out, "--json")
    mine = tmp_path / "py"
    r = loomkin.drive.correct(SHUTTLE, wif=TWILL, natural_hz=60, damping_ratio=0.05, output=mine)
    cycles = r.pop("cycles")
    files = r.pop("files")
    ref_files = ref.pop("files")
    same(r, ref)
    assert [pathlib.Path(f).name for f in files] == [pathlib.Path(f).name for f in ref_files] == list(cycles)
    for name, text in cycles.items():
        assert (out / name).read_text() == text == (mine / name).read_text()
        # The written cam is a cycle the package reads.
        assert loomkin.Cycle.from_toml(text) is not None
    assert r["max_timing_error_deg_after"] < 1e-5 < r["max_timing_error_deg_before"]


def test_drive_errors_name_the_field():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.ripple(SHUTTLE, wif=TWILL, flywheel_kg_m2=-1)
    assert e.value.field == "flywheel_kg_m2" and e.value.low == 0
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.ripple(SHUTTLE, wif=TWILL, target_ripple_pct=0)
    assert e.value.field == "target_ripple_pct"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.drive.ripple(SHUTTLE, wif=TWILL, flywheel_kg_m2=1, target_ripple_pct=1)
    assert e.value.field == "target_ripple_pct"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.drive.ripple(SHUTTLE, motor="diesel")
    assert e.value.field == "motor" and "induction" in str(e.value)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.drive.ripple(SHUTTLE, motor="induction", motor_curve="cubic")
    assert e.value.field == "motor_curve"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.drive.ripple(SHUTTLE, motor="servo")
    assert e.value.field == "drive.servo_gain_n_m_s"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.ripple(SHUTTLE, motor="induction", rated_power_kw=-5)
    assert e.value.field == "drive.rated_power_kw"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.inertia(SHUTTLE, step_deg=0)
    assert e.value.field == "step_deg"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.ripple(SHUTTLE, step_deg=20)
    assert e.value.field == "step_deg"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.drive.correct(SHUTTLE, natural_hz=-1)
    assert e.value.field == "natural_hz"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin._loomkin.drive_ripple(SHUTTLE.read_text(), rated_power_kw="big")
    assert e.value.field == "rated_power_kw"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin._loomkin.drive_ripple(SHUTTLE.read_text(), horsepower=3)
    assert e.value.field == "horsepower"
