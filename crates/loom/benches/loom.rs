//! Benchmarks of the loom model: the torque over a 24-frame, 48-pick repeat at 0.5° (target
//! < 5 ms), the stagger optimisation for 24 frames (target < 1 s), and `loom check` of a long
//! repeat (the 48-pick draft 200 times, 9,600 picks; target: 10⁵ picks in seconds), and both on
//! random lift plans whose turns do not repeat (10⁵ picks checked, 1,000 staggered; issue 27).

mod common;
use loomkin_loom::{Drive, Loom, Motion, Objective, Pattern, check, optimise_stagger};

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

/// The 48-pick draft repeated `times` times.
fn repeated(times: usize) -> Pattern {
    let (_, pattern) = setup();
    let rows = (0..times * pattern.picks())
        .map(|p| (0..24).map(|s| pattern.is_up(p % pattern.picks(), s)).collect())
        .collect();
    Pattern::new(24, rows).unwrap()
}

/// `loom check` (geometry, refined peak, RMS, every pick's window) of 9,600 picks: each distinct
/// turn computed once, the torque grid read a turn at a time.
#[divan::bench(sample_count = 5)]
fn check_24_frames_9600_picks(bencher: divan::Bencher) {
    let (loom, _) = setup();
    let pattern = repeated(200);
    bencher.bench_local(|| check(&loom, &pattern).unwrap().peak_torque_n_m);
}

/// The torque curve of 480 picks at 0.1° (1.7·10⁶ points) made a turn at a time, as `loom torque
/// --csv` streams it: what [`Drive::CPU_S_PER_POINT`] adds the printing to.
#[divan::bench(sample_count = 3)]
fn torque_points_24_frames_480_picks(bencher: divan::Bencher) {
    let (loom, _) = setup();
    let pattern = repeated(10);
    let motion = Motion::new(&loom, &pattern).unwrap();
    let drive = Drive::new(&loom, &motion, &pattern);
    bencher.bench_local(|| drive.torque_points(divan::black_box(0.1)).map(|(_, t)| t).sum::<f64>());
}

/// `loom check` of 10⁵ random picks on 24 frames (no turn repeats: the frames' rows made once,
/// every pick summed from them; was 96 s, one turn worked out whole per pick).
#[divan::bench(sample_count = 3, sample_size = 1)]
fn check_24_frames_100000_random_picks(bencher: divan::Bencher) {
    let (loom, _) = setup();
    let pattern = common::random_plan(100_000);
    bencher.bench_local(|| check(&loom, &pattern).unwrap().rms_torque_n_m);
}

/// The stagger search (peak objective, per frame) on 1,000 random picks of 24 frames.
#[divan::bench(sample_count = 2, sample_size = 1)]
fn stagger_24_frames_1000_random_picks(bencher: divan::Bencher) {
    let (loom, _) = setup();
    let pattern = common::random_plan(1_000);
    bencher.bench_local(|| optimise_stagger(&loom, &pattern, Objective::Peak).unwrap().best.peak_torque_n_m);
}
