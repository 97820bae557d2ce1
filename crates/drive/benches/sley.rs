//! Benchmarks of the sley: the closed-form state (θ and its three rates) at 3,600 main-shaft
//! angles, the analysis `loomkin sley analyze` prints, and the synthesis.

use loomkin_drive::{Assembly, FourBarSley, SleyTable, SleyTarget};
use loomkin_units::ShaftSpeed;

fn main() {
    divan::main();
}

/// A crank-rocker sley (the rapier example's before it took a cam sley: a short sword, a 113 mm stroke).
fn sley() -> FourBarSley {
    FourBarSley::new(SleyTable {
        crank_mm: 40.0,
        rod_mm: 120.0,
        sword_mm: 200.0,
        pivot_x_mm: 120.0,
        pivot_y_mm: -200.0,
        reed_height_mm: 280.0,
        mass_kg: 30.0,
        gyration_mm: 230.0,
        centre_mm: Some(200.0),
        beat_up_deg: 0.0,
        beat_up_force_n: 2000.0,
        beat_up_range_deg: 15.0,
        assembly: Assembly::Up,
    })
    .unwrap()
}

/// `state` at 3,600 angles (every 0.1°): positions and the rocker's first three rates.
#[divan::bench]
fn state_3600_angles(bencher: divan::Bencher) {
    let s = sley();
    bencher.bench_local(|| {
        (0..3600).map(|i| s.state(divan::black_box(i as f64 * std::f64::consts::TAU / 3600.0)).rocker_d3).sum::<f64>()
    });
}

/// `reduced_inertia_kg_m2` and `load_torque_n_m` at 3,600 angles (what the drive study asks).
#[divan::bench]
fn inertia_and_load_3600_angles(bencher: divan::Bencher) {
    let s = sley();
    bencher.bench_local(|| {
        (0..3600)
            .map(|i| {
                let phi = divan::black_box(i as f64 * std::f64::consts::TAU / 3600.0);
                s.reduced_inertia_kg_m2(phi).1 + s.load_torque_n_m(phi)
            })
            .sum::<f64>()
    });
}

/// The whole analysis: dwell roots and eight located extremes.
#[divan::bench(sample_count = 20)]
fn analyze(bencher: divan::Bencher) {
    let s = sley();
    let speed = ShaftSpeed::from_rpm(500.0).unwrap();
    bencher.bench_local(|| s.analyze(speed, divan::black_box(1.0)).unwrap().peak_crank_torque_n_m);
}

/// The synthesis for 110 mm and 40° at 1 mm.
#[divan::bench(sample_count = 5)]
fn synthesize(bencher: divan::Bencher) {
    let t = SleyTarget {
        stroke_mm: 110.0,
        back_dwell_deg: 40.0,
        dwell_tolerance_mm: 1.0,
        reed_height_mm: 400.0,
        sword_mm: None,
    };
    bencher.bench_local(|| divan::black_box(t).synthesize().unwrap().min_transmission_angle_deg);
}
