//! Benchmarks of the speed-ripple solver: the periodic solution on 3,600 angles (one turn at
//! 0.1°) for each motor model (target < 1 ms).

use loomkin_drive::{Induction, Motor, MotorCurve, Servo, Shaft, Table, solve};
use std::f64::consts::PI;

fn main() {
    divan::main();
}

/// A loom-like shaft: J = 1.2·(1 + 0.3 cos 2φ + 0.1 sin 3φ) kg·m², M = 20 + 60 sin φ + 25 cos 2φ N·m.
struct Synthetic;

impl Shaft for Synthetic {
    fn period_rad(&self) -> f64 {
        2.0 * PI
    }
    fn inertia(&self, p: f64) -> (f64, f64) {
        (
            1.2 * (1.0 + 0.3 * (2.0 * p).cos() + 0.1 * (3.0 * p).sin()),
            1.2 * (-0.6 * (2.0 * p).sin() + 0.3 * (3.0 * p).cos()),
        )
    }
    fn load_torque(&self, p: f64) -> f64 {
        20.0 + 60.0 * p.sin() + 25.0 * (2.0 * p).cos()
    }
}

fn motor(name: &str) -> Motor {
    match name {
        "constant" => Motor::Constant { speed_rad_s: 500.0 * PI / 30.0 },
        "induction" => Motor::Induction(Induction::new(1500.0, 1450.0, 5.5, 2.5, MotorCurve::Kloss, 2.9).unwrap()),
        _ => Motor::Servo(Servo::new(500.0, 20.0, 0.05, 1000.0).unwrap()),
    }
}

/// The periodic solution with its report (extremes located, RMS), the table built once.
#[divan::bench(args = ["constant", "induction", "servo"])]
fn periodic_solution_3600_angles(bencher: divan::Bencher, which: &str) {
    let table = Table::new(&Synthetic, 0.1).unwrap();
    let motor = motor(which);
    bencher.bench_local(|| solve(&table, &motor, divan::black_box(0.0)).unwrap().report.speed_ripple_pct);
}
