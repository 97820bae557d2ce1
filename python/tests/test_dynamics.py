"""Dynamics: parity with `loomkin dyn response --json` and `--csv`, errors."""

import csv
import io

import numpy as np
import pytest

import loomkin
from conftest import REPO, same

FILE = REPO / "examples" / "heald-frame-cycle.toml"
ARGS = ["dyn", "response", "examples/heald-frame-cycle.toml", "--speed-rpm", "600", "--natural-hz", "54",
        "--damping-ratio", "0.05"]


@pytest.mark.parametrize("steady", [False, True])
def test_response_matches_dyn_response(cli, steady):
    ref = cli(*ARGS, *(["--steady"] if steady else []), "--json")
    r = loomkin.dynamics.response(FILE, 54, damping_ratio=0.05, speed_rpm=600, steady=steady)
    r.pop("samples")
    same(r, ref)


def test_samples_match_dyn_response_csv(cli):
    text = cli(*ARGS, "--mass-kg", "12", "--preload-n", "300", "--points", "91", "--csv", text=True)
    rows = list(csv.DictReader(io.StringIO(text)))
    r = loomkin.dynamics.response(FILE, 54, damping_ratio=0.05, speed_rpm=600, mass_kg=12, preload_n=300, points=91)
    s = r["samples"]
    assert list(s) == list(rows[0])
    for k in s:
        # The CSV prints shortest round-trip decimals: parsed back they are the same doubles.
        np.testing.assert_array_equal(s[k], [float(row[k]) for row in rows])


def test_dynamics_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.response(FILE, -1)
    assert e.value.field == "natural_hz"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.response(FILE, 54, cycles=0)
    assert e.value.field == "cycles"


def test_sweep_matches_dyn_sweep(cli):
    ref = cli("dyn", "sweep", "examples/heald-frame-cycle.toml", "--natural-hz", "54", "--damping-ratio", "0.05",
              "--speed-rpm", "200:1000:10", "--json")
    speeds = np.arange(200.0, 1000.0 + 1e-9, 10.0)
    r = loomkin.dynamics.sweep(FILE, speeds, 54, damping_ratio=0.05)
    pts = r.pop("points")
    ref_pts = ref.pop("points")
    same(r, ref)
    # The CLI's span 200:1000:10 computes its speeds as from + i·step: the same doubles as arange here.
    for k in pts:
        np.testing.assert_array_equal(pts[k], [p[k] for p in ref_pts])
    # A point of the sweep is the response at that speed (the two entry points agree).
    one = loomkin.dynamics.response(FILE, 54, damping_ratio=0.05, speed_rpm=speeds[7])
    for k in ("peak_dynamic_error_mm", "residual_amplitude_mm", "rigidity_ratio"):
        assert pts[k][7] == one[k]
    # The dwell after the rise (180°…240°) starts with the residual amplitude and decays: no
    # sampled error there exceeds it.
    s = one["samples"]
    dwell = (s["angle_deg"] >= 180) & (s["angle_deg"] <= 240)
    assert np.abs(s["error_mm"][dwell]).max() <= one["residual_amplitude_mm"] * (1 + 1e-9)
