"""Shedding: parity with `loomkin shed … --json`, tables as arrays and DataFrames, errors."""

import numpy as np
import pytest

import loomkin
from conftest import records, same


def test_presets_match_shed_list(cli):
    same(loomkin.shed.presets(), cli("shed", "list", "--json")["laws"])


def test_law_matches_shed_law(cli):
    same(loomkin.shed.law("dobby", threshold=0.95), cli("shed", "law", "dobby", "--threshold", "0.95", "--json"))
    same(
        loomkin.shed.law("smooth", motion_deg=240, stroke_mm=120, speed_rpm=500),
        cli("shed", "law", "smooth", "--motion-deg", "240", "--stroke-mm", "120", "--speed-rpm", "500", "--json"),
    )


def _rows(t):
    return [{k: v for k, v in r.items() if v is not None} for r in records(t)]


def test_table_matches_shed_table(cli):
    same(_rows(loomkin.shed.table()), cli("shed", "table", "--json")["rows"])
    same(
        _rows(loomkin.shed.table(design="table1", motion_deg="240,300")),
        cli("shed", "table", "--design", "table1", "--motion-deg", "240,300", "--json")["rows"],
    )


def test_pareto_matches_shed_pareto(cli):
    t = loomkin.shed.pareto(step=0.1)
    same(_rows(t), cli("shed", "pareto", "--step", "0.1", "--json")["rows"])
    # Independent route: no row of the front is dominated by another (window larger or equal and
    # peak acceleration smaller or equal, one strictly).
    w, a = t["window_deg"], t["peak_accel_m_s2"]
    for i in range(len(w)):
        dominated = (w >= w[i]) & (a <= a[i]) & ((w > w[i]) | (a < a[i]))
        assert not dominated.any()


def test_best_matches_shed_best(cli):
    same(loomkin.shed.best(175, step=0.02), cli("shed", "best", "--window-deg", "175", "--step", "0.02", "--json"))


def test_table_frame():
    pd = pytest.importorskip("pandas")
    f = loomkin.shed.table().frame()
    assert isinstance(f, pd.DataFrame) and "window_deg" in f.columns and len(f) == len(loomkin.shed.presets())


def test_shed_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.shed.law("dobby", threshold=1.5)
    assert e.value.field == "threshold"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.shed.table(design="random")
    assert e.value.field == "design"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.shed.law("dobby", stroke_mm=0)
    assert e.value.field == "stroke_mm"


LOOM = ["--carrier-speed-m-s", "24", "--reed-width-m", "1.8", "--carrier-length-m", "0.09",
        "--crossing-range-deg", "15", "--speed-rpm", "250"]


def test_window_matches_shed_window(cli):
    r = loomkin.shed.window(24, 1.8, carrier_length_m=0.09, crossing_range_deg=15, speed_rpm=250)
    same(r, cli("shed", "window", *LOOM, "--json"))
    # Closed form: the flight 6n(L_cloth + l)/v deg, plus the crossing range; T = 1/(1 + excess).
    assert r["flight_deg"] == pytest.approx(6 * 250 * (1.8 + 0.09) / 24, rel=1e-14)
    assert r["required_window_deg"] == pytest.approx(r["flight_deg"] + 15, rel=1e-14)
    assert r["threshold"] == pytest.approx(1 / 1.05, rel=1e-14)
    same(loomkin.shed.window(30, 2.2, cloth_width_m=1.9, shed_excess=0.1),
         cli("shed", "window", "--carrier-speed-m-s", "30", "--reed-width-m", "2.2", "--cloth-width-m", "1.9",
             "--shed-excess", "0.1", "--json"))


def test_window_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.shed.window(24, 0)
    assert e.value.field == "reed_width_m" and e.value.low == 0 and not e.value.low_inclusive
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.shed.window(24, 1.8, cloth_width_m=2.0)
    assert e.value.field == "cloth_width_m" and e.value.high == 1.8 and e.value.unit == "m"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.shed.window(24, 1.8, speed_rpm=-5)
    assert e.value.field == "speed_rpm"
