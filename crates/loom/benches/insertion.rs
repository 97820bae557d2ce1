//! Benchmarks of the carrier on the loom: the rapier's clearance over a 10⁴-pick repeat of 24
//! frames (target < 10 ms), for a repeat that repeats its frame states (the 24-frame point twill
//! over and over) and for one that does not (every pick drawn at random: no state repeats).

use loomkin_loom::insertion::{clearance, rapier_of};
use loomkin_loom::{Loom, Pattern};

mod common;
use common::random_plan;

fn main() {
    divan::main();
}

fn rapier() -> Loom {
    Loom::from_toml(include_str!("../../../examples/rapier-loom.toml")).unwrap()
}

/// The point twill of examples/point-24.wif repeated to at least `picks` picks (whole repeats).
fn point_repeated(picks: usize) -> Pattern {
    let one = Pattern::from_wif(include_str!("../../../examples/point-24.wif")).unwrap();
    let lines: Vec<String> = (0..one.picks())
        .map(|p| (0..24).filter(|&i| one.is_up(p, i)).map(|i| (i + 1).to_string()).collect::<Vec<_>>().join(" "))
        .collect();
    let n = picks.div_ceil(lines.len()) * lines.len();
    Pattern::from_lift_plan(&(0..n).map(|p| lines[p % lines.len()].as_str()).collect::<Vec<_>>().join("\n")).unwrap()
}

/// `insert rapier`'s clearance: 24 frames, the point twill repeated to 10 000 picks.
#[divan::bench(sample_count = 10)]
fn rapier_clearance_24_frames_10k_picks_repeating(bencher: divan::Bencher) {
    let loom = rapier();
    let pattern = point_repeated(10_000);
    let r = rapier_of(&loom).unwrap();
    bencher.bench_local(|| clearance(&loom, divan::black_box(&pattern), r).unwrap().min_clearance_mm);
}

/// The same with every pick drawn at random (no repeated states: each pick scanned).
#[divan::bench(sample_count = 3)]
fn rapier_clearance_24_frames_10k_picks_random(bencher: divan::Bencher) {
    let loom = rapier();
    let pattern = random_plan(10_000);
    let r = rapier_of(&loom).unwrap();
    bencher.bench_local(|| clearance(&loom, divan::black_box(&pattern), r).unwrap().min_clearance_mm);
}
