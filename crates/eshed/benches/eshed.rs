//! Benches of electronic shedding: 24 frames over a 10⁴-pick repeat (issue 31: < 50 ms).
//!
//! `cargo bench -p loomkin-eshed --bench eshed`. Two lift plans: a 12/12 twill on 24 shafts tiled to
//! 10⁴ picks (24 distinct picks: the bus windows are reused), and a pseudo-random plan (every pick's
//! window distinct: the bus's worst case).

#[path = "../tests/common/mod.rs"]
mod common;

use loomkin_eshed::{Bus, FrameInput, FrameLoad, FramePlan, FrameSetup, MoveLaws, analyse};
use loomkin_laws::LawSpec;

fn main() {
    divan::main();
}

const FRAMES: usize = 24;
const PICKS: usize = 10_000;

fn setups(plan: &[Vec<bool>]) -> Vec<FrameSetup> {
    let servo = common::servo();
    plan.iter()
        .enumerate()
        .map(|(i, up)| {
            let stroke = 0.09 * (1.0 + 0.06 * i as f64);
            let p = FramePlan::new(
                &FrameInput { up, stroke_m: stroke, centre_deg: -10.0, motion_deg: 280.0, fall_motion_deg: 280.0 },
                false,
            )
            .unwrap();
            let load = FrameLoad {
                mass_kg: 5.5,
                spring_n_m: 0.0,
                preload_n: 0.0,
                stroke_m: stroke,
                start_level_m: p.start_level_m(),
            };
            FrameSetup { plan: p, laws: laws(), load, servo: servo.clone() }
        })
        .collect()
}

fn laws() -> MoveLaws {
    let spec = LawSpec::ModifiedSine;
    let law = spec.build().unwrap();
    MoveLaws::new((spec.clone(), law.clone()), (spec, law))
}

fn twill() -> Vec<Vec<bool>> {
    (0..FRAMES).map(|i| (0..PICKS).map(|p| (p + i) % FRAMES < FRAMES / 2).collect()).collect()
}

fn random() -> Vec<Vec<bool>> {
    let mut x = 12345u64;
    (0..FRAMES)
        .map(|_| {
            (0..PICKS)
                .map(|_| {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    (x >> 33) % 2 == 1
                })
                .collect()
        })
        .collect()
}

#[divan::bench(sample_count = 5)]
fn twill_24_frames_10k_picks(b: divan::Bencher) {
    let s = setups(&twill());
    b.bench(|| analyse(&s, &Bus::default(), 500.0, false).unwrap());
}

#[divan::bench(sample_count = 3)]
fn random_24_frames_10k_picks(b: divan::Bencher) {
    let s = setups(&random());
    b.bench(|| analyse(&s, &Bus::default(), 500.0, false).unwrap());
}
