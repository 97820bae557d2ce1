//! The closed form against numerical integration, and the closed form against its own equation.

use loomkin_picking::{Mechanism, Method, Outcome, PickError, Settings, StartRule, history, simulate};
use proptest::prelude::*;

fn rel(a: f64, b: f64, scale: f64) -> f64 {
    (a - b).abs() / (a.abs().max(b.abs()).max(scale))
}

/// Every end-of-pick value of two outcomes agrees to `tol` relative (accelerations against a
/// 1 m/s² floor, distances against 1 mm, times against 1 µs, so that values crossing zero do not
/// demand absolute agreement beyond the solver's tolerance).
fn assert_agree(c: &Outcome, o: &Outcome, tol: f64) {
    let pairs = [
        ("t_end_s", c.t_end_s, o.t_end_s, 1e-6),
        ("distance_m", c.distance_m, o.distance_m, 1e-3),
        ("velocity_m_s", c.velocity_m_s, o.velocity_m_s, 1e-3),
        ("accel_end_m_s2", c.accel_end_m_s2, o.accel_end_m_s2, 1.0),
        ("accel_peak_m_s2", c.accel_peak_m_s2, o.accel_peak_m_s2, 1.0),
    ];
    for (name, a, b, floor) in pairs {
        assert!(rel(a, b, floor) < tol, "{name}: closed {a} vs ode {b} (rel {:e})", rel(a, b, floor));
    }
    assert_eq!(c.end, o.end);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Closed form (eqs. 29–47, corrected) and DOP853 agree to 1e-7 over the settings' ranges.
    #[test]
    fn closed_form_matches_integration(
        speed in 120.0..320.0f64,
        play in 0.0..55.0f64,
        strap in 12.0..45.0f64,
        shuttle in 250.0..700.0f64,
        checking in 0.0..12.0f64,
        equilibrium in any::<bool>(),
    ) {
        let m = Mechanism::paper_default();
        let start = if equilibrium { StartRule::Equilibrium } else { StartRule::Paper };
        let st = Settings::designed(&m).with_speed_rpm(speed).with_play_mm(play).with_strap_cm(strap)
            .with_shuttle_g(shuttle).with_checking_kgf(checking).with_start(start);
        match (simulate(&m, &st, Method::Closed), simulate(&m, &st, Method::Ode)) {
            (Ok(c), Ok(o)) => {
                // The closed form answers itself, except for a pick so short against a natural
                // period that its terms cancel (play at the edge of the cam's reach): then it says
                // so and the numerical route answers (`CANCELLATION_LIMIT`).
                if c.method != Method::Closed {
                    prop_assert!(c.note.as_deref().is_some_and(|n| n.contains("terms cancel")), "{:?}", c.note);
                    prop_assert!(c.t_end_s * o.natural_1_s < 0.5, "a long pick fell back: {c:?}");
                }
                assert_agree(&c, &o, 1e-7);
            }
            (Err(PickError::PlayBeyondReach { .. }), Err(PickError::PlayBeyondReach { .. })) => {}
            // Both routes refuse an equilibrium start whose static deflection exceeds the cam's travel.
            (Err(PickError::CheckingBeyondReach { .. }), Err(PickError::CheckingBeyondReach { .. })) => {}
            (a, b) => prop_assert!(false, "routes disagree on validity: {a:?} / {b:?}"),
        }
    }
}

/// The closed-form history satisfies eq. 28, B'·ẍ + (C'+1)·x = (s − s₀) − D', at every sample,
/// and its velocity and acceleration are the derivatives of its displacement (central differences).
#[test]
fn closed_form_satisfies_the_equation_and_differentiates() {
    let m = Mechanism::paper_default();
    for st in [
        Settings::designed(&m).with_play_mm(15.5),
        Settings::designed(&m).with_speed_rpm(230.0).with_strap_cm(17.0),
        Settings::designed(&m).with_play_mm(45.0).with_checking_kgf(9.0),
    ] {
        let h = history(&m, &st, Method::Closed, 400).unwrap();
        // The nominal acceleration jumps by A·B·μ²·q² at the stage joint t₁: skip the window there.
        let t1 = loomkin_picking::closed_form_constants(&m, &st).unwrap().t1;
        let o = &h.outcome;
        for s in &h.samples {
            let lhs = o.b_s2 * s.actual.a_m_s2 + (o.c + 1.0) * s.actual.x_m;
            let rhs = s.nominal.s_m - o.d_m;
            assert!((lhs - rhs).abs() < 1e-12, "t = {}: {lhs} vs {rhs}", s.t_s);
        }
        let dt = h.samples[1].t_s - h.samples[0].t_s;
        for w in h.samples.windows(3) {
            let fv = (w[2].actual.x_m - w[0].actual.x_m) / (2.0 * dt);
            let fa = (w[2].actual.v_m_s - w[0].actual.v_m_s) / (2.0 * dt);
            assert!((fv - w[1].actual.v_m_s).abs() < 2e-4 * o.velocity_m_s.abs().max(1.0));
            assert!((fa - w[1].actual.a_m_s2).abs() < 5e-3 * o.accel_peak_m_s2.abs().max(1.0));
            if w[0].t_s <= t1 && t1 <= w[2].t_s {
                continue;
            }
            let fsv = (w[2].nominal.s_m - w[0].nominal.s_m) / (2.0 * dt);
            assert!(
                (fsv - w[1].nominal.v_m_s).abs() < 2e-4 * w[1].nominal.v_m_s.abs().max(1.0),
                "t = {} {fsv} {:?}",
                w[1].t_s,
                w[1].nominal
            );
        }
        let first = h.samples[0].actual;
        assert!(first.x_m.abs() < 1e-15 && first.v_m_s.abs() < 1e-13, "starts from rest: {first:?}");
    }
}

/// At the designed setting both routes give back the design: V = 17 m/s at X = 0.22 m, ẍ = A.
#[test]
fn designed_setting_returns_the_design() {
    let m = Mechanism::paper_default();
    let a = m.design().a_m_s2;
    for method in [Method::Closed, Method::Ode] {
        let o = simulate(&m, &Settings::designed(&m), method).unwrap();
        assert!((o.velocity_m_s - 17.0).abs() < 1e-9, "{method:?}: {}", o.velocity_m_s);
        assert!((o.distance_m - 0.22).abs() < 1e-11);
        assert!((o.accel_end_m_s2 - a).abs() < 1e-7 && (o.accel_peak_m_s2 - a).abs() < 1e-7);
        assert_eq!(o.t0_s, 0.0);
        assert!((o.t_end_s - m.design().t_end_s).abs() < 1e-15);
    }
}

/// Near ψ = μ·q the closed form still agrees; at it, it hands over to the integrator and says so.
#[test]
fn resonance_is_detected_and_answered_numerically() {
    let m = Mechanism::paper_default();
    let k = m.params().constants();
    let q_res = k.natural_1_s() / m.design().mu_1_s;
    let n_res = q_res * m.design_spec().speed_rpm;
    // 0.1 % away: the closed form answers and agrees.
    let near = Settings::designed(&m).with_speed_rpm(n_res * 1.001);
    let (c, o) = (simulate(&m, &near, Method::Closed).unwrap(), simulate(&m, &near, Method::Ode).unwrap());
    assert_eq!(c.method, Method::Closed);
    assert_agree(&c, &o, 1e-7);
    // On it: resonance, numerical answer, a note that says why.
    let on = Settings::designed(&m).with_speed_rpm(n_res);
    let r = simulate(&m, &on, Method::Closed).unwrap();
    assert_eq!(r.method, Method::Ode);
    let note = r.note.as_deref().unwrap_or("");
    assert!(note.contains("resonance") && note.contains("numerical"), "{note}");
    let o = simulate(&m, &on, Method::Ode).unwrap();
    assert_eq!(r.velocity_m_s, o.velocity_m_s);
    assert!(r.velocity_m_s.is_finite() && r.accel_peak_m_s2.is_finite());
}

/// The result is continuous in the play at zero and in the speed across the design point.
#[test]
fn outcomes_are_continuous_in_the_settings() {
    let m = Mechanism::paper_default();
    let base = simulate(&m, &Settings::designed(&m), Method::Closed).unwrap();
    let tiny = simulate(&m, &Settings::designed(&m).with_play_mm(1e-6), Method::Closed).unwrap();
    assert!((tiny.velocity_m_s - base.velocity_m_s).abs() < 1e-3);
    let fast = simulate(&m, &Settings::designed(&m).with_speed_rpm(200.0 + 1e-6), Method::Closed).unwrap();
    assert!((fast.distance_m - base.distance_m).abs() < 1e-8);
}

/// The paper's mechanism made 1/3.1e-5 times stiffer in the stick and strap (ψ ≈ 2.9·10⁴ 1/s,
/// about 180 times the paper's): the pick lasts tens to hundreds of natural periods.
fn stiff() -> Mechanism {
    let paper = Mechanism::paper_default();
    let mut p = *paper.params();
    p.c1_m_per_n *= 3.1e-5;
    p.c23_m_per_n *= 3.1e-5;
    Mechanism::new(p, *paper.design_spec()).unwrap()
}

/// With many natural periods in the pick, the closed form's scan must not step over the first
/// dip of the contact force (separation) nor pick the wrong one of many nearly equal acceleration
/// peaks: the stored integration steps of the numerical route are an independent scan.
/// (Regression: a fixed 512-point scan found the separation ~9 periods late and a peak 1.5e-4 low.)
#[test]
fn many_natural_periods_events_and_peaks_agree() {
    let m = stiff();
    assert!(m.params().constants().natural_1_s() > 2.5e4);
    for st in [
        Settings::designed(&m).with_speed_rpm(150.0).with_play_mm(2.0).with_checking_kgf(200.0),
        Settings::designed(&m).with_speed_rpm(40.0).with_checking_kgf(50.0),
        Settings::designed(&m).with_speed_rpm(35.0).with_play_mm(5.0),
    ] {
        let (c, o) = (simulate(&m, &st, Method::Closed).unwrap(), simulate(&m, &st, Method::Ode).unwrap());
        assert_eq!(c.method, Method::Closed);
        assert_agree(&c, &o, 1e-7);
    }
}

/// Settings the routes cannot follow are refused with an error naming the limit, not answered
/// with noise: a mechanism 10⁸ times stiffer, or a strap so low that B', C', D' overflow.
#[test]
fn unfollowable_settings_are_refused() {
    let paper = Mechanism::paper_default();
    let mut p = *paper.params();
    p.c1_m_per_n *= 1e-8;
    p.c23_m_per_n *= 1e-8;
    let m = Mechanism::new(p, *paper.design_spec()).unwrap();
    for method in [Method::Closed, Method::Ode] {
        let e = simulate(&m, &Settings::designed(&m), method).unwrap_err();
        assert!(matches!(e, PickError::TooManyOscillations { .. }), "{e}");
        assert!(e.to_string().contains("natural frequency"));
    }
    // 1 rev/min: many periods, still followed (the paper's mechanism is never refused).
    let slow = Settings::designed(&paper).with_speed_rpm(1.0).with_strap_cm(73.9);
    let (c, o) = (simulate(&paper, &slow, Method::Closed).unwrap(), simulate(&paper, &slow, Method::Ode).unwrap());
    assert_agree(&c, &o, 1e-7);
    let e = simulate(&paper, &Settings::designed(&paper).with_strap_cm(1e-300), Method::Closed).unwrap_err();
    assert!(matches!(e, PickError::StrapTooLow { .. }) && e.to_string().contains("strap_cm = 1e-300"), "{e}");
}
