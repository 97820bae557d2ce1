//! Machine cycles from TOML.

use loomkin_laws::{Cycle, LawSpec};
use std::f64::consts::PI;

const CYCLE: &str = r#"
unit = "mm"
stroke = 100
[[segment]]
kind = "dwell"
to_deg = 60
[[segment]]
kind = "rise"
to_deg = 180
law = "cycloidal"
[[segment]]
kind = "dwell"
to_deg = 240
[[segment]]
kind = "return"
to_deg = 360
law = "modified-trapezoid"
params = { ramp = 0.125 }
"#;

#[test]
fn physical_units_follow_the_chain_rule() {
    let c = Cycle::from_toml(CYCLE).unwrap();
    let rpm = 300.0;
    let omega = rpm * 2.0 * PI / 60.0;
    let beta = 120f64.to_radians();
    // Peak acceleration of the cycloidal rise: h·2π·(ω/β)².
    let k = c.eval(60f64.to_radians() + 0.25 * beta, rpm);
    assert!((k.a - 0.1 * 2.0 * PI * (omega / beta).powi(2)).abs() < 1e-9 * k.a);
    assert!((k.s - 0.1 * LawSpec::Cycloidal.build().unwrap().eval(0.25).s).abs() < 1e-15);
    // In the dwell after the rise the follower sits at the full stroke.
    assert!((c.eval(200f64.to_radians(), rpm).s - 0.1).abs() < 1e-15);
    // Velocity against a finite difference in time.
    let dt = 1e-7;
    let th = 100f64.to_radians();
    let fdv = (c.eval(th + omega * dt, rpm).s - c.eval(th - omega * dt, rpm).s) / (2.0 * dt);
    assert!((fdv - c.eval(th, rpm).v).abs() < 1e-6);
    let pts = c.sample(361, rpm);
    assert!(pts.last().unwrap().kin.s.abs() < 1e-9, "the cycle closes");
    assert!((pts.last().unwrap().time_s - 0.2).abs() < 1e-12, "one turn at 300 rpm takes 0.2 s");
}

#[test]
fn errors_name_the_field() {
    let gap = CYCLE.replace("to_deg = 360", "to_deg = 350");
    let e = Cycle::from_toml(&gap).unwrap_err().to_string();
    assert!(e.contains("segment[3].to_deg") && e.contains("close"), "{e}");
    let bad_law = CYCLE.replace(
        "law = \"cycloidal\"",
        "law = \"piecewise\"\nparams = { segments = \"0.6:constant:1,0.6:constant:-1\" }",
    );
    let e = Cycle::from_toml(&bad_law).unwrap_err().to_string();
    assert!(e.contains("segment[1].law") && e.contains("sum to 1.2"), "{e}");
    let e = Cycle::from_toml("unit = \"mm\"\n[[segment]]\nkind = \"fly\"\nto_deg = 360\n").unwrap_err().to_string();
    assert!(e.contains("cycle file"), "{e}");
    let unbalanced = CYCLE.replace("params = { ramp = 0.125 }", "params = { ramp = 0.125 }\nstroke = 90");
    let e = Cycle::from_toml(&unbalanced).unwrap_err().to_string();
    assert!(e.contains("rises and returns must balance"), "{e}");
}

#[test]
fn swinging_follower_in_radians_and_a_shifted_start() {
    let text = r#"
unit = "deg"
[[segment]]
kind = "rise"
from_deg = 30
length_deg = 90
law = "poly345"
stroke = 20
[[segment]]
kind = "dwell"
length_deg = 90
[[segment]]
kind = "return"
length_deg = 180
law = "cycloidal"
stroke = 20
"#;
    let c = Cycle::from_toml(text).unwrap();
    let rpm = 120.0;
    let omega = rpm * 2.0 * PI / 60.0;
    let h = 20f64.to_radians();
    // Mid-rise of the 3-4-5 law: s = h/2, v = h·(15/8)·ω/β.
    let k = c.eval(75f64.to_radians(), rpm);
    assert!((k.s - h / 2.0).abs() < 1e-14);
    assert!((k.v - h * 15.0 / 8.0 * omega / 90f64.to_radians()).abs() < 1e-12);
    // Angles wrap: 390° is 30°, the start of the rise; 10° lies in the return (210°–390°).
    assert!(c.eval(390f64.to_radians(), rpm).s.abs() < 1e-15);
    let back = c.eval(10f64.to_radians(), rpm);
    let law = LawSpec::Cycloidal.build().unwrap();
    let x = (370.0 - 210.0) / 180.0;
    assert!((back.s - h * (1.0 - law.eval(x).s)).abs() < 1e-14);
    assert!(back.v < 0.0, "returning");
}

/// The last sample is the cycle's end as the left limit: the return's law at x = 1, scaled by the
/// chain rule (h·a(1)·(ω/β)², h·j(1)·(ω/β)³) from the normalised law alone. A law ends at rest, so
/// the acceleration there is rounding (the modified trapezoid's a(1) is −6e-16); evaluated 1e-12 of
/// the period before the end it was j·Δt = 4.1e-9 m/s², 3e-11 of the peak.
#[test]
fn last_sample_is_the_left_limit_at_the_end() {
    let c = Cycle::from_toml(CYCLE).unwrap();
    let rpm = 300.0;
    let r = rpm * 2.0 * PI / 60.0 / 120f64.to_radians();
    let law = LawSpec::ModifiedTrapezoid { ramp: 0.125 }.build().unwrap().eval(1.0);
    let end = c.sample(3, rpm)[2];
    assert_eq!(end.angle_deg, 360.0);
    let want = [0.1 - 0.1 * law.s, -0.1 * law.v * r, -0.1 * law.a * r * r, -0.1 * law.j * r.powi(3)];
    let got = [end.kin.s, end.kin.v, end.kin.a, end.kin.j];
    for (k, (g, w)) in got.iter().zip(want).enumerate() {
        assert!((g - w).abs() <= 1e-12 * w.abs().max(1e-3), "derivative {k}: {g:e} vs {w:e}");
    }
    assert!(end.kin.a.abs() < 1e-12, "{:e}", end.kin.a);
}
