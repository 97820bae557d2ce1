"""Dobby: parity with `loomkin dobby analyze|synthesize --json`, errors."""

import csv
import io

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same


def test_analyze_matches_dobby_analyze(cli):
    ref = cli("dobby", "analyze", "--alpha-deg", "47", "--step-deg", "5", "--json")
    r = loomkin.dobby.analyze(alpha_deg=47, step_deg=5)
    same(records(r.pop("rows")), ref.pop("rows"))
    same(r, ref)


def test_analyze_ellipse_and_points_give_the_paper_cam(cli):
    ref = cli("dobby", "analyze", "--cam", "ellipse:a=0.366,b=0.577", "--speed-rpm", "300", "--step-deg", "10",
              "--json")
    r = loomkin.dobby.analyze("ellipse:a=0.366,b=0.577", speed_rpm=300, step_deg=10)
    same(records(r.pop("rows")), ref.pop("rows"))
    same(r, ref)


def test_synthesize_matches_dobby_synthesize(cli):
    ref = cli("dobby", "synthesize", "--dwell-deg", "40", "--roller-m", "0.03", "--step-deg", "5", "--json")
    r = loomkin.dobby.synthesize(dwell_deg=40, roller_m=0.03, step_deg=5)
    cam, counter, rows = r.pop("cam"), r.pop("counter_cam"), r.pop("rows")
    same(records(rows), ref.pop("rows"))
    same(r, ref)
    # The cam's roller-centre curve is the rows' roller B positions (b_x_m, b_y_m), point for point
    # (the closed curve without the row at 360°, which repeats 0°).
    n = len(cam["centre_m"])
    assert n == len(rows["b_x_m"]) - 1
    np.testing.assert_array_equal(cam["centre_m"][:, 0], rows["b_x_m"][:n])
    np.testing.assert_array_equal(counter["centre_m"][:, 1], rows["c_y_m"][:n])
    # Independent route: each groove wall lies one roller radius from the centre curve.
    gap = np.hypot(*(cam["wall_left_m"] - cam["centre_m"]).T)
    np.testing.assert_allclose(gap, 0.03, rtol=1e-12)


def test_dobby_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dobby.analyze(alpha_deg=500)
    assert e.value.field == "alpha_deg"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.dobby.analyze("circle:r=1")
    assert e.value.field == "cam"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.dobby.synthesize(law="no-such-law")
    assert e.value.field == "law"


def test_tolerance_matches_dobby_tolerance(cli, tmp_path):
    tomllib = pytest.importorskip("tomllib")

    from loomkin._inputs import study_text

    d = tomllib.loads((REPO / "examples" / "dobby-tolerance.toml").read_text())
    d["draws"], d["step_deg"] = 60, 4
    path = tmp_path / "tol.toml"
    path.write_text(study_text(d))
    ref = cli("dobby", "tolerance", path, "--json")
    text = cli("dobby", "tolerance", path, "--csv", text=True)
    r = loomkin.dobby.tolerance(d)
    draws = r.pop("per_draw")
    same(r, ref)
    rows = list(csv.DictReader(io.StringIO(text)))
    assert list(draws) == list(rows[0])
    for k in draws:
        np.testing.assert_array_equal(draws[k], [float(row[k]) for row in rows])
    # The drawn dimensions keep their truncation bounds.
    assert draws["cam_a_m"].min() >= 0.3657 and draws["cam_a_m"].max() <= 0.3663


def test_tolerance_errors():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.dobby.tolerance({"draws": 10, "seed": 1, "dimensions": {"l2_m": {"dist": "normal", "mean": 0.66}}})
    assert e.value.field is not None


def test_sweep_matches_dobby_sweep(cli):
    ref = cli("dobby", "sweep", "--from", "40", "--to", "50", "--by", "5", "--step-deg", "2", "--json")
    r = loomkin.dobby.sweep([40, 45, 50], step_deg=2)
    assert isinstance(r["rows"], loomkin.Table)
    same(records(r["rows"]), ref["rows"])
    # A row of the sweep is the analysis at that α (the two entry points agree).
    one = loomkin.dobby.analyze(alpha_deg=45, step_deg=2)["summary"]
    for k in ("omega6_min_rad_s", "omega6_max_rad_s", "mu_out_max_deg", "mu_b_max_deg", "rho_c_min_m"):
        assert r["rows"]["an_" + k][1] == one[k], k
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dobby.sweep(np.arange(0.5, 180, 0.1))
    assert e.value.field == "alpha_deg" and e.value.high == 1000
