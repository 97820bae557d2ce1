"""Cam tables: parity with `loomkin cam table --json` and the file it writes, errors."""

import pytest

import loomkin
from conftest import REPO, same


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
