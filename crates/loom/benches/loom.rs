//! Benchmarks of the loom model: the torque over a 24-frame, 48-pick repeat at 0.5° (target
//! < 5 ms) and the stagger optimisation for 24 frames (target < 1 s).

use loomkin_loom::{Drive, Loom, Motion, Objective, Pattern, optimise_stagger};

fn main() {
    divan::main();
}

fn setup() -> (Loom, Pattern) {
    let loom = Loom::from_toml(include_str!("../../../examples/rapier-loom.toml")).unwrap();
    let pattern = Pattern::from_wif(include_str!("../../../examples/point-24.wif")).unwrap();
    (loom, pattern)
}

/// Motion of 24 frames over 48 picks and the torque at every 0.5° of the 17 280° repeat (34 560 points).
#[divan::bench]
fn torque_24_frames_48_picks_half_degree(bencher: divan::Bencher) {
    let (loom, pattern) = setup();
    bencher.bench_local(|| {
        let motion = Motion::new(&loom, &pattern).unwrap();
        Drive::new(&loom, &motion, &pattern).torque_curve(divan::black_box(0.5)).len()
    });
}

/// The same with the refined peak and the quadrature RMS (what `loom check` adds).
#[divan::bench(sample_count = 10)]
fn torque_peak_and_rms_24_frames_48_picks(bencher: divan::Bencher) {
    let (loom, pattern) = setup();
    let motion = Motion::new(&loom, &pattern).unwrap();
    let drive = Drive::new(&loom, &motion, &pattern);
    bencher.bench_local(|| (drive.peak(0.5).torque_n_m, drive.rms()));
}

/// Stagger optimisation of 24 frames (per frame) on the 48-pick draft, peak objective.
#[divan::bench(sample_count = 3)]
fn stagger_24_frames(bencher: divan::Bencher) {
    let (loom, pattern) = setup();
    bencher.bench_local(|| optimise_stagger(&loom, &pattern, Objective::Peak).unwrap().best.peak_torque_n_m);
}
