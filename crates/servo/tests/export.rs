//! Exported coefficients and cam tables against the law they came from.

use loomkin_servo::{
    CamTable, Drive, Interpolation, SplineEnd, SplineLaw, export_coefficients, export_coeffs_text, export_json,
    parse_points, poly5_segments, quintic_hermite, read_coeffs_text, read_json, slave_at,
};

fn laws() -> Vec<SplineLaw> {
    vec![
        SplineLaw::default_law(),
        SplineLaw::new(&parse_points("0:0,0.05:0.7,0.12:1,0.3:0.8,0.42:0.3,0.5:0").unwrap(), SplineEnd::Clamped)
            .unwrap(),
        SplineLaw::new(&parse_points("0:0,0.2:1,0.35:-0.2,0.5:0").unwrap(), SplineEnd::Natural).unwrap(),
    ]
}

fn horner(c: &[f64], x: f64) -> f64 {
    c.iter().rev().fold(0.0, |a, &k| a * x + k)
}

#[test]
fn json_and_text_coefficients_reproduce_the_law() {
    for sl in laws() {
        let law = sl.law();
        let json = read_json(&export_json(&sl)).unwrap();
        let text = read_coeffs_text(&export_coeffs_text(&sl)).unwrap();
        assert_eq!(json.intervals.len(), 2 * (sl.points().len() - 1));
        // Text and JSON carry the same numbers (serde_json's float parsing may differ by an ulp).
        assert_eq!(text.len(), json.intervals.len());
        for (t, j) in text.iter().zip(&json.intervals) {
            let (a, b) = (
                t.position.iter().chain(&t.velocity).chain(&t.accel),
                j.position.iter().chain(&j.velocity).chain(&j.accel),
            );
            for (x, y) in a.zip(b) {
                assert!((x - y).abs() <= 1e-15 * x.abs().max(1.0), "{x} vs {y}");
            }
        }
        assert!(
            (json.intervals[0].x_start).abs() < 1e-15 && (json.intervals.last().unwrap().x_end - 1.0).abs() < 1e-15
        );
        let mut worst = 0.0f64;
        for (iv, seg) in json.intervals.iter().zip(law.segments()) {
            assert!((iv.x_start - seg.x0()).abs() < 1e-15 && (iv.x_end - seg.x1()).abs() < 1e-15);
            for k in 0..=20 {
                let x = iv.x_start + (iv.x_end - iv.x_start) * k as f64 / 20.0;
                // Evaluate at the interval's own x (from the left at a joint) against the law.
                let e = seg.eval(x);
                worst = worst
                    .max((horner(&iv.position, x) - e.s).abs())
                    .max((horner(&iv.velocity, x) - e.v).abs())
                    .max((horner(&iv.accel, x) - e.a).abs() / (1.0 + law.metrics().ca));
                // The paper's b: f through the definition points, a = scale · f.
                assert!((horner(&iv.b, x) - sl.accel_image(x)).abs() < 1e-8 * (1.0 + sl.accel_image(x).abs()));
            }
        }
        assert!(worst < 1e-9, "worst {worst}");
        // Spot check via the export's own evaluator.
        let [s, v, a] = json.eval(0.37);
        let k = law.eval(0.37);
        assert!((s - k.s).abs() < 1e-9 && (v - k.v).abs() < 1e-9 && (a - k.a).abs() < 1e-8);
        // The first-half b equal the spline coefficients.
        let b = sl.spline_coefficients();
        for (j, bj) in b.iter().enumerate() {
            for k in 0..4 {
                assert!((json.intervals[j].b[k] - bj[k]).abs() < 1e-8 * (1.0 + bj[k].abs()), "b[{k}][{j}]");
            }
        }
    }
    let e = export_coefficients(&SplineLaw::default_law());
    assert_eq!(e.def_points.len(), 7);
}

#[test]
fn poly5_segments_reproduce_the_cycle_exactly() {
    let d = Drive::needle_rack_default();
    for sl in laws() {
        let segs = poly5_segments(sl.law(), &d).unwrap();
        assert!((segs[0].master_start_deg).abs() < 1e-12 && (segs.last().unwrap().master_end_deg - 360.0).abs() < 1e-9);
        for g in &segs {
            for k in 0..=10 {
                let tau = (g.master_end_deg - g.master_start_deg) * k as f64 / 10.0;
                // Evaluate inside the segment (nudge off the right end to stay in the same phase).
                let th = (g.master_start_deg + tau).min(g.master_end_deg - 1e-9);
                let y = slave_at(sl.law(), &d, th).unwrap()[0];
                let p = horner(&g.coeffs, th - g.master_start_deg);
                assert!((p - y).abs() < 1e-12 * d.stroke_m * 10.0, "{th}: {p} vs {y}");
            }
        }
    }
}

#[test]
fn quintic_hermite_matches_its_end_conditions() {
    let (y0, y1, h) = ([0.1, -0.3, 2.0], [0.7, 0.4, -1.5], 0.8);
    let c = quintic_hermite(y0, y1, h);
    let d: Vec<f64> = (1..6).map(|k| k as f64 * c[k]).collect();
    let dd: Vec<f64> = (1..5).map(|k| k as f64 * d[k]).collect();
    for (got, want) in [
        (horner(&c, 0.0), y0[0]),
        (horner(&d, 0.0), y0[1]),
        (horner(&dd, 0.0), y0[2]),
        (horner(&c, h), y1[0]),
        (horner(&d, h), y1[1]),
        (horner(&dd, h), y1[2]),
    ] {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}

#[test]
fn cam_table_errors_shrink_with_the_step_at_the_expected_orders() {
    let d = Drive::needle_rack_default();
    let sl = SplineLaw::default_law();
    let err =
        |step: f64, mode| CamTable::new(sl.law(), &d, step).unwrap().interpolation_error(sl.law(), &d, mode).unwrap();
    // Linear: O(h²) in position. Quintic Hermite on a quintic law: only where a table interval
    // straddles a joint of the law; O(h^6) there in position.
    let (l1, l2) = (err(2.0, Interpolation::Linear), err(1.0, Interpolation::Linear));
    let r = l1.max_position_error_m / l2.max_position_error_m;
    assert!(r > 3.5 && r < 4.5, "linear ratio {r}");
    let (q1, q2) = (err(2.0, Interpolation::QuinticHermite), err(1.0, Interpolation::QuinticHermite));
    assert!(q2.max_position_error_m < q1.max_position_error_m / 16.0, "{q1:?} {q2:?}");
    let c2 = err(1.0, Interpolation::CubicSpline);
    assert!(q2.max_position_error_m < c2.max_position_error_m && c2.max_position_error_m < l2.max_position_error_m);
    assert!(q2.rel_accel_error < c2.rel_accel_error && c2.rel_accel_error < 1.0);
    // Linear interpolation has no acceleration at all: the error is the whole acceleration.
    assert!((l2.rel_accel_error - 1.0).abs() < 1e-12);
    let t = CamTable::new(sl.law(), &d, 1.0).unwrap();
    assert_eq!(t.points.len(), 361);
    assert!(t.to_csv().starts_with("master_deg,slave_m,slave_v_m_per_deg,slave_a_m_per_deg2\n"));
    assert_eq!(t.to_xyva().lines().filter(|l| !l.starts_with('#')).count(), 362);
}

#[test]
fn bad_export_requests_are_errors() {
    let d = Drive::needle_rack_default();
    let law = loomkin_laws::LawSpec::Cycloidal.build().unwrap();
    assert!(poly5_segments(&law, &d).is_err());
    let sl = SplineLaw::default_law();
    assert!(CamTable::new(sl.law(), &d, 0.0).is_err());
    assert!(CamTable::new(sl.law(), &d, f64::NAN).is_err());
    assert!(read_json("{").is_err());
    assert!(read_coeffs_text("1 2 3").is_err());
}
