//! Exported coefficients and cam tables against the law they came from.

use loomkin_cams::table::Format;
use loomkin_servo::{
    Drive, ExportFormat, Interpolation, SplineEnd, SplineLaw, export, export_coefficients, export_coeffs_text,
    export_json, parse_points, read_coeffs_text, read_json, spline_motion,
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

/// `Y` (mm) at master angle `deg` of the drive's turn, from the law's own formula.
fn slave_mm(law: &loomkin_laws::Law, d: &Drive, deg: f64) -> f64 {
    let lay = d.layout().unwrap();
    let st = lay.starts_deg();
    let h = d.stroke_m * 1e3;
    if deg < st[1] {
        h * law.eval(deg / lay.rise_deg).s
    } else if deg < st[2] {
        h
    } else if deg < st[3] {
        h * (1.0 - law.eval((deg - st[2]) / lay.return_deg).s)
    } else {
        0.0
    }
}

/// The poly5 export has one segment per piece of the law (the spline law is piecewise quintic, so
/// each segment is the law itself) and follows the law to the rounding of its columns.
#[test]
fn poly5_segments_reproduce_the_cycle_to_their_decimals() {
    let d = Drive::needle_rack_default();
    for sl in laws() {
        let text = export(&sl, &d, ExportFormat::Poly5, 1.0).unwrap().text;
        assert!(text.contains("b0_mm,b1_mm,b2_mm,b3_mm,b4_mm,b5_mm"), "{text}");
        let segs = Format::Poly5.read(&text).unwrap();
        let pieces = spline_motion(&sl, &d).unwrap().pieces().len();
        assert_eq!(segs.len(), pieces);
        assert_eq!((segs[0].start_deg, segs.last().unwrap().end_deg), (0.0, 360.0));
        let mut worst = 0.0f64;
        for g in &segs {
            for k in 0..=10 {
                // Inside the segment (nudged off the right end to stay in the same phase).
                let th = (g.start_deg + g.width() * k as f64 / 10.0).min(g.end_deg - 1e-9);
                worst = worst.max((g.eval(th)[0] - slave_mm(sl.law(), &d, th)).abs());
            }
        }
        // The position column's last digit is 1e-6 of the 80 mm stroke at most.
        assert!(worst < 1e-6 * 80.0, "{worst:e}");
    }
}

#[test]
fn cam_table_errors_shrink_with_the_step_at_the_expected_orders() {
    let d = Drive::needle_rack_default();
    let sl = SplineLaw::default_law();
    let err = |step: f64, mode| {
        let t = export(&sl, &d, ExportFormat::Csv, step).unwrap().table.unwrap();
        *t.reinterpolation.iter().find(|e| e.mode == mode).unwrap()
    };
    // Linear: O(h²) in position.
    let (l1, l2) = (err(2.0, Interpolation::Linear), err(1.0, Interpolation::Linear));
    let r = l1.max_position_error_m / l2.max_position_error_m;
    assert!(r > 3.5 && r < 4.5, "linear ratio {r}");
    // Quintic Hermite on a quintic law with a point on every joint: only the rounding of the
    // columns (a last digit of 1e-6 of the stroke at most) remains, at any step.
    let (q1, q2) = (err(2.0, Interpolation::QuinticHermite), err(1.0, Interpolation::QuinticHermite));
    assert!(q1.rel_position_error < 1e-6 && q2.rel_position_error < 1e-6, "{q1:?} {q2:?}");
    let c2 = err(1.0, Interpolation::CubicSpline);
    assert!(q2.max_position_error_m < c2.max_position_error_m && c2.max_position_error_m < l2.max_position_error_m);
    assert!(q2.rel_accel_error < c2.rel_accel_error && c2.rel_accel_error < 1.0);
    // Linear interpolation has no acceleration at all: the error is the whole acceleration.
    assert!((l2.rel_accel_error - 1.0).abs() < 1e-6, "{}", l2.rel_accel_error);
    let csv = export(&sl, &d, ExportFormat::Csv, 1.0).unwrap();
    assert!(csv.text.starts_with("master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3\n"));
    let xyva = export(&sl, &d, ExportFormat::Xyva, 1.0).unwrap();
    assert_eq!(xyva.text.lines().filter(|l| !l.starts_with('#')).count(), xyva.table.unwrap().points + 1);
}

/// `servo export`'s tables are `loomkin cam table`'s on the exported cycle file: one engine.
#[test]
fn the_tables_are_those_of_the_cycle_file() {
    let d = Drive::needle_rack_default();
    let sl = &laws()[1];
    let cycle = export(sl, &d, ExportFormat::Cycle, 1.0).unwrap().text;
    let motion = loomkin_cams::table::Motion::from_cycle(&loomkin_laws::Cycle::from_toml(&cycle).unwrap());
    for (format, written, spacing) in [
        (ExportFormat::Csv, Format::Csv, 2.5),
        (ExportFormat::Xyva, Format::Xyva, 2.5),
        (ExportFormat::Poly5, Format::Poly5, 360.0),
    ] {
        let table = loomkin_cams::table::CamTable::new(motion.clone(), loomkin_cams::table::Spacing::StepDeg(spacing));
        let want = table.unwrap().export(written).unwrap().text;
        assert_eq!(export(sl, &d, format, 2.5).unwrap().text, want, "{format:?}");
    }
}

#[test]
fn bad_export_requests_are_errors() {
    let d = Drive::needle_rack_default();
    let sl = SplineLaw::default_law();
    for step in [0.0, f64::NAN, -1.0] {
        let e = export(&sl, &d, ExportFormat::Csv, step).unwrap_err();
        assert!(e.to_string().starts_with("step_deg "), "{e}");
    }
    assert!(read_json("{").is_err());
    assert!(read_coeffs_text("1 2 3").is_err());
}
