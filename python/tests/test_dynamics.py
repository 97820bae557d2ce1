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


def test_spectrum_matches_dyn_spectrum_csv(cli):
    laws = ["cycloidal", "modified-trapezoid:ramp=0.2", "examples/sley-cycle.toml"]
    text = cli("dyn", "spectrum", *laws, "--damping-ratio", "0,0.05", "--ratio", "0.5:5:0.05", "--csv", text=True)
    rows = list(csv.DictReader(io.StringIO(text)))
    ratio = np.array([float(row["motion_time_over_natural_period"]) for row in rows])
    t = loomkin.dynamics.spectrum(["cycloidal", "modified-trapezoid:ramp=0.2", REPO / "examples" / "sley-cycle.toml"],
                                  ratio, damping_ratio=[0, 0.05])
    assert list(t) == list(rows[0])
    for k in t:
        np.testing.assert_array_equal(t[k], [float(row[k]) for row in rows])
    # A law given twice: its own column each, named as the CLI names them (`cycloidal_2`).
    twice = cli("dyn", "spectrum", "cycloidal", "cycloidal", "--ratio", "0.5:1:0.5", "--csv", text=True)
    assert ",".join(loomkin.dynamics.spectrum(["cycloidal", "cycloidal"], [0.5, 1.0])) == twice.splitlines()[0]
    # The CLI's default ratios (0.5:10:0.01) are the package's default.
    default = loomkin.dynamics.spectrum(loomkin.Law("cycloidal"))["motion_time_over_natural_period"]
    assert default[0] == 0.5 and default[-1] == 10.0 and len(default) == 951
    # A second route: the cycloidal law's undamped spectrum in closed form, |sin πr| / (π r |r² − 1|).
    r = np.linspace(0.5, 10, 400)
    r = r[np.abs(r - 1) > 1e-3]
    pct = loomkin._loomkin.dyn_spectrum(loomkin.Law("cycloidal"), r)
    closed = 100 * np.abs(np.sin(np.pi * r)) / (np.pi * r * np.abs(r * r - 1))
    np.testing.assert_allclose(pct, closed, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("zeta", ["0", "0.05"])
def test_compensate_matches_dyn_compensate(cli, tmp_path, zeta):
    tomllib = pytest.importorskip("tomllib")

    args = ["dyn", "compensate", "examples/heald-frame-cycle.toml", "--speed-rpm", "600", "--natural-hz", "54",
            "--damping-ratio", zeta, "--points", "91"]
    out_csv, out_toml = tmp_path / "c.csv", tmp_path / "c.toml"
    cli(*args, "-o", out_csv, text=True)
    cli(*args, "-o", out_toml, text=True)
    r = loomkin.dynamics.compensate(FILE, 54, damping_ratio=float(zeta), speed_rpm=600, points=91)
    rows = list(csv.DictReader(io.StringIO(out_csv.read_text())))
    s = r["samples"]
    assert list(s) == list(rows[0])
    for k in s:
        np.testing.assert_array_equal(s[k], [float(row[k]) for row in rows])
    ref = tomllib.loads(out_toml.read_text())
    for k in ("speed_rpm", "natural_hz", "damping_ratio", "designed_class", "input_class"):
        assert r[k] == ref[k], k
    assert len(r["pieces"]) == len(ref["piece"])
    for p, q in zip(r["pieces"], ref["piece"]):
        assert p["from_deg"] == q["from_deg"] and p["to_deg"] == q["to_deg"]
        assert p["poly"] == q["poly"]
        assert (p["sine"] is None) == ("sin_cos" not in q)
        if p["sine"] is not None:
            assert p["sine"][:2] == q["sin_cos"] and p["sine"][2] == q["omega_rad_s"]
        assert (p["exp"] or None) == q.get("exp")
    # A second route: the input drives the follower onto the designed motion, so (undamped)
    # x'' + ω²(x − s) = 0 with x the design: the input's acceleration is not needed, its position is
    # s = x + x''/ω² (no mass, so no loads).
    if zeta == "0":
        cyc = loomkin.cycles.load(FILE)
        a = cyc(s["angle_deg"][1:-1], speed_rpm=600)["a"]
        w = 2 * np.pi * 54
        np.testing.assert_allclose(s["s_mm"][1:-1], 1000 * (cyc(s["angle_deg"][1:-1], speed_rpm=600)["s"] + a / w**2),
                                   rtol=0, atol=1e-9)


def test_optimize_matches_dyn_optimize(cli, tmp_path):
    out = tmp_path / "quiet.toml"
    ref = cli("dyn", "optimize", "examples/heald-frame-cycle.toml", "--speed-rpm", "600", "--natural-hz", "54",
              "--damping-ratio", "0.05", "--band-pct", "10", "-o", out, "--json")
    r = loomkin.dynamics.optimize(FILE, 54, damping_ratio=0.05, speed_rpm=600, band_pct=10)
    assert r.pop("cycle_toml") == out.read_text()
    same(r, ref)
    # The optimised file is a cycle the package reads, quieter across the band than the original.
    quiet = loomkin.Cycle.from_toml(out.read_text())
    speeds = np.linspace(540, 660, 13)
    before = loomkin.dynamics.sweep(FILE, speeds, 54, damping_ratio=0.05)["points"]["residual_amplitude_mm"]
    after = loomkin.dynamics.sweep(quiet, speeds, 54, damping_ratio=0.05)["points"]["residual_amplitude_mm"]
    assert after.max() < before.max()


@pytest.mark.parametrize("steady", [False, True])
def test_two_mass_matches_dyn_two_mass(cli, steady):
    args = ["dyn", "two-mass", "examples/heald-frame-cycle.toml", "--speed-rpm", "400", "--drive-mass-kg", "20",
            "--drive-stiffness-n-m", "5e6", "--frame-mass-kg", "30", "--frame-stiffness-n-m", "8e6",
            "--damping-ratio", "0.03"]
    ref = cli(*args, *(["--steady"] if steady else []), "--json")
    r = loomkin.dynamics.two_mass(FILE, 20, 5e6, 30, 8e6, damping_ratio=0.03, speed_rpm=400, steady=steady)
    same(r, ref)
    # A second route: the modal frequencies are the roots of det(K − ω²M) = 0.
    m1, k1, m2, k2 = 20.0, 5e6, 30.0, 8e6
    K = np.array([[k1 + k2, -k2], [-k2, k2]])
    M = np.diag([m1, m2])
    w2 = np.sort(np.linalg.eigvals(np.linalg.solve(M, K)).real)
    np.testing.assert_allclose(r["natural_hz"], np.sqrt(w2) / (2 * np.pi), rtol=1e-12)


def test_new_dynamics_errors():
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.spectrum("cycloidal", [0.0, 1.0])
    assert e.value.field == "ratio" and e.value.low == 0 and not e.value.low_inclusive
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.spectrum("cycloidal", [1.0], damping_ratio=1.0)
    assert e.value.field == "damping_ratio" and e.value.high == 1 and not e.value.high_inclusive
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.dynamics.spectrum("no-such-law", [1.0])
    assert e.value.field is not None and "cycloidal" in e.value.allowed
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.optimize(FILE, 54, band_pct=95)
    assert e.value.field == "band_pct" and e.value.high == 90 and e.value.unit == "%"
    with pytest.raises(loomkin.OutOfRangeError) as e:
        loomkin.dynamics.two_mass(FILE, -1, 5e6, 30, 8e6)
    assert e.value.field is not None and e.value.value == -1
    # A cycle whose designed acceleration jumps has no undamped compensation.
    jumpy = {"unit": "mm", "stroke": 50, "segment": [
        {"kind": "rise", "to_deg": 120, "law": "harmonic"}, {"kind": "dwell", "to_deg": 180},
        {"kind": "return", "to_deg": 300, "law": "harmonic"}, {"kind": "dwell", "to_deg": 360}]}
    with pytest.raises(loomkin.LoomkinError) as e:
        loomkin.dynamics.compensate(jumpy, 54)
    assert e.value.field == "cycle"
