//! Cam tables: every format re-read from its text and checked against the motion at dense points
//! (an independent route to the reported error), the placement of points, and snapshots.

use loomkin_cams::table::{CamTable, Format, Interval, Motion, Spacing, reinterpolation_error};
use loomkin_laws::{Cycle, LawSpec, StrokeUnit};
use proptest::prelude::*;

/// The heald-frame cycle of examples/ (dwell, modified-sine rise, dwell, modified-trapezoid return).
const CYCLE_MM: &str = include_str!("../../../examples/heald-frame-cycle.toml");

const CYCLE_DEG: &str = r#"
unit = "deg"
stroke = 22.5
[[segment]]
kind = "rise"
length_deg = 100
law = "harmonic"
[[segment]]
kind = "dwell"
length_deg = 80
[[segment]]
kind = "return"
length_deg = 130
law = "piecewise"
params = { segments = "0.25:constant:1,0.25:zero,0.5:half-cosine:-0.5:-0.5" }
[[segment]]
kind = "dwell"
length_deg = 50
"#;

fn cycle(text: &str) -> Motion {
    Motion::from_cycle(&Cycle::from_toml(text).unwrap())
}

/// Largest |Y_interval − Y_motion| over `per` evenly spaced points of every interval, plus the
/// value at `at` (the reported location).
fn dense_error(m: &Motion, ivs: &[Interval], per: usize) -> f64 {
    let mut worst = 0.0f64;
    for iv in ivs {
        for i in 0..=per {
            let x = iv.start_deg + iv.width() * i as f64 / per as f64;
            // The motion's formula on the side of the interval (a joint belongs to both sides).
            let piece = &m.pieces()[m.piece_index(x.clamp(iv.start_deg, iv.end_deg - 1e-12 * iv.width()))];
            let e = (iv.eval(x)[0] - piece.eval(x)[0]).abs();
            worst = worst.max(e);
        }
    }
    worst
}

fn check_route(m: &Motion, spacing: Spacing) {
    let table = CamTable::new(m.clone(), spacing).unwrap();
    for f in Format::ALL {
        let out = table.export(f).unwrap();
        for line in out.text.lines().filter(|l| !l.starts_with('#') && !l.starts_with("(*")) {
            let noise = line.contains("e-") || line.contains("e1") || line.contains("NaN") || line.contains("inf");
            let negative_zero = line.split([',', ' ', '(', ')']).any(|t| {
                t.starts_with("-0") && t.trim_start_matches("-0").trim_start_matches('.').chars().all(|c| c == '0')
            });
            assert!(!noise && !negative_zero, "{f:?}: {line}");
        }
        // Re-read the text as written, independently of the table.
        let ivs = f.read(&out.text).unwrap();
        let again = reinterpolation_error(m, &ivs);
        assert_eq!(again, out.error, "{f:?}: the header's error is the error of the file");
        let dense = dense_error(m, &ivs, 400);
        let rep = out.error.max_position_error;
        // (1e-13 of the stroke: the rounding of evaluating positions of that size in doubles.)
        assert!(dense <= rep * (1.0 + 1e-9) + 1e-13 * m.stroke(), "{f:?}: dense {dense:e} above reported {rep:e}");
        assert!(dense >= rep * (1.0 - 2e-3), "{f:?}: dense {dense:e} far below reported {rep:e}");
        // Where it is attained, the reported error is the difference there.
        let at = out.error.max_position_error_at_deg;
        let iv = ivs.iter().find(|iv| at >= iv.start_deg && at <= iv.end_deg).unwrap();
        let piece = &m.pieces()[m.piece_index(at.clamp(iv.start_deg, iv.end_deg - 1e-12 * iv.width()))];
        let there = (iv.eval(at)[0] - piece.eval(at)[0]).abs();
        assert!((there - rep).abs() <= 1e-9 * rep.max(1e-300), "{f:?}: {there:e} vs {rep:e}");
    }
}

#[test]
fn every_format_reread_bounds_and_attains_its_reported_error() {
    let law = LawSpec::ModifiedTrapezoid { ramp: 0.125 }.build().unwrap();
    check_route(&Motion::rise(&law, 40.0, 120.0, StrokeUnit::Mm).unwrap(), Spacing::StepDeg(7.0));
    check_route(&cycle(CYCLE_MM), Spacing::StepDeg(2.5));
    check_route(&cycle(CYCLE_DEG), Spacing::StepDeg(3.0));
    check_route(&cycle(CYCLE_MM), Spacing::Tolerance(0.01));
    check_route(&cycle(CYCLE_DEG), Spacing::Tolerance(0.002));
}

#[test]
fn points_fall_on_joints_plus_an_exact_step_with_a_shorter_last_step() {
    let law = LawSpec::ModifiedTrapezoid { ramp: 0.125 }.build().unwrap();
    let m = Motion::rise(&law, 40.0, 120.0, StrokeUnit::Mm).unwrap();
    let t = CamTable::new(m.clone(), Spacing::StepDeg(7.0)).unwrap();
    let xs: Vec<f64> = t.points().iter().map(|p| p.master_deg).collect();
    // The joints of the modified trapezoid at 120°: 1/8, 3/8, 5/8, 7/8 of the motion.
    let joints = [0.0, 15.0, 45.0, 75.0, 105.0, 120.0];
    for j in joints {
        assert!(xs.contains(&j), "joint {j} missing in {xs:?}");
    }
    for w in joints.windows(2) {
        let inside: Vec<f64> = xs.iter().copied().filter(|&x| x >= w[0] && x <= w[1]).collect();
        for p in inside.windows(2) {
            let step = p[1] - p[0];
            let last = p[1] == w[1];
            assert!((step - 7.0).abs() < 1e-9 || (last && step < 7.0), "{w:?}: step {step} in {inside:?}");
        }
    }
    assert_eq!(&xs[..4], &[0.0, 7.0, 14.0, 15.0]);
}

#[test]
fn a_cycle_in_degrees_writes_degree_headers() {
    let t = CamTable::new(cycle(CYCLE_DEG), Spacing::StepDeg(10.0)).unwrap();
    let csv = t.export(Format::Csv).unwrap().text;
    assert!(csv.starts_with("master_deg,slave_deg,slave_v_deg_per_deg,slave_a_deg_per_deg2,slave_j_deg_per_deg3\n"));
    let t = CamTable::new(cycle(CYCLE_MM), Spacing::StepDeg(10.0)).unwrap();
    let csv = t.export(Format::Csv).unwrap().text;
    assert!(csv.starts_with("master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3\n"));
}

#[test]
fn tolerance_placement_keeps_every_interval_within_and_is_locally_fewest() {
    let m = cycle(CYCLE_MM);
    let tol = 0.005;
    let t = CamTable::new(m.clone(), Spacing::Tolerance(tol)).unwrap();
    let pts = t.points();
    let joints = m.joints();
    for w in pts.windows(2) {
        let iv = Interval::hermite(w[0].master_deg, w[1].master_deg, w[0].yva(), w[1].yva());
        let e = reinterpolation_error(&m, &[iv]).max_position_error;
        assert!(e <= tol, "interval {:?}: {e}", (w[0].master_deg, w[1].master_deg));
    }
    // Any interval that does not end on a joint would break the tolerance one grid step longer.
    for w in pts.windows(2) {
        if joints.iter().any(|&j| (j - w[1].master_deg).abs() < 1e-9) {
            continue;
        }
        let x = w[1].master_deg + 0.001;
        let y = m.eval(x);
        let iv = Interval::hermite(w[0].master_deg, x, w[0].yva(), [y[0], y[1], y[2]]);
        assert!(reinterpolation_error(&m, &[iv]).max_position_error > 0.99 * tol);
    }
    // Far fewer points than a 1° table, whose error is also within the tolerance.
    let fine = CamTable::new(m, Spacing::StepDeg(1.0)).unwrap();
    assert!(pts.len() * 4 < fine.points().len(), "{} vs {}", pts.len(), fine.points().len());
}

#[test]
fn bad_spacings_name_the_field() {
    let law = LawSpec::Cycloidal.build().unwrap();
    let m = Motion::rise(&law, 40.0, 120.0, StrokeUnit::Mm).unwrap();
    let e = CamTable::new(m.clone(), Spacing::StepDeg(0.0)).unwrap_err().to_string();
    assert!(e.starts_with("step_deg = 0 is out of range"), "{e}");
    let e = CamTable::new(m.clone(), Spacing::Tolerance(-1.0)).unwrap_err().to_string();
    assert!(e.starts_with("tolerance = -1 is out of range") && e.ends_with("≤ 1000000 mm"), "{e}");
    let swing = Motion::rise(&law, 30.0, 120.0, StrokeUnit::Deg).unwrap();
    let e = CamTable::new(swing, Spacing::Tolerance(1e9)).unwrap_err().to_string();
    assert!(e.ends_with("≤ tolerance ≤ 1000000 deg"), "the slave unit of a swinging follower: {e}");
    let e = Motion::rise(&law, 0.0, 120.0, StrokeUnit::Mm).unwrap_err().to_string();
    assert!(e.starts_with("stroke_mm = 0"), "{e}");
    let e = Format::parse("xyvb").unwrap_err().to_string();
    assert!(e.starts_with("format: unknown format 'xyvb'"), "{e}");
}

#[test]
fn snapshots_of_every_format_on_a_small_law() {
    let law = LawSpec::Poly345.build().unwrap();
    let m = Motion::rise(&law, 20.0, 90.0, StrokeUnit::Mm).unwrap();
    let t = CamTable::new(m, Spacing::StepDeg(15.0)).unwrap();
    for f in Format::ALL {
        insta::assert_snapshot!(format!("poly345_{}", f.name()), t.export(f).unwrap().text);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn reported_error_bounds_the_dense_error(
        which in 0usize..6,
        stroke in 1.0f64..200.0,
        motion in 20.0f64..300.0,
        step in 0.7f64..20.0,
    ) {
        let spec = [
            LawSpec::Cycloidal,
            LawSpec::Harmonic,
            LawSpec::ConstantAcceleration,
            LawSpec::Poly4567,
            LawSpec::ModifiedSine,
            LawSpec::ModifiedTrapezoid { ramp: 0.1 },
        ][which].clone();
        let law = spec.build().unwrap();
        let m = Motion::rise(&law, stroke, motion, StrokeUnit::Mm).unwrap();
        let t = CamTable::new(m.clone(), Spacing::StepDeg(step)).unwrap();
        let out = t.export(Format::Xyvaj).unwrap();
        let ivs = Format::Xyvaj.read(&out.text).unwrap();
        let dense = dense_error(&m, &ivs, 200);
        // Positions of magnitude H carry a rounding of a few 1e-16·H in any double evaluation (the
        // law's and the quintic's), so the bound holds to that: 1e-13·H.
        prop_assert!(dense <= out.error.max_position_error * (1.0 + 1e-9) + 1e-13 * stroke);
    }
}

/// A dwell, a constant-acceleration rise (A jumps at both dwell edges and in the middle), a dwell
/// and a cycloidal return (A continuous, J jumps at both ends).
const JOINTS_MM: &str = r#"
unit = "mm"
stroke = 30
[[segment]]
kind = "dwell"
to_deg = 60
[[segment]]
kind = "rise"
to_deg = 180
law = "constant-acceleration"
[[segment]]
kind = "dwell"
to_deg = 240
[[segment]]
kind = "return"
to_deg = 360
law = "cycloidal"
"#;

/// `[Y, V, A, J]` of [`JOINTS_MM`] in closed form, written out here independently of the library:
/// `side` −1 takes the formula of the piece that ends at `x`, +1 of the one that starts there.
fn joints_exact(x: f64, side: f64) -> [f64; 4] {
    use std::f64::consts::PI;
    let (h, b) = (30.0, 120.0);
    let x = x + side * 1e-12; // only picks the piece; the formula is then evaluated at x itself
    let on = |lo: f64, hi: f64| x > lo && x < hi;
    let x = x - side * 1e-12;
    if on(60.0, 120.0) {
        let u = x - 60.0;
        [2.0 * h * u * u / (b * b), 4.0 * h * u / (b * b), 4.0 * h / (b * b), 0.0]
    } else if on(120.0, 180.0) {
        let w = 180.0 - x;
        [h - 2.0 * h * w * w / (b * b), 4.0 * h * w / (b * b), -4.0 * h / (b * b), 0.0]
    } else if on(180.0, 240.0) {
        [h, 0.0, 0.0, 0.0]
    } else if on(240.0, 360.0 + 1.0) {
        let u = (x - 240.0) / b;
        let (s, c) = (2.0 * PI * u).sin_cos();
        [
            h * (1.0 - (u - s / (2.0 * PI))),
            -h * (1.0 - c) / b,
            -h * 2.0 * PI * s / (b * b),
            -h * 4.0 * PI * PI * c / (b * b * b),
        ]
    } else {
        [0.0; 4]
    }
}

/// At a joint the table holds the values of the piece that starts there (never the mean of the
/// two sides), and the reported re-interpolation error covers the interval on either side of it:
/// both checked against the closed form above.
#[test]
fn a_joint_holds_the_starting_piece_and_the_error_covers_both_sides() {
    let m = cycle(JOINTS_MM);
    let t = CamTable::new(m.clone(), Spacing::StepDeg(7.0)).unwrap();
    let d = t.decimals();
    let r = |x: f64, n: usize| (x * 10f64.powi(n as i32)).round() / 10f64.powi(n as i32) + 0.0;
    let out = t.export(Format::Csv).unwrap();
    let pts = loomkin_cams::table::csv::read(&out.text).unwrap();
    let a0 = 4.0 * 30.0 / (120.0f64 * 120.0);
    for (x, want_a) in [(60.0, a0), (120.0, -a0), (180.0, 0.0), (240.0, 0.0)] {
        let p = pts.iter().find(|p| p.master_deg == x).unwrap();
        let e = joints_exact(x, 1.0);
        assert_eq!(p.a, r(want_a, d.a), "A at {x}°");
        assert_eq!([p.y, p.v, p.a, p.j], [r(e[0], d.y), r(e[1], d.v), r(e[2], d.a), r(e[3], d.j)], "at {x}°");
    }
    // The cycloidal return starts with the jerk −4π²H/B³, the dwell before it has none.
    let j240 = pts.iter().find(|p| p.master_deg == 240.0).unwrap().j;
    assert_eq!(j240, r(-4.0 * std::f64::consts::PI.powi(2) * 30.0 / 120.0f64.powi(3), d.j));
    // The issue's case: never the mean of the sides (0.0104 here, where they are 0 and 0.0208).
    assert!(pts.iter().all(|p| (p.a.abs() - 0.5 * a0).abs() > 1e-6), "a mean of two sides is written");

    let jumps = [(60.0, a0), (120.0, -2.0 * a0), (180.0, a0), (240.0, 0.0)];
    for f in Format::ALL {
        let out = t.export(f).unwrap();
        let ivs = f.read(&out.text).unwrap();
        // Errors of every interval against the closed form of its own side, dense, ends included.
        let mut worst = [0.0f64; 3];
        for iv in &ivs {
            for i in 0..=400 {
                let x = iv.start_deg + iv.width() * i as f64 / 400.0;
                let side = if i == 400 { -1.0 } else { 1.0 };
                let (got, want) = (iv.eval(x), joints_exact(x, side));
                for k in 0..3 {
                    worst[k] = worst[k].max((got[k] - want[k]).abs());
                }
            }
        }
        let rep = [out.error.max_position_error, out.error.max_velocity_error, out.error.max_accel_error];
        for k in 0..3 {
            assert!(worst[k] <= rep[k] * (1.0 + 1e-9) + 1e-12, "{f:?} order {k}: dense {:e} > {:e}", worst[k], rep[k]);
            assert!(worst[k] >= rep[k] * (1.0 - 2e-3), "{f:?} order {k}: dense {:e} ≪ {:e}", worst[k], rep[k]);
        }
        // Each side of each joint on its own: the interval that ends there against the piece that
        // ends there, the one that starts there against the piece that starts there.
        for (x, jump) in jumps {
            let before = ivs.iter().find(|iv| iv.end_deg == x).unwrap();
            let after = ivs.iter().find(|iv| iv.start_deg == x).unwrap();
            let left = (before.eval(x)[2] - joints_exact(x, -1.0)[2]).abs();
            let right = (after.eval(x)[2] - joints_exact(x, 1.0)[2]).abs();
            assert!(left.max(right) <= rep[2] * (1.0 + 1e-9), "{f:?} at {x}°: {left:e} {right:e} vs {:e}", rep[2]);
            // Both sides exact to the rounding of A (and, for poly5, of the coefficients).
            assert!(right < 1e-8, "{f:?} at {x}°: right {right:e}");
            if f == Format::Poly5 {
                // poly5 carries both sides: each segment ends on the A of its own piece.
                assert!(left < 1e-8, "{f:?} at {x}°: left {left:e}");
            } else {
                // A point holds the starting side: the interval that ends on a jump of A misses
                // the ending piece's A by the whole jump there.
                assert!((left - jump.abs()).abs() < 1e-8, "{f:?} at {x}°: left {left:e}, jump {jump:e}");
            }
        }
    }
}
