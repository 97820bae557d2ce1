//! The crank-and-lever transmission against independent routes: its derivatives against finite
//! differences, its closed-form loop against a Newton solve of the loop equations and against the
//! four-bar of loomkin-drive (hand-derived rates), its closed-form inverse against the root finder,
//! the chain rule, the energy over a move, and the linear drive it approaches on a small stroke.

use loomkin_cams::profile::Jet;
use loomkin_laws::{Cycle, StrokeUnit};
use loomkin_servo::{Axis, CrankBranch, CrankLever, Limits, Load, Motor, check_axis, operating_points};
use std::f64::consts::PI;

const STROKE_MM: f64 = 100.0;

fn geometry() -> CrankLever {
    CrankLever {
        crank_radius_mm: 40.0,
        rod_length_mm: 200.0,
        lever_input_arm_mm: 100.0,
        lever_output_arm_mm: 200.0,
        lever_angle_deg: 0.0,
        rocking_shaft_x_mm: -100.0,
        rocking_shaft_y_mm: 200.0,
        frame_link_mm: Some(400.0),
        lever_inertia_kg_m2: 0.02,
        crank_branch: CrankBranch::Ccw,
        gear_ratio: 1.0,
        mid_stroke_mm: STROKE_MM / 2.0,
    }
}

fn motor() -> Motor {
    Motor {
        rated_torque_nm: 12.0,
        peak_torque_nm: 36.0,
        rated_speed_rpm: 3000.0,
        max_speed_rpm: 4500.0,
        rotor_inertia_kg_m2: 1.1e-3,
        torque_at_max_speed_nm: None,
    }
}

fn axis(cl: CrankLever, efficiency: f64, friction_n: f64, viscous: f64) -> Axis {
    Axis {
        motor: motor(),
        load: Load {
            moving_mass_kg: Some(6.0),
            load_inertia_kg_m2: None,
            travel_mm_per_rev: None,
            gear_ratio: None,
            efficiency,
            friction_n,
            viscous_n_s_m: viscous,
            spring_n_m: 800.0,
            constant_force_n: 90.0,
            extra_inertia_kg_m2: 2e-4,
            crank_lever: Some(cl),
        },
        limits: Limits::default(),
    }
}

fn cycle(stroke_mm: f64, law: &str) -> Cycle {
    Cycle::from_toml(&format!(
        "unit = \"mm\"\nstroke = {stroke_mm}\n\
         [[segment]]\nkind = \"rise\"\nlength_deg = 140\nlaw = \"{law}\"\n\
         [[segment]]\nkind = \"dwell\"\nlength_deg = 40\n\
         [[segment]]\nkind = \"return\"\nlength_deg = 140\nlaw = \"{law}\"\n\
         [[segment]]\nkind = \"dwell\"\nlength_deg = 40\n"
    ))
    .unwrap()
}

/// Motor angles over the stroke (every 1/40 of it, ends included).
fn angles(cl: &CrankLever) -> Vec<f64> {
    let l = cl.linkage().unwrap();
    (0..=40).map(|k| l.motor_angle((k as f64 / 40.0 - 0.5) * STROKE_MM * 1e-3).unwrap()).collect()
}

#[test]
fn derivatives_match_finite_differences() {
    for link in [None, Some(400.0), Some(150.0)] {
        let cl = CrankLever { frame_link_mm: link, ..geometry() };
        let l = cl.linkage().unwrap();
        let y = |a: f64| l.height(Jet::cst(a)).0.v();
        for a in angles(&cl) {
            let (j, _) = l.height(Jet::var(a));
            let h = 1e-4;
            let d1 = (y(a + h) - y(a - h)) / (2.0 * h);
            let d2 = (y(a + h) - 2.0 * y(a) + y(a - h)) / (h * h);
            let h3 = 2e-3;
            let d3 = (y(a + 2.0 * h3) - 2.0 * y(a + h3) + 2.0 * y(a - h3) - y(a - 2.0 * h3)) / (2.0 * h3 * h3 * h3);
            let scale = j.d(1).abs().max(1e-3);
            assert!((j.d(1) - d1).abs() < 1e-8 * scale, "{link:?} {a}: {} vs {d1}", j.d(1));
            assert!((j.d(2) - d2).abs() < 1e-5 * scale, "{link:?} {a}: {} vs {d2}", j.d(2));
            assert!((j.d(3) - d3).abs() < 1e-3 * scale, "{link:?} {a}: {} vs {d3}", j.d(3));
            // The higher orders against differences of the analytic lower ones.
            let g = |a: f64| l.height(Jet::var(a)).0;
            let d4 = (g(a + h).d(3) - g(a - h).d(3)) / (2.0 * h);
            let d5 = (g(a + h).d(4) - g(a - h).d(4)) / (2.0 * h);
            assert!((j.d(4) - d4).abs() < 1e-6 * j.d(4).abs().max(scale), "{a}: {} vs {d4}", j.d(4));
            assert!((j.d(5) - d5).abs() < 1e-6 * j.d(5).abs().max(scale), "{a}: {} vs {d5}", j.d(5));
        }
    }
}

/// The closed-form loop against Newton's method on the loop equations `A + b·e(β) = Q + c·e(θ)` and
/// `|G − P| = L`, and the lever's rates against loomkin-drive's crank-rocker (hand-derived).
#[test]
fn the_closed_form_loop_solves_the_loop_equations() {
    let cl = geometry();
    let l = cl.linkage().unwrap();
    let (r, b, c, e, q) = (l.r, l.b, l.c, l.e, l.q);
    let link = l.link.unwrap();
    let mut guess = {
        let (_, phi) = l.height(Jet::cst(angles(&cl)[0]));
        let theta = phi.v() + l.delta + 0.01;
        (theta, 1.5_f64)
    };
    for a in angles(&cl) {
        // Newton on F(θ, β) = A + b e(β) − Q − c e(θ) = 0 from the previous solution.
        let (mut th, mut be) = guess;
        for _ in 0..50 {
            let f0 = r * a.cos() + b * be.cos() - q[0] - c * th.cos();
            let f1 = r * a.sin() + b * be.sin() - q[1] - c * th.sin();
            // Jacobian [[c sinθ, −b sinβ], [−c cosθ, b cosβ]].
            let (j00, j01, j10, j11) = (c * th.sin(), -b * be.sin(), -c * th.cos(), b * be.cos());
            let det = j00 * j11 - j01 * j10;
            th -= (f0 * j11 - j01 * f1) / det;
            be -= (j00 * f1 - j10 * f0) / det;
        }
        guess = (th, be);
        let (y, phi) = l.height(Jet::var(a));
        let d = (phi.v() + l.delta - th + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
            - std::f64::consts::PI;
        assert!(d.abs() < 1e-12, "α = {a}: θ {} vs Newton {th}", phi.v() + l.delta);
        // The frame link: the frame's pin G on the vertical through the tip at mid-stroke, L from P.
        let p = [q[0] + e * phi.v().cos(), q[1] + e * phi.v().sin()];
        let g = [q[0] + e, q[1] + link + y.v()];
        assert!(((g[0] - p[0]).hypot(g[1] - p[1]) - link).abs() < 1e-12, "α = {a}");
        // The lever's rates: the crank-rocker of loomkin-drive, its own formulas.
        let fb = loomkin_drive::fourbar::CrankRocker { r, b, c, qx: q[0], qy: q[1], kappa: l.kappa };
        let s = fb.at_crank(a);
        assert!((s.rocker_d1 - phi.d(1)).abs() < 1e-10 * s.rocker_d1.abs().max(1.0), "{} {}", s.rocker_d1, phi.d(1));
        assert!((s.rocker_d2 - phi.d(2)).abs() < 1e-9 * s.rocker_d2.abs().max(1.0));
        assert!((s.rocker_d3 - phi.d(3)).abs() < 1e-9 * s.rocker_d3.abs().max(1.0));
    }
}

/// The closed-form inverse against the root finder on `y(α) − y` over the working branch, and
/// forward(inverse(y)) = y.
#[test]
fn the_inverse_is_the_root_of_the_forward_map() {
    for branch in [CrankBranch::Ccw, CrankBranch::Cw] {
        for link in [None, Some(400.0)] {
            let cl = CrankLever { crank_branch: branch, frame_link_mm: link, ..geometry() };
            let l = cl.linkage().unwrap();
            let h = 0.5 * STROKE_MM * 1e-3;
            let (a_lo, a_hi) = (l.motor_angle(-h * 1.05).unwrap(), l.motor_angle(h * 1.05).unwrap());
            let (lo, hi) = (a_lo.min(a_hi), a_lo.max(a_hi));
            for k in 0..=50 {
                let y = (k as f64 / 50.0 * 2.0 - 1.0) * h;
                let a = l.motor_angle(y).unwrap();
                let f = |x: f64| l.height(Jet::var(x)).0;
                let lo_negative = f(lo).v() < y;
                let root = loomkin_numeric::refine_root(lo, hi, lo_negative, |x| {
                    let j = f(x);
                    (j.v() - y, j.d(1))
                });
                assert!((a - root).abs() < 1e-12, "{branch:?} {link:?} y = {y}: {a} vs {root}");
                assert!((f(a).v() - y).abs() < 1e-12 * h, "{branch:?} y = {y}: {}", f(a).v());
            }
        }
    }
}

/// The motor's rates from the reverted series against the chain rule written out:
/// `α̇ = ẏ/y'`, `α̈ = (ÿ − y''α̇²)/y'`, `α⃛ = (y⃛ − 3y''α̇α̈ − y'''α̇³)/y'`.
#[test]
fn motor_rates_follow_the_chain_rule() {
    let cl = geometry();
    let l = cl.linkage().unwrap();
    for (k, &(s, v, a, j)) in
        [(0.01, 1.3, -40.0, 900.0), (0.05, -2.0, 15.0, -3e3), (0.093, 0.4, 120.0, 2e4)].iter().enumerate()
    {
        let m = l.motor(Jet::from_derivs([s, v, a, j, 0.0, 0.0])).unwrap();
        let (y, _) = l.height(Jet::var(m.alpha.v()));
        assert!((y.v() + l.mid_m - s).abs() < 1e-14, "{k}");
        let (g1, g2, g3) = (y.d(1), y.d(2), y.d(3));
        let w = v / g1;
        let acc = (a - g2 * w * w) / g1;
        let jerk = (j - 3.0 * g2 * w * acc - g3 * w * w * w) / g1;
        assert!((m.alpha.d(1) - w).abs() < 1e-13 * w.abs(), "{k}");
        assert!((m.alpha.d(2) - acc).abs() < 1e-12 * acc.abs(), "{k}");
        assert!((m.alpha.d(3) - jerk).abs() < 1e-11 * jerk.abs(), "{k}");
        assert!((m.dy_dalpha.v() - g1).abs() < 1e-15);
    }
}

/// Gauss–Legendre on `panels` equal parts of `[a, b]`.
fn integrate(a: f64, b: f64, panels: usize, f: impl Fn(f64) -> f64) -> f64 {
    let rule = loomkin_laws::gauss_legendre(8);
    let h = (b - a) / panels as f64;
    (0..panels)
        .map(|i| {
            let m = a + (i as f64 + 0.5) * h;
            rule.iter().map(|&(x, w)| 0.5 * h * w * f(m + 0.5 * h * x)).sum::<f64>()
        })
        .sum()
}

/// Over the rise (rest to rest) the motor's work is the frame's potential energy gained plus the
/// losses, all through the efficiency: `∫T·α̇ dt = (ΔV + c∫ẏ²dt + F_μ·H)/η` (the kinetic energies
/// of frame, lever and motor are zero at both ends); to 1e-9.
#[test]
fn the_energy_over_a_move_closes() {
    for gear_ratio in [1.0, 7.5] {
        energy_over_a_move(gear_ratio);
    }
}

fn energy_over_a_move(gear_ratio: f64) {
    let (eta, fmu, c) = (0.9, 7.0, 30.0);
    let ax = axis(CrankLever { gear_ratio, ..geometry() }, eta, fmu, c);
    let cyc = cycle(STROKE_MM, "poly345");
    let omega = loomkin_units::rad_per_s_from_rpm(400.0);
    let seg = &cyc.segments[0];
    let (_, law) = seg.law.as_ref().unwrap();
    let tau = seg.length_rad / omega;
    let h = seg.stroke_si;
    let slave = |t: f64| {
        let k = law.eval(t / tau);
        Jet::from_derivs([h * k.s, h * k.v / tau, h * k.a / (tau * tau), h * k.j / tau.powi(3), 0.0, 0.0])
    };
    let work = integrate(0.0, tau, 64, |t| {
        let (tq, a) = ax.motor_series(slave(t)).unwrap();
        tq.v() * a.d(1)
    });
    let v2 = integrate(0.0, tau, 64, |t| slave(t).d(1).powi(2));
    let (ks, f0) = (800.0, 90.0);
    let dv = f0 * h + 0.5 * ks * h * h;
    let expected = (dv + c * v2 + fmu * h) / eta;
    assert!((work - expected).abs() < 1e-9 * expected, "{work} vs {expected}");
}

/// On a small stroke about mid-stroke the crank and lever is the linear drive of its ratio at
/// mid-stroke: the torques approach each other as the stroke shrinks.
#[test]
fn a_small_stroke_approaches_the_linear_drive() {
    for gear in [1.0, 4.0] {
        approaches_the_linear_drive(gear);
    }
}

fn approaches_the_linear_drive(gear_ratio: f64) {
    let mut last = f64::INFINITY;
    for stroke in [8.0, 2.0, 0.5] {
        let cl = CrankLever { lever_inertia_kg_m2: 0.0, mid_stroke_mm: stroke / 2.0, gear_ratio, ..geometry() };
        let crank = axis(cl, 0.95, 0.0, 10.0);
        let k = crank.motor_rad_per_unit();
        let mut linear = crank.clone();
        linear.load.crank_lever = None;
        // The crank turns backwards as the frame rises on this branch: the same drive, |k|.
        linear.load.travel_mm_per_rev = Some(2.0 * std::f64::consts::PI / k.abs() * 1e3);
        let cyc = cycle(stroke, "cycloidal");
        let a = check_axis(&crank, &cyc, 500.0).unwrap();
        let b = check_axis(&linear, &cyc, 500.0).unwrap();
        let rel = ((a.peak_torque_nm - b.peak_torque_nm) / b.peak_torque_nm)
            .abs()
            .max(((a.rms_torque_nm - b.rms_torque_nm) / b.rms_torque_nm).abs())
            .max(((a.peak_motor_speed_rpm - b.peak_motor_speed_rpm) / b.peak_motor_speed_rpm).abs());
        assert!(rel < last / 3.0, "stroke {stroke}: {rel} after {last}");
        last = rel;
        assert!((a.inertia_ratio - b.inertia_ratio).abs() < 1e-12 * b.inertia_ratio);
    }
    assert!(last < 5e-3, "{last}");
}

/// The check's peaks bound dense samples of the operating points and are attained; its RMS is a
/// fine trapezoid rule's.
#[test]
fn the_check_locates_the_crank_levers_peaks() {
    let ax = axis(geometry(), 0.92, 5.0, 20.0);
    let cyc = cycle(STROKE_MM, "modified-sine");
    let r = check_axis(&ax, &cyc, 450.0).unwrap();
    let pts = operating_points(&ax, &cyc, 450.0, 100_001).unwrap();
    let pk_t = pts.iter().map(|p| p.torque_nm.abs()).fold(0.0, f64::max);
    let pk_n = pts.iter().map(|p| p.motor_speed_rpm.abs()).fold(0.0, f64::max);
    assert!(pk_t <= r.peak_torque_nm * (1.0 + 1e-12) && pk_t >= r.peak_torque_nm * (1.0 - 1e-6), "{pk_t} {r:?}");
    assert!(pk_n <= r.peak_motor_speed_rpm * (1.0 + 1e-12) && pk_n >= r.peak_motor_speed_rpm * (1.0 - 1e-6));
    let dt = r.cycle_time_s / (pts.len() - 1) as f64;
    let int: f64 = pts.windows(2).map(|w| 0.5 * (w[0].torque_nm.powi(2) + w[1].torque_nm.powi(2)) * dt).sum();
    let rms = (int / r.cycle_time_s).sqrt();
    assert!((rms - r.rms_torque_nm).abs() < 1e-6 * r.rms_torque_nm, "{rms} vs {}", r.rms_torque_nm);
}

#[test]
fn a_geometry_that_cannot_make_the_stroke_is_refused_naming_the_field() {
    // A short crank: the frame's dead centre inside the stroke.
    let short = axis(CrankLever { crank_radius_mm: 15.0, ..geometry() }, 1.0, 0.0, 0.0);
    let e = check_axis(&short, &cycle(STROKE_MM, "cycloidal"), 300.0).unwrap_err().to_string();
    assert!(e.starts_with("load.crank_lever.crank_radius_mm: the crank and lever move the frame only to "), "{e}");
    assert!(e.contains("the stroke needs -50 … 50 mm"), "{e}");
    // A rod that cannot reach the lever at mid-stroke.
    let far = axis(CrankLever { rod_length_mm: 100.0, ..geometry() }, 1.0, 0.0, 0.0);
    let e = far.validate(StrokeUnit::Mm).unwrap_err().to_string();
    assert!(e.starts_with("load.crank_lever.rod_length_mm: the crank cannot reach the lever"), "{e}");
    // A crank and lever with a travel per revolution as well.
    let mut both = axis(geometry(), 1.0, 0.0, 0.0);
    both.load.travel_mm_per_rev = Some(100.0);
    assert!(both.validate(StrokeUnit::Mm).unwrap_err().to_string().starts_with("load.crank_lever:"));
    // Out of range.
    let neg = axis(CrankLever { lever_output_arm_mm: -1.0, ..geometry() }, 1.0, 0.0, 0.0);
    let e = neg.validate(StrokeUnit::Mm).unwrap_err().to_string();
    assert!(e.starts_with("load.crank_lever.lever_output_arm_mm"), "{e}");
}

/// An axis file takes the crank and lever as `[load.crank_lever]`.
#[test]
fn an_axis_file_reads_the_crank_lever() {
    let text = "[motor]\nrated_torque_nm = 12\npeak_torque_nm = 36\nrated_speed_rpm = 3000\nmax_speed_rpm = 4500\n\
                rotor_inertia_kg_m2 = 1.1e-3\n[load]\nmoving_mass_kg = 6\n[load.crank_lever]\ncrank_radius_mm = 40\n\
                rod_length_mm = 200\nlever_input_arm_mm = 100\nlever_output_arm_mm = 200\nrocking_shaft_x_mm = -100\n\
                rocking_shaft_y_mm = 200\nframe_link_mm = 400\nmid_stroke_mm = 50\n";
    let ax = Axis::from_toml(text, StrokeUnit::Mm).unwrap();
    assert_eq!(ax.load.crank_lever, Some(CrankLever { lever_inertia_kg_m2: 0.0, ..geometry() }));
    let r = check_axis(&ax, &cycle(STROKE_MM, "cycloidal"), 400.0).unwrap();
    assert!(r.peak_torque_nm > 0.0 && r.peak_motor_speed_rpm > 0.0);
}

/// A small deterministic generator (xorshift64*), uniform on `[lo, hi)`.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let u = (self.0.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * u
    }
}

/// The frame's reach on one side of mid-stroke by another route: march the height outward from
/// mid-stroke on a dense grid while the closed-form inverse exists, `dy/dα` of the forward map
/// keeps its sign and the crank angle keeps moving the same way (the central difference of `α(y)`
/// over `±10⁻⁵` of the output arm: the inverse runs smoothly through a lock, where the crank turns
/// back); then bisect between the last good height and the first bad one.
fn scanned_reach(l: &loomkin_servo::Linkage, up: bool, span: f64, steps: usize) -> f64 {
    let h = 1e-5 * l.e;
    let turn = |y: f64| match (l.motor_angle(y - h), l.motor_angle(y + h)) {
        (Some(a), Some(b)) => Some(b - a),
        _ => None,
    };
    let (slope0, turn0) = (l.height(Jet::var(l.motor_angle(0.0).unwrap())).0.d(1).signum(), turn(0.0).unwrap());
    let good = |y: f64| {
        l.motor_angle(y).is_some_and(|a| {
            let g = l.height(Jet::var(a)).0.d(1);
            g.is_finite() && g.signum() == slope0 && turn(y).is_none_or(|t| t * turn0 > 0.0)
        })
    };
    let side = if up { 1.0 } else { -1.0 };
    let mut last = 0.0;
    for k in 1..=steps {
        let y = side * span * k as f64 / steps as f64;
        if !good(y) {
            return loomkin_numeric::bisect(last, y, good);
        }
        last = y;
    }
    panic!("no dead centre within {span} m");
}

/// A random crank and lever about mid-stroke 0 (a frame link in three of four), for the property tests.
fn random_geometry(rng: &mut Rng) -> CrankLever {
    let link = if rng.uniform(0.0, 1.0) < 0.25 { None } else { Some(rng.uniform(20.0, 600.0)) };
    CrankLever {
        crank_radius_mm: rng.uniform(10.0, 100.0),
        rod_length_mm: rng.uniform(50.0, 400.0),
        lever_input_arm_mm: rng.uniform(30.0, 200.0),
        lever_output_arm_mm: rng.uniform(50.0, 300.0),
        lever_angle_deg: rng.uniform(-180.0, 180.0),
        rocking_shaft_x_mm: rng.uniform(-300.0, 300.0),
        rocking_shaft_y_mm: rng.uniform(-300.0, 300.0),
        frame_link_mm: link,
        crank_branch: if rng.uniform(0.0, 1.0) < 0.5 { CrankBranch::Ccw } else { CrankBranch::Cw },
        mid_stroke_mm: 0.0,
        ..geometry()
    }
}

/// The closed-form dead centres ([`loomkin_servo::Linkage::reach`]) against a dense scan of the
/// kinematics refined by bisection, on random geometries (every branch, with and without a frame
/// link, every kind of dead centre).
#[test]
fn the_closed_form_dead_centres_match_a_dense_scan() {
    use loomkin_servo::DeadCentre;
    let mut rng = Rng(0x5eed_0031_c0ff_ee01);
    let (mut tried, mut kinds) = (0, std::collections::BTreeMap::<String, usize>::new());
    while tried < 120 {
        let cl = random_geometry(&mut rng);
        let Ok(l) = cl.linkage() else { continue };
        tried += 1;
        let span = 1.001 * (l.e + l.link.unwrap_or(0.0));
        for up in [true, false] {
            let reach = l.reach(up);
            let scanned = scanned_reach(&l, up, span, 20_000);
            // Where dy/dα = 0 the inverse ceases: the bisection finds that to rounding (worst
            // 1.9e-15 of the output arm). Where dy/dα = ∞ (a lock) the scan finds where the crank
            // turns back from differences of α(y): rounding over the step and the step's square
            // (truncation) leave ~1e-8 of the arm on these geometries (worst 5.4e-8).
            let locks = matches!(reach.kind, DeadCentre::Lever | DeadCentre::FrameLink);
            let tol = if locks { 1e-7 } else { 1e-12 } * l.e;
            assert!(
                (reach.height_m - scanned).abs() <= tol,
                "{cl:?} up = {up}: closed form {reach:?}, scanned {scanned}"
            );
            *kinds.entry(format!("{:?}", reach.kind)).or_default() += 1;
            // The refusal is the same limit: a stroke just inside passes, one just beyond is refused.
            let (inside, beyond) = (reach.height_m * (1.0 - 1e-6), reach.height_m * (1.0 + 1e-6));
            let check = |y: f64| if up { cl.check_stroke(0.0, y, "x") } else { cl.check_stroke(y, 0.0, "x") };
            assert!(check(inside).is_ok(), "{cl:?} {reach:?}");
            let field = match reach.kind {
                DeadCentre::Crank => "crank_radius_mm",
                DeadCentre::Lever => "rod_length_mm",
                DeadCentre::OutputArm => "lever_output_arm_mm",
                DeadCentre::FrameLink => "frame_link_mm",
            };
            let e = check(beyond).unwrap_err().to_string();
            assert!(e.starts_with(&format!("x.{field}: the crank and lever move the frame only to ")), "{e}");
        }
    }
    // Every kind of dead centre was met.
    assert_eq!(kinds.len(), 4, "{kinds:?}");
}

/// A crank that reaches its dead centre only over a narrow band of the stroke (the crank and rod
/// just in line at 15.7 mm above mid-stroke, less than 1/512 of the stroke wide, between two of a
/// 512-interval grid's heights): the grid sees nothing wrong, the closed form refuses it.
#[test]
fn a_narrow_dead_centre_between_grid_heights_is_refused() {
    let (e_mm, half_mm) = (200.0f64, 40.0f64);
    let grid_mm = 2.0 * half_mm / 512.0;
    let y_star = grid_mm * 100.5;
    let phi_star = (y_star / e_mm).asin();
    let (qx, qy, c, r) = (-100.0f64, 200.0f64, 100.0, 40.0);
    let psi = qy.atan2(qx);
    // |B(φ)| is largest, |Q| + c, where φ + δ = ψ; the crank and rod reach 1e-6 mm less.
    let cl = CrankLever {
        crank_radius_mm: r,
        rod_length_mm: qx.hypot(qy) + c - r - 1e-6,
        lever_input_arm_mm: c,
        lever_output_arm_mm: e_mm,
        lever_angle_deg: (psi - phi_star).to_degrees(),
        rocking_shaft_x_mm: qx,
        rocking_shaft_y_mm: qy,
        frame_link_mm: None,
        mid_stroke_mm: 0.0,
        ..geometry()
    };
    let l = cl.linkage().unwrap();
    // Every height of the 512-interval grid passes the grid check this replaces: the inverse
    // exists and dy/dα there keeps its sign.
    let slope0 = l.height(Jet::var(l.alpha_mid)).0.d(1);
    for k in 0..=512 {
        let y = (-half_mm + grid_mm * k as f64) * 1e-3;
        let a = l.motor_angle(y).unwrap_or_else(|| panic!("grid height {y}"));
        let h = l.height(Jet::var(a)).0;
        assert!(h.d(1) * slope0 > 0.0, "{y}: {h:?}");
    }
    // Between the grid's heights the crank cannot follow.
    assert!(l.motor_angle(y_star * 1e-3).is_none());
    let reach = l.reach(true);
    assert_eq!(reach.kind, loomkin_servo::DeadCentre::Crank);
    assert!(reach.height_m < y_star * 1e-3 && reach.height_m > (y_star - grid_mm / 2.0) * 1e-3, "{reach:?}");
    let e = cl.check_stroke(-half_mm * 1e-3, half_mm * 1e-3, "load.crank_lever").unwrap_err().to_string();
    assert!(e.starts_with("load.crank_lever.crank_radius_mm: the crank and lever move the frame only to 15.6"), "{e}");
    assert!(e.contains("above mid-stroke, the stroke needs -40 … 40 mm: the crank reaches its dead centre"), "{e}");
}

/// The inverse is continuous and monotone over the whole reach on random geometries, also where
/// the crank turns more than half a turn from its angle at mid-stroke (1.5 % of them: the angle
/// was taken into ±180° of it and jumped by a turn), and the forward map returns the height.
#[test]
fn the_inverse_is_continuous_over_the_reach() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    let (mut n, mut beyond_half_turn) = (0, 0);
    while n < 1000 {
        let cl = random_geometry(&mut rng);
        let Ok(l) = cl.linkage() else { continue };
        n += 1;
        let (lo, hi) = (l.reach(false).height_m, l.reach(true).height_m);
        const STEPS: usize = 2000;
        let angles: Vec<f64> =
            (1..STEPS).map(|k| l.motor_angle(lo + (hi - lo) * k as f64 / STEPS as f64).unwrap()).collect();
        let rising = angles[1] > angles[0];
        for (k, w) in angles.windows(2).enumerate() {
            assert!((w[1] > w[0]) == rising && (w[1] - w[0]).abs() < 0.5, "{cl:?} at {k}: {w:?}");
        }
        for (k, &a) in angles.iter().enumerate().step_by(97) {
            let y = lo + (hi - lo) * (k + 1) as f64 / STEPS as f64;
            assert!((l.height(Jet::var(a)).0.v() - y).abs() < 1e-9 * l.e, "{cl:?} y = {y}");
        }
        if angles.iter().any(|a| (a - l.alpha_mid).abs() > PI) {
            beyond_half_turn += 1;
        }
    }
    assert!(beyond_half_turn > 0, "no geometry turns the crank more than half a turn from mid-stroke");
}
