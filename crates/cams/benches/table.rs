//! Cam tables of the heald-frame example cycle: placement, export with the exact error.

use loomkin_cams::table::{CamTable, Format, Motion, Spacing};
use loomkin_laws::Cycle;

fn main() {
    divan::main();
}

fn motion() -> Motion {
    Motion::from_cycle(&Cycle::from_toml(include_str!("../../../examples/heald-frame-cycle.toml")).unwrap())
}

/// A 1° table (≈ 365 points) written as XYVAJ with its exact re-interpolation error.
#[divan::bench]
fn step_1deg_xyvaj(b: divan::Bencher) {
    let m = motion();
    b.bench(|| CamTable::new(m.clone(), Spacing::StepDeg(1.0)).unwrap().export(Format::Xyvaj).unwrap());
}

/// Greedy placement for a 1 µm tolerance, written as XYVAJ.
#[divan::bench]
fn tolerance_1um_xyvaj(b: divan::Bencher) {
    let m = motion();
    b.bench(|| CamTable::new(m.clone(), Spacing::Tolerance(0.001)).unwrap().export(Format::Xyvaj).unwrap());
}
