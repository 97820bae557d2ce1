//! Catalogue laws as the nominal cam law (numerical route), checked by an independent fixed-step
//! integrator; the stiff limit; sweeps equal point-by-point simulation.

use loomkin_laws::LawSpec;
use loomkin_picking::{Mechanism, Method, PickEnd, Setting, Settings, history, simulate, sweep};

/// Classical RK4 with a fixed step on B·ẍ + κ·x = f(t), from rest: an integrator independent of
/// the crate's DOP853 wrapper.
fn rk4(f: &dyn Fn(f64) -> f64, b: f64, kappa: f64, t_end: f64, n: usize) -> (f64, f64) {
    let h = t_end / n as f64;
    let acc = |t: f64, x: f64| (f(t) - kappa * x) / b;
    let (mut x, mut v) = (0.0, 0.0);
    for i in 0..n {
        let t = i as f64 * h;
        let (k1x, k1v) = (v, acc(t, x));
        let (k2x, k2v) = (v + 0.5 * h * k1v, acc(t + 0.5 * h, x + 0.5 * h * k1x));
        let (k3x, k3v) = (v + 0.5 * h * k2v, acc(t + 0.5 * h, x + 0.5 * h * k2x));
        let (k4x, k4v) = (v + h * k3v, acc(t + h, x + h * k3x));
        x += h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
    }
    (x, v)
}

#[test]
fn catalogue_cams_match_an_independent_integrator() {
    let paper = Mechanism::paper_default();
    let (stroke, rise) = (paper.design().stroke_m(), paper.design().t_end_s);
    for name in ["cycloidal", "modified-sine", "poly345", "harmonic"] {
        let spec = LawSpec::parse::<&str, &str>(name, &[]).unwrap();
        let law = spec.build().unwrap();
        let m = paper.clone().with_law(spec).unwrap();
        let st = Settings::designed(&m).with_speed_rpm(190.0).with_play_mm(5.0);
        let o = simulate(&m, &st, Method::Ode).unwrap();
        // The forcing rebuilt here from the law core: s(u) = D + stroke·law(u/rise), u = q·t + u₀.
        let d = m.design().constants.d_m;
        let q = 190.0 / 200.0;
        let u0 = o.t0_s * q;
        let f = |t: f64| d + stroke * law.eval((q * t + u0) / rise).s - o.play_picker_m - o.d_m;
        let (x, v) = rk4(&f, o.b_s2, o.c + 1.0, o.t_end_s, 40_000);
        assert!((x / o.distance_m - 1.0).abs() < 1e-7, "{name}: x {x} vs {}", o.distance_m);
        assert!((v / o.velocity_m_s - 1.0).abs() < 1e-7, "{name}: v {v} vs {}", o.velocity_m_s);
        // A rise-to-rest cam slows the picker: the shuttle leaves when m·ẍ + F₀ reaches zero.
        assert_eq!(o.end, PickEnd::Separation, "{name}");
        assert!((o.accel_end_m_s2 + st.checking_n / st.shuttle_kg).abs() < 1e-6);
        let closed = simulate(&m, &st, Method::Closed).unwrap();
        assert_eq!(closed.method, Method::Ode);
        assert!(closed.note.unwrap().contains(name));
    }
}

/// With a nearly rigid mechanism the shuttle follows the cam: x ≈ s − s(0), for any cam.
/// (10⁻⁴ of the paper's compliances: ψ ≈ 1.6·10⁴ 1/s, within the accepted ψ ≤ 3·10⁴ 1/s; the
/// deflection B·ẍ + C·x + D is then below 3 µm.)
#[test]
fn a_stiff_mechanism_follows_the_cam() {
    let paper = Mechanism::paper_default();
    let mut p = *paper.params();
    p.c1_m_per_n *= 1e-4;
    p.c23_m_per_n *= 1e-4;
    let stiff = Mechanism::new(p, *paper.design_spec()).unwrap();
    for m in [stiff.clone(), stiff.clone().with_law(LawSpec::Cycloidal).unwrap()] {
        let h = history(&m, &Settings::designed(&m), Method::Ode, 101).unwrap();
        let s0 = h.samples[0].nominal.s_m;
        for s in &h.samples {
            assert!((s.actual.x_m - (s.nominal.s_m - s0)).abs() < 1e-5, "{s:?}");
        }
    }
}

/// The parallel sweep returns, point for point, what `simulate` returns.
#[test]
fn sweep_equals_pointwise_simulation() {
    let m = Mechanism::paper_default();
    let base = Settings::designed(&m).with_play_mm(4.0);
    for setting in Setting::ALL {
        let (a, b) = setting.paper_range();
        let s = sweep(&m, &base, setting, a, b, 7, Method::Closed).unwrap();
        assert_eq!(s.rows.len(), 7);
        assert_eq!(s.rows[0].value, a);
        assert_eq!(s.rows[6].value, b);
        for r in &s.rows {
            let o = simulate(&m, &setting.apply(base, r.value), Method::Closed).unwrap();
            assert_eq!(o, r.outcome);
        }
    }
}
