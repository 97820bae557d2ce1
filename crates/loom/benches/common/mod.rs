//! What the loom's benches share: the tests' random lift plans (one generator).

use loomkin_loom::Pattern;

#[path = "../../tests/common/mod.rs"]
mod tests_common;

/// A lift plan of `picks` picks on 24 shafts, each shaft up or down at random (a fixed LCG).
pub fn random_plan(picks: usize) -> Pattern {
    tests_common::random_plan(0x2545_f491_4f6c_dd1d, picks, 24)
}
