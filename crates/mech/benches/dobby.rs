//! A full input revolution of the modulator at 0.1° steps (3601 positions): analysis of the paper's
//! ellipse, analysis of a spline cam, synthesis of the default law; plus the vector-loop primitives.

use loomkin_mech::{
    AnalysisOptions, Cam, ModulatorGeometry, NewtonOptions, OutputLawSpec, SynthesisOptions, Vec2, analyze,
    analyze_into, cam_loop, synthesize, synthesize_into,
};
use nalgebra::SVector;

fn main() {
    divan::main();
}

/// Task 1 with the paper's ellipse, 3601 positions with rates and all checks.
#[divan::bench]
fn analyze_ellipse_0_1deg(bencher: divan::Bencher) {
    let (g, cam) = (ModulatorGeometry::PAPER, Cam::paper());
    let o = AnalysisOptions { step_deg: 0.1, ..AnalysisOptions::default() };
    bencher.counter(divan::counter::ItemsCount::new(3601usize)).bench_local(|| analyze(&g, &cam, &o).unwrap());
}

/// As `analyze_ellipse_0_1deg`, into the previous result (`analyze_into`, tables' memory reused),
/// as a loop of analyses (sweep, tolerance study) runs it.
#[divan::bench]
fn analyze_ellipse_0_1deg_into(bencher: divan::Bencher) {
    let (g, cam) = (ModulatorGeometry::PAPER, Cam::paper());
    let o = AnalysisOptions { step_deg: 0.1, ..AnalysisOptions::default() };
    let mut out = analyze(&g, &cam, &o).unwrap();
    bencher
        .counter(divan::counter::ItemsCount::new(3601usize))
        .bench_local(|| analyze_into(&g, &cam, &o, &mut out).unwrap());
}

/// Task 1 with a synthesised cam given as 720 points (periodic spline).
#[divan::bench]
fn analyze_spline_cam_0_1deg(bencher: divan::Bencher) {
    let g = ModulatorGeometry::PAPER;
    let s =
        synthesize(&g, &OutputLawSpec::default(), &SynthesisOptions { step_deg: 0.5, ..Default::default() }).unwrap();
    let pts: Vec<Vec2> = s.cam.centre.iter().map(|p| Vec2::new(p[0], p[1])).collect();
    let cam = Cam::from_points(&pts).unwrap();
    let o = AnalysisOptions { step_deg: 0.1, ..AnalysisOptions::default() };
    bencher.counter(divan::counter::ItemsCount::new(3601usize)).bench_local(|| analyze(&g, &cam, &o).unwrap());
}

/// Task 2 with the default law: 3601 closed-form positions, walls and all checks.
#[divan::bench]
fn synthesize_default_0_1deg(bencher: divan::Bencher) {
    let (g, law) = (ModulatorGeometry::PAPER, OutputLawSpec::default());
    let o = SynthesisOptions { step_deg: 0.1, ..SynthesisOptions::default() };
    bencher.counter(divan::counter::ItemsCount::new(3601usize)).bench_local(|| synthesize(&g, &law, &o).unwrap());
}

/// As `synthesize_default_0_1deg`, into the previous result (`synthesize_into`, tables' memory
/// reused).
#[divan::bench]
fn synthesize_default_0_1deg_into(bencher: divan::Bencher) {
    let (g, law) = (ModulatorGeometry::PAPER, OutputLawSpec::default());
    let o = SynthesisOptions { step_deg: 0.1, ..SynthesisOptions::default() };
    let mut out = synthesize(&g, &law, &o).unwrap();
    bencher
        .counter(divan::counter::ItemsCount::new(3601usize))
        .bench_local(|| synthesize_into(&g, &law, &o, &mut out).unwrap());
}

/// The bare continuation of loop (2) over 3601 inputs (Newton + rates per step).
#[divan::bench]
fn trace_cam_loop_0_1deg(bencher: divan::Bencher) {
    let (g, cam) = (ModulatorGeometry::PAPER, Cam::paper());
    let sys = cam_loop(&g, &cam).unwrap();
    let q0 = loomkin_mech::assemble(&g, &cam, 0.0).unwrap();
    let xs: Vec<f64> = (0..=3600).map(|i| (i as f64 * 0.1).to_radians()).collect();
    bencher
        .counter(divan::counter::ItemsCount::new(3601usize))
        .bench_local(|| sys.trace(&xs, SVector::<f64, 2>::new(q0[0], q0[1]), &NewtonOptions::default()).unwrap());
}

/// One draw of the tolerance study (examples/dobby-tolerance.toml) at its analysis step of 2° and at
/// 0.1°: the figures behind the study's cost estimate (`Tolerance::cost`).
#[divan::bench(args = [2.0, 0.1])]
fn tolerance_draw(bencher: divan::Bencher, step_deg: f64) {
    let text = include_str!("../../../examples/dobby-tolerance.toml")
        .replace("step_deg = 2 ", &format!("step_deg = {step_deg} "));
    let t = loomkin_mech::Tolerance::from_toml(&text).unwrap();
    let mut i = 0u64;
    bencher.bench_local(|| {
        i = (i + 1) % t.draws;
        t.draw(i)
    });
}
