//! Benchmarks of the dynamics crate: the speed sweep (issue 13 asks for 10⁴ speeds in under 50 ms).

use loomkin_dynamics::{Follower, Response, Start, sweep};
use loomkin_laws::Cycle;
use loomkin_units::ShaftSpeed;

fn main() {
    divan::main();
}

const HEALD: &str = include_str!("../../../examples/heald-frame-cycle.toml");

/// 10⁴ speeds from 300 to 1300 rpm (the loom range), from rest, one cycle each: residual, peak error, peak force.
#[divan::bench(sample_count = 10)]
fn sweep_10k_speeds(b: divan::Bencher) {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let f = Follower::new(54.0, 0.05).unwrap().with_loads(20.0, 5e3, 200.0).unwrap();
    let speeds: Vec<f64> = (0..10_000).map(|i| 300.0 + 0.1 * i as f64).collect();
    b.bench(|| sweep(&cycle, &f, divan::black_box(&speeds), Start::Rest).unwrap());
}

/// One response with its summary at 600 rpm.
#[divan::bench]
fn response_summary_600rpm(b: divan::Bencher) {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let f = Follower::new(54.0, 0.05).unwrap();
    let s = ShaftSpeed::from_rpm(600.0).unwrap();
    b.bench(|| Response::new(&cycle, s, &f, Start::Rest, 1).unwrap().summary());
}

/// One sweep point (the work per speed of the sweep, single-threaded) at 600 rpm.
#[divan::bench]
fn sweep_point_600rpm(b: divan::Bencher) {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let f = Follower::new(54.0, 0.05).unwrap().with_loads(20.0, 5e3, 200.0).unwrap();
    let s = ShaftSpeed::from_rpm(600.0).unwrap();
    b.bench(|| loomkin_dynamics::sweep_point(&cycle, &f, s, Start::Rest).unwrap());
}
