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
