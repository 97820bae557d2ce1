//! The loom's J(φ) and M_load(φ) against independent routes: finite differences for dJ/dφ,
//! `loom torque` at constant speed (power balance), dense sampling for the extremes and means,
//! and the speed-ripple solver on the rapier loom.

mod common;

use common::{edited, example, wif};
use loomkin_drive::{Motor, Table, solve};
use loomkin_loom::{Drive, Loom, LoomShaft, Motion, Pattern};

/// The rapier loom's file without its `[drive]` table (the tests give their own).
fn rapier_text() -> String {
    let text = example("rapier-loom.toml");
    text[..text.find("\n# The main-shaft drive").unwrap()].to_string()
}

fn rapier_with(efficiency: &str) -> Loom {
    let text = edited(&rapier_text(), "efficiency = 0.9", efficiency);
    Loom::from_toml(&format!("{text}\n[drive]\nrotating_inertia_kg_m2 = 0.8\nfriction_torque_n_m = 4\n")).unwrap()
}

#[test]
fn dj_matches_finite_differences() {
    let loom = rapier_with("efficiency = 0.9");
    let pattern = wif("point-24.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let joints = motion.joints();
    let mut checked = 0;
    for k in 0..2000 {
        let th = 0.37 + k as f64 * motion.repeat_deg() / 2000.0;
        // Away from the joints, where J is smooth on the difference's scale.
        if joints.iter().any(|j| (j - th).abs() < 0.01) {
            continue;
        }
        let h = 1e-4; // deg
        let fd = (shaft.inertia_at(th + h).0 - shaft.inertia_at(th - h).0) / (2.0 * h.to_radians());
        let (j, dj) = shaft.inertia_at(th);
        assert!((fd - dj).abs() <= 1e-6 * (dj.abs() + j), "{th}: {fd} vs {dj}");
        checked += 1;
    }
    assert!(checked > 1500);
}

#[test]
fn the_load_is_loom_torque_less_its_inertial_part() {
    // At constant speed ω the shaft gives M_load + ½ω²·dJ/dφ; `loom torque` divides the frames'
    // whole force by η, so its torque is M_load + ½ω²·(dJ/dφ)/η, friction apart.
    for eta in ["efficiency = 1", "efficiency = 0.9"] {
        let loom = rapier_with(eta);
        let pattern = wif("point-24.wif");
        let motion = Motion::new(&loom, &pattern).unwrap();
        let shaft = LoomShaft::new(&loom, &motion, &pattern);
        let drive = Drive::new(&loom, &motion, &pattern);
        let w = loom.speed.rad_per_s();
        let fr = loom.drive.friction_torque_n_m;
        for k in 0..5000 {
            let th = k as f64 * motion.repeat_deg() / 5000.0 + 0.013;
            // The sley is the example's too: its beat-up and inertia are not `loom torque`'s.
            let sley = loom.sley.as_ref().unwrap();
            let phi = th.to_radians().rem_euclid(std::f64::consts::TAU);
            let dj = shaft.inertia_at(th).1 - shaft.sley_inertia(th).1;
            let ours = shaft.load_at(th) - fr - sley.load_torque_n_m(phi) + 0.5 * w * w * dj / loom.efficiency;
            let theirs = drive.torque_at(th);
            assert!((ours - theirs).abs() <= 1e-11 * (theirs.abs() + 1.0), "{eta} {th}: {ours} vs {theirs}");
        }
    }
}

#[test]
fn the_report_meets_a_dense_scan() {
    let loom = rapier_with("efficiency = 0.9");
    let pattern = wif("point-24.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let r = shaft.report(0.5).unwrap();
    let period = motion.repeat_deg();
    // Mean by composite Simpson on 0.02° (measured 4e-12 apart).
    let n = (period / 0.02) as usize;
    let h = period / n as f64;
    let f = |x: f64| shaft.inertia_at(x).0;
    let simpson: f64 =
        (0..n).map(|k| h / 6.0 * (f(k as f64 * h) + 4.0 * f((k as f64 + 0.5) * h) + f((k + 1) as f64 * h))).sum();
    let mean = simpson / period;
    assert!((r.j_mean_kg_m2 - mean).abs() <= 1e-10 * mean, "{} vs {mean}", r.j_mean_kg_m2);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..2 * n {
        let v = f(k as f64 * h / 2.0);
        lo = lo.min(v);
        hi = hi.max(v);
    }
    // The located extremes are at least as extreme as any sample, and are J where they are said to
    // be (the cam sley's J peaks sharply: a 0.01° sample falls ~7e-9 short of its top).
    assert!(r.j_max_kg_m2 >= hi - 1e-13 * hi && r.j_max_kg_m2 <= hi * (1.0 + 1e-8), "{} vs {hi}", r.j_max_kg_m2);
    assert!(r.j_min_kg_m2 <= lo + 1e-13 * lo && r.j_min_kg_m2 >= lo * (1.0 - 1e-8), "{} vs {lo}", r.j_min_kg_m2);
    assert!((f(r.total.j_max_angle_deg) - r.j_max_kg_m2).abs() <= 1e-13 * hi, "{}", r.total.j_max_angle_deg);
    assert!((f(r.total.j_min_angle_deg) - r.j_min_kg_m2).abs() <= 1e-13 * hi, "{}", r.total.j_min_angle_deg);
    // Mechanisms add up to the total's mean; each frame's extremes are those of its own scan.
    let sum: f64 = r.mechanisms.iter().map(|m| m.j_mean_kg_m2).sum();
    assert!((sum - r.j_mean_kg_m2).abs() <= 1e-12 * sum);
    let front = &r.mechanisms[0];
    let fmax = (0..2 * n).map(|k| shaft.frame_inertia(0, k as f64 * h / 2.0).0).fold(0.0, f64::max);
    assert!(front.j_max_kg_m2 >= fmax && front.j_max_kg_m2 <= fmax * (1.0 + 1e-9));
    assert_eq!(front.j_min_kg_m2, 0.0);
    assert_eq!(r.mechanisms.last().unwrap().j_mean_kg_m2, 0.8);
}

#[test]
fn the_rapier_loom_runs_with_each_motor() {
    let text = format!(
        "{}\n[drive]\nrotating_inertia_kg_m2 = 0.8\nfriction_torque_n_m = 4\nmotor = \"induction\"\nrated_power_kw = 5.5\nmotor_curve = \"kloss\"\n",
        rapier_text()
    );
    let loom = Loom::from_toml(&text).unwrap();
    let pattern = Pattern::plain(24).unwrap();
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let table = Table::new(&shaft, 0.1).unwrap();
    for motor in
        [Motor::Constant { speed_rad_s: loom.speed.rad_per_s() }, loom.drive.motor.build(500.0, "drive.").unwrap()]
    {
        let sol = solve(&table, &motor, 0.0).unwrap();
        let r = &sol.report;
        assert!(r.speed_ripple_pct > 0.0 && r.speed_ripple_pct < 50.0, "{r:?}");
        assert!(r.min_speed_rpm < r.mean_speed_rpm && r.mean_speed_rpm < r.max_speed_rpm);
        let closure = (r.motor_work_j - r.load_work_j).abs() / (r.load_work_j.abs() + r.energy_swing_j);
        assert!(closure <= 1e-9, "{closure:e}");
    }
    let e = Loom::from_toml(&format!("{}\n[drive]\nmotor = \"diesel\"\n", rapier_text())).unwrap_err();
    assert_eq!(e.to_string(), "drive.motor: 'diesel': expected constant, induction or servo");
    let e = Loom::from_toml(&format!("{}\n[drive]\nfriction_torque_n_m = -1\n", rapier_text())).unwrap_err();
    assert!(e.to_string().starts_with("drive.friction_torque_n_m = -1 is out of range"), "{e}");
}

/// The side view (the workbench's animation) keeps every link's length, puts the reed's beating
/// point at the fell at beat-up and a stroke behind it at the back dead centre, and every heald eye
/// on the level warp line at mid-stroke, its lift the frame's.
#[test]
fn the_side_view_keeps_the_links_and_meets_the_fell_at_beat_up() {
    // The shuttle loom's crank-rocker sley (the rapier's is a cam sley).
    let loom = Loom::from_toml(&example("shuttle-loom.toml")).unwrap();
    let pattern = wif("twill-2-2.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let t = loom.sley.as_ref().and_then(|s| s.four_bar()).unwrap().table();
    let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
    let mut furthest: f64 = 0.0;
    for k in 0..720 {
        let th = k as f64 * 0.5;
        let v = shaft.side_view(th);
        let s = v.sley.unwrap();
        for (got, want) in [
            (dist(s.crank_pin, s.crank_centre), t.crank_mm),
            (dist(s.sword_pin, s.crank_pin), t.rod_mm),
            (dist(s.sword_pin, s.rocking_shaft), t.sword_mm),
            (dist(s.reed, s.rocking_shaft), t.reed_height_mm),
            (dist(s.rocking_shaft, s.crank_centre), t.pivot_x_mm.hypot(t.pivot_y_mm)),
        ] {
            assert!((got - want).abs() < 1e-9 * want, "{th}°: {got} vs {want}");
        }
        // The reed never passes the fell; it leaves it by the reed's travel along the arc.
        assert!(s.reed[0] >= -1e-9, "{th}°: {:?}", s.reed);
        furthest = furthest.max(dist(s.reed, [0.0, 0.0]));
        for (i, e) in v.heald_eyes_mm.iter().enumerate() {
            let g = &loom.geometry;
            let level = g.warp_line_m * g.frame_m[i] / g.back_rest_m * 1e3;
            assert!((e[0] - g.frame_m[i] * 1e3).abs() < 1e-9);
            assert!((e[1] - level - motion.frame(i, th).y_m * 1e3).abs() < 1e-9);
        }
    }
    let beat = shaft.side_view(t.beat_up_deg).sley.unwrap().reed;
    assert!(beat[0].abs() < 1e-9 && beat[1].abs() < 1e-9, "{beat:?}");
    // The chord to the back dead centre: the arc's stroke subtends 2·asin(chord / 2h) at the shaft.
    let stroke_mm = loom.sley.as_ref().unwrap().stroke_m() * 1e3;
    let h = t.reed_height_mm;
    let chord = 2.0 * h * (stroke_mm / (2.0 * h)).sin();
    assert!((furthest - chord).abs() < 1e-3 * chord, "{furthest} vs {chord}");
}

/// A cam sley whose law's joints fall inside the mean's 10° panels (the modified sine's eighths of
/// a 70° move at 8.75° and 61.25°): the sley's mean J against composite Simpson on 0.005° over a
/// turn (the grid holds every joint: 8.75 and 61.25 are multiples of 0.005).
#[test]
fn a_cam_sleys_mean_splits_at_its_laws_joints() {
    let text = example("projectile-loom.toml");
    let text = edited(&edited(&text, "to_deg = 80\nlaw", "to_deg = 70\nlaw"), "to_deg = 280", "to_deg = 290");
    let text = edited(&text, "max_pressure_deg = 35", "max_pressure_deg = 40");
    let loom = Loom::from_toml(&text).unwrap();
    let pattern = wif("point-24.wif");
    let motion = Motion::new(&loom, &pattern).unwrap();
    let shaft = LoomShaft::new(&loom, &motion, &pattern);
    let r = shaft.report(0.5).unwrap();
    let sley = r.mechanisms.iter().find(|m| m.name == "sley").unwrap();
    let n = 72_000;
    let h = 360.0 / n as f64;
    let f = |x: f64| shaft.sley_inertia(x).0;
    let mean: f64 = (0..n)
        .map(|k| h / 6.0 * (f(k as f64 * h) + 4.0 * f((k as f64 + 0.5) * h) + f((k + 1) as f64 * h)))
        .sum::<f64>()
        / 360.0;
    assert!((sley.j_mean_kg_m2 - mean).abs() <= 1e-12 * mean, "{} vs {mean}", sley.j_mean_kg_m2);
}
