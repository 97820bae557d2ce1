//! Cost of the Pareto front and of the simplex grid on a million points.

use loomkin_study::{Design, Sense, pareto_front};

fn main() {
    divan::main();
}

/// A million pseudo-random two-objective points (a fixed linear congruential sequence).
fn cloud(n: usize) -> Vec<[f64; 2]> {
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1_442_695_040_888_963_407);
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n).map(|_| [next() * 360.0, next() * 100.0]).collect()
}

#[divan::bench]
fn front_1m_two_objectives(bencher: divan::Bencher) {
    let p = cloud(1_000_000);
    bencher.bench_local(|| pareto_front(divan::black_box(&p), &[Sense::Maximize, Sense::Minimize]).unwrap().len());
}

#[divan::bench]
fn simplex_grid_4_parts_step_0_005(bencher: divan::Bencher) {
    bencher.bench_local(|| Design::simplex(4, 0.005, 0.95, divan::black_box(0.005)).unwrap().len());
}
