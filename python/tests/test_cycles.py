"""Cycles: parity with `loomkin cycle FILE --json`, dict input, errors."""

import sys

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same

FILE = REPO / "examples" / "heald-frame-cycle.toml"


def test_report_matches_cycle_json(cli):
    ref = cli("cycle", "examples/heald-frame-cycle.toml", "--speed-rpm", "400", "--points", "361", "--json")
    r = loomkin.cycles.report(FILE, speed_rpm=400, points=361)
    samples = r.pop("samples")
    same(records(samples), ref.pop("samples"))
    same(r, ref)


def test_file_speed_is_the_default(cli):
    ref = cli("cycle", "examples/heald-frame-cycle.toml", "--json")
    r = loomkin.cycles.load(FILE).report()
    assert r["speed_rpm"] == ref["speed_rpm"] == 300
    same(records(r["samples"]), ref["samples"])


@pytest.mark.skipif(sys.version_info < (3, 11), reason="tomllib is Python ≥ 3.11")
def test_dict_gives_the_same_cycle_as_the_file():
    import tomllib

    spec = tomllib.loads(FILE.read_text())
    a = loomkin.cycles.report(spec, speed_rpm=500, points=181)
    b = loomkin.cycles.report(FILE, speed_rpm=500, points=181)
    same(a["segments"], b["segments"])
    same(a["samples"], {k: v.tolist() for k, v in b["samples"].items()})


def test_call_matches_samples():
    c = loomkin.cycles.load(FILE)
    s = c.report(speed_rpm=300, points=7)["samples"]
    out = c(s["angle_deg"][:-1], 300)
    np.testing.assert_array_equal(out["s"], s["s_m"][:-1])
    np.testing.assert_array_equal(out["a"], s["a_m_s2"][:-1])


def test_bad_cycles_raise():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.cycles.from_dict({"unit": "mm", "stroke": 10, "segment": [{"kind": "rise", "to_deg": 200}]})
    assert e.value.field is not None
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.cycles.load(FILE).report(speed_rpm=-5)
    assert e.value.field == "speed_rpm"


def test_sample_matches_cycle_csv(cli):
    import csv
    import io

    text = cli("cycle", "examples/sley-cycle.toml", "--speed-rpm", "450", "--points", "1001", "--csv", text=True)
    rows = list(csv.DictReader(io.StringIO(text)))
    s = loomkin.cycles.sample(REPO / "examples" / "sley-cycle.toml", speed_rpm=450, points=1001)
    assert isinstance(s, loomkin.Table) and list(s) == list(rows[0])
    for k in s:
        assert s[k].dtype == np.float64 and s[k].flags["C_CONTIGUOUS"] and s[k].flags["WRITEABLE"]
        np.testing.assert_array_equal(s[k], [float(row[k]) for row in rows])


def test_to_toml_and_laws():
    c = loomkin.cycles.load(FILE)
    back = loomkin.Cycle.from_toml(c.to_toml())
    same(back.report(points=91), c.report(points=91))
    laws = c.laws()
    assert [i for i, _ in laws] == [1, 3]
    assert all(isinstance(law, loomkin.Law) for _, law in laws)
    # The segment's law sampled as a law is the cycle's motion there, scaled.
    _, rise = laws[0]
    x = np.linspace(0, 1, 11)
    seg = c.segments()[1]
    ang = seg["from_deg"] + x * (seg["to_deg"] - seg["from_deg"])
    np.testing.assert_allclose(c(ang[:-1])["s"], seg["stroke_m"] * rise(x[:-1])["s"], rtol=0, atol=1e-15)
