//! Cost of one scenario by each route and of a 1000-point parallel sweep.

use loomkin_picking::{Mechanism, Method, Setting, Settings, simulate, sweep};

fn main() {
    divan::main();
}

const METHODS: &[Method] = &[Method::Closed, Method::Ode];

/// One scenario (15.5 mm strap play, the paper's Fig. 3) by each route.
#[divan::bench(args = METHODS)]
fn scenario_play(bencher: divan::Bencher, method: Method) {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m).with_play_mm(15.5);
    bencher.bench_local(|| simulate(&m, divan::black_box(&st), method).map(|o| o.velocity_m_s));
}

/// The designed scenario by each route.
#[divan::bench(args = METHODS)]
fn scenario_design(bencher: divan::Bencher, method: Method) {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m);
    bencher.bench_local(|| simulate(&m, divan::black_box(&st), method).map(|o| o.velocity_m_s));
}

/// A 1000-point sweep of the loom speed, 160–240 rev/min (Fig. 5), in parallel.
#[divan::bench(args = METHODS, sample_count = 10, sample_size = 1)]
fn sweep_speed_1000(bencher: divan::Bencher, method: Method) {
    let m = Mechanism::paper_default();
    let st = Settings::designed(&m);
    bencher.counter(divan::counter::ItemsCount::new(1000usize)).bench_local(|| {
        sweep(&m, &st, Setting::Speed, 160.0, 240.0, divan::black_box(1000), method).map(|s| s.rows.len())
    });
}

/// 10 000 draws of `examples/pick-montecarlo.toml` (closed form, ODE only where it does not apply)
/// on one thread, with the report: ×100 is the time of 10⁶ draws on one core (goal < 10 s).
#[divan::bench(sample_count = 5, sample_size = 1)]
fn montecarlo_10k_one_thread(bencher: divan::Bencher) {
    let m = Mechanism::paper_default();
    let mut mc =
        loomkin_picking::MonteCarlo::from_toml(include_str!("../../../examples/pick-montecarlo.toml")).unwrap();
    mc.draws = 10_000;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
    bencher.counter(divan::counter::ItemsCount::new(10_000usize)).bench_local(|| {
        pool.install(|| {
            let draws = mc.run(&m, 0..divan::black_box(10_000), loomkin_study::Progress::Hidden);
            mc.report(&draws).failing
        })
    });
}
