//! Costs of the servo workbench operations: one drag update, exact summaries, the optimiser.

use loomkin_laws::Kinematics;
use loomkin_servo::{
    Drive, ExportFormat, Objective, OptimizeOptions, SplineEnd, SplineLaw, default_points, export, optimize, summary,
    torque_curve,
};

fn main() {
    divan::main();
}

/// One drag update of the workbench: rebuild the law from the points, 1000 samples of the law,
/// the torque curve (1000 points) and the exact summary at 600 and 750 1/min.
#[divan::bench]
fn drag_update(bencher: divan::Bencher) {
    let pts = default_points();
    let drive = Drive::needle_rack_default();
    let mut out = vec![Kinematics::default(); 1000];
    bencher.bench_local(|| {
        let law = SplineLaw::new(divan::black_box(&pts), SplineEnd::Natural).unwrap();
        law.law().sample_into(&mut out);
        let mut acc = out[500].s;
        for n in [600.0, 750.0] {
            let c = torque_curve(law.law(), &drive, n, 1000).unwrap();
            let s = summary(law.law(), &drive, n).unwrap();
            acc += c[10].torque_nm + s.peak_torque_nm;
        }
        acc
    });
}

/// Building the spline law alone (spline solve, mirror, closed-form integration).
#[divan::bench]
fn build_law(bencher: divan::Bencher) {
    let pts = default_points();
    bencher.bench_local(|| SplineLaw::new(divan::black_box(&pts), SplineEnd::Natural).unwrap());
}

/// The exact summary (peaks, RMS, power) at one speed.
#[divan::bench]
fn summary_one_speed(bencher: divan::Bencher) {
    let law = SplineLaw::default_law();
    let drive = Drive::needle_rack_default();
    bencher.bench_local(|| summary(law.law(), &drive, divan::black_box(600.0)).unwrap());
}

/// The full optimisation of the default points for the default drive (peak torque).
#[divan::bench(args = [1, 2], sample_count = 10)]
fn optimize_peak(bencher: divan::Bencher, speeds: usize) {
    let start = SplineLaw::default_law();
    let drive = Drive::needle_rack_default();
    let speeds_rpm = [600.0, 750.0][..speeds].to_vec();
    let opts = OptimizeOptions { speeds_rpm, objective: Objective::Peak, ..OptimizeOptions::default() };
    bencher.bench_local(|| optimize(&start, &drive, &opts).unwrap().objective_after_nm);
}

/// A 1° cam table (`servo export --format csv`) and its re-interpolation errors in the three modes.
#[divan::bench]
fn cam_table_1deg(bencher: divan::Bencher) {
    let law = SplineLaw::default_law();
    let drive = Drive::needle_rack_default();
    bencher.bench_local(|| export(&law, &drive, ExportFormat::Csv, 1.0).unwrap().table.unwrap().points);
}

/// One objective evaluation of the optimiser (the figure behind `EVAL_S_PER_POINT_SPEED`): a start
/// capped at 200 evaluations, for 7 and 33 definition points at 1 and 6 speeds, both objectives.
/// Time per evaluation = the time shown / the evaluations counted (printed once).
#[divan::bench(args = [(7, 1), (7, 6), (33, 1), (33, 6)], sample_count = 5)]
fn optimize_eval(bencher: divan::Bencher, (points, speeds): (usize, usize)) {
    let def: Vec<[f64; 2]> = (0..points)
        .map(|i| {
            let x = 0.5 * i as f64 / (points - 1) as f64;
            [x, if i == 0 || i + 1 == points { 0.0 } else { (std::f64::consts::TAU * x).sin() }]
        })
        .collect();
    let start = SplineLaw::new(&def, SplineEnd::Natural).unwrap();
    let drive = Drive::needle_rack_default();
    let speeds_rpm: Vec<f64> = (0..speeds).map(|i| 500.0 + 50.0 * i as f64).collect();
    for objective in [Objective::Peak, Objective::Rms] {
        let opts = OptimizeOptions {
            speeds_rpm: speeds_rpm.clone(),
            objective,
            starts: 1,
            max_evals_per_start: 200,
            ..OptimizeOptions::default()
        };
        optimize(&start, &drive, &opts).unwrap();
        eprintln!(
            "optimize_eval {points} points, {speeds} speeds, {objective:?}: {} evaluations",
            opts.evaluated.get()
        );
    }
    let opts = OptimizeOptions {
        speeds_rpm,
        objective: Objective::Rms,
        starts: 1,
        max_evals_per_start: 200,
        ..OptimizeOptions::default()
    };
    bencher.bench_local(|| optimize(&start, &drive, &opts).unwrap().objective_after_nm);
}
