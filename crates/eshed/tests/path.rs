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
