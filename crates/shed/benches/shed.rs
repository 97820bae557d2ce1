//! Throughput of the criteria: generic path (law core) against the fast closed-form path, and a
//! whole grid of about a million laws in parallel.

use loomkin_shed::{Progress, Template, evaluate_rows, grid_design};

fn main() {
    divan::main();
}

const LENGTHS: [f64; 4] = [0.1, 0.2, 0.45, 0.25];

#[divan::bench]
fn criteria_generic_one_law(bencher: divan::Bencher) {
    let t = Template::lead_trapezoid();
    bencher.bench_local(|| t.evaluate_generic(divan::black_box(&LENGTHS), 0.95).unwrap());
}

#[divan::bench]
fn criteria_fast_one_law(bencher: divan::Bencher) {
    let t = Template::lead_trapezoid();
    bencher.bench_local(|| t.evaluate_fast(divan::black_box(&LENGTHS), 0.95).unwrap());
}

/// The 4-part cube k1, k2, k3 ∈ {0.005, 0.010, …, 0.95}, k4 = 1 − Σ within [0.005, 0.95]: 1 293 363 laws.
#[divan::bench(sample_count = 3)]
fn grid_4_parts_step_0_005_all_criteria(bencher: divan::Bencher) {
    let t = Template::lead_trapezoid();
    let d = grid_design(4, 0.005, 0.95, 0.005).unwrap();
    bencher
        .counter(divan::counter::ItemsCount::new(d.len()))
        .bench_local(|| evaluate_rows(&t, &d, 0.95, Progress::Hidden).unwrap().len());
}

/// Output rows of a streamed table, the library's part (criteria scaled, CSV line): the 3-part grid at
/// step 0.05 (153 laws) at 100 motion angles, each row's criteria scaled and formatted as CSV.
#[divan::bench(sample_count = 10)]
fn table_rows_csv(bencher: divan::Bencher) {
    use loomkin_shed::{Conditions, DesignKind, GridSpec, Study};
    let study = Study::new(DesignKind::Grid, None, GridSpec::TABLE).unwrap();
    let cond = Conditions::new(0.95, 0.1, 300.0).unwrap();
    let motions: Vec<f64> = (0..100).map(|i| 200.0 + i as f64).collect();
    let rows = study.design.len() * motions.len();
    bencher.counter(divan::counter::ItemsCount::new(rows)).bench_local(|| {
        let mut out = String::new();
        for r in study.rows_in(&motions, &cond, Progress::Hidden, 0..study.design.len()).unwrap() {
            loomkin_shed::csv_line(&r, false, &mut out);
            out.clear();
        }
    });
}
