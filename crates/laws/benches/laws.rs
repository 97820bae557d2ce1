//! Throughput of law evaluation and the cost of metrics.

use loomkin_laws::{Kinematics, LawSpec};

fn main() {
    divan::main();
}

const LAWS: &[&str] = &["cycloidal", "poly345", "modified-trapezoid", "modified-sine"];

/// Every catalogue law with its default parameters.
const CATALOGUE: &[&str] =
    &["constant-acceleration", "harmonic", "cycloidal", "poly345", "poly4567", "modified-trapezoid", "modified-sine"];

/// 10 000 evaluations on a uniform grid through the segment-walking sampler.
#[divan::bench(args = LAWS)]
fn sample_grid_10k(bencher: divan::Bencher, name: &str) {
    let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
    let mut out = vec![Kinematics::default(); 10_000];
    bencher.counter(divan::counter::ItemsCount::new(10_000usize)).bench_local(|| {
        law.sample_into(divan::black_box(&mut out));
    });
}

/// 10⁷ evaluations on a uniform grid into one large buffer (the issue-15 workload: memory traffic
/// counts here, 320 MB of output).
#[divan::bench(args = ["cycloidal", "poly345"], sample_count = 10)]
fn sample_grid_10m(bencher: divan::Bencher, name: &str) {
    let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
    let mut out = vec![Kinematics::default(); 10_000_000];
    bencher.counter(divan::counter::ItemsCount::new(10_000_000usize)).bench_local(|| {
        law.sample_into(divan::black_box(&mut out));
    });
}

/// Tables of 10⁵ to 3·10⁶ points (3.2 to 96 MB): where the output leaves the caches and
/// `sample_into` switches to non-temporal stores (at 4 MiB, 131 072 points).
#[divan::bench(args = [100_000, 300_000, 1_000_000, 3_000_000], sample_count = 30)]
fn sample_grid_sizes(bencher: divan::Bencher, n: usize) {
    let law = LawSpec::Cycloidal.build().unwrap();
    let mut out = vec![Kinematics::default(); n];
    bencher.counter(divan::counter::ItemsCount::new(n)).bench_local(|| {
        law.sample_into(divan::black_box(&mut out));
    });
}

/// 10 000 pointwise evaluations through `Law::eval`.
#[divan::bench(args = LAWS)]
fn eval_pointwise_10k(bencher: divan::Bencher, name: &str) {
    let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
    bencher.counter(divan::counter::ItemsCount::new(10_000usize)).bench_local(|| {
        let mut acc = 0.0;
        for i in 0..10_000 {
            let k = law.eval(divan::black_box(i as f64 * 1e-4));
            acc += k.s + k.v + k.a + k.j;
        }
        acc
    });
}

/// Exact metrics of one law.
#[divan::bench(args = CATALOGUE)]
fn metrics(bencher: divan::Bencher, name: &str) {
    let law = LawSpec::parse::<&str, &str>(name, &[]).unwrap().build().unwrap();
    bencher.bench_local(|| divan::black_box(&law).metrics());
}

/// What `law sample --json` and `cycle --json` spend per row (the figures behind their budget
/// estimates): 10⁵ rows serialised as pretty JSON, or formatted as CSV, into a sink.
const ROWS: usize = 100_000;

#[divan::bench(sample_count = 10)]
fn law_sample_json_rows(bencher: divan::Bencher) {
    let law = LawSpec::parse::<&str, &str>("cycloidal", &[]).unwrap().build().unwrap();
    bencher.counter(divan::counter::ItemsCount::new(ROWS)).bench_local(|| {
        let rows: Vec<[f64; 5]> = law.samples(ROWS).map(|(x, k)| [k.a, k.j, k.s, k.v, x]).collect();
        serde_json::to_writer_pretty(std::io::sink(), &rows).unwrap();
    });
}

#[divan::bench(sample_count = 10)]
fn law_sample_csv_rows(bencher: divan::Bencher) {
    use std::io::Write;
    let law = LawSpec::parse::<&str, &str>("cycloidal", &[]).unwrap().build().unwrap();
    bencher.counter(divan::counter::ItemsCount::new(ROWS)).bench_local(|| {
        let mut out = std::io::BufWriter::new(std::io::sink());
        for (x, k) in law.samples(ROWS) {
            writeln!(out, "{x},{},{},{},{}", k.s, k.v, k.a, k.j).unwrap();
        }
    });
}

#[divan::bench(sample_count = 10)]
fn cycle_json_rows(bencher: divan::Bencher) {
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml")).unwrap();
    let cycle = loomkin_laws::Cycle::from_toml(&text).unwrap();
    let speed = loomkin_units::ShaftSpeed::from_rpm(300.0).unwrap();
    bencher.counter(divan::counter::ItemsCount::new(ROWS)).bench_local(|| {
        serde_json::to_writer_pretty(std::io::sink(), &cycle.report_streamed(speed, ROWS, || {})).unwrap();
    });
}

#[divan::bench(sample_count = 10)]
fn cycle_csv_rows(bencher: divan::Bencher) {
    use std::io::Write;
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/heald-frame-cycle.toml")).unwrap();
    let cycle = loomkin_laws::Cycle::from_toml(&text).unwrap();
    bencher.counter(divan::counter::ItemsCount::new(ROWS)).bench_local(|| {
        let mut out = std::io::BufWriter::new(std::io::sink());
        for p in cycle.samples(ROWS, 300.0) {
            writeln!(out, "{},{},{},{},{},{}", p.angle_deg, p.time_s, p.kin.s, p.kin.v, p.kin.a, p.kin.j).unwrap();
        }
    });
}
