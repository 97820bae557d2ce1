//! Time-true cams against a shaft whose time is known in closed form: `1/ω = (1 + ε·cos φ)/ω₀`,
//! so `t(φ) = (φ + ε·sin φ)/ω₀` exactly and the mean speed is ω₀.

use loomkin_drive::{TimeMap, correct_move};
use loomkin_laws::{Law, LawSpec};
use std::f64::consts::TAU;

const W0: f64 = 50.0;
const EPS: f64 = 0.03;

fn exact_t(p: f64) -> f64 {
    (p + EPS * p.sin()) / W0
}

/// The map through a grid of `n` steps over a turn, fed the exact values.
fn map(n: usize, eps: f64) -> TimeMap {
    let phi: Vec<f64> = (0..=n).map(|k| TAU * k as f64 / n as f64).collect();
    let t = phi.iter().map(|p| (p + eps * p.sin()) / W0).collect();
    let w = phi.iter().map(|p| W0 / (1.0 + eps * p.cos())).collect();
    let dw = phi.iter().map(|p| W0 * eps * p.sin() / (1.0 + eps * p.cos()).powi(2)).collect();
    TimeMap::new(phi, t, w, dw)
}

/// The shaft's angle at time `t` on the exact map (Newton).
fn exact_angle(t: f64) -> f64 {
    let mut p = t * W0;
    for _ in 0..50 {
        let step = (exact_t(p) - t) * W0 / (1.0 + EPS * p.cos());
        p -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    p
}

#[test]
fn the_time_map_interpolates_the_time_between_its_points() {
    let m = map(3600, EPS);
    assert!((m.mean_speed_rad_s() - W0).abs() <= 1e-13 * W0);
    let mut worst: f64 = 0.0;
    let mut worst_angle: f64 = 0.0;
    for k in 0..10_007 {
        // Beyond the repeat too: periodic.
        let p = -3.0 + 20.0 * k as f64 / 10_007.0;
        let [t, d, _] = m.time(p);
        worst = worst.max((t - exact_t(p)).abs() * W0);
        assert!((d - (1.0 + EPS * p.cos()) / W0).abs() <= 1e-11 / W0, "{p}");
        worst_angle = worst_angle.max((m.angle(t) - p).abs());
    }
    // Quintic Hermite at 0.1°: truncation ~1e-20 rad; what is left is rounding.
    assert!(worst <= 1e-14, "{worst:e} rad");
    assert!(worst_angle <= 1e-13, "{worst_angle:e}");
}

/// The corrected law against the exact composition (1° quintic Hermite panels: measured 8e-15 of
/// the stroke over a 280° move, 4.5e-12 over a 90° one, whose law bends more per degree) s(ψ(φ)), ψ = a + ω₀·(t(φ) − t(a)).
fn check(law: &Law, spec: &LawSpec, start: f64, motion: f64, tol: f64) -> f64 {
    let m = map(3600, EPS);
    let anchor = start + motion / 2.0;
    let c = correct_move(&m, law, start, motion, anchor).unwrap();
    let psi = |p: f64| anchor + W0 * (exact_t(p) - exact_t(anchor));
    // The ends map onto the design's ends.
    assert!((psi(c.start_rad) - start).abs() <= 1e-12, "{spec:?}");
    assert!((psi(c.start_rad + c.length_rad) - (start + motion)).abs() <= 1e-12);
    let mut worst: f64 = 0.0;
    for k in 0..=4000 {
        let x = k as f64 / 4000.0;
        let p = c.start_rad + x * c.length_rad;
        let u = ((psi(p) - start) / motion).clamp(0.0, 1.0);
        worst = worst.max((c.law.eval(x).s - law.eval(u).s).abs());
    }
    assert!(worst <= tol, "{spec:?}: {worst:e}");
    // In time: the follower of the corrected cam, at the angle the shaft has reached at time t,
    // is where the design law puts it at the constant mean speed, t from the anchor's time.
    let t_a = exact_t(anchor);
    let mut worst_t: f64 = 0.0;
    for k in 0..=2000 {
        let tau = (k as f64 / 2000.0 - 0.5) * motion / W0;
        let p = exact_angle(t_a + tau);
        let x = ((p - c.start_rad) / c.length_rad).clamp(0.0, 1.0);
        let u = ((anchor + W0 * tau - start) / motion).clamp(0.0, 1.0);
        worst_t = worst_t.max((c.law.eval(x).s - law.eval(u).s).abs());
    }
    assert!(worst_t <= tol, "{spec:?} in time: {worst_t:e}");
    worst.max(worst_t)
}

#[test]
fn a_corrected_move_runs_in_time_as_designed() {
    for spec in
        [LawSpec::ModifiedTrapezoid { ramp: 0.125 }, LawSpec::Cycloidal, LawSpec::Poly345, LawSpec::ModifiedSine]
    {
        let law = spec.build().unwrap();
        // A 280° move starting at 210°, and a short one (90°).
        let a = check(&law, &spec, 210f64.to_radians(), 280f64.to_radians(), 1e-11);
        let b = check(&law, &spec, 1.0, 90f64.to_radians(), 1e-11);
        eprintln!("{spec:?}: largest |Δs| {a:.1e} (280°), {b:.1e} (90°) of the stroke");
    }
}

#[test]
fn at_a_constant_speed_nothing_is_corrected() {
    let m = map(360, 0.0);
    let spec = LawSpec::ModifiedTrapezoid { ramp: 0.125 };
    let law = spec.build().unwrap();
    let c = correct_move(&m, &law, 0.5, 4.0, 2.5).unwrap();
    assert!((c.start_rad - 0.5).abs() <= 1e-15 && (c.length_rad - 4.0).abs() <= 1e-14);
    for k in 0..=1000 {
        let x = k as f64 / 1000.0;
        let (a, b) = (c.law.eval(x), law.eval(x));
        assert!((a.s - b.s).abs() <= 1e-12 && (a.v - b.v).abs() <= 1e-10, "{x}: {a:?} {b:?}");
    }
}
