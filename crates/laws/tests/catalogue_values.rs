//! Metrics of the catalogue laws against their textbook closed forms, to 1e-9 relative.

use loomkin_laws::{LawSpec, Metrics};
use std::f64::consts::PI;

fn metrics(name: &str) -> Metrics {
    LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap().metrics()
}

#[track_caller]
fn close(got: f64, want: f64, what: &str) {
    let rel = (got - want).abs() / want.abs();
    assert!(rel < 1e-9, "{what}: got {got}, want {want} (relative error {rel:e})");
}

#[test]
fn cycloidal() {
    let m = metrics("cycloidal");
    close(m.cv, 2.0, "Cv");
    close(m.ca, 2.0 * PI, "Ca");
    close(m.cj, 4.0 * PI * PI, "Cj");
    close(m.cm, 3.0 * 3f64.sqrt() * PI / 2.0, "Cm");
    close(m.ca_pos, 2.0 * PI, "Ca+");
    close(m.ca_neg, -2.0 * PI, "Ca-");
    close(m.ca_rms, 2.0 * PI / 2f64.sqrt(), "Ca_rms");
    close(m.x_ca_pos, 0.25, "x of Ca+");
}

#[test]
fn poly345() {
    let m = metrics("poly345");
    close(m.cv, 15.0 / 8.0, "Cv");
    close(m.ca, 10.0 / 3f64.sqrt(), "Ca");
    close(m.cj, 60.0, "Cj");
    // ∫(60x − 180x² + 120x³)² dx = 120/7
    close(m.ca_rms, (120.0f64 / 7.0).sqrt(), "Ca_rms");
}

#[test]
fn poly4567() {
    let m = metrics("poly4567");
    close(m.cv, 35.0 / 16.0, "Cv");
    close(m.cj, 52.5, "Cj");
    // Ca of 4-5-6-7 is 84√5/25 at x = (5 − √5)/10 (a'' = 0 there).
    close(m.ca, 84.0 * 5f64.sqrt() / 25.0, "Ca");
}

#[test]
fn modified_trapezoid() {
    let m = metrics("modified-trapezoid");
    close(m.cv, 2.0, "Cv");
    close(m.ca, 8.0 * PI / (2.0 + PI), "Ca");
    close(m.cj, 32.0 * PI * PI / (2.0 + PI), "Cj");
}

#[test]
fn modified_trapezoid_with_quarter_ramps_is_cycloidal() {
    let a = LawSpec::ModifiedTrapezoid { ramp: 0.25 }.build().unwrap();
    let c = LawSpec::Cycloidal.build().unwrap();
    for i in 0..=100 {
        let x = i as f64 / 100.0;
        let (ka, kc) = (a.eval(x), c.eval(x));
        assert!((ka.s - kc.s).abs() < 1e-13 && (ka.a - kc.a).abs() < 1e-11, "x = {x}");
    }
}

#[test]
fn modified_sine() {
    let m = metrics("modified-sine");
    close(m.cv, 4.0 * PI / (4.0 + PI), "Cv");
    close(m.ca, 4.0 * PI * PI / (4.0 + PI), "Ca");
    close(m.cj, 16.0 * PI.powi(3) / (4.0 + PI), "Cj");
}

#[test]
fn harmonic() {
    let m = metrics("harmonic");
    close(m.cv, PI / 2.0, "Cv");
    close(m.ca, PI * PI / 2.0, "Ca");
    close(m.cm, PI.powi(3) / 8.0, "Cm");
    close(m.cj, PI.powi(3) / 2.0, "Cj");
}

#[test]
fn constant_acceleration() {
    let m = metrics("constant-acceleration");
    close(m.cv, 2.0, "Cv");
    close(m.ca, 4.0, "Ca");
    close(m.cm, 8.0, "Cm");
    close(m.ca_rms, 4.0, "Ca_rms");
    assert_eq!(m.cj, 0.0, "no jerk inside the segments");
}

#[test]
fn continuity_classes() {
    let class = |name: &str| LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap().continuity().class;
    assert_eq!(class("constant-acceleration"), 1, "a jumps at the ends and the middle");
    assert_eq!(class("harmonic"), 1, "a jumps against the dwells");
    assert_eq!(class("cycloidal"), 2);
    assert_eq!(class("poly345"), 2);
    assert_eq!(class("poly4567"), 3);
    assert_eq!(class("modified-sine"), 2);
    let ca = LawSpec::ConstantAcceleration.build().unwrap().continuity();
    assert!((ca.joints[0].da + 8.0).abs() < 1e-12, "a jumps from +4 to −4 at the middle");
    assert!((ca.start.da - 4.0).abs() < 1e-12);
}

#[test]
fn bad_parameters_name_the_field() {
    let e = LawSpec::parse("modified-trapezoid", &[("ramp", "0.3")]).unwrap_err().to_string();
    assert!(e.contains("ramp") && e.contains("0.25"), "{e}");
    let e = LawSpec::parse::<&str, &str>("nonsense", &[]).unwrap_err().to_string();
    assert!(e.contains("cycloidal"), "{e}");
    let e = LawSpec::parse("cycloidal", &[("ramp", "0.1")]).unwrap_err().to_string();
    assert!(e.contains("ramp"), "{e}");
    let e = LawSpec::parse("piecewise", &[("segments", "0.5:constant:1,0.4:constant:-1")]).unwrap_err().to_string();
    assert!(e.contains("sum to 0.9"), "{e}");
    let e = LawSpec::parse("piecewise", &[("segments", "0.5:constant:1,0.5:constant:-2")])
        .unwrap()
        .build()
        .unwrap_err()
        .to_string();
    assert!(e.contains("velocity does not return to zero"), "{e}");
}

#[test]
fn derivative_roots_of_the_cycloid() {
    let law = LawSpec::Cycloidal.build().unwrap();
    let seg = &law.segments()[0];
    // a = 2π sin 2πx vanishes at ½ inside (and at the ends, where rounding decides whether the value
    // is exactly zero); j = 4π² cos 2πx at ¼, ¾.
    let a: Vec<f64> = seg.derivative_roots(2).into_iter().filter(|&t| t > 1e-9 && t < 1.0 - 1e-9).collect();
    assert_eq!(a.len(), 1, "{a:?}");
    assert!((a[0] - 0.5).abs() < 1e-14, "{a:?}");
    let j = seg.derivative_roots(3);
    assert_eq!(j.len(), 2, "{j:?}");
    assert!((j[0] - 0.25).abs() < 1e-14 && (j[1] - 0.75).abs() < 1e-14, "{j:?}");
}

/// The narrowest ramp allowed is exact; a narrower one is refused naming `ramp` and its range.
#[test]
fn the_narrowest_ramp_is_exact_and_a_narrower_one_is_refused() {
    // Independent route: s(1) = 2∫₀^½ (½ − x)·a(x) dx of the unit-level acceleration by 40-digit
    // quadrature (mpmath), Ca = 1/s(1), Cj = Ca·π/(2·ramp).
    let m = LawSpec::ModifiedTrapezoid { ramp: 1e-6 }.build().unwrap().metrics();
    assert!((m.ca / 4.000005814092093 - 1.0).abs() < 1e-13, "{}", m.ca);
    assert!((m.cj / 6_283_194.439_934_09 - 1.0).abs() < 1e-12, "{}", m.cj);
    assert_eq!(LawSpec::ModifiedTrapezoid { ramp: 1e-6 }.build().unwrap().continuity().class, 2);
    for r in ["9.99e-7", "1e-20", "5e-324"] {
        let e = LawSpec::parse("modified-trapezoid", &[("ramp", r)]).unwrap_err().to_string();
        assert!(e.contains("allowed 1e-6 ≤ ramp ≤ 0.25"), "{e}");
    }
}

/// The scale of a piecewise law's levels does not matter (it is normalised to a unit stroke):
/// levels of ±1e-308 (which made s(1) subnormal and 1/s(1) infinite) give the law of ±1.
#[test]
fn tiny_and_huge_levels_give_the_unit_level_law() {
    let unit = LawSpec::parse("piecewise", &[("segments", "0.5:constant:1,0.5:constant:-1")]).unwrap().build().unwrap();
    let want = unit.metrics();
    for level in ["1e-308", "5e-324", "1e300", "1.7e308"] {
        let segs = format!("0.5:constant:{level},0.5:constant:-{level}");
        let law = LawSpec::parse("piecewise", &[("segments", segs.as_str())]).unwrap().build().unwrap();
        let m = law.metrics();
        for (got, want) in [(m.cv, want.cv), (m.ca, want.ca), (m.cj, want.cj), (m.cm, want.cm), (m.ca_rms, want.ca_rms)]
        {
            assert!(got.is_finite() && (got - want).abs() <= 1e-12 * want.abs().max(1.0), "{level}: {got} vs {want}");
        }
    }
}

/// A net displacement tiny against the acceleration (areas all but cancelling) would scale the
/// law past the largest double: refused naming the segments, never a law with infinite metrics.
#[test]
fn a_nearly_cancelling_law_is_refused_not_infinite() {
    // A push and a pull of 1e-100 each, then rest: s(1) = 1e-200, so a unit stroke needs
    // a = 1e200 and a² overflows.
    let segs = "1e-100:constant:1,1e-100:constant:-1,1:zero";
    let e = LawSpec::parse("piecewise", &[("segments", segs)]).unwrap().build().unwrap_err();
    assert_eq!(loomkin_units::FieldError::field(&e), Some("segments"));
    let text = e.to_string();
    assert!(text.contains("net displacement") && !text.contains("inf") && !text.contains("NaN"), "{text}");
    // A piece too narrow to have a place of its own at the end of the motion is named as such.
    let segs = "0.5:constant:1,0.5:constant:-1,1e-170:constant:1";
    let e = LawSpec::parse("piecewise", &[("segments", segs)]).unwrap().build().unwrap_err();
    assert_eq!(loomkin_units::FieldError::field(&e), Some("segments[2]"));
    assert!(e.to_string().contains("too narrow"), "{e}");
}

fn piecewise(segments: &str) -> loomkin_laws::Law {
    LawSpec::parse("piecewise", &[("segments", segments)]).unwrap().build().unwrap()
}

/// Narrow segments and lengths that sum to 1 only within the allowed 1e-9. Two half sine arcs of
/// levels 1 and −1 are the cycloid, `a = sin 2πx` (Cv = 2, Ca = 2π, Cj = 4π², C2), however their
/// lengths round: summing to 1 + 9e-10 they left a jump of 1.8e-8 in a at the joint (C1 reported),
/// because each shape kept its nominal width on a place scaled by the sum. Half-cosine ramps of
/// width w between constant levels ±1 make a law with j = 0 on both sides of every joint (C3),
/// with Cj/Ca = π/(2w) exactly; at w = 1e-6 the jerk's rounding at the joints (1e-9) made it C2.
/// A sine arc of width 1e-6 at the end has a = 2.8e-4 there (1.8e-10 of Ca, its place rounded): C1 was reported.
#[test]
fn narrow_and_rounded_segments_keep_their_shapes() {
    let cyc = piecewise("0.5000000005:sine-arc:1,0.5000000004:sine-arc:-1");
    let m = cyc.metrics();
    close(m.cv, 2.0, "Cv");
    close(m.ca, 2.0 * PI, "Ca");
    close(m.cj, 4.0 * PI * PI, "Cj");
    assert_eq!(cyc.continuity().class, 2);
    for w in [1e-6, 1e-8] {
        let p = 0.5 - 2.0 * w;
        let law = piecewise(&format!(
            "{w}:half-cosine:0:1,{p}:constant:1,{}:half-cosine:1:-1,{p}:constant:-1,{w}:half-cosine:-1:0",
            2.0 * w
        ));
        let m = law.metrics();
        close(m.cj / m.ca, PI / (2.0 * w), "Cj/Ca");
        let c = law.continuity();
        assert_eq!(c.class, 3, "w = {w}: {c:?}");
    }
    let law = piecewise("0.999999:sine-arc:1,0.000001:sine-arc:-999999");
    let c = law.continuity();
    assert_eq!(c.class, 2, "{c:?}");
    assert!(c.end.da.abs() < 1e-9 * law.metrics().ca, "{c:?}");
}

/// The scale continuity is judged against: the sampled peaks of v, a, j agree with the exact
/// metrics (Cv, Ca, Cj, found by root-finding) to a few per cent and never exceed them; the peak of
/// s is the stroke. Every catalogue law, and the narrowest ramp.
#[test]
fn the_derivative_scale_is_the_laws_peaks() {
    let mut specs: Vec<LawSpec> = loomkin_laws::laws_of_class(-1);
    specs.push(LawSpec::ModifiedTrapezoid { ramp: 1e-6 });
    assert!(specs.len() >= 7, "{specs:?}");
    for spec in specs {
        let law = spec.build().unwrap();
        let (m, peak) = (law.metrics(), law.derivative_scale().peak);
        assert!((peak[0] - 1.0).abs() < 1e-12, "{spec:?}: {peak:?}");
        for (got, exact, name) in [(peak[1], m.cv, "Cv"), (peak[2], m.ca, "Ca"), (peak[3], m.cj, "Cj")] {
            // Constant acceleration has no jerk inside its segments.
            if exact == 0.0 {
                assert_eq!(got, 0.0, "{spec:?} {name}");
                continue;
            }
            assert!(got <= exact * (1.0 + 1e-12) && got >= 0.95 * exact, "{spec:?} {name}: {got} vs {exact}");
        }
    }
}

/// The laws advice names for a class are exactly those of that class or higher, judged by their own
/// continuity report, with the classes derived from their formulas in `continuity_classes`.
#[test]
fn laws_of_class_lists_the_smooth_enough() {
    let names = |c: i32| loomkin_laws::laws_of_class(c).iter().map(|l| l.name()).collect::<Vec<_>>();
    assert_eq!(names(3), ["poly4567"]);
    assert_eq!(names(2), ["cycloidal", "poly345", "poly4567", "modified-trapezoid", "modified-sine"]);
    assert_eq!(names(1).len(), 7);
}

/// A real jump of a law is one however small, down to the tolerance (1e-9 of the law's peak): a
/// cycloid (`a = sin 2πx` before normalisation) with a step of 1e-6 or 1e-8 of its peak added to
/// `a` over the third quarter and taken off over the fourth is C1, with the jumps where the steps
/// are; a step of 1e-11 is below the tolerance and, like rounding, counts as none.
#[test]
fn small_real_jumps_are_jumps() {
    use loomkin_laws::{AccelPiece, EndCondition, Law, Sine};
    let stepped = |step: f64| {
        let arc = |phase: f64| Some(Sine { amp: 1.0, omega: 2.0 * PI, phase });
        let pieces = [
            AccelPiece { width: 0.5, poly: vec![], sine: arc(0.0) },
            AccelPiece { width: 0.25, poly: vec![step], sine: arc(PI) },
            AccelPiece { width: 0.25, poly: vec![-step], sine: arc(1.5 * PI) },
        ];
        Law::from_accel_pieces(&pieces, EndCondition::Rest, "test").unwrap()
    };
    for step in [1e-6, 1e-8] {
        let law = stepped(step);
        let (c, ca) = (law.continuity(), law.metrics().ca);
        assert_eq!(c.class, 1, "{c:?}");
        // Peak of the unnormalised a is 1 + step (just after ¾): the jumps relative to it.
        let rel = step / (1.0 + step);
        for (got, want) in [(c.joints[0].da, rel), (c.joints[1].da, -2.0 * rel), (c.end.da, rel)] {
            assert!((got / ca - want).abs() < 1e-6 * rel, "{step:e}: {got} vs {want}");
        }
        assert!(c.joints.iter().chain([&c.start, &c.end]).all(|j| j.flags()[1]), "s and v stay continuous");
        assert_eq!(c.start.continuous_up_to, 2, "the start is the cycloid's");
    }
    assert_eq!(stepped(0.0).continuity().class, 2);
    assert_eq!(stepped(1e-11).continuity().class, 2);
}
