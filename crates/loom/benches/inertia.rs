//! Benchmarks of the loom on its main shaft: the reduced inertia of 24 frames and the sley over a
//! 10⁴-pick repeat (target < 50 ms), and the speed ripple of the rapier loom over its 48 picks.

use loomkin_drive::{Table, solve};
use loomkin_loom::{Loom, LoomShaft, Motion, Pattern};

mod common;
use common::random_plan;

fn main() {
    divan::main();
}

fn rapier() -> Loom {
    Loom::from_toml(include_str!("../../../examples/rapier-loom.toml")).unwrap()
}

/// `drive inertia`'s report: J min/max/mean of 24 frames, the sley and the total over 10⁴ picks at 0.5°.
#[divan::bench(sample_count = 10)]
fn inertia_24_frames_10k_picks(bencher: divan::Bencher) {
    let loom = rapier();
    let pattern = random_plan(10_000);
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    bencher.bench_local(|| shaft.report(divan::black_box(0.5)).unwrap().j_max_kg_m2);
}

/// The periodic solution of the rapier loom over 48 picks at 0.1° (172 800 steps), the table built once.
#[divan::bench(sample_count = 10)]
fn ripple_rapier_48_picks(bencher: divan::Bencher) {
    let loom = rapier();
    let pattern = Pattern::from_wif(include_str!("../../../examples/point-24.wif")).unwrap();
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let table = Table::new(&shaft, 0.1).unwrap();
    let motor = loom.drive.motor.build(loom.speed.rpm(), "drive.").unwrap();
    bencher.bench_local(|| solve(&table, &motor, 0.0).unwrap().report.speed_ripple_pct);
}
