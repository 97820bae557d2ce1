//! A cam profile with all its extremes (pressure angle, curvature of every track, undercut,
//! largest roller) for the 4-segment heald-frame cycle: `cargo bench -p loomkin-cams --bench profile`.

use loomkin_cams::profile::{CamDesign, CamProfile, Closure, Follower, Size};
use loomkin_cams::table::Motion;
use loomkin_laws::Cycle;

fn main() {
    divan::main();
}

fn heald() -> Motion {
    Motion::from_cycle(&Cycle::from_toml(include_str!("../../../examples/heald-frame-cycle.toml")).unwrap())
}

fn design(closure: Closure, size: Size) -> CamDesign {
    CamDesign { follower: Follower::Translating { offset_mm: 5.0 }, closure, roller_radius_mm: 10.0, size }
}

/// Given prime radius: pitch curve, profile, pressure angle, curvature and their extremes.
#[divan::bench]
fn profile_given_prime_radius(b: divan::Bencher) {
    let m = heald();
    b.bench(|| CamProfile::new(divan::black_box(&m), &design(Closure::Single, Size::PrimeRadiusMm(80.0))).unwrap());
}

/// The same with the least prime circle for 30° sized first.
#[divan::bench]
fn profile_sized_for_30_deg(b: divan::Bencher) {
    let m = heald();
    b.bench(|| CamProfile::new(divan::black_box(&m), &design(Closure::Single, Size::MaxPressureDeg(30.0))).unwrap());
}

/// Conjugate pair (two tracks), sized for 30°.
#[divan::bench]
fn conjugate_sized_for_30_deg(b: divan::Bencher) {
    let m = heald();
    b.bench(|| CamProfile::new(divan::black_box(&m), &design(Closure::Conjugate, Size::MaxPressureDeg(30.0))).unwrap());
}
