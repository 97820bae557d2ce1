//! The speed-ripple solver against independent routes: the free shaft's exact solution, the
//! constant-torque closed form, a time-domain integration (DOP853 at 1e-13) run to steady state,
//! the energy balance over a repeat, and flywheel practice's I = ΔE/(δ·ω²).

use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_drive::{Induction, Motor, MotorCurve, Servo, Shaft, Table, flywheel_for, solve};
use std::f64::consts::PI;

/// J = J₀(1 + a·cos 2φ + b·sin 3φ), M = c + d·sin φ + e·cos 2φ over one turn.
struct Synthetic {
    j0: f64,
    a: f64,
    b: f64,
    c: f64,
    d: f64,
    e: f64,
}

impl Shaft for Synthetic {
    fn period_rad(&self) -> f64 {
        2.0 * PI
    }
    fn inertia(&self, p: f64) -> (f64, f64) {
        let j = self.j0 * (1.0 + self.a * (2.0 * p).cos() + self.b * (3.0 * p).sin());
        let dj = self.j0 * (-2.0 * self.a * (2.0 * p).sin() + 3.0 * self.b * (3.0 * p).cos());
        (j, dj)
    }
    fn load_torque(&self, p: f64) -> f64 {
        self.c + self.d * p.sin() + self.e * (2.0 * p).cos()
    }
}

fn loom_like() -> Synthetic {
    Synthetic { j0: 1.2, a: 0.3, b: 0.1, c: 20.0, d: 60.0, e: 25.0 }
}

fn induction() -> Motor {
    Motor::Induction(Induction::new(1500.0, 1450.0, 5.5, 2.5, MotorCurve::Kloss, 2.9).unwrap())
}

fn servo() -> Motor {
    Motor::Servo(Servo::new(500.0, 20.0, 0.05, 1000.0).unwrap())
}

/// The equation of motion in time: θ̇ = ω, J(θ)·ω̇ = M_motor − M_load(θ) − ½·J′(θ)·ω², and for
/// the servo ż = K_p/T_i·(ω_ref − ω) (the test keeps it off its limit).
struct TimeDomain<'a> {
    shaft: &'a Synthetic,
    motor: Motor,
}

impl ODE<f64, [f64; 3]> for TimeDomain<'_> {
    fn diff(&self, _t: f64, y: &[f64; 3], dy: &mut [f64; 3]) {
        let (th, w, z) = (y[0], y[1], y[2]);
        let (j, dj) = self.shaft.inertia(th);
        let (m, dz) = match self.motor {
            Motor::Constant { .. } => unreachable!(),
            Motor::Induction(i) => (i.torque(w).0, 0.0),
            Motor::Servo(s) => {
                let (m, limited) = s.torque(w, z);
                assert!(!limited);
                (m, s.gain_n_m_s / s.integral_s * (s.speed_rad_s - w))
            }
        };
        dy[0] = w;
        dy[1] = (m - self.shaft.load_torque(th) - 0.5 * dj * w * w) / j;
        dy[2] = dz;
    }
}

fn integrate(shaft: &Synthetic, motor: Motor, y0: [f64; 3], t1: f64) -> [f64; 3] {
    let eq = TimeDomain { shaft, motor };
    let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-13).max_steps(10_000_000);
    let sol = IVP::ode(&eq, 0.0, t1, y0).method(method).solve().unwrap();
    *sol.last().unwrap().1
}

#[test]
fn a_free_shaft_keeps_its_energy_exactly() {
    // No load, no motor torque: ½Jω² constant, ω = ω₀·√(J₀/J(φ)).
    let s = Synthetic { c: 0.0, d: 0.0, e: 0.0, ..loom_like() };
    let table = Table::new(&s, 0.1).unwrap();
    let w_target = 500.0 * PI / 30.0;
    let sol = solve(&table, &Motor::Constant { speed_rad_s: w_target }, 0.0).unwrap();
    let e0 = sol.energy_j()[0];
    let j0 = s.inertia(0.0).0;
    let w0 = (2.0 * e0 / j0).sqrt();
    let mut worst: f64 = 0.0;
    for (k, &p) in sol.angles_rad().iter().enumerate() {
        let exact = w0 * (j0 / s.inertia(p).0).sqrt();
        worst = worst.max((sol.omega()[k] - exact).abs() / exact);
    }
    for k in 0..1000 {
        let p = k as f64 * 0.00628318;
        let exact = w0 * (j0 / s.inertia(p).0).sqrt();
        worst = worst.max((sol.omega_at(p) - exact).abs() / exact);
    }
    assert!(worst <= 1e-14, "{worst:e}");
    // The extremes where J is least and largest, located between the grid points.
    let jmin = (0..200_000).map(|k| s.inertia(k as f64 * 2.0 * PI / 2e5).0).fold(f64::INFINITY, f64::min);
    let r = &sol.report;
    let wmax = w0 * (j0 / jmin).sqrt() * 30.0 / PI;
    assert!((r.max_speed_rpm - wmax).abs() <= 1e-12 * wmax, "{} vs {wmax}", r.max_speed_rpm);
    // The mean speed is the repeat over its time: ∫dφ/ω by 2000-panel Simpson independently.
    let n = 20_000;
    let h = 2.0 * PI / n as f64;
    let t: f64 = (0..n)
        .map(|k| {
            let f = |p: f64| 1.0 / (w0 * (j0 / s.inertia(p).0).sqrt());
            let a = k as f64 * h;
            h / 6.0 * (f(a) + 4.0 * f(a + h / 2.0) + f(a + h))
        })
        .sum();
    assert!((2.0 * PI / t - w_target).abs() <= 1e-12 * w_target);
    assert!((r.mean_speed_rpm - 500.0).abs() <= 1e-12 * 500.0, "{}", r.mean_speed_rpm);
}

#[test]
fn constant_torque_meets_its_closed_form() {
    // M = c̄ (the mean load): E(φ) = E₀ + d·(cos φ − 1) − (e/2)·sin 2φ exactly.
    let s = loom_like();
    let table = Table::new(&s, 0.1).unwrap();
    let sol = solve(&table, &Motor::Constant { speed_rad_s: 500.0 * PI / 30.0 }, 0.0).unwrap();
    let e0 = sol.energy_j()[0];
    let mut worst: f64 = 0.0;
    for (k, &p) in sol.angles_rad().iter().enumerate() {
        let exact = e0 + s.d * (p.cos() - 1.0) - 0.5 * s.e * (2.0 * p).sin();
        worst = worst.max((sol.energy_j()[k] - exact).abs() / exact);
    }
    // Simpson's rule on the 0.1° grid (the rule RK4 becomes when M does not depend on E).
    assert!(worst <= 1e-13, "{worst:e}");
    let r = &sol.report;
    assert!((r.mean_load_torque_n_m - s.c).abs() <= 1e-12 * s.c);
    assert!((r.peak_motor_torque_n_m - s.c).abs() <= 1e-12 * s.c);
    assert!((r.rms_motor_torque_n_m - s.c).abs() <= 1e-12 * s.c);
    // The swing of E: max − min of d·cos φ − (e/2)·sin 2φ by a dense scan refined.
    let g = |p: f64| s.d * p.cos() - 0.5 * s.e * (2.0 * p).sin();
    let max = loomkin_numeric::scan_max(0.0, 2.0 * PI, 100_000, g).value;
    let min = -loomkin_numeric::scan_max(0.0, 2.0 * PI, 100_000, |p| -g(p)).value;
    assert!((r.energy_swing_j - (max - min)).abs() <= 1e-9 * (max - min), "{} vs {}", r.energy_swing_j, max - min);
    assert!((r.motor_work_j - r.load_work_j).abs() <= 1e-12 * r.load_work_j);
}

#[test]
fn the_periodic_solution_is_where_time_integration_settles() {
    for motor in [induction(), servo()] {
        let s = loom_like();
        let table = Table::new(&s, 0.1).unwrap();
        let sol = solve(&table, &motor, 0.0).unwrap();
        let w0 = sol.omega()[0];
        let z0 = match motor {
            // The integrator's state: the torque at φ = 0 less the proportional part.
            Motor::Servo(sv) => sol.motor_torque()[0] - sv.gain_n_m_s * (sv.speed_rad_s - w0),
            _ => 0.0,
        };
        // Start 3 % fast with the integrator off by 5 N·m, run 60 repeats in time.
        let t = 60.0 * 2.0 * PI / w0;
        let y = integrate(&s, motor, [0.0, 1.03 * w0, z0 + 5.0], t);
        let w_sol = sol.omega_at(y[0]);
        let rel = (y[1] - w_sol).abs() / w_sol;
        // RK4 at 0.1° (h = 1.7e-3 rad) and its Hermite interpolant against DOP853 at 1e-13:
        // measured 9.1e-14 (induction) and 2.5e-14 (servo).
        assert!(rel <= 1e-12, "{}: {rel:e}", motor.name());
        eprintln!("{}: time domain vs periodic solution {rel:.2e}", motor.name());
        // Energy over a repeat closes: the motor gives what the load takes.
        let r = &sol.report;
        let closure = (r.motor_work_j - r.load_work_j).abs() / (r.load_work_j.abs() + r.energy_swing_j);
        assert!(closure <= 1e-9, "{}: {closure:e}", motor.name());
    }
}

#[test]
fn the_servo_holds_the_mean_speed_at_its_set_point() {
    let s = loom_like();
    let table = Table::new(&s, 0.1).unwrap();
    let r = solve(&table, &servo(), 0.0).unwrap().report;
    assert!((r.mean_speed_rpm - 500.0).abs() <= 1e-9 * 500.0, "{}", r.mean_speed_rpm);
    // A stiffer loop holds the speed tighter.
    let stiff = Motor::Servo(Servo::new(500.0, 200.0, 0.05, 1000.0).unwrap());
    let r2 = solve(&table, &stiff, 0.0).unwrap().report;
    assert!(r2.speed_ripple_pct < r.speed_ripple_pct, "{} vs {}", r2.speed_ripple_pct, r.speed_ripple_pct);
}

#[test]
fn a_flywheel_sized_for_a_ripple_holds_it_and_no_less_does() {
    let s = loom_like();
    let table = Table::new(&s, 0.1).unwrap();
    for motor in [Motor::Constant { speed_rad_s: 500.0 * PI / 30.0 }, induction()] {
        let bare = solve(&table, &motor, 0.0).unwrap().report.speed_ripple_pct;
        let target = bare / 5.0;
        let (jf, sol) = flywheel_for(&table, &motor, target).unwrap();
        assert!((sol.report.speed_ripple_pct - target).abs() <= 1e-9 * target, "{}", sol.report.speed_ripple_pct);
        let less = solve(&table, &motor, jf * (1.0 - 1e-6)).unwrap().report.speed_ripple_pct;
        assert!(less > target);
        // Flywheel practice: with a large flywheel on a shaft of constant inertia the ripple tends
        // to ΔE/(J·ω²) (a varying J adds its own ripple, ΔJ/(2J), which the formula leaves out).
        let big = 100.0;
        let flat = Synthetic { a: 0.0, b: 0.0, ..loom_like() };
        let flat_table = Table::new(&flat, 0.1).unwrap();
        let r = solve(&flat_table, &motor, big).unwrap().report;
        let w = r.mean_speed_rpm * PI / 30.0;
        let classic = r.energy_swing_j / ((big + s.j0) * w * w) * 100.0;
        assert!((r.speed_ripple_pct / classic - 1.0).abs() < 0.01, "{} vs {classic}", r.speed_ripple_pct);
    }
}

#[test]
fn a_motor_too_weak_is_refused_with_its_field() {
    let s = Synthetic { c: 2000.0, ..loom_like() };
    let table = Table::new(&s, 0.5).unwrap();
    let e = solve(&table, &induction(), 0.0).map(|_| ()).unwrap_err();
    assert!(e.to_string().starts_with("motor: "), "{e}");
    let none = Synthetic { j0: 0.0, ..loom_like() };
    let table = Table::new(&none, 0.5).unwrap();
    let e = solve(&table, &induction(), 0.0).map(|_| ()).unwrap_err();
    assert!(e.to_string().starts_with("rotating_inertia_kg_m2"), "{e}");
}

/// A shaft with joints: J and M_load piecewise (a load that acts over half a turn only, a J kinked
/// where it starts), the grid split at the joints.
struct Jointed;

impl Shaft for Jointed {
    fn period_rad(&self) -> f64 {
        2.0 * PI
    }
    fn inertia(&self, p: f64) -> (f64, f64) {
        let (j, dj) = loom_like().inertia(p);
        let on = p > 1.0 && p < 1.0 + PI;
        if on { (j + 0.2 * (p - 1.0).sin(), dj + 0.2 * (p - 1.0).cos()) } else { (j, dj) }
    }
    fn load_torque(&self, p: f64) -> f64 {
        let on = p > 1.0 && p < 1.0 + PI;
        loom_like().load_torque(p) + if on { 80.0 * (p - 1.0).sin() } else { 0.0 }
    }
    fn breaks_rad(&self) -> Vec<f64> {
        vec![1.0, 1.0 + PI]
    }
}

#[test]
fn the_presolve_moves_no_output_beyond_1e_12() {
    // The periodic start found on a 1° grid first, then on the grid itself, against Newton on the
    // grid from the first guess (the algorithm before it): every report number and every curve
    // within 1e-12 of its own size (an angle of an extreme within 1e-12 of a turn).
    let linear = Motor::Induction(Induction::new(1500.0, 1450.0, 5.5, 2.5, MotorCurve::Linear, 2.9).unwrap());
    let constant = Motor::Constant { speed_rad_s: 500.0 * PI / 30.0 };
    let smooth = loom_like();
    let shafts: [(&str, &dyn Shaft); 2] = [("smooth", &smooth), ("jointed", &Jointed)];
    let mut worst: f64 = 0.0;
    let mut moved: f64 = 0.0;
    for (name, shaft) in shafts {
        for step in [0.1, 0.07, 0.25] {
            let table = Table::new(shaft, step).unwrap();
            let reference = Table::new(shaft, step).unwrap().without_presolve();
            for motor in [constant, induction(), linear, servo()] {
                for flywheel in [0.0, 3.0] {
                    let new = solve(&table, &motor, flywheel).unwrap();
                    let old = solve(&reference, &motor, flywheel).unwrap();
                    let (a, b) = (&new.report, &old.report);
                    let what = format!("{name} {step}° {} +{flywheel} kg·m²", motor.name());
                    let mut close = |key: &str, x: f64, y: f64, size: f64| {
                        let d = (x - y).abs() / size;
                        worst = worst.max(d);
                        assert!(d <= 1e-12, "{what} {key}: {x} vs {y} ({d:e})");
                    };
                    for (key, x, y) in [
                        ("mean_speed_rpm", a.mean_speed_rpm, b.mean_speed_rpm),
                        ("min_speed_rpm", a.min_speed_rpm, b.min_speed_rpm),
                        ("max_speed_rpm", a.max_speed_rpm, b.max_speed_rpm),
                        ("speed_ripple_pct", a.speed_ripple_pct, b.speed_ripple_pct),
                        ("energy_swing_j", a.energy_swing_j, b.energy_swing_j),
                        ("peak_motor_torque_n_m", a.peak_motor_torque_n_m, b.peak_motor_torque_n_m),
                        ("rms_motor_torque_n_m", a.rms_motor_torque_n_m, b.rms_motor_torque_n_m),
                        ("mean_load_torque_n_m", a.mean_load_torque_n_m, b.mean_load_torque_n_m),
                        ("motor_work_j", a.motor_work_j, b.motor_work_j),
                        ("load_work_j", a.load_work_j, b.load_work_j),
                    ] {
                        close(key, x, y, y.abs());
                    }
                    // An extreme's angle is as ill-conditioned as a flat top makes it (a change δ of
                    // the values moves it by ~√δ): the new angle must be an extreme of the old
                    // solution to 1e-12, however far it moved (measured: ~1e-9 of a turn).
                    let old_at = |deg: f64| old.omega_at(deg.to_radians()) * 30.0 / PI;
                    close(
                        "speed at min_speed_angle_deg",
                        old_at(a.min_speed_angle_deg),
                        b.min_speed_rpm,
                        b.min_speed_rpm,
                    );
                    close(
                        "speed at max_speed_angle_deg",
                        old_at(a.max_speed_angle_deg),
                        b.max_speed_rpm,
                        b.max_speed_rpm,
                    );
                    moved = moved
                        .max((a.min_speed_angle_deg - b.min_speed_angle_deg).abs())
                        .max((a.max_speed_angle_deg - b.max_speed_angle_deg).abs());
                    assert_eq!(a.points, b.points);
                    for (k, ((x, y), t)) in new.omega().iter().zip(old.omega()).zip(old.time_s()).enumerate() {
                        close(&format!("omega[{k}]"), *x, y, y);
                        close(&format!("t[{k}]"), new.time_s()[k], *t, *old.time_s().last().unwrap());
                    }
                    let (mn, mo) = (new.motor_torque(), old.motor_torque());
                    let size = mo.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                    for (k, (x, y)) in mn.iter().zip(&mo).enumerate() {
                        close(&format!("motor_torque[{k}]"), *x, *y, size);
                    }
                }
            }
        }
    }
    eprintln!("presolve against Newton from the first guess: worst {worst:.2e}, extremes' angles moved {moved:.2e}°");
}
