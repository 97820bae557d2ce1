//! The closed-form response against DOP853 (differential-equations) at tight tolerance, compared at
//! the integrator's own steps (its dense output is ~100× less accurate, see /work/shared/CRATES.md).
//! The forcing of the integrated equation is taken from `Cycle::eval` of the laws crate — not from
//! the time pieces the closed form uses — so the excitation is checked too.

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_dynamics::{Follower, Response, Start};
use loomkin_laws::Cycle;
use loomkin_units::ShaftSpeed;
use proptest::prelude::*;

struct Eq<'a> {
    cycle: &'a Cycle,
    rpm: f64,
    w: f64,
    z: f64,
    eps: f64,
    f0: f64,
    start_rad: f64,
    omega_shaft: f64,
    /// The piece being integrated: the forcing is read a few ulps inside it, so that `Cycle::eval` never
    /// reads the neighbouring side of a jump in acceleration (a law's inner joint, e.g. the constant-
    /// acceleration law's middle, lies where the rounded angle `ω·t` may fall on either side). Read on the
    /// wrong side at the piece's first point, the jump made DOP853 shrink its step below an ulp of t and stall.
    piece: (f64, f64),
}

impl ODE<f64, [f64; 2]> for Eq<'_> {
    fn diff(&self, t: f64, y: &[f64; 2], d: &mut [f64; 2]) {
        let (lo, hi) = self.piece;
        let margin = 8.0 * f64::EPSILON * hi.abs();
        let t = if hi - lo > 4.0 * margin { t.clamp(lo + margin, hi - margin) } else { 0.5 * (lo + hi) };
        let k = self.cycle.eval(self.start_rad + self.omega_shaft * t, self.rpm);
        d[0] = y[1];
        d[1] = -k.a - self.eps * k.s - self.f0 - 2.0 * self.z * self.w * y[1] - self.w * self.w * y[0];
    }
}

/// Integrates the error equation piece by piece over `cycles` cycles from `y0`; returns the steps.
fn integrate(r: &Response, cycle: &Cycle, eps: f64, f0: f64, y0: [f64; 2]) -> Vec<(f64, [f64; 2])> {
    let osc = r.channel.osc;
    let mut out = vec![(0.0, y0)];
    let mut y = y0;
    for p in &r.pieces {
        // Integrate inside the piece, where the forcing is smooth.
        let (a, b) = (p.t0, p.t0 + p.sol.duration());
        let eq = Eq {
            cycle,
            rpm: r.exc.speed_rpm,
            w: osc.omega_n(),
            z: osc.zeta(),
            eps,
            f0,
            start_rad: cycle.segments[0].start_rad,
            omega_shaft: r.exc.speed_rpm * std::f64::consts::TAU / 60.0,
            piece: (a, b),
        };
        let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-16).max_steps(1_000_000);
        let sol = IVP::ode(&eq, a, b, y).method(method).solve().expect("DOP853 ran");
        let (t, ys) = sol.into_tuple();
        for (ti, yi) in t.into_iter().zip(ys).skip(1) {
            out.push((ti, yi));
        }
        y = out.last().map(|p| p.1).unwrap_or(y);
    }
    out
}

fn check(text: &str, rpm: f64, fn_hz: f64, zeta: f64, start: Start, cycles: usize) {
    let cycle = Cycle::from_toml(text).unwrap();
    let follower = Follower::new(fn_hz, zeta).unwrap();
    let r = Response::new(&cycle, ShaftSpeed::from_rpm(rpm).unwrap(), &follower, start, cycles).unwrap();
    let y0 = r.pieces[0].sol.state(0.0);
    let steps = integrate(&r, &cycle, 0.0, 0.0, [y0.0, y0.1]);
    let scale = steps.iter().map(|s| s.1[0].abs()).fold(0.0, f64::max);
    // Velocities are measured on the scale of the oscillator's state (y, y'/ω_n), not on max |y'| alone:
    // where the follower is much stiffer than the shaft is fast (71 rpm, 199 Hz) the response is nearly
    // quasi-static, max |y'| is only ~80·max |y| while a free vibration turns a position error δy into a
    // velocity error ω_n·δy = 1250·δy. DOP853's own position error at rtol 1e-13 (2e-15 m, 3e-11 of max |y|
    // after a 0.12 s rise) then read as 5e-10 "relative" velocity error; the closed form's end state for that
    // rise agrees with a 40-digit quadrature to 2e-18 m and 3e-17 m/s (`rise_residual_matches_quadrature`).
    let w = r.channel.osc.omega_n();
    let vscale = steps.iter().map(|s| s.1[1].abs()).fold(w * scale, f64::max);
    let mut worst: f64 = 0.0;
    for (t, y) in &steps {
        let st = r.state(*t);
        let e = ((st[3] - y[0]).abs() / scale).max((st[4] - y[1]).abs() / vscale);
        worst = worst.max(e);
    }
    assert!(worst < 1e-9, "relative deviation {worst:e} at {rpm} rpm, f_n {fn_hz} Hz, ζ {zeta}");
}

/// The heald-frame cycle of examples/ (dwell, modified-sine rise, dwell, modified-trapezoid return).
const HEALD: &str = include_str!("../../../../examples/heald-frame-cycle.toml");

#[test]
fn heald_cycle_from_rest_matches_dop853() {
    check(HEALD, 600.0, 54.0, 0.05, Start::Rest, 2);
    check(HEALD, 300.0, 20.0, 0.0, Start::Rest, 1);
}

#[test]
fn steady_state_matches_dop853_and_repeats() {
    check(HEALD, 800.0, 48.0, 0.03, Start::Steady, 1);
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let f = Follower::new(48.0, 0.03).unwrap();
    let r = Response::new(&cycle, ShaftSpeed::from_rpm(800.0).unwrap(), &f, Start::Steady, 3).unwrap();
    let (a, b) = (r.pieces[0].sol.state(0.0), r.pieces.last().unwrap().sol.end());
    assert!((a.0 - b.0).abs() < 1e-12 * a.0.abs().max(1e-6) && (a.1 - b.1).abs() < 1e-9 * a.1.abs().max(1e-3));
}

/// A poly4567 return of ω_n·T just above 0.5 — where the polynomial route once lost seven digits (found by
/// `random_cycles_match_dop853` at 2e-9; see `series_below`).
#[test]
fn return_at_the_old_series_switch_matches_dop853() {
    let text = "unit = \"mm\"\nstroke = 80\n[[segment]]\nkind = \"rise\"\nlength_deg = 21.106566445041018\n\
                law = \"harmonic\"\n[[segment]]\nkind = \"dwell\"\nlength_deg = 94.68099189754909\n[[segment]]\n\
                kind = \"return\"\nlength_deg = 46.93144450461266\nlaw = \"poly4567\"\n[[segment]]\nkind = \"dwell\"\n\
                length_deg = 197.28099715279723\n";
    check(text, 976.6276434586697, 9.951557397943324, 0.4773255883655891, Start::Steady, 1);
    check(text, 976.6276434586697, 9.951557397943324, 0.0, Start::Rest, 1);
}

/// The residual vibration after a poly4567 rise of 53° at 71 rpm on a 199 Hz undamped follower — a small
/// result (1/400 of the quasi-static deflection) left by cancellation — against Duhamel's integral
/// y(T) = −∫₀ᵀ a(u)·sin(ω(T−u))/ω du, y'(T) = −∫₀ᵀ a(u)·cos(ω(T−u)) du evaluated by mpmath at 40 digits
/// (`scripts/rise_residual_quadrature.py`).
#[test]
fn rise_residual_matches_quadrature() {
    let text = "unit = \"mm\"\nstroke = 80\n[[segment]]\nkind = \"rise\"\nlength_deg = 53\nlaw = \"poly4567\"\n\
                [[segment]]\nkind = \"dwell\"\nlength_deg = 58\n[[segment]]\nkind = \"return\"\nlength_deg = 35\n\
                law = \"poly4567\"\n[[segment]]\nkind = \"dwell\"\nlength_deg = 214\n";
    let cycle = Cycle::from_toml(text).unwrap();
    let follower = Follower::new(199.0, 0.0).unwrap();
    let r = Response::new(&cycle, ShaftSpeed::from_rpm(71.0).unwrap(), &follower, Start::Rest, 1).unwrap();
    let rise = &r.pieces[0].sol;
    // T = 53° / (71 rpm · 6 °/s per rpm), the value the quadrature used.
    assert!((rise.duration() - 53.0 / 426.0).abs() < 1e-16);
    let (y, v) = rise.end();
    let (y_ref, v_ref) = (-1.292_141_306_489_469_7e-7, -1.534_311_926_557_838_7e-4);
    // Judged on the scale the closed form works at: the quasi-static deflection a_max/ω² (poly4567's peak
    // acceleration 7.513·h/T² = 38.8 m/s²) and the velocity a_max/ω; 1e-12 of them is 2.5e-17 m, 3e-14 m/s.
    let (w, a_max) = (std::f64::consts::TAU * 199.0, 7.513 * 0.08 / (53.0f64 / 426.0).powi(2));
    assert!((y - y_ref).abs() < 1e-12 * a_max / (w * w), "{y:e} vs {y_ref:e}");
    assert!((v - v_ref).abs() < 1e-12 * a_max / w, "{v:e} vs {v_ref:e}");
}

fn law_name() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "cycloidal",
        "harmonic",
        "poly345",
        "poly4567",
        "modified-sine",
        "modified-trapezoid",
        "constant-acceleration",
    ])
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, ..ProptestConfig::default() })]
    #[test]
    fn random_cycles_match_dop853(
        rise in law_name(), ret in law_name(), a in 20.0f64..100.0, b in 20.0f64..100.0, c in 20.0f64..100.0,
        rpm in 60.0f64..1200.0, fn_hz in 0.5f64..200.0, zeta in prop_oneof![Just(0.0), 0.0f64..0.5, 0.5f64..0.99], steady in any::<bool>()
    ) {
        let text = format!(
            "unit = \"mm\"\nstroke = 80\n[[segment]]\nkind = \"rise\"\nlength_deg = {a}\nlaw = \"{rise}\"\n\
             [[segment]]\nkind = \"dwell\"\nlength_deg = {b}\n[[segment]]\nkind = \"return\"\nlength_deg = {c}\n\
             law = \"{ret}\"\n[[segment]]\nkind = \"dwell\"\nlength_deg = {}\n", 360.0 - a - b - c
        );
        let start = if steady && zeta > 0.0 { Start::Steady } else { Start::Rest };
        check(&text, rpm, fn_hz, zeta, start, 1);
    }
}

/// y'' + 2ζωy' + ω²y = b·sin(Ωt + φ) + c₀ + c₁t from (y₀, v₀), integrated by DOP853.
struct Sine {
    w: f64,
    z: f64,
    b: f64,
    om: f64,
    ph: f64,
    c: [f64; 2],
}

impl ODE<f64, [f64; 2]> for Sine {
    fn diff(&self, t: f64, y: &[f64; 2], d: &mut [f64; 2]) {
        d[0] = y[1];
        d[1] = self.b * (self.om * t + self.ph).sin() + self.c[0] + self.c[1] * t
            - 2.0 * self.z * self.w * y[1]
            - self.w * self.w * y[0];
    }
}

/// Through and around resonance of the sinusoidal term (both routes and the switch between them).
#[test]
fn near_resonance_matches_dop853() {
    use loomkin_dynamics::{Forcing, Harmonic, Oscillator};
    let w = 2.0 * std::f64::consts::PI * 50.0;
    for &zeta in &[0.0, 1e-7, 0.02] {
        for &gap in &[0.0, 1e-12, 1e-6, 2e-5, 1e-4, 1e-3, 0.1] {
            for &dur in &[0.01, 0.2] {
                let om = w * (1.0 + gap);
                let osc = Oscillator::new(w, zeta);
                let mut poly = [0.0; 8];
                poly[0] = 3.0;
                poly[1] = -40.0;
                let f = Forcing { poly, sine: Some(Harmonic { amp: 1e3, omega: om, phase: 0.7 }) };
                let sol = osc.solve(&f, dur, 1e-3, -0.2);
                let eq = Sine { w, z: osc.zeta(), b: 1e3, om, ph: 0.7, c: [3.0, -40.0] };
                let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-16).max_steps(1_000_000);
                let res = IVP::ode(&eq, 0.0, dur, [1e-3, -0.2]).method(method).solve().expect("DOP853 ran");
                let (ts, ys) = res.into_tuple();
                let scale = ys.iter().map(|y| y[0].abs()).fold(0.0, f64::max);
                let vscale = ys.iter().map(|y| y[1].abs()).fold(0.0, f64::max);
                for (t, y) in ts.iter().zip(&ys) {
                    let (cy, cv) = sol.state(*t);
                    assert!(cy.is_finite() && cv.is_finite());
                    let e = ((cy - y[0]).abs() / scale).max((cv - y[1]).abs() / vscale);
                    assert!(e < 1e-9, "ζ {zeta} gap {gap} T {dur}: {e:e} at t = {t}");
                }
            }
        }
    }
}

/// With a return spring and a closing force the model is the picking study's `B·x'' + (C+1)·x = s − D`
/// (mass-normalised: ω² = (C+1)/B, k_r/m = C/B, F₀/m = D/B): checked against DOP853 of that equation.
#[test]
fn picking_form_with_loads_matches_dop853() {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    // B = 1/κ with κ = k/m; C = k_r/k; D = F₀/k.
    let (b, c, d) = (1.0 / (2.0 * std::f64::consts::PI * 45.0f64).powi(2) / 1.3, 0.3, 2e-4);
    let w2 = (c + 1.0) / b;
    let m = 10.0;
    let fn_hz = w2.sqrt() / std::f64::consts::TAU;
    let f = Follower::new(fn_hz, 0.0).unwrap().with_loads(m, m * c / b, m * d / b).unwrap();
    let r = Response::new(&cycle, ShaftSpeed::from_rpm(500.0).unwrap(), &f, Start::Rest, 2).unwrap();
    let y0 = r.pieces[0].sol.state(0.0);
    // Rest: x = (s₀ − D)/(C+1) = −D/(C+1), so y₀ = −D/(C+1).
    assert!((y0.0 + d / (c + 1.0)).abs() < 1e-18);
    let steps = integrate(&r, &cycle, c / b, d / b, [y0.0, y0.1]);
    let scale = steps.iter().map(|s| s.1[0].abs()).fold(0.0, f64::max);
    for (t, y) in &steps {
        let st = r.state(*t);
        assert!((st[3] - y[0]).abs() < 1e-9 * scale, "t {t}: {} vs {}", st[3], y[0]);
    }
}

struct Two<'a> {
    cycle: &'a Cycle,
    rpm: f64,
    omega_shaft: f64,
    m: [f64; 2],
    k: [[f64; 2]; 2],
    c: [[f64; 2]; 2],
}

impl ODE<f64, [f64; 4]> for Two<'_> {
    fn diff(&self, t: f64, y: &[f64; 4], d: &mut [f64; 4]) {
        let a = self.cycle.eval(self.omega_shaft * t, self.rpm).a;
        let (q, v) = ([y[0], y[1]], [y[2], y[3]]);
        d[0] = v[0];
        d[1] = v[1];
        for i in 0..2 {
            let f = -self.m[i] * a
                - (self.k[i][0] * q[0] + self.k[i][1] * q[1])
                - (self.c[i][0] * v[0] + self.c[i][1] * v[1]);
            d[2 + i] = f / self.m[i];
        }
    }
}

/// The two-mass modal closed form against DOP853 of the physical 4-state system (C built from the modal ζ).
#[test]
fn two_mass_matches_dop853() {
    use loomkin_dynamics::{Excitation, TwoMass};
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let (m1, k1, m2, k2, zeta) = (8.0, 3.0e6, 20.0, 2.2e6, 0.04);
    let tm = TwoMass::new(m1, k1, m2, k2, zeta).unwrap();
    let speed = ShaftSpeed::from_rpm(500.0).unwrap();
    let exc = Excitation::from_cycle(&cycle, speed);
    let modes = tm.respond(&exc, Start::Rest, 1).unwrap();
    // C = MΦ diag(2ζωᵢ/μᵢ) ΦᵀM.
    let mut c = [[0.0; 2]; 2];
    for i in 0..2 {
        let phi = [1.0, tm.phi2[i]];
        let mu = m1 + m2 * phi[1] * phi[1];
        let mphi = [m1 * phi[0], m2 * phi[1]];
        for r in 0..2 {
            for s in 0..2 {
                c[r][s] += 2.0 * zeta * tm.omega[i] / mu * mphi[r] * mphi[s];
            }
        }
    }
    let eq = Two {
        cycle: &cycle,
        rpm: 500.0,
        omega_shaft: speed.rad_per_s(),
        m: [m1, m2],
        k: [[k1 + k2, -k2], [-k2, k2]],
        c,
    };
    let mut y = [0.0; 4];
    let mut worst: f64 = 0.0;
    let mut scale: f64 = 0.0;
    for p in &exc.pieces {
        let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-16).max_steps(1_000_000);
        let sol = IVP::ode(&eq, p.t0, p.t0 + p.duration, y).method(method).solve().expect("DOP853 ran");
        let (ts, ys) = sol.into_tuple();
        for (t, yy) in ts.iter().zip(&ys) {
            let e = tm.errors(&modes, *t);
            worst = worst.max((e[0] - yy[0]).abs()).max((e[2] - yy[1]).abs());
            scale = scale.max(yy[1].abs());
        }
        y = *ys.last().unwrap();
    }
    assert!(worst < 1e-9 * scale, "two-mass: {worst:e} of {scale:e}");
    assert!(tm.frame_residual_bound(&exc, &modes) > 0.0);
}

/// The two-mass error extremes, located by Newton on the closed form, bound a dense sampling of the
/// same closed form and are reached by it (to the sampling's second-order error), and the value at the
/// reported time is the reported value.
#[test]
fn two_mass_extremes_are_exact() {
    use loomkin_dynamics::{Excitation, TwoMass};
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let tm = TwoMass::new(8.0, 3.0e6, 20.0, 2.2e6, 0.04).unwrap();
    let exc = Excitation::from_cycle(&cycle, ShaftSpeed::from_rpm(500.0).unwrap());
    let modes = tm.respond(&exc, Start::Rest, 1).unwrap();
    let [drive, frame] = tm.error_extremes(&modes);
    let total: f64 = exc.pieces.iter().map(|p| p.duration).sum();
    let n = 400_000;
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for i in 0..=n {
        let e = tm.errors(&modes, total * i as f64 / n as f64);
        for (j, v) in [e[0], e[2]].into_iter().enumerate() {
            lo[j] = lo[j].min(v);
            hi[j] = hi[j].max(v);
        }
    }
    for (j, ex) in [drive, frame].iter().enumerate() {
        let scale = ex.max.0.abs().max(ex.min.0.abs());
        assert!(hi[j] <= ex.max.0 + 1e-12 * scale && lo[j] >= ex.min.0 - 1e-12 * scale, "mass {j}: sampled beyond");
        assert!(ex.max.0 - hi[j] < 1e-6 * scale && lo[j] - ex.min.0 < 1e-6 * scale, "mass {j}: not reached");
        let at = tm.errors(&modes, ex.max.1);
        let v = if j == 0 { at[0] } else { at[2] };
        assert!((v - ex.max.0).abs() < 1e-12 * scale, "mass {j}: value at the location");
    }
}

/// The case proptest found (slow frame, short motions, undamped): the polynomial route lost 7 digits.
#[test]
fn slow_frame_short_motions() {
    let text = "unit = \"mm\"\nstroke = 80\n[[segment]]\nkind = \"rise\"\nlength_deg = 20\nlaw = \"poly4567\"\n\
                [[segment]]\nkind = \"dwell\"\nlength_deg = 20\n[[segment]]\nkind = \"return\"\nlength_deg = 20\n\
                law = \"cycloidal\"\n[[segment]]\nkind = \"dwell\"\nlength_deg = 300\n";
    check(text, 839.763583748289, 5.0, 0.0, Start::Rest, 1);
    check(text, 1200.0, 0.5, 0.3, Start::Steady, 1);
}

/// A follower far stiffer than the shaft is fast: the vibration a cycloidal rise leaves, undamped, against
/// Duhamel's closed form `A/h = |sin πr|/(π r |r² − 1|)` (r = f_n·T) at r = 600.25 and 20000.25 (and after
/// the return, which adds the same vibration negated and delayed), where A is
/// 1e-10 m and 3e-15 m on a 0.1 m stroke — at and below the rounding of `s` itself (1.4e-17 m). The two
/// sides of the rise's end, evaluated from different pieces, differ by that rounding; the error y used to
/// take the difference as a jump, which set a floor of ~2e-16 of the stroke under every residual (r = 600:
/// 1e-7 off, r = 20000: 0.5 % off). And at 0.001 rpm on a 1 MHz follower the rounding jump rang at
/// ω_n²·1e-17 m = 4e-4 m/s² against an input acceleration of 5e-10 m/s²: the follower must follow the input
/// (their difference is s''''/ω_n², 1e-20 of it).
#[test]
fn stiff_follower_residual_matches_closed_form() {
    let text = "unit = \"mm\"\nstroke = 100\n[[segment]]\nkind = \"dwell\"\nto_deg = 60\n[[segment]]\nkind = \"rise\"\n\
                to_deg = 180\nlaw = \"cycloidal\"\n[[segment]]\nkind = \"dwell\"\nto_deg = 240\n[[segment]]\n\
                kind = \"return\"\nto_deg = 360\nlaw = \"cycloidal\"\n";
    let cycle = Cycle::from_toml(text).unwrap();
    // 300 rpm: T = 120° / 1800 °/s = 1/15 s.
    for r_ratio in [600.25, 20000.25] {
        let follower = Follower::new(15.0 * r_ratio, 0.0).unwrap();
        let r = Response::new(&cycle, ShaftSpeed::from_rpm(300.0).unwrap(), &follower, Start::Rest, 1).unwrap();
        let d = r.dwell_residuals();
        let rise = 0.1 * loomkin_dynamics::cycloidal_undamped(r_ratio);
        // The return is the rise negated and started Δ = 0.1 s later: A·|1 − e^{iω_nΔ}| = 2A·|sin(1.5πr)|.
        let both = 2.0 * rise * (1.5 * std::f64::consts::PI * r_ratio).sin().abs();
        for (k, want) in [(1, rise), (2, both)] {
            let got = d[k].amplitude_si;
            assert!((got - want).abs() < 1e-9 * want, "r = {r_ratio}, dwell {k}: {got:e} vs {want:e}");
        }
    }
    let follower = Follower::new(1e6, 0.0).unwrap();
    let r = Response::new(&cycle, ShaftSpeed::from_rpm(0.001).unwrap(), &follower, Start::Rest, 1).unwrap();
    let s = r.summary();
    let (x2, s2) = (s.peak_acceleration.value, s.peak_input_acceleration.value);
    assert!((x2 - s2).abs() < 1e-9 * s2, "|x''| = {x2:e}, |s''| = {s2:e}");
    assert!(s.residual_amplitude_si < 1e-20 * 0.1, "{:e}", s.residual_amplitude_si);
}

/// Damping at the top of its range (ζ < 1, up to the largest double below 1): the dwell residual
/// `A = √(δ² + ((δ' + ζω_nδ)/ω_d)²)` from DOP853's state at the start of the dwell, with
/// `ω_d = ω_n·√((1 − ζ)(1 + ζ))` formed in the test, against the closed form. The oscillator clamped ζ
/// to 1 − 10⁻¹², so at ζ = 1 − 2⁻⁵³ it reported a residual 95× too small. (δ' + ζω_nδ does not cancel
/// here: |δ'| is 0.63 of it.)
#[test]
fn damping_next_to_critical_keeps_its_residual() {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    for zeta in [1.0 - 1e-9, 1.0 - f64::EPSILON / 2.0] {
        let follower = Follower::new(54.0, zeta).unwrap();
        let r = Response::new(&cycle, ShaftSpeed::from_rpm(300.0).unwrap(), &follower, Start::Rest, 1).unwrap();
        let dwell = r.dwell_residuals()[1];
        let t_dwell = r.pieces.iter().find(|p| r.exc.pieces[p.piece].segment == 2).unwrap().t0;
        let steps = integrate(&r, &cycle, 0.0, 0.0, [0.0, 0.0]);
        let (_, [d, dv]) = *steps.iter().find(|(t, _)| (*t - t_dwell).abs() < 1e-12).unwrap();
        let w = std::f64::consts::TAU * 54.0;
        let wd = w * ((1.0 - zeta) * (1.0 + zeta)).sqrt();
        let want = d.hypot((dv + zeta * w * d) / wd);
        let got = dwell.amplitude_si;
        assert!((got - want).abs() < 1e-9 * want, "ζ = {zeta}: {got:e} vs {want:e}");
    }
}
