"""Cam tables and disc cam profiles: parity with `loomkin cam table|profile --json` and the files
they write, the geometry by a second route, errors."""

import csv
import io
import warnings

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same


@pytest.mark.parametrize("fmt", loomkin.cams.FORMATS)
def test_table_matches_cam_table(cli, tmp_path, monkeypatch, fmt):
    monkeypatch.chdir(REPO)
    out = tmp_path / f"table.{fmt}"
    ref = cli("cam", "table", "examples/heald-frame-cycle.toml", "--format", fmt, "--step-deg", "2", "-o", out,
              "--json")
    r = loomkin.cams.table("examples/heald-frame-cycle.toml", fmt, step_deg=2)
    assert r.pop("text") == out.read_text()
    same(r, ref)


def test_tolerance_spacing_matches(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    out = tmp_path / "t.csv"
    ref = cli("cam", "table", "examples/sley-cycle.toml", "--format", "csv", "--tolerance", "1e-4", "-o", out, "--json")
    r = loomkin.cams.table("examples/sley-cycle.toml", "csv", tolerance=1e-4)
    assert r.pop("text") == out.read_text()
    same(r, ref)
    # The table keeps the error it promises.
    assert r[f"max_position_error_{r['unit']}"] <= 1e-4


def test_cam_errors():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.table(REPO / "examples" / "heald-frame-cycle.toml", "pdf")
    assert e.value.field == "format"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.cams.table(REPO / "examples" / "heald-frame-cycle.toml", "csv", step_deg=0)
    assert e.value.field is not None


def test_table_of_a_law_matches_cam_table_law(cli, tmp_path):
    out = tmp_path / "rise.csv"
    ref = cli("cam", "table", "--law", "modified-trapezoid", "--param", "ramp=0.2", "--stroke-mm", "40",
              "--motion-deg", "120", "--format", "csv", "--step-deg", "2", "-o", out, "--json")
    r = loomkin.cams.table(None, "csv", step_deg=2, law="modified-trapezoid", params={"ramp": 0.2}, stroke_mm=40,
                           motion_deg=120)
    assert r.pop("text") == out.read_text()
    same(r, ref)


# One case per follower kind and closure (the CLI's flags, then the same as keywords).
PROFILES = [
    (["examples/heald-frame-cycle.toml", "--follower", "translating", "--max-pressure-deg", "30",
      "--roller-radius-mm", "15"],
     dict(cycle="examples/heald-frame-cycle.toml", follower="translating", max_pressure_deg=30, roller_radius_mm=15)),
    (["examples/heald-frame-cycle.toml", "--follower", "translating", "--prime-radius-mm", "90", "--offset-mm", "10",
      "--roller-radius-mm", "12", "--conjugate"],
     dict(cycle="examples/heald-frame-cycle.toml", follower="translating", prime_radius_mm=90, offset_mm=10,
          roller_radius_mm=12, closure="conjugate")),
    (["examples/sley-cycle.toml", "--follower", "oscillating", "--arm-mm", "160", "--pivot-mm", "190",
      "--roller-radius-mm", "20", "--conjugate", "--max-pressure-deg", "40", "--step-deg", "3"],
     dict(cycle="examples/sley-cycle.toml", follower="oscillating", arm_mm=160, pivot_mm=190, roller_radius_mm=20,
          closure="conjugate", max_pressure_deg=40, step_deg=3)),
    (["examples/heald-frame-cycle.toml", "--follower", "flat", "--prime-radius-mm", "150", "--step-deg", "5"],
     dict(cycle="examples/heald-frame-cycle.toml", follower="flat", prime_radius_mm=150, step_deg=5)),
    (["--law", "cycloidal", "--stroke-deg", "20", "--motion-deg", "120", "--follower", "oscillating", "--arm-mm", "100",
      "--pivot-mm", "120", "--roller-radius-mm", "8", "--groove"],
     dict(law="cycloidal", stroke_deg=20, motion_deg=120, follower="oscillating", arm_mm=100, pivot_mm=120,
          roller_radius_mm=8, closure="groove")),
    (["--law", "harmonic", "--stroke-mm", "50", "--motion-deg", "180", "--follower", "flat", "--prime-radius-mm", "25"],
     dict(law="harmonic", stroke_mm=50, motion_deg=180, follower="flat", prime_radius_mm=25)),
]


@pytest.mark.parametrize("args,kw", PROFILES, ids=["radial", "offset-conjugate", "oscillating-conjugate", "flat",
                                                   "law-groove", "law-flat"])
def test_profile_matches_cam_profile(cli, monkeypatch, args, kw):
    monkeypatch.chdir(REPO)
    ref = cli("cam", "profile", *args, "--json")
    csv_text = cli("cam", "profile", *args, "--csv", text=True)
    kw = dict(kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an undercut cam warns; the report says it too
        r = loomkin.cams.profile(kw.pop("cycle", None), **kw)
    tracks = [("points", "")] + ([("counter_points", "counter_")] if "counter_points" in ref else [])
    rows = list(csv.DictReader(io.StringIO(csv_text)))
    for key, prefix in tracks:
        cols, ref_pts = r.pop(key), ref.pop(key)
        assert isinstance(cols, loomkin.Table)
        extra = cols.pop("curvature_profile_per_mm")
        same(records(cols), ref_pts)
        if not prefix:
            # The column the JSON leaves out is the CSV's.
            np.testing.assert_array_equal(extra, [float(row["curvature_profile_per_mm"]) for row in rows])
    same(r, ref)


def test_profile_dxf_matches_cam_profile_dxf(cli, tmp_path, monkeypatch):
    monkeypatch.chdir(REPO)
    out = tmp_path / "cams.dxf"
    cli("cam", "profile", "examples/heald-frame-cycle.toml", "--follower", "translating", "--prime-radius-mm", "90",
        "--roller-radius-mm", "12", "--conjugate", "--dxf", out, "--chord-tol-mm", "0.05", "--json")
    r = loomkin.cams.profile("examples/heald-frame-cycle.toml", "translating", prime_radius_mm=90,
                             roller_radius_mm=12, closure="conjugate", dxf=True, chord_tol_mm=0.05)
    assert r["dxf"] == out.read_text()


def test_profile_geometry():
    """Beyond parity: the pitch point lies at the prime radius plus the lift along the radial
    follower's line, and the working profile is one roller radius inside the pitch curve."""
    c = loomkin.cycles.load(REPO / "examples" / "heald-frame-cycle.toml")
    r = loomkin.cams.profile(c, "translating", prime_radius_mm=120, roller_radius_mm=15, step_deg=0.5)
    p = r["points"]
    lift_mm = 1000 * c(p["angle_deg"])["s"]
    np.testing.assert_allclose(np.hypot(p["x_mm"], p["y_mm"]), 120 + lift_mm, rtol=0, atol=1e-9)
    gap = np.hypot(p["x_mm"] - p["profile_x_mm"], p["y_mm"] - p["profile_y_mm"])
    np.testing.assert_allclose(gap, 15, rtol=0, atol=1e-9)
    assert r["base_radius_mm"] == pytest.approx(120 - 15)


def test_undercut_cam_warns_and_is_not_drawn():
    # A steep rise (60 mm over 40°) on a 40 mm prime circle: the largest roller is about 15.5 mm.
    args = dict(follower="translating", prime_radius_mm=40, roller_radius_mm=20, law="cycloidal", stroke_mm=60,
                motion_deg=40)
    with pytest.warns(UserWarning, match="undercut"):
        r = loomkin.cams.profile(**args)
    assert r["undercut"] and r["roller_max_mm"] < 20
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.profile(dxf=True, **args)
    assert e.value.field == "roller_radius_mm"


def test_profile_errors():
    f = REPO / "examples" / "heald-frame-cycle.toml"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.profile(f, "swinging")
    assert e.value.field == "follower" and "oscillating" in e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.profile(f, "translating", closure="double")
    assert e.value.field == "closure" and "groove" in e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.profile(f, "oscillating", arm_mm=100)
    assert e.value.field == "pivot_mm" and e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.profile(f, "flat")
    assert e.value.field == "prime_radius_mm"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.cams.profile(f, "translating", step_deg=100)
    assert e.value.field == "step_deg" and e.value.high == 90 and e.value.unit == "deg"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.cams.profile(None, "translating", law="cycloidal", stroke_mm=40, motion_deg=200)
    assert e.value.field == "motion_deg" and e.value.high == 180
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cams.table(None, "csv", law="cycloidal", motion_deg=100)
    assert e.value.field == "stroke_mm"


def test_single_rise_arguments_with_a_cycle_are_refused():
    # As `loomkin cam table|profile CYCLE --stroke-mm …` is: the cycle sets the strokes, a stroke
    # given beside it would be ignored.
    f = REPO / "examples" / "heald-frame-cycle.toml"
    for kw in (dict(stroke_mm=50), dict(motion_deg=120), dict(stroke_deg=20), dict(params={"ramp": 0.1})):
        with pytest.raises(loomkin.LoomkinError) as e:
            loomkin.cams.table(f, "csv", **kw)
        assert e.value.field == next(iter(kw)), kw
        with pytest.raises(loomkin.LoomkinError) as e:
            loomkin.cams.profile(f, "translating", **kw)
        assert e.value.field == next(iter(kw)), kw
