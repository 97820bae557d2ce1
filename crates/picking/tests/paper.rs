//! Jederán's published figures: those that the model reproduces, and checks of the reasons why
//! the others cannot be (the full list: docs/design/picking.md).

use loomkin_picking::{Mechanism, Method, Outcome, Setting, Settings, required_velocity_crossings, simulate, sweep};
use std::f64::consts::FRAC_PI_2;

fn run(st: Settings) -> Outcome {
    let m = Mechanism::paper_default();
    let c = simulate(&m, &st, Method::Closed).unwrap();
    let o = simulate(&m, &st, Method::Ode).unwrap();
    assert!((c.velocity_m_s / o.velocity_m_s - 1.0).abs() < 1e-7);
    c
}

fn designed() -> Settings {
    Settings::designed(&Mechanism::paper_default())
}

/// §1.2: A = 690 m/s², T = 3.3·10⁻² s.
#[test]
fn design_values() {
    let d = *Mechanism::paper_default().design();
    assert!((d.a_m_s2 - 690.0).abs() < 0.5);
    assert!((d.t_end_s - 3.3e-2).abs() < 0.05e-2);
}

/// The printed μ = 67.95 1/s and τ = 2.3116·10⁻² s agree with each other (τ = π/2μ) but not with
/// eq. 19: from A = 690.29 m/s² and X₁ = 8.6 cm both forms of eq. 19 give μ = 67.69 1/s.
/// A μ of 67.95 would need A = 695.6 m/s², which eq. 20 does not give.
#[test]
fn printed_mu_is_inconsistent_with_eq19() {
    let d = *Mechanism::paper_default().design();
    assert!((FRAC_PI_2 / 67.95 - 2.3116e-2).abs() < 1e-6, "printed τ follows printed μ");
    assert!((d.mu_1_s - 67.95).abs() > 0.2 && (d.mu_from_distance() - d.mu_1_s).abs() < 1e-9);
    let a_needed = 67.95f64.powi(2) * 0.086 / (FRAC_PI_2 - 1.0);
    assert!((a_needed - d.a_m_s2).abs() > 5.0);
}

/// Fig. 3: with 15.5 mm of strap play the final velocity is higher by ΔV = 3.88 m/s (22.8 %) and
/// the largest acceleration by 1021.17 m/s² (148 %), reached before the end of the pick.
#[test]
fn fig3_play_15_5_mm() {
    let o = run(designed().with_play_mm(15.5));
    assert!((o.velocity_m_s - 17.0 - 3.88).abs() < 0.03, "{}", o.velocity_m_s);
    let a = Mechanism::paper_default().design().a_m_s2;
    assert!((o.accel_peak_m_s2 - a - 1021.17).abs() < 3.0, "{}", o.accel_peak_m_s2);
    assert!(o.t_peak_s < o.t_end_s && o.accel_end_m_s2 < o.accel_peak_m_s2);
}

/// Fig. 4: strap at k = 13 cm: V = 15.33 m/s (90.17 %), X = 14.77 cm (67.14 %), acceleration at
/// the end higher by 329.39 m/s² (47.7 %).
#[test]
fn fig4_strap_13_cm() {
    let o = run(designed().with_strap_cm(13.0));
    assert!((o.velocity_m_s - 15.33).abs() < 0.01, "{}", o.velocity_m_s);
    assert!((o.distance_m - 0.1477).abs() < 0.0002, "{}", o.distance_m);
    let a = Mechanism::paper_default().design().a_m_s2;
    assert!((o.accel_end_m_s2 - a - 329.39).abs() < 1.0, "{}", o.accel_end_m_s2 - a);
}

/// Fig. 5: deviation from the required velocity −5.2 % at 160 rev/min, largest (+1.8 %) near
/// 225 rev/min; 200 → 240 rev/min raises the acceleration by 77 %.
#[test]
fn fig5_speed() {
    let m = Mechanism::paper_default();
    let s = sweep(&m, &designed(), Setting::Speed, 160.0, 240.0, 81, Method::Closed).unwrap();
    let first = &s.rows[0].outcome;
    assert!((first.velocity_vs_required_pct + 5.2).abs() < 0.2, "{}", first.velocity_vs_required_pct);
    let best = s
        .rows
        .iter()
        .max_by(|a, b| a.outcome.velocity_vs_required_pct.total_cmp(&b.outcome.velocity_vs_required_pct))
        .unwrap();
    assert!((best.value - 225.0).abs() <= 8.0 && (best.outcome.velocity_vs_required_pct - 1.8).abs() < 0.15);
    let a = m.design().a_m_s2;
    let last = &s.rows[80].outcome;
    assert!((last.accel_peak_m_s2 / a - 1.77).abs() < 0.01, "{}", last.accel_peak_m_s2 / a);
    // Not reproduced: the paper's +17.85 % velocity at 240 rev/min. The model gives +21.9 %
    // (V/V_r = +1.6 %); +17.85 % would put V 1.8 % below V_r(240) = 20.4 m/s, a fall of 3.6 points
    // within 15 rev/min that the paper's description of Fig. 5 does not mention.
    assert!((last.velocity_m_s / 17.0 - 1.219).abs() < 0.001);
}

/// Fig. 6: the velocity peaks near 12.5 mm of play; 35 mm raises the end acceleration to 340 %;
/// 60 mm leaves 1.1 % of the designed distance.
#[test]
fn fig6_play() {
    let m = Mechanism::paper_default();
    let s = sweep(&m, &designed(), Setting::Play, 0.0, 60.0, 121, Method::Closed).unwrap();
    let best = s.rows.iter().max_by(|a, b| a.outcome.velocity_m_s.total_cmp(&b.outcome.velocity_m_s)).unwrap();
    assert!((best.value - 12.5).abs() <= 1.5, "peak at {}", best.value);
    let a = m.design().a_m_s2;
    let at35 = &s.rows[70].outcome;
    assert!((at35.accel_end_m_s2 / a - 3.40).abs() < 0.06, "{}", at35.accel_end_m_s2 / a);
    let at60 = &s.rows[120].outcome;
    assert!((at60.distance_m / 0.22 - 0.011).abs() < 0.001, "{}", at60.distance_m / 0.22);
}

/// Fig. 8: 0 → 10 kgf of checking raises V by 0.83 m/s (5 %) and shortens the pick by 0.25 cm.
#[test]
fn fig8_checking() {
    let (a, b) = (run(designed().with_checking_kgf(0.0)), run(designed().with_checking_kgf(10.0)));
    assert!((b.velocity_m_s - a.velocity_m_s - 0.83).abs() < 0.005);
    assert!((a.distance_m - b.distance_m - 0.0025).abs() < 0.0001);
}

/// Fig. 10: V highest (+2.4 %) at k ≈ 19–20 cm, a transitory fall of 4.6 % above 23 cm, rising
/// again towards 35 cm; rapid decrease below 19 cm.
#[test]
fn fig10_strap() {
    let m = Mechanism::paper_default();
    let s = sweep(&m, &designed(), Setting::Strap, 13.0, 35.0, 23, Method::Closed).unwrap();
    let v = |k: f64| s.rows.iter().find(|r| (r.value - k).abs() < 1e-9).unwrap().outcome.velocity_m_s;
    assert!((v(20.0) / 17.0 - 1.024).abs() < 0.002, "{}", v(20.0) / 17.0);
    let upper: Vec<_> = s.rows.iter().filter(|r| r.value > 23.0).collect();
    let low = upper.iter().min_by(|a, b| a.outcome.velocity_m_s.total_cmp(&b.outcome.velocity_m_s)).unwrap();
    assert!((low.outcome.velocity_m_s / 17.0 - (1.0 - 0.046)).abs() < 0.002 && low.value < 33.0);
    assert!(v(35.0) > low.outcome.velocity_m_s && v(13.0) < v(17.0) && v(17.0) < v(19.0));
}

/// Fig. 7 (380–520 g): the direction (velocity rises, distance falls by 4.3 %, the paper 4.5 %) is
/// reproduced; the printed 2 cm and 1.44 m/s (8.5 %) are not — they are ~2× and ~3× the model's.
#[test]
fn fig7_shuttle_weight() {
    let (a, b) = (run(designed().with_shuttle_g(380.0)), run(designed().with_shuttle_g(520.0)));
    assert!(b.velocity_m_s > a.velocity_m_s && b.distance_m < a.distance_m);
    assert!(((a.distance_m - b.distance_m) / 0.22 - 0.043).abs() < 0.002);
    assert!((b.velocity_m_s - a.velocity_m_s - 0.44).abs() < 0.01);
}

/// Where the velocity falls below V_r over a play sweep: located on the model (the margin there is
/// zero to rounding), bracketed by the sweep's own rows, and the same as a 10× denser sweep's
/// linear interpolation to that grid's accuracy.
#[test]
fn play_sweep_crossing_of_the_required_velocity() {
    let m = Mechanism::paper_default();
    let s = sweep(&m, &designed(), Setting::Play, 0.0, 60.0, 13, Method::Closed).unwrap();
    let margin = |o: &Outcome| o.velocity_m_s - o.required_velocity_m_s;
    let xs = required_velocity_crossings(&m, &designed(), &s, Method::Closed).unwrap();
    let changes =
        s.rows.windows(2).filter(|w| margin(&w[0].outcome).signum() != margin(&w[1].outcome).signum()).count();
    assert_eq!(xs.len(), changes);
    assert!(!xs.is_empty(), "the play sweep crosses V_r");
    let dense = sweep(&m, &designed(), Setting::Play, 0.0, 60.0, 121, Method::Closed).unwrap();
    for x in xs {
        let o = simulate(&m, &Setting::Play.apply(designed(), x), Method::Closed).unwrap();
        assert!(margin(&o).abs() < 1e-9 * o.required_velocity_m_s, "margin {} at {x}", margin(&o));
        let w = dense.rows.windows(2).find(|w| w[0].value <= x && x <= w[1].value).unwrap();
        let (fa, fb) = (margin(&w[0].outcome), margin(&w[1].outcome));
        let lin = w[0].value + (w[1].value - w[0].value) * fa / (fa - fb);
        assert!((lin - x).abs() < 0.5 * (w[1].value - w[0].value), "{lin} vs {x}");
    }
}
