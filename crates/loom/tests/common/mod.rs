//! Files shared by the tests: the examples of the repository.

#![allow(dead_code)]

use loomkin_loom::{Loom, Pattern};

pub fn example(name: &str) -> String {
    std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples").join(name)).unwrap()
}

pub fn rapier() -> Loom {
    Loom::from_toml(&example("rapier-loom.toml")).unwrap()
}

pub fn shuttle() -> Loom {
    Loom::from_toml(&example("shuttle-loom.toml")).unwrap()
}

pub fn wif(name: &str) -> Pattern {
    Pattern::from_wif(&example(name)).unwrap()
}

/// The loom file with `key = old` in its text replaced by `key = new`.
pub fn edited(text: &str, old: &str, new: &str) -> String {
    assert!(text.contains(old), "{old} not in the file");
    text.replacen(old, new, 1)
}

/// `picks` picks on `shafts` shafts, each up or down at random (an LCG from `seed`; at least one
/// shaft up in every pick). The benches draw theirs here too.
pub fn random_plan(seed: u64, picks: usize, shafts: usize) -> Pattern {
    let mut state = seed;
    let mut text = String::new();
    for _ in 0..picks {
        let mut up = Vec::new();
        for s in 1..=shafts {
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
