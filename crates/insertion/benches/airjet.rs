//! Bench of the air jet: one flight with 20 relay groups across 1.9 m (issue 30: < 1 ms).
//!
//! `cargo bench -p loomkin-insertion --bench airjet`.

use loomkin_insertion::{Airjet, AirjetTable};
use loomkin_units::ShaftSpeed;

fn main() {
    divan::main();
}

/// The tests' loom: 20 groups of two nozzles 48 mm apart, a 20 tex yarn.
fn twenty_groups() -> Airjet {
    let t = AirjetTable {
        yarn_tex: 20.0,
        yarn_diameter_mm: 0.25,
        tail_mm: 600.0,
        main_speed_m_s: 250.0,
        main_core_mm: 40.0,
        reed_entry_mm: 100.0,
        relay_speed_m_s: 200.0,
        relay_core_mm: 25.0,
        relay_pitch_mm: 48.0,
        first_relay_mm: Some(20.0),
        nozzles_per_group: 2,
        groups: 20,
        launch_deg: 80.0,
        ..Default::default()
    };
    Airjet::new(&t, 1.9, "insertion.airjet").unwrap()
}

/// The report: the flight to the far selvedge and the relay plan.
#[divan::bench]
fn flight_20_groups(b: divan::Bencher) {
    let a = twenty_groups();
    let speed = ShaftSpeed::from_rpm(800.0).unwrap();
    b.bench(|| divan::black_box(&a).report(speed).unwrap());
}

/// Building the field's stretches and the flight together.
#[divan::bench]
fn build_and_fly_20_groups(b: divan::Bencher) {
    let speed = ShaftSpeed::from_rpm(800.0).unwrap();
    b.bench(|| twenty_groups().report(speed).unwrap());
}
