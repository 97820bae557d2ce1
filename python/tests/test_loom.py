"""Loom: parity with `loomkin loom check|torque|stagger --json`, errors."""

import csv
import io

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same

EX = REPO / "examples"


def test_check_matches_loom_check(cli):
    ref = cli("loom", "check", "examples/rapier-loom.toml", "--wif", "examples/point-24.wif", "--json")
    same(loomkin.loom.check(EX / "rapier-loom.toml", wif=EX / "point-24.wif"), ref)


def test_torque_matches_loom_torque(cli):
    ref = cli("loom", "torque", "examples/shuttle-loom.toml", "--wif", "examples/twill-2-2.wif", "--step-deg", "1",
              "--json")
    r = loomkin.loom.torque(EX / "shuttle-loom.toml", wif=EX / "twill-2-2.wif", step_deg=1)
    same(records(r.pop("points")), ref.pop("points"))
    same(r, ref)
    # Independent route: the RMS of the sampled curve approaches the exact RMS.
    t = loomkin.loom.torque(EX / "shuttle-loom.toml", wif=EX / "twill-2-2.wif", step_deg=0.1)
    sampled = np.sqrt(np.mean(t["points"]["torque_n_m"] ** 2))
    assert sampled == pytest.approx(t["rms_torque_n_m"], rel=2e-3)


def test_stagger_matches_loom_stagger(cli):
    ref = cli("loom", "stagger", "examples/shuttle-loom.toml", "--wif", "examples/twill-2-2.wif", "--json")
    same(loomkin.loom.stagger(EX / "shuttle-loom.toml", wif=EX / "twill-2-2.wif"), ref)


def test_servo_matches_loom_servo(cli):
    ref = cli("loom", "servo", "examples/servo-shedding-loom.toml", "--wif", "examples/point-24.wif", "--json")
    r = loomkin.loom.servo(EX / "servo-shedding-loom.toml", wif=EX / "point-24.wif")
    same(r, ref)
    assert len(r["frames"]) == 24 and r["min_clearance_mm"] > 0
    # Each frame's laws by kind of move, as the loom file names them (here the [shedding] preset's).
    assert (r["frames"][0]["rise_law"], r["frames"][0]["fall_law"]) == ("dobby preset", "dobby preset")
    assert "through_law" not in r["frames"][0]
    # --optimize: the same search, the same optimum and the same before/after keys.
    ref = cli("loom", "servo", "examples/servo-shedding-loom.toml", "--wif", "examples/twill-2-2.wif", "--optimize",
              "--objective", "rms", "--json")
    o = loomkin.loom.servo(EX / "servo-shedding-loom.toml", wif=EX / "twill-2-2.wif", optimize=True, objective="rms")
    same(o, ref)
    assert o["worst_rms_torque_n_m_after"] < o["worst_rms_torque_n_m_before"]
    # --min-clearance-mm: the same floor kept, the same optimum; out of its range, the CLI's refusal
    # (the same descriptor) naming the keyword.
    ref = cli("loom", "servo", "examples/servo-shedding-loom.toml", "--wif", "examples/twill-2-2.wif", "--optimize",
              "--min-clearance-mm", "0.5", "--json")
    o = loomkin.loom.servo(EX / "servo-shedding-loom.toml", wif=EX / "twill-2-2.wif", optimize=True,
                           min_clearance_mm=0.5)
    same(o, ref)
    assert o["min_clearance_kept_mm"] == 0.5 and o["min_clearance_mm_after"] >= 0.5
    for bad in (-1.0, 1000.5, float("nan")):
        with pytest.raises(loomkin.OutOfRangeError) as e:
            loomkin.loom.servo(EX / "servo-shedding-loom.toml", wif=EX / "twill-2-2.wif", optimize=True,
                               min_clearance_mm=bad)
        assert e.value.field == "min_clearance_mm" and e.value.low == 0 and e.value.high == 1000, str(e.value)
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.loom.servo(EX / "rapier-loom.toml", wif=EX / "point-24.wif")
    assert "shedding.drive" in str(e.value)


def test_loom_errors(tmp_path):
    bad = tmp_path / "loom.toml"
    bad.write_text((EX / "shuttle-loom.toml").read_text().replace("speed_rpm = ", "speed_rpm = -"))
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.loom.check(bad)
    assert e.value.field is not None
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.loom.stagger(EX / "shuttle-loom.toml", objective="mean")
    assert e.value.field == "objective"


def test_a_wif_in_the_windows_code_page_reads_as_in_the_cli(cli, tmp_path):
    # Issue 27: a WIF saved in Windows-1252 raised a raw UnicodeDecodeError. The library decodes it
    # (UTF-8, else Windows-1252) with a note: a UserWarning here, a note on stderr in the CLI.
    text = (EX / "twill-2-2.wif").read_text().replace("; 2/2 twill", "; Köper 2/2 — “twill”")
    cp = tmp_path / "koeper.wif"
    cp.write_bytes(text.encode("cp1252"))
    utf8 = tmp_path / "koeper-utf8.wif"
    utf8.write_text(text, encoding="utf-8")
    with pytest.warns(UserWarning, match="Windows-1252"):
        r = loomkin.loom.check(EX / "shuttle-loom.toml", wif=cp)
    same(r, loomkin.loom.check(EX / "shuttle-loom.toml", wif=utf8))
    same(r, cli("loom", "check", "examples/shuttle-loom.toml", "--wif", str(cp), "--json"))


def test_sley_matches_sley_analyze(cli):
    path = REPO / "examples" / "rapier-loom.toml"
    ref = cli("sley", "analyze", "examples/rapier-loom.toml", "--speed-rpm", "500", "--json")
    r = loomkin.loom.sley(path, speed_rpm=500, points=73)
    curve = r.pop("curve")
    same(r, ref)
    text = cli("sley", "analyze", "examples/rapier-loom.toml", "--speed-rpm", "500", "--points", "73", "--csv", text=True)
    rows = list(csv.DictReader(io.StringIO(text)))
    assert type(curve) is loomkin.Table and list(curve) == list(rows[0])
    for k in curve:
        np.testing.assert_array_equal(curve[k], [float(row[k]) for row in rows])
    # The stroke is the travel of the reed over the turn (an independent reading of the curve).
    assert r["reed_stroke_mm"] >= curve["reed_mm"].max() - curve["reed_mm"].min() - 1e-9
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.loom.sley(path, points=-3)
    assert e.value.field == "points"


def test_sley_synthesize_matches_sley_synthesize(cli):
    ref = cli("sley", "synthesize", "--reed-stroke-mm", "110", "--back-dwell-deg", "60", "--json")
    r = loomkin.loom.sley_synthesize(110, 60)
    same(r, ref)
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.loom.sley_synthesize(-1, 60)
    assert e.value.field is not None


def test_servo_through_a_crank_and_lever_matches_loom_servo(cli):
    # The loom file's crank-and-lever transmission (issue 31): the same study through Python.
    ref = cli("loom", "servo", "examples/servo-shedding-crank-loom.toml", "--wif", "examples/point-24.wif", "--json")
    r = loomkin.loom.servo(EX / "servo-shedding-crank-loom.toml", wif=EX / "point-24.wif")
    same(r, ref)
    lin = loomkin.loom.servo(EX / "servo-shedding-loom.toml", wif=EX / "point-24.wif")
    assert all(a["peak_speed_rpm"] != b["peak_speed_rpm"] for a, b in zip(r["frames"], lin["frames"]))
