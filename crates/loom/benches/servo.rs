//! Benches of electronic shedding on the loom (issue 31): the study of 24 servo-driven frames over
//! a 10⁴-pick repeat (goal < 50 ms) — the bus, every frame's servo check and the clear shed over
//! the plans — and the optimiser (goal < 2 s on one core), for each objective (`*_rms_*`: the
//! worst frame's RMS torque).
//!
//! `cargo bench -p loomkin-loom --bench servo`. The loom is examples/servo-shedding-loom.toml; the
//! lift plan a 12/12 twill on 24 shafts tiled to 10⁴ picks. The `crank_*` rows: the same 24 frames
//! on the crank and lever of examples/servo-shedding-crank-loom.toml, `loom servo --optimize` of its
//! plain weave (both objectives) and of examples/point-24.wif.

use loomkin_loom::{Loom, Objective, Pattern, optimise_servo, servo_setups, servo_study_of};

fn main() {
    divan::main();
}

fn loom() -> Loom {
    Loom::from_toml(include_str!("../../../examples/servo-shedding-loom.toml")).unwrap()
}

/// A 12/12 twill on 24 shafts, `picks` picks.
fn twill(picks: usize) -> Pattern {
    let rows = (0..picks).map(|p| (0..24).map(|i| (p + i) % 24 < 12).collect()).collect();
    Pattern::new(24, rows).unwrap()
}

/// `loom servo`'s study of the tiled twill: the plans, the bus, the servo checks, the clear shed.
#[divan::bench(sample_count = 10)]
fn study_24_frames_10k_picks(b: divan::Bencher) {
    let (loom, pattern) = (loom(), twill(10_000));
    b.bench(|| {
        let setups = servo_setups(&loom, &pattern, None, None).unwrap();
        servo_study_of(&loom, &pattern, &setups).unwrap().peak_bus_power_w
    });
}

/// `loom servo --optimize` (peak bus power) of the tiled twill.
#[divan::bench(sample_count = 2)]
fn optimise_24_frames_10k_picks(b: divan::Bencher) {
    let (loom, pattern) = (loom(), twill(10_000));
    b.bench(|| {
        optimise_servo(&loom, &pattern, Objective::Peak, &Default::default(), &|_, _| {})
            .unwrap()
            .peak_bus_power_w_after
    });
}

/// `loom servo --optimize --objective rms` (the worst frame's RMS torque) of the tiled twill.
#[divan::bench(sample_count = 2)]
fn optimise_rms_24_frames_10k_picks(b: divan::Bencher) {
    let (loom, pattern) = (loom(), twill(10_000));
    b.bench(|| {
        optimise_servo(&loom, &pattern, Objective::Rms, &Default::default(), &|_, _| {})
            .unwrap()
            .worst_rms_torque_n_m_after
    });
}

fn crank_loom() -> Loom {
    Loom::from_toml(include_str!("../../../examples/servo-shedding-crank-loom.toml")).unwrap()
}

/// `loom servo examples/servo-shedding-crank-loom.toml --optimize` (its plain weave, 2 picks).
#[divan::bench(sample_count = 3)]
fn crank_optimise_plain(b: divan::Bencher) {
    let loom = crank_loom();
    let pattern = Pattern::plain(loom.frame_count()).unwrap();
    b.bench(|| {
        optimise_servo(&loom, &pattern, Objective::Peak, &Default::default(), &|_, _| {})
            .unwrap()
            .peak_bus_power_w_after
    });
}

/// `loom servo examples/servo-shedding-crank-loom.toml --optimize --objective rms`.
#[divan::bench(sample_count = 2)]
fn crank_optimise_rms_plain(b: divan::Bencher) {
    let loom = crank_loom();
    let pattern = Pattern::plain(loom.frame_count()).unwrap();
    b.bench(|| {
        optimise_servo(&loom, &pattern, Objective::Rms, &Default::default(), &|_, _| {})
            .unwrap()
            .worst_rms_torque_n_m_after
    });
}

/// `loom servo examples/servo-shedding-crank-loom.toml --wif examples/point-24.wif --optimize`.
#[divan::bench(sample_count = 2)]
fn crank_optimise_point_24(b: divan::Bencher) {
    let loom = crank_loom();
    let pattern = Pattern::from_wif(include_str!("../../../examples/point-24.wif")).unwrap();
    b.bench(|| {
        optimise_servo(&loom, &pattern, Objective::Peak, &Default::default(), &|_, _| {})
            .unwrap()
            .peak_bus_power_w_after
    });
}
