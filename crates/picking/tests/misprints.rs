//! Each correction of the printed eqs. 33–47 is justified here: the printed form disagrees with
//! the numerical integration of eq. 28, the corrected form agrees to 1e-7.

use loomkin_picking::{Mechanism, Method, PaperConstants, Settings, closed_form_constants, history, simulate};
use std::f64::consts::PI;

/// Stage-2 displacement (eq. 42) with given homogeneous constants.
fn x2(pc: &PaperConstants, k3: f64, k4: f64, t: f64) -> f64 {
    let w = t + pc.t0;
    pc.h * w * w + pc.i * w + pc.m + k3 * (pc.psi * t).cos() + k4 * (pc.psi * t).sin()
}

/// Eq. 45 from N, P and ϱ.
fn k34(pc: &PaperConstants, n: f64, p: f64, rho: f64) -> (f64, f64) {
    (n * rho.cos() - p / pc.psi * rho.sin(), n * rho.sin() + p / pc.psi * rho.cos())
}

fn ode_x_end(m: &Mechanism, st: &Settings) -> (f64, f64) {
    let o = simulate(m, st, Method::Ode).unwrap();
    (o.t_end_s, o.distance_m)
}

/// Eq. 46 as printed has +Hτ²; the continuity of x at τ requires −Hτ².
#[test]
fn eq46_sign_of_h_tau_squared() {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m).with_play_mm(15.5);
    let pc = closed_form_constants(&m, &st).unwrap();
    let (t_end, x_ode) = ode_x_end(&m, &st);
    let tau = m.design().tau_s;
    let w = PI / (2.0 - PI);
    let (s, c) = (pc.rho.sin(), pc.rho.cos());
    let base = w * pc.i * tau - pc.m + pc.k1 * c + pc.k2 * s + pc.e - pc.g; // q = 1
    let (k3p, k4p) = k34(&pc, base + pc.h * tau * tau, pc.p, pc.rho); // printed
    let (k3c, k4c) = k34(&pc, base - pc.h * tau * tau, pc.p, pc.rho); // corrected
    assert!((x2(&pc, k3c, k4c, t_end) / x_ode - 1.0).abs() < 1e-7);
    assert!((x2(&pc, k3p, k4p, t_end) / x_ode - 1.0).abs() > 1e-2, "the printed sign is off by 2Hτ²");
}

/// Eq. 34 prints sin μ(t+t₀); eqs. 31–33 and 35–36 have sin μq(t+t₀). With q ≠ 1 only the latter
/// satisfies x(0) = 0 with the K₁ of eq. 37.
#[test]
fn eq34_needs_q_in_the_sine() {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m).with_speed_rpm(240.0).with_play_mm(8.0);
    let pc = closed_form_constants(&m, &st).unwrap();
    let x1 = |t: f64, q_in_sine: f64| {
        let w = t + pc.t0;
        pc.k1 * (pc.psi * t).cos() + pc.k2 * (pc.psi * t).sin() + pc.e + pc.a / pc.mu_q * pc.q * pc.q * pc.f * w
            - pc.g * (pc.mu_q / pc.q * q_in_sine * w).sin()
    };
    assert!(x1(0.0, pc.q).abs() < 1e-15);
    assert!(x1(0.0, 1.0).abs() > 1e-4, "printed form starts at x(0) = {} m", x1(0.0, 1.0));
    // Against the integration inside the first stage: the corrected form agrees, the printed not.
    let h = history(&m, &st, Method::Ode, 41).unwrap();
    let mut checked = 0;
    for s in h.samples.iter().filter(|s| s.t_s > 0.0 && s.t_s < pc.t1) {
        let x = s.actual.x_m;
        assert!((x1(s.t_s, pc.q) - x).abs() < 1e-7 * x.abs().max(1e-3), "t = {}", s.t_s);
        assert!((x1(s.t_s, 1.0) - x).abs() > 1e-4, "t = {}", s.t_s);
        checked += 1;
    }
    assert!(checked >= 5, "{checked} samples in the first stage");
}

/// Fig. 3's caption "s₀ = 15.5 mm" is the strap-loop play s'₀ (§2.2 says "a play of s'₀ = 15.5
/// mm"): only that reading gives the printed ΔV = 3.88 m/s; 15.5 mm at the picker (s'₀ = 15.5·k/l)
/// gives about 2.4 m/s.
#[test]
fn fig3_caption_is_the_strap_play() {
    let m = Mechanism::paper_default();
    let base = simulate(&m, &Settings::designed(&m), Method::Ode).unwrap().velocity_m_s;
    let strap = simulate(&m, &Settings::designed(&m).with_play_mm(15.5), Method::Ode).unwrap();
    let k_over_l = m.params().k_m / m.params().l_m;
    let picker = simulate(&m, &Settings::designed(&m).with_play_mm(15.5 * k_over_l), Method::Ode).unwrap();
    assert!((picker.play_picker_m - 0.0155).abs() < 1e-12);
    assert!((strap.velocity_m_s - base - 3.88).abs() < 0.03);
    assert!((picker.velocity_m_s - base - 3.88).abs() > 1.0);
}

/// The stage switch is where the cam's design time reaches τ: t₁ = τ/q − t₀, not the printed
/// t = τ − t₀; and at the switch sin μq(t₁+t₀) = sin(π/2), not the printed sin(qπ/2).
#[test]
fn stage_switch_at_design_time_tau() {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m).with_speed_rpm(240.0);
    let pc = closed_form_constants(&m, &st).unwrap();
    let tau = m.design().tau_s;
    assert!((pc.t1 - (tau / pc.q - pc.t0)).abs() < 1e-18);
    assert!(((pc.mu_q * (pc.t1 + pc.t0)).sin() - 1.0).abs() < 1e-12);
    let (t_end, x_ode) = ode_x_end(&m, &st);
    // Printed: switch at t = τ − t₀, with sin(qπ/2), cos(qπ/2), Hτ² and Iτ unscaled by q.
    let t1p = tau - pc.t0;
    let rho = pc.psi * t1p;
    let (s, c) = (rho.sin(), rho.cos());
    let w = PI / (2.0 - PI);
    let n = pc.h * tau * tau + w * pc.i * tau - pc.m + pc.k1 * c + pc.k2 * s + pc.e - pc.g * (pc.q * PI / 2.0).sin();
    let p = -2.0 * pc.h * tau + w * pc.i + pc.k2 * pc.psi * c
        - pc.k1 * pc.psi * s
        - pc.g * pc.mu_q * (pc.q * PI / 2.0).cos();
    let (k3, k4) = k34(&pc, n, p, rho);
    assert!((x2(&pc, pc.k3, pc.k4, t_end) / x_ode - 1.0).abs() < 1e-7);
    assert!((x2(&pc, k3, k4, t_end) / x_ode - 1.0).abs() > 1e-2);
}

/// Eq. 47, T = (T' − t₀)/q, holds with t₀ the delay in design time (u₀ = q·t₀ real); with the
/// real-time t₀ of eq. 21 it reads T = T'/q − t₀. Both say: the pick ends when u = T'.
#[test]
fn eq47_end_of_pick() {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m).with_speed_rpm(180.0).with_play_mm(10.0);
    let o = simulate(&m, &st, Method::Closed).unwrap();
    let q = 180.0 / 200.0;
    let tp = m.design().t_end_s;
    assert!((o.t_end_s - (tp / q - o.t0_s)).abs() < 1e-15);
    assert!((o.t_end_s - (tp - q * o.t0_s) / q).abs() < 1e-15);
}

/// The condition printed with eq. 33, (C+1)/μ² − B ≠ 0 ("the cam profile is not straight"), is
/// not needed: when it fails, G = 0 and the closed form still agrees with the integration. The
/// condition the coefficients really need is C'+1 − μ²q²B' ≠ 0 (no resonance).
#[test]
fn eq33_condition_is_not_needed() {
    let paper = Mechanism::paper_default();
    let mut p = *paper.params();
    let spec = *paper.design_spec();
    let mu = paper.design().mu_1_s;
    let k = p.constants();
    // Choose Θ so that B = (C+1)/μ²: a straight first-stage cam, s₁ = D + A(C+1)t/μ.
    p.theta_kg_m2 = ((k.c + 1.0) / (mu * mu) - p.shuttle_kg * p.c1_m_per_n) * p.k_m * p.k_m / p.c23_m_per_n
        - p.shuttle_kg * p.l_m * p.l_m;
    let m = Mechanism::new(p, spec).unwrap();
    let d = m.design();
    assert!(((d.constants.c + 1.0) / (mu * mu) - d.constants.b_s2).abs() < 1e-18);
    let st = Settings::designed(&m).with_speed_rpm(215.0).with_play_mm(6.0);
    let pc = closed_form_constants(&m, &st).unwrap();
    assert!(pc.g.abs() < 1e-15);
    let (c, o) = (simulate(&m, &st, Method::Closed).unwrap(), simulate(&m, &st, Method::Ode).unwrap());
    assert!((c.velocity_m_s / o.velocity_m_s - 1.0).abs() < 1e-7);
    assert!((c.distance_m / o.distance_m - 1.0).abs() < 1e-7);
}
