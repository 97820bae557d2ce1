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
