//! What the loom's benches share.

use loomkin_loom::Pattern;

/// A lift plan of `picks` picks on 24 shafts, each shaft up or down at random (a fixed LCG).
pub fn random_plan(picks: usize) -> Pattern {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut text = String::new();
    for _ in 0..picks {
        let mut up = Vec::new();
        for s in 1..=24 {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
            if state >> 63 == 1 {
                up.push(s.to_string());
            }
        }
        if up.is_empty() {
            up.push("1".into());
        }
        text += &(up.join(" ") + "\n");
    }
    Pattern::from_lift_plan(&text).unwrap()
}
