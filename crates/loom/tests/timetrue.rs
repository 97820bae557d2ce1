//! Time-true cams of the rapier loom's frames: the cycle files written, read back and run through
//! a separate time-domain integration of the shaft (DOP853 on J·ω̇ = M_motor − M_load − ½J′ω²,
//! with the time-true cams in J and M_load) put every frame where the design law puts it at the
//! constant mean speed.

mod common;

use common::{example, wif};
use differential_equations::prelude::{ExplicitRungeKutta, IVP, ODE};
use loomkin_drive::{Motor, Shaft, Table, solve};
use loomkin_laws::Cycle;
use loomkin_loom::{Loom, LoomShaft, Motion, correct};

struct TimeDomain<'a> {
    shaft: &'a LoomShaft<'a>,
    motor: Motor,
}

impl ODE<f64, [f64; 2]> for TimeDomain<'_> {
    fn diff(&self, _t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        let (th, w) = (y[0], y[1]);
        let p = self.shaft.period_rad();
        let (j, dj) = self.shaft.inertia(th.rem_euclid(p));
        let m = match self.motor {
            Motor::Induction(i) => i.torque(w).0,
            _ => unreachable!(),
        };
        dy[0] = w;
        dy[1] = (m - self.shaft.load_torque(th.rem_euclid(p)) - 0.5 * dj * w * w) / j;
    }
}

#[test]
fn the_written_cams_move_the_frames_in_time_as_designed() {
    let loom = Loom::from_toml(&example("rapier-loom.toml")).unwrap();
    let pattern = wif("twill-2-2.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let motor = loom.drive.motor.build(loom.speed.rpm(), "drive.").unwrap();
    assert!(matches!(motor, Motor::Induction(_)));
    let c = correct(&loom, &motion, &pattern, &motor, 0.0, 0.1, None).unwrap();
    let r = &c.report;
    eprintln!(
        "timing before {:.4}°, after {:.2e}°, {} rounds",
        r.max_timing_error_deg_before, r.max_timing_error_deg_after, r.rounds
    );
    assert!(r.max_timing_error_deg_before > 0.1);
    // The frames (the rapier loom's cam sley, corrected for the pick-mean speed, has its own after).
    let frames_after = r.frames.iter().map(|f| f.max_timing_error_deg_after).fold(0.0, f64::max);
    assert!(frames_after <= 1e-5, "{frames_after}");
    // The shaft with the time-true cams, and its periodic speed.
    let shaft = LoomShaft::new(&loom, &motion, &pattern).with_corrected(&c.frames);
    let table = Table::new(&shaft, 0.1).unwrap();
    let sol = solve(&table, &motor, 0.0).unwrap();
    let w_mean = c.corrected_map.mean_speed_rad_s();
    let mut worst: f64 = 0.0;
    for i in 0..motion.frames() {
        let spec = c.frames.cycle_spec(i, 500.0);
        let cycle = Cycle::from_toml(&spec.to_toml().unwrap()).unwrap();
        let design = motion.moves(i);
        if design.is_empty() {
            continue;
        }
        let h = motion.stroke_m(i);
        let before = if design[0].rising { -h / 2.0 } else { h / 2.0 };
        for (k, (start, length, _)) in c.frames.moves(i).into_iter().enumerate() {
            // From the corrected move's start at its periodic speed, one move's time in the time domain.
            let s0 = start.to_radians();
            let y0 = [s0, sol.omega_at(s0.rem_euclid(table.nodes()[table.nodes().len() - 1]))];
            let t1 = length.to_radians() / w_mean * 1.02;
            let eq = TimeDomain { shaft: &shaft, motor };
            let method = ExplicitRungeKutta::dop853().rtol(1e-13).atol(1e-13).max_steps(1_000_000);
            let run = IVP::ode(&eq, 0.0, t1, y0).method(method).solve().unwrap();
            let design_start = design[k].start_deg.to_radians();
            for (t, y) in run.iter() {
                let file = before + cycle.eval(y[0], 500.0).s;
                let want = motion.frame(i, (design_start + w_mean * t).to_degrees()).y_m;
                worst = worst.max((file - want).abs());
            }
        }
    }
    eprintln!("largest |y_file(φ(t)) − y_design(ω̄t)| {worst:.2e} m");
    // Measured 3.3e-10 m: the cams' own timing error (2e-7° here) times the frames' slope, and the file's fit.
    assert!(worst <= 1e-9, "{worst:e} m");
}

/// The projectile loom's cam sley: one cam for every pick, corrected for the pick-mean speed. The
/// written cycle file, read back and driven by the shaft's real speed re-timed by numerical
/// integration (composite Simpson of dt = dφ/ω over each pick, ω from the periodic solution's
/// energy and the exact J: not the time map the correction used), puts the rocking shaft where the
/// design law puts it at the constant mean speed on the mean pick; each pick's own time-true angle
/// departs from the mean pick's by at most the reported `max_timing_error_deg_after`.
#[test]
fn the_cam_sley_moves_in_time_on_the_mean_pick() {
    use std::f64::consts::TAU;
    let loom = Loom::from_toml(&example("projectile-loom.toml")).unwrap();
    let pattern = wif("twill-2-2.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let motor = loom.drive.motor.build(loom.speed.rpm(), "drive.").unwrap();
    let c = correct(&loom, &motion, &pattern, &motor, 0.0, 0.1, None).unwrap();
    let sc = c.sley.as_ref().expect("a cam sley is corrected");
    let timing = c.report.sley.as_ref().unwrap();
    assert!(c.report.not_corrected.is_empty(), "{:?}", c.report.not_corrected);
    let cam = loom.sley.as_ref().and_then(|s| s.cam()).unwrap();
    let shift = cam.phase_deg().to_radians();
    let anchor = sc.anchor_rad;
    assert_eq!(anchor, cam.front_dead_centre_rad());
    // The file as `drive correct` writes it, read back as `cam` and `dyn` read it.
    let files = c.cycle_files("test").unwrap();
    let (_, text) = files.iter().find(|(name, _)| name == "sley.toml").unwrap();
    let corrected = Cycle::from_toml(text).unwrap();
    let design = Cycle::new(&cam.table().cycle).unwrap();
    // The shaft with the time-true frames (what the sley was corrected against) and its speed.
    let shaft = LoomShaft::new(&loom, &motion, &pattern).with_corrected(&c.frames);
    let table = Table::new(&shaft, 0.1).unwrap();
    let sol = solve(&table, &motor, 0.0).unwrap();
    let picks = motion.picks();
    // Each pick's time from its anchor, on 0.02° nodes over a turn, by Simpson's rule.
    let m = 18_000;
    let h = TAU / m as f64;
    let times: Vec<Vec<f64>> = (0..picks)
        .map(|p| {
            let base = anchor + TAU * p as f64;
            let inv = |x: f64| 1.0 / sol.omega_at(x);
            let mut t = vec![0.0];
            for k in 0..m {
                let x = base + k as f64 * h;
                t.push(t[k] + h / 6.0 * (inv(x) + 4.0 * inv(x + 0.5 * h) + inv(x + h)));
            }
            t
        })
        .collect();
    let mean: Vec<f64> = (0..=m).map(|k| times.iter().map(|t| t[k]).sum::<f64>() / picks as f64).collect();
    let w_mean = TAU / mean[m];
    assert!((w_mean - sc.mean_map.mean_speed_rad_s()).abs() <= 1e-9 * w_mean);
    let moving = |phi: f64| {
        corrected.segments.iter().any(|s| {
            s.law.is_some() && {
                let d = (phi - shift - s.start_rad).rem_euclid(TAU);
                d > 0.0 && d < s.length_rad
            }
        })
    };
    let (mut worst, mut spread) = (0.0f64, 0.0f64);
    for k in 0..m {
        let phi = anchor + k as f64 * h;
        let psi = anchor + w_mean * mean[k];
        let file = corrected.eval(phi - shift, 300.0).s;
        let want = design.eval(psi - shift, 300.0).s;
        worst = worst.max((file - want).abs());
        if moving(phi) {
            for t in &times {
                spread = spread.max((w_mean * (t[k] - mean[k])).abs());
            }
        }
    }
    let stroke = cam.table().cycle.stroke.unwrap().to_radians();
    eprintln!(
        "sley: |s_file(φ) − s_design(ψ̄(φ))| ≤ {:.2e} of the stroke; timing {:.4}° before, {:.4}° after (spread by integration {:.4}°)",
        worst / stroke,
        timing.max_timing_error_deg_before,
        timing.max_timing_error_deg_after,
        spread.to_degrees()
    );
    // Measured 8.4e-10: the file's quintic panels and the two routes to t(φ).
    assert!(worst <= 5e-9 * stroke, "{:e} of the stroke", worst / stroke);
    assert!(timing.max_timing_error_deg_before > 4.0 * timing.max_timing_error_deg_after);
    let after = timing.max_timing_error_deg_after;
    assert!((spread.to_degrees() - after).abs() <= 1e-3 * after, "{} vs {after}", spread.to_degrees());
}

/// The time-true sley cam re-checked on the follower the cam was designed for: its pressure angle
/// and the pitch curve's least convex radius against a computation of their own — the contact
/// normal through the roller's centre and the instant centre of cam and follower on the line of
/// centres (Aronhold–Kennedy), the pitch curve in the cam's frame curved by differences — on the
/// law `drive correct` writes (read back), the arm, the pivot and the design cam's prime circle.
/// Projectile example with point-24: the correction pushes the cam past the 35° it was sized for,
/// and the warning says so.
#[test]
fn the_corrected_sley_cam_is_checked_on_its_follower() {
    use std::f64::consts::TAU;
    let loom = Loom::from_toml(&example("projectile-loom.toml")).unwrap();
    let pattern = wif("point-24.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let motor = loom.drive.motor.build(loom.speed.rpm(), "drive.").unwrap();
    let c = correct(&loom, &motion, &pattern, &motor, 0.0, 0.1, None).unwrap();
    let timing = c.report.sley.as_ref().unwrap();
    let sley = loom.sley.as_ref().and_then(|s| s.cam()).unwrap();
    let files = c.cycle_files("test").unwrap();
    let (_, text) = files.iter().find(|(name, _)| name == "sley.toml").unwrap();
    let corrected = Cycle::from_toml(text).unwrap();
    let design = Cycle::new(&sley.table().cycle).unwrap();
    let (d, l, rp) = (sley.table().pivot_mm, sley.table().arm_mm, sley.cam().prime_radius_mm());
    let g0 = ((d * d + l * l - rp * rp) / (2.0 * d * l)).acos();
    let stroke = 23f64.to_radians();
    // The largest pressure angle over both cams and the least convex radius of the pitch curves.
    let check = |cycle: &Cycle| {
        let rpm = 300.0;
        let w = rpm * TAU / 60.0;
        let n = 36_000;
        let angles: Vec<f64> = (0..n).map(|k| k as f64 * TAU / n as f64).collect();
        let low = angles.iter().map(|u| cycle.eval(*u, rpm).s).fold(f64::INFINITY, f64::min);
        let swing = |u: f64| {
            let k = cycle.eval(u, rpm);
            (k.s - low, k.v / w)
        };
        // Roller centres of the two cams (the conjugate's arm below the line of centres).
        let centres = |s: f64| {
            let (g1, g2) = (g0 + s, g0 + stroke - s);
            [
                ([d - l * g1.cos(), l * g1.sin()], [g1.sin(), g1.cos()]),
                ([d - l * g2.cos(), -l * g2.sin()], [-g2.sin(), g2.cos()]),
            ]
        };
        let mut pressure: f64 = 0.0;
        let mut radius = f64::INFINITY;
        for &u in &angles {
            let (s, ds) = swing(u);
            // The instant centre on O–Q: the cam (ω = 1) and the arm (ω = −s′) move alike there.
            let x = ds * d / (1.0 + ds);
            for (track, (cc, e)) in centres(s).into_iter().enumerate() {
                let (nx, ny) = (cc[0] - x, cc[1]);
                let cos = ((nx * e[0] + ny * e[1]) / nx.hypot(ny)).abs();
                pressure = pressure.max(cos.min(1.0).acos().to_degrees());
                // The pitch curve in the cam's frame, P(ψ) = R(−ψ)·C(ψ), curved by differences.
                let h = 1e-4;
                let p = |v: f64| {
                    let c = centres(swing(v).0)[track].0;
                    [v.cos() * c[0] + v.sin() * c[1], v.cos() * c[1] - v.sin() * c[0]]
                };
                let (a, b, m) = (p(u - h), p(u + h), p(u));
                let d1 = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
                let d2 = [(b[0] - 2.0 * m[0] + a[0]) / (h * h), (b[1] - 2.0 * m[1] + a[1]) / (h * h)];
                let curvature = -(d1[0] * d2[1] - d1[1] * d2[0]) / d1[0].hypot(d1[1]).powi(3);
                if curvature > 0.0 {
                    radius = radius.min(1.0 / curvature);
                }
            }
        }
        (pressure, radius)
    };
    let (p_before, r_before) = check(&design);
    let (p_after, r_after) = check(&corrected);
    // A 0.01° grid finds the largest pressure angle to ~1e-6°; the curvature by differences to 1e-4.
    assert!((timing.max_pressure_angle_deg_before - p_before).abs() < 1e-4, "{p_before}");
    assert!((timing.max_pressure_angle_deg_after - p_after).abs() < 1e-4, "{p_after}");
    assert!((timing.min_curvature_radius_mm_before / r_before - 1.0).abs() < 1e-3, "{r_before}");
    assert!((timing.min_curvature_radius_mm_after / r_after - 1.0).abs() < 1e-3, "{r_after}");
    // Sized for 35°: the design cam meets it; the time-true law needs more on the same cam.
    assert!((timing.max_pressure_angle_deg_before - 35.0).abs() < 1e-6);
    assert_eq!(timing.pressure_angle_limit_deg, 35.0);
    assert!(timing.max_pressure_angle_deg_after > 35.0);
    assert!(timing.undercut_at_deg_after.is_none() && r_after > timing.roller_radius_mm);
    let warning = timing.warning().unwrap();
    let says = format!("sley: the time-true cam needs a pressure angle of {p_after:.3}°");
    assert!(
        warning.starts_with(&says) && warning.contains("past its limit of 35°") && !warning.contains('\n'),
        "{warning}"
    );
}
