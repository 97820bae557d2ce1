"""Servo: parity with `loomkin servo … --json` and every export, errors."""

import pytest

import loomkin
from conftest import records, same

DEF = "0:0,0.1:0.9,0.25:1,0.4:0.6,0.5:0"


def test_law_matches_servo_law(cli):
    same(loomkin.servo.law(DEF), cli("servo", "law", "--def", DEF, "--json"))
    same(loomkin.servo.law(), cli("servo", "law", "--json"))
    pairs = [[0, 0], [0.1, 0.9], [0.25, 1], [0.4, 0.6], [0.5, 0]]
    same(loomkin.servo.law(pairs, end="clamped"), cli("servo", "law", "--def", DEF, "--end", "clamped", "--json"))


def test_spline_law_samples_match_servo_law_sample(cli):
    ref = cli("servo", "law", "--def", DEF, "--sample", "41", "--json")
    law = loomkin.servo.spline_law(DEF)
    assert law.name == "servo-spline"
    same(records(law.sample(41)), ref["points"])


def test_torque_matches_servo_torque(cli):
    same(loomkin.servo.torque([600, 750], DEF), cli("servo", "torque", "--def", DEF, "--speed-rpm", "600,750", "--json"))


def test_torque_curve_peak_is_the_located_peak():
    s = loomkin.servo.torque(600)["results"][0]
    c = loomkin.servo.torque_curve(600, points=3601)
    # Independent route: the sampled curve's largest |M| approaches the exactly located peak from below.
    sampled = abs(c["torque_nm"]).max()
    assert sampled <= s["peak_torque_nm"] * (1 + 1e-12)
    assert sampled >= s["peak_torque_nm"] * (1 - 1e-4)
    assert set(c["phase"]) == {"rise", "dwell-after-rise", "return", "dwell-after-return"}


def test_optimize_matches_servo_optimize(cli):
    ref = cli("servo", "optimize", "--speed-rpm", "600", "--starts", "1", "--json")
    r = loomkin.servo.optimize(600, starts=1)
    same(r, ref)
    assert r["after"]["peak_torque_nm"] < r["before"]["peak_torque_nm"]


@pytest.mark.parametrize("fmt", loomkin.servo.EXPORT_FORMATS)
def test_every_export_matches_the_file_the_cli_writes(cli, tmp_path, fmt):
    out = tmp_path / f"law.{fmt}"
    args = ["servo", "export", "--def", DEF, "--format", fmt, "--step-deg", "2", "-o", str(out)]
    e = loomkin.servo.export(fmt, step_deg=2, def_points=DEF)
    if fmt in ("csv", "xyva"):
        ref = cli(*args, "--json")
        same({k: e[k] for k in ("points", "reinterpolation", "interpolation")}, {k: ref[k] for k in ("points", "reinterpolation", "interpolation")})
    else:
        cli(*args, text=True)
    assert e["text"] == out.read_text()
    assert e["format"] == fmt


def test_drive_as_dict_and_file(tmp_path):
    base = loomkin.servo.torque(600)["drive"]
    keys = {k: v for k, v in base.items() if k != "layout_deg"}
    a = loomkin.servo.torque(600, drive=keys)
    p = tmp_path / "drive.json"
    import json

    p.write_text(json.dumps({"drive": keys}))
    b = loomkin.servo.torque(600, drive=p)
    same(a, b)
    same(a["results"], loomkin.servo.torque(600)["results"])


def test_servo_errors():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.servo.law("0:0,0.5:0")
    assert e.value.field == "def_points"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.servo.torque(0)
    assert e.value.field == "speed_rpm" and e.value.low == 0.001 and e.value.low_inclusive and e.value.unit == "rpm"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.servo.export("pdf")
    assert e.value.field == "format" and "xyva" in e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.servo.optimize(600, objective="mean")
    assert e.value.field == "objective"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.servo.optimize(600, starts=0)
    assert e.value.field == "starts"


AXIS = "examples/servo-axis.toml"


def test_check_matches_servo_check(cli):
    from conftest import REPO

    ref = cli("servo", "check", AXIS, "--cycle", "examples/needle-rack-cycle.toml", "--json")
    r = loomkin.servo.check(REPO / AXIS, REPO / "examples/needle-rack-cycle.toml")
    same(r, ref)
    assert r["pass"] == all(c["pass"] for c in r["checks"])
    ref = cli("servo", "check", AXIS, "--law", "cycloidal", "--stroke-mm", "80", "--motion-deg", "150",
              "--speed-rpm", "750", "--json")
    same(loomkin.servo.check(REPO / AXIS, law="cycloidal", stroke_mm=80, motion_deg=150, speed_rpm=750), ref)


def test_check_axis_as_dict_and_cycle_object():
    from conftest import REPO

    tomllib = pytest.importorskip("tomllib")
    axis = tomllib.loads((REPO / AXIS).read_text())
    cycle = loomkin.cycles.load(REPO / "examples/needle-rack-cycle.toml")
    same(loomkin.servo.check(axis, cycle, speed_rpm=500),
         loomkin.servo.check(REPO / AXIS, REPO / "examples/needle-rack-cycle.toml", speed_rpm=500))


def test_check_errors():
    from conftest import REPO

    axis = str(REPO / AXIS)
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.servo.check(axis, law="cycloidal", stroke_mm=80, motion_deg=150, speed_rpm=0)
    assert e.value.field == "speed_rpm" and e.value.unit == "rpm"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.servo.check({"motor": {"rated_torque_nm": 3.2, "peak_torque_nm": 1.0, "rated_speed_rpm": 3000,
                                       "max_speed_rpm": 4500, "rotor_inertia_kg_m2": 1e-4},
                             "load": {"moving_mass_kg": 0.45, "travel_mm_per_rev": 157.08}},
                            law="cycloidal", stroke_mm=80, motion_deg=150)
    assert e.value.field == "motor.peak_torque_nm" and e.value.low == 3.2
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.servo.check(axis, REPO / "examples/needle-rack-cycle.toml", law="cycloidal")
    assert e.value.field == "law"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.servo.check({"motor": {}}, law="cycloidal", stroke_mm=80, motion_deg=150)
    assert e.value.field == "axis file" and "[motor]" in e.value.allowed
