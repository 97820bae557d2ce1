"""Laws: parity with `loomkin law … --json`, arrays, errors."""

import numpy as np
import pytest

import loomkin
from conftest import records, same

PIECEWISE = "0.25:sine-ramp:0:1,0.5:half-cosine:1:-1,0.25:cosine-ramp:-1:0"


def test_catalogue_matches_law_list(cli):
    same(loomkin.laws.catalogue(), cli("law", "list", "--json")["laws"])


@pytest.mark.parametrize(
    "name,params",
    [
        ("cycloidal", {}),
        ("poly4567", {}),
        ("modified-trapezoid", {"ramp": 0.1}),
        ("modified-sine", {}),
        ("piecewise", {"segments": PIECEWISE}),
        ("polynomial", {"segments": "0.5:1,0.5:-1"}),
    ],
)
def test_info_matches_law_info(cli, name, params):
    args = [f"--param={k}={v}" for k, v in params.items()]
    same(loomkin.laws.info(name, **params), cli("law", "info", name, *args, "--json"))


def test_sample_matches_law_sample(cli):
    ref = cli("law", "sample", "modified-trapezoid", "--param", "ramp=0.1", "--points", "101", "--json")
    t = loomkin.laws.sample("modified-trapezoid", 101, ramp=0.1)
    assert list(t) == ["x", "s", "v", "a", "j"]
    assert all(isinstance(c, np.ndarray) and c.dtype == np.float64 and c.shape == (101,) for c in t.values())
    same(records(t), ref["points"])


def test_call_evaluates_at_given_positions():
    law = loomkin.Law("cycloidal")
    x = np.linspace(0.0, 1.0, 7)
    out = law(x)
    # Independent route: the cycloidal law in closed form, s = x − sin(2πx)/(2π).
    np.testing.assert_allclose(out["s"], x - np.sin(2 * np.pi * x) / (2 * np.pi), rtol=0, atol=1e-15)
    np.testing.assert_allclose(out["a"], 2 * np.pi * np.sin(2 * np.pi * x), rtol=0, atol=1e-12)
    # A list is accepted too, and the samples (an angle-addition recurrence, not one evaluation
    # per point) agree with the evaluation at the same points to rounding.
    np.testing.assert_allclose(law(list(x))["v"], law.sample(7)["v"], rtol=0, atol=1e-14)


def test_law_object_reports():
    law = loomkin.Law("modified-trapezoid", ramp=0.1)
    assert law.name == "modified-trapezoid" and law.params == {"ramp": 0.1}
    assert law.label == "modified-trapezoid (ramp=0.1)"
    m = law.metrics()
    assert m["cv"] == pytest.approx(2.0, abs=1e-12)
    c = law.continuity()
    assert c["class"] == 2 and len(c["joints"]) == law.segments - 1
    assert len(law.joints) == law.segments - 1


def test_out_of_range_parameter_raises_with_field_and_range():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.Law("modified-trapezoid", ramp=0.3)
    err = e.value
    assert isinstance(err, ValueError) and isinstance(err, loomkin.LoomkinError)
    assert err.field == "ramp" and err.value == 0.3
    assert err.low == 1e-6 and err.high == 0.25 and err.low_inclusive and err.high_inclusive
    assert err.allowed == "1e-6 ≤ ramp ≤ 0.25"
    assert "ramp = 0.3 is out of range" in str(err)


def test_unknown_law_and_parameter_raise():
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.Law("no-such-law")
    assert e.value.field == "law" and "cycloidal" in e.value.allowed
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.Law("cycloidal", ramp=0.1)
    assert e.value.field == "ramp"
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.Law("piecewise", segments="0.5:constant:1,0.4:constant:-1")
    assert e.value.field == "segments"


def test_too_few_points_raise():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.Law("cycloidal").sample(1)
    assert e.value.field == "points" and e.value.low == 2
