"""Laws: parity with `loomkin law … --json`, arrays, errors."""

import numpy as np
import pytest

import loomkin
from conftest import REPO, records, same

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


def test_one_result_type_for_samples():
    """issue 27: Law.sample() returned a dict while laws.sample() returned a Table."""
    law = loomkin.Law("cycloidal")
    for t in (law.sample(11), loomkin.laws.sample("cycloidal", 11), law(np.linspace(0, 1, 11))):
        assert type(t) is loomkin.Table and list(t) == ["x", "s", "v", "a", "j"]
    np.testing.assert_array_equal(law.sample(11)["s"], loomkin.laws.sample("cycloidal", 11)["s"])
    assert type(loomkin.cycles.load(REPO / "examples" / "heald-frame-cycle.toml").sample(points=5)) is loomkin.Table


def test_call_broadcasts_as_numpy_functions_do():
    """issue 27: Law(…)(0.5) and 2-D arrays raised `dimensionality mismatch`."""
    law = loomkin.Law("cycloidal")
    one = law(0.25)
    assert all(isinstance(v, float) for v in one.values())
    # Independent route: the closed form at x = 1/4, s = 1/4 − 1/(2π), v = 1 − cos(π/2) = 1.
    assert one["s"] == pytest.approx(0.25 - 1 / (2 * np.pi), abs=1e-15)
    assert one["v"] == pytest.approx(1.0, abs=1e-15)
    x = np.linspace(0.0, 1.0, 12).reshape(3, 4)
    grid = law(x)
    flat = law(x.ravel())
    for k in ("x", "s", "v", "a", "j"):
        assert grid[k].shape == (3, 4)
        np.testing.assert_array_equal(grid[k].ravel(), flat[k])
    # A transposed (non-contiguous) view keeps its logical order; a 0-d array is a number.
    np.testing.assert_array_equal(law(x.T)["s"], grid["s"].T)
    assert isinstance(law(np.float64(0.5))["s"], float)
    c = loomkin.cycles.load(REPO / "examples" / "heald-frame-cycle.toml")
    assert isinstance(c(90.0)["s"], float) and c(np.zeros((2, 5)))["a"].shape == (2, 5)


@pytest.mark.parametrize("name", ["cycloidal", "modified-sine", "poly345", "constant-acceleration", "harmonic"])
def test_outside_the_rise_the_follower_dwells(name):
    """issue 27: outside [0, 1] s, v, a took the dwell values but j kept 39.48 (cycloidal): the
    derivatives of a dwell are 0, and s holds the end the follower rests at."""
    law = loomkin.Law(name)
    before, after = law(np.array([-1e-9, -0.5, -3.0])), law(np.array([1 + 1e-9, 1.5, 40.0]))
    for out, s in ((before, law(0.0)["s"]), (after, law(1.0)["s"])):
        np.testing.assert_array_equal(out["s"], s)
        for k in ("v", "a", "j"):
            np.testing.assert_array_equal(out[k], 0.0)


def test_bad_counts_raise_the_package_error_naming_the_field():
    """issue 27: sample(-5) raised a raw OverflowError."""
    law = loomkin.Law("cycloidal")
    for bad in (-5, 2**70, -(2**70), 1):
        with pytest.raises(loomkin.OutOfRangeError) as e:
            law.sample(bad)
        assert e.value.field == "points" and e.value.low == 2 and e.value.value == float(bad)
    for bad in ("ten", 2.5, True, None):
        with pytest.raises(loomkin.LoomkinError) as e:
            loomkin.laws.sample("cycloidal", bad)
        assert e.value.field == "points" and "whole number" in e.value.allowed
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.picking.history(points=-1)
    assert e.value.field == "points"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dobby.synthesize(cycles=-2)
    assert e.value.field == "cycles"
    # numpy integers are integers.
    assert law.sample(np.int64(5))["x"].shape == (5,)
