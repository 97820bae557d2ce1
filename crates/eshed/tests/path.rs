//! A frame's path looked up with the remembered segment is the path looked up afresh, at every
//! angle, in any order (the hint never changes an answer).

use loomkin_eshed::{FrameInput, FramePath, FramePlan, MoveLaws};
use loomkin_laws::LawSpec;
use proptest::prelude::*;

fn laws() -> MoveLaws {
    let spec = LawSpec::ModifiedSine;
    let law = spec.build().unwrap();
    MoveLaws::new((spec.clone(), law.clone()), (spec, law))
}

fn plan(up: &[bool], pass_through: bool) -> FramePlan {
    FramePlan::new(
        &FrameInput { up, stroke_m: 0.09, centre_deg: -12.5, motion_deg: 260.0, fall_motion_deg: 260.0 },
        pass_through,
    )
    .unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn the_remembered_segment_never_changes_a_height_or_a_key(
        up in proptest::collection::vec(any::<bool>(), 1..40),
        pass_through in any::<bool>(),
        angles in proptest::collection::vec(-2000.0f64..16_000.0, 1..200),
    ) {
        let (p, l) = (plan(&up, pass_through), laws());
        let path = FramePath::new(&p, &l);
        for &a in &angles {
            // A fresh path has no memory of earlier look-ups.
            let fresh = FramePath::new(&p, &l);
            prop_assert_eq!(path.y_m(a).to_bits(), fresh.y_m(a).to_bits());
            let (mut k1, mut k2) = (Vec::new(), Vec::new());
            path.key_words(a, -10.0, 350.0, &mut k1);
            FramePath::new(&p, &l).key_words(a, -10.0, 350.0, &mut k2);
            prop_assert_eq!(k1, k2);
        }
        // In increasing order too (what the timing does), and at every joint exactly.
        let mut sorted = angles.clone();
        sorted.sort_by(f64::total_cmp);
        let joints: Vec<f64> = p.levels().iter().map(|s| s.start_deg).collect();
        for &a in sorted.iter().chain(&joints) {
            prop_assert_eq!(path.y_m(a).to_bits(), FramePath::new(&p, &l).y_m(a).to_bits());
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_resting_frame_has_its_rest_height_at_every_angle_of_the_span(
        up in proptest::collection::vec(any::<bool>(), 1..40),
        pass_through in any::<bool>(),
        spans in proptest::collection::vec((-2000.0f64..16_000.0, 0.0f64..400.0), 1..100),
    ) {
        let (p, l) = (plan(&up, pass_through), laws());
        let path = FramePath::new(&p, &l);
        for &(from, width) in &spans {
            let to = from + width;
            let Some(y) = path.rest_m(from, to) else {
                // Not refused when the span lies inside a dwell 10⁻⁵° clear of its ends.
                let period = p.period_deg;
                let levels = p.levels();
                let inside = levels.iter().enumerate().any(|(j, s)| {
                    let end = levels.get(j + 1).map_or(p.start_deg + period, |n| n.start_deg);
                    let k = ((from - s.start_deg) / period).floor();
                    s.kind == loomkin_laws::SegmentKind::Dwell
                        && s.start_deg + k * period + 1e-5 <= from
                        && to + 1e-5 <= end + k * period
                });
                prop_assert!(!inside, "[{}, {}] lies in a dwell", from, to);
                continue;
            };
            // At both ends and on a grid between, in order and not, the height is the rest's.
            for k in 0..=64 {
                let t = if k == 64 { to } else { from + width * k as f64 / 64.0 };
                prop_assert_eq!(path.y_m(t).to_bits(), y.to_bits(), "{} in [{}, {}]", t, from, to);
                prop_assert_eq!(FramePath::new(&p, &l).y_m(t).to_bits(), y.to_bits());
            }
        }
    }
}

#[test]
fn a_span_inside_a_dwell_rests_and_one_over_a_move_does_not() {
    // Frame up on picks 0–1, down on 2–5: moves into picks 0 and 2, centred on −12.5° and
    // 707.5°, 260° long ([−142.5°, 117.5°] and [577.5°, 837.5°]); the dwells between.
    let up = [true, true, false, false, false, false];
    let (p, l) = (plan(&up, false), laws());
    let path = FramePath::new(&p, &l);
    let top = path.y_m(300.0);
    assert_eq!(path.rest_m(120.0, 570.0), Some(top));
    assert_eq!(path.rest_m(-1000.0, -600.0), Some(path.y_m(-800.0)));
    assert_eq!(path.rest_m(100.0, 200.0), None);
    assert_eq!(path.rest_m(500.0, 578.0), None);
    // Within the margin of a move's end.
    assert_eq!(path.rest_m(117.5 + 1e-7, 200.0), None);
    assert!(path.rest_m(117.5 + 1e-5, 577.5 - 1e-5).is_some());
    // A frame that never moves rests everywhere.
    let still = FramePath::new(&plan(&[true; 4], false), &l);
    assert_eq!(still.rest_m(-5000.0, 5000.0), Some(still.y_m(0.0)));
}
