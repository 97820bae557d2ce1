//! The closed-form integration against an independent numerical quadrature, and the criteria
//! against brute-force sampling on fine grids.

use loomkin_laws::{Shape, ShapeSegment};
use loomkin_shed::{Dimensionless, PRESETS, ShedLaw, Template, mirror};

/// The acceleration of a piecewise law evaluated straight from the shape definitions (not through
/// the core's pieces), at relative coordinate `u` of each segment.
fn shape_accel(shape: &Shape, u: f64) -> f64 {
    use std::f64::consts::{FRAC_PI_2, PI};
    match *shape {
        Shape::Zero => 0.0,
        Shape::Constant { level } => level,
        Shape::Linear { from, to } => from + (to - from) * u,
        Shape::SineRamp { from, to } => from + (to - from) * (FRAC_PI_2 * u).sin(),
        Shape::CosineRamp { from, to } => from + (to - from) * (1.0 - (FRAC_PI_2 * u).cos()),
        Shape::HalfCosine { from, to } => from + (to - from) * (1.0 - (PI * u).cos()) / 2.0,
        Shape::SineArc { peak } => peak * (PI * u).sin(),
    }
}

fn accel(positive: &[ShapeSegment], x: f64) -> f64 {
    let (segs, y) = if x <= 0.5 { (positive.to_vec(), 2.0 * x) } else { (mirror(positive), 2.0 * x - 1.0) };
    let mut x0 = 0.0;
    for (i, s) in segs.iter().enumerate() {
        let x1 = x0 + s.length;
        if s.length > 0.0 && (y < x1 || i + 1 == segs.len()) {
            return shape_accel(&s.shape, ((y - x0) / s.length).clamp(0.0, 1.0));
        }
        x0 = x1;
    }
    0.0
}

/// Panel ends are evaluated just inside the panel so that a jump of `a` at a grid point is seen
/// from the correct side.
const IN: f64 = 1e-13;

/// Integrates `a` twice with composite Simpson panels between consecutive grid points (the
/// velocity by Simpson on each panel, the displacement by Simpson on `v`), normalised to s(1) = 1.
fn quadrature(positive: &[ShapeSegment], n: usize) -> Vec<(f64, f64, f64)> {
    let h = 1.0 / n as f64;
    let mut v = vec![0.0; n + 1];
    for i in 0..n {
        let x = i as f64 * h;
        v[i + 1] = v[i]
            + h / 6.0 * (accel(positive, x + IN) + 4.0 * accel(positive, x + h / 2.0) + accel(positive, x + h - IN));
    }
    // v at the panel midpoints by the same rule over half panels.
    let mut s = vec![0.0; n + 1];
    for i in 0..n {
        let x = i as f64 * h;
        let q = h / 4.0;
        let vm =
            v[i] + q / 3.0 * (accel(positive, x + IN) + 4.0 * accel(positive, x + q) + accel(positive, x + 2.0 * q));
        s[i + 1] = s[i] + h / 6.0 * (v[i] + 4.0 * vm + v[i + 1]);
    }
    let k = 1.0 / s[n];
    (0..=n).map(|i| (i as f64 * h, s[i] * k, v[i] * k)).collect()
}

#[test]
fn closed_form_matches_numerical_quadrature() {
    let mut laws: Vec<Vec<ShapeSegment>> = PRESETS.iter().map(|p| p.law().unwrap().positive().to_vec()).collect();
    let t = Template::lead_trapezoid();
    laws.push(t.law(300.0, &[0.1, 0.2, 0.45, 0.25]).unwrap().positive().to_vec());
    let lt = Template::linear_trapezoid();
    laws.push(lt.law(300.0, &[0.3, 0.1, 0.6]).unwrap().positive().to_vec());
    let arc = Template::parse("arc", "sine-arc:1,half-cosine:0.5:0").unwrap();
    laws.push(arc.law(300.0, &[0.7, 0.3]).unwrap().positive().to_vec());
    for positive in laws {
        let law = ShedLaw::symmetric(300.0, positive.clone()).unwrap().build().unwrap();
        // Joints that fall inside a panel make Simpson's error O(h²) there (a kink or a jump of
        // a); with 4000 panels that stays below 1e-7 of the stroke.
        for (x, s, v) in quadrature(&positive, 4000) {
            let k = law.eval(x);
            assert!((k.s - s).abs() < 1e-7, "{positive:?} at {x}: {} vs {s}", k.s);
            assert!((k.v - v).abs() < 1e-6, "{positive:?} at {x}: {} vs {v}", k.v);
        }
    }
}

/// Criteria by brute force: a million samples, the largest |a|, |j| (by central differences of a
/// away from joints), v·a, and by scanning the first `x` with `|s| > 1 − T` and the last with
/// `|s − 1| > 1 − T`.
fn brute(positive: &[ShapeSegment], threshold: f64) -> Dimensionless {
    brute_law(&ShedLaw::symmetric(300.0, positive.to_vec()).unwrap(), threshold)
}

fn brute_law(law: &ShedLaw, threshold: f64) -> Dimensionless {
    let law = law.build().unwrap();
    let n = 1_000_000;
    let pts = law.sample(n + 1);
    let (mut cv, mut ca, mut cm, mut a2) = (0.0f64, 0.0f64, f64::MIN, 0.0);
    let (mut depart, mut arrive) = (1.0f64, 0.0f64);
    for (i, (x, k)) in pts.iter().enumerate() {
        cv = cv.max(k.v);
        ca = ca.max(k.a.abs());
        cm = cm.max(k.v * k.a);
        if i < n {
            a2 += k.a * k.a / n as f64;
        }
        // Still: within 1 − T of the stroke from the start (s = 0) or the end (s = 1) position.
        if k.s.abs() > 1.0 - threshold {
            depart = depart.min(*x);
        }
        if (k.s - 1.0).abs() > 1.0 - threshold {
            arrive = arrive.max(*x);
        }
    }
    let h = 1e-6;
    let mut cj = 0.0f64;
    for i in 1..n {
        let x = i as f64 / n as f64;
        let near_joint = law.joints().any(|j| (j - x).abs() < 2.0 * h) || (x - 0.5).abs() < 2.0 * h;
        if !near_joint {
            cj = cj.max(((law.eval(x + h).a - law.eval(x - h).a) / (2.0 * h)).abs());
        }
    }
    Dimensionless {
        threshold,
        cv,
        ca,
        cj,
        cm,
        ca_rms: a2.sqrt(),
        a_jump: 0.0, // not sampled (compared between the fast and generic paths only)
        lead: 0.0,
        tail: 1.0,
        x_depart: depart,
        x_arrive: arrive,
    }
}

#[test]
fn criteria_match_brute_force_sampling() {
    let cases: Vec<(Template, Vec<f64>)> = vec![
        (Template::trapezoid(), vec![0.5, 0.0, 0.5]),
        (Template::trapezoid(), vec![0.25, 0.5, 0.25]),
        (Template::trapezoid(), vec![0.05, 0.15, 0.8]),
        (Template::lead_trapezoid(), vec![0.0, 0.2, 0.45, 0.35]),
        (Template::linear_trapezoid(), vec![0.3, 0.1, 0.6]),
        (Template::parse("arc", "sine-arc:1,half-cosine:0.5:0").unwrap(), vec![0.7, 0.3]),
    ];
    for (t, k) in cases {
        for threshold in [0.75, 0.85, 0.95, 0.99] {
            let fast = t.evaluate_fast(&k, threshold).unwrap();
            let generic = t.evaluate_generic(&k, threshold).unwrap();
            let b = brute(t.law(300.0, &k).unwrap().positive(), threshold);
            let grid = 1e-6; // sample spacing
            for (name, f, g, bb, tol) in [
                ("cv", fast.cv, generic.cv, b.cv, 1e-9),
                ("ca", fast.ca, generic.ca, b.ca, 1e-9),
                ("cm", fast.cm, generic.cm, b.cm, 1e-9),
                ("ca_rms", fast.ca_rms, generic.ca_rms, b.ca_rms, 1e-4),
                ("x_depart", fast.x_depart, generic.x_depart, b.x_depart, grid),
                ("x_arrive", fast.x_arrive, generic.x_arrive, b.x_arrive, grid),
            ] {
                assert!((f - g).abs() < 1e-10 * (1.0 + g.abs()), "{} {k:?} {name}: fast {f} generic {g}", t.name());
                // Sampled peaks never exceed the exact ones and come within the sampling error.
                assert!(
                    (f - bb).abs() <= tol * (1.0 + f.abs()) + 1e-6 * f.abs(),
                    "{} {k:?} {name}: {f} vs {bb}",
                    t.name()
                );
            }
            assert!((fast.cj - generic.cj).abs() < 1e-9 * generic.cj, "{} cj", t.name());
            assert!((fast.cj - b.cj).abs() < 1e-4 * fast.cj, "{} {k:?} cj {} vs {}", t.name(), fast.cj, b.cj);
            assert!(b.ca <= fast.ca * (1.0 + 1e-12) && b.cv <= fast.cv * (1.0 + 1e-12));
        }
    }
}

#[test]
fn asymmetric_law_criteria_match_brute_force() {
    let law = ShedLaw::from_toml(
        r#"
        motion_deg = 320
        positive = "0.3:sine-ramp:0:1,0.4:constant:1,0.3:cosine-ramp:1:0"
        negative = "0.2:sine-ramp:0:-1,0.6:constant:-1,0.2:cosine-ramp:-1:0"
        positive_fraction = 0.4
    "#,
    )
    .unwrap();
    for threshold in [0.8, 0.95] {
        let d = Dimensionless::of_law(&law.build().unwrap(), threshold).unwrap();
        let b = brute_law(&law, threshold);
        assert!((d.x_depart - b.x_depart).abs() < 1e-6 && (d.x_arrive - b.x_arrive).abs() < 1e-6);
        // Asymmetric: the departure and arrival sides differ.
        assert!((d.x_depart - (1.0 - d.x_arrive)).abs() > 1e-3);
        assert!((d.ca - b.ca).abs() < 1e-9 * d.ca && (d.cv - b.cv).abs() < 1e-9 * d.cv);
        assert!((d.cm - b.cm).abs() < 1e-6 * d.cm && (d.ca_rms - b.ca_rms).abs() < 1e-4 * d.ca_rms);
    }
}

/// A law that swings past its end positions by more than `1 − T` is not still there: the dwell band
/// is `|s − 1| ≤ 1 − T` around the top, `|s| ≤ 1 − T` around the bottom, not `s ≥ T`.
#[test]
fn overshooting_law_is_not_still_beyond_its_end() {
    // a = 1 on [0, ½], −3 on [½, ¾], +1 on [¾, 1] (rescale factor 1): raw v(½) = ½, v(¾) = −¼,
    // v(1) = 0 and raw s(1) = 1/8; over the last part s_raw = 1/8 + (1 − x)²/2, so the normalised
    // s = 1 + 4(1 − x)² peaks at 4/3 (at x = 2/3) and re-enters |s − 1| ≤ 1 − T at
    // 1 − x = √((1 − T)/4).
    let law = ShedLaw::from_toml(
        r#"
        motion_deg = 300
        positive = "1:constant:1"
        negative = "0.5:constant:-3,0.5:constant:1"
        positive_fraction = 0.5
    "#,
    )
    .unwrap();
    let built = law.build().unwrap();
    assert!((built.eval(2.0 / 3.0).s - 4.0 / 3.0).abs() < 1e-12);
    for threshold in [0.8, 0.95, 0.99] {
        let d = Dimensionless::of_law(&built, threshold).unwrap();
        let x_arrive = 1.0 - ((1.0 - threshold) / 4.0).sqrt();
        assert!((d.x_arrive - x_arrive).abs() < 1e-12, "T {threshold}: {} vs {x_arrive}", d.x_arrive);
        // Departure: raw s = x²/2 on the first half, normalised s = 4x², s = 1 − T at √((1 − T)/4).
        assert!((d.x_depart - ((1.0 - threshold) / 4.0).sqrt()).abs() < 1e-12);
        let b = brute_law(&law, threshold);
        assert!((d.x_arrive - b.x_arrive).abs() < 2e-6 && (d.x_depart - b.x_depart).abs() < 2e-6);
    }
    // And one that first undershoots its start: a = −1 then +3 over the positive phase.
    let law = ShedLaw::from_toml(
        r#"
        motion_deg = 300
        positive = "0.5:constant:-1,0.5:constant:3"
        negative = "1:constant:-1"
    "#,
    )
    .unwrap();
    let built = law.build().unwrap();
    let threshold = 0.99;
    let d = Dimensionless::of_law(&built, threshold).unwrap();
    let b = brute_law(&law, threshold);
    assert!(built.eval(0.125).s < -(1.0 - threshold), "the law must undershoot by more than the band");
    assert!(built.eval(d.x_depart).s < 0.0, "it leaves the band downwards");
    assert!((d.x_depart - b.x_depart).abs() < 2e-6 && (d.x_arrive - b.x_arrive).abs() < 2e-6);
}
