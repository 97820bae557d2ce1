//! The rapier drives against independent routes: the crank drive's loop solved numerically, the
//! rates against finite differences, the servo law's ends, the transfer's symmetry.

use loomkin_insertion::{HeadDrive, Rapier, RapierTable};
use loomkin_units::ShaftSpeed;
use proptest::prelude::*;
use std::f64::consts::TAU;

const CRANK: &str = r#"
drive = "crank"
crank_mm = 100
rod_mm = 400
rocker_mm = 250
pivot_x_mm = 400
pivot_y_mm = -150
sector_mm = 400
pinion_mm = 50
wheel_mm = 200
outer_mm = 370
"#;

fn rapier(bringer: &str, taker: &str, width_m: f64) -> Result<Rapier, String> {
    let text = format!("[bringer]\n{bringer}\n[taker]\n{taker}\n");
    let t: RapierTable = toml::from_str(&text).map_err(|e| e.to_string())?;
    Rapier::new(&t, width_m, "insertion.rapier").map_err(|e| e.to_string())
}

fn crank(inner_deg: f64) -> String {
    format!("{CRANK}inner_deg = {inner_deg}\n")
}

/// The rocker angle solved numerically from the loop `|A(α) − B(θ)| = b` by bisection in a
/// bracket around the previous angle's solution (continuation along the crank's turn), not from
/// the closed form.
fn rocker_numeric(alpha: f64, near: f64) -> f64 {
    let (r, b, c, qx, qy) = (0.1, 0.4, 0.25, 0.4, -0.15);
    let f = |th: f64| {
        let (ax, ay) = (r * alpha.cos(), r * alpha.sin());
        let (bx, by) = (qx + c * th.cos(), qy + c * th.sin());
        (bx - ax).hypot(by - ay) - b
    };
    let (lo, hi) = (near - 0.05, near + 0.05);
    assert!(f(lo).signum() != f(hi).signum(), "bracket at {alpha}");
    let lo_neg = f(lo) < 0.0;
    loomkin_numeric::bisect(lo, hi, |m| (f(m) < 0.0) == lo_neg)
}

/// The crank drive's head displacement against the numerical loop solve: u = G·(θ − θ_outer),
/// G = wheel·sector/pinion = 1.6 m/rad; the outer reversing point is where u is least.
#[test]
fn crank_drive_against_a_numerical_loop_solve() {
    let r = rapier(&crank(180.0), &crank(180.0), 1.9).unwrap();
    let HeadDrive::Crank { linkage, phase, .. } = r.bringer else { panic!("crank") };
    let g = 0.2 * 0.4 / 0.05;
    // Continuation from the closed form's value at one angle only, then the loop alone.
    let mut th = linkage.rocker_at_crank(phase);
    let mut thetas = Vec::new();
    for k in 0..=3600 {
        let phi = TAU * k as f64 / 3600.0;
        th = rocker_numeric(phi + phase, th);
        thetas.push((phi, th));
    }
    let th_min = thetas.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
    for &(phi, th) in &thetas {
        let u = r.bringer.motion(phi).u_m;
        assert!((u - g * (th - th_min)).abs() < 1e-6, "{phi}: {u} vs {}", g * (th - th_min));
    }
    // The stroke: the swing times G, both from the numerical solve (the grid's extremes lie within
    // (0.1°)² of the true ones: a relative error below 1e-5).
    let th_max = thetas.iter().map(|t| t.1).fold(f64::NEG_INFINITY, f64::max);
    let rep = r.report(ShaftSpeed::from_rpm(500.0).unwrap()).unwrap();
    assert!((rep.bringer.stroke_mm / (g * (th_max - th_min) * 1e3) - 1.0).abs() < 1e-5, "{}", rep.bringer.stroke_mm);
    // The inner reversing point at 180°, at rest.
    assert!((rep.bringer.inner_deg - 180.0).abs() < 1e-6, "{}", rep.bringer.inner_deg);
    assert!(r.bringer.motion(std::f64::consts::PI).du.abs() < 1e-9);
}

/// Rates against central differences of the next lower one (h = 1e-5 rad).
fn check_rates(d: &HeadDrive, skip: impl Fn(f64) -> bool) {
    let h = 1e-5;
    for k in 0..720 {
        let phi = TAU * (k as f64 + 0.37) / 720.0;
        if skip(phi) {
            continue;
        }
        let (m, p, q) = (d.motion(phi), d.motion(phi + h), d.motion(phi - h));
        let fd1 = (p.u_m - q.u_m) / (2.0 * h);
        let fd2 = (p.du - q.du) / (2.0 * h);
        let fd3 = (p.d2u - q.d2u) / (2.0 * h);
        let scale = [m.du.abs(), m.d2u.abs(), m.d3u.abs()].into_iter().fold(1.0, f64::max);
        assert!((m.du - fd1).abs() < 1e-7 * scale, "{phi}: du {} vs {fd1}", m.du);
        assert!((m.d2u - fd2).abs() < 1e-6 * scale, "{phi}: d2u {} vs {fd2}", m.d2u);
        assert!((m.d3u - fd3).abs() < 1e-5 * scale, "{phi}: d3u {} vs {fd3}", m.d3u);
    }
}

#[test]
fn crank_rates_match_finite_differences() {
    let r = rapier(&crank(150.0), &crank(200.0), 1.9).unwrap();
    check_rates(&r.bringer, |_| false);
    check_rates(&r.taker, |_| false);
}

/// A servo law (cycloidal out over 120°, back over 120°): at rest at both reversing points, the
/// stroke reached at `inner_deg`, rates continuous inside the segments.
#[test]
fn servo_law_reaches_its_stroke_at_the_inner_angle() {
    let servo =
        "drive = \"servo\"\nlaw = \"cycloidal\"\nmotion_deg = 120\nstroke_mm = 1100\nouter_mm = 150\ninner_deg = 190\n";
    let r = rapier(servo, servo, 1.9).unwrap();
    let at = 190f64.to_radians();
    let m = r.bringer.motion(at);
    assert!((m.u_m - 1.1).abs() < 1e-12 && m.du.abs() < 1e-12, "{m:?}");
    // Outside from 310° to 70°: at rest at the outer reversing point.
    for deg in [310.5, 0.0, 69.5] {
        let m = r.bringer.motion(f64::to_radians(deg));
        assert!(m.u_m.abs() < 1e-12 && m.du == 0.0, "{deg}: {m:?}");
    }
    // The segments' joints (70°, 190°, 310°) are skipped by the differences.
    check_rates(&r.bringer, |phi| [70.0f64, 190.0, 310.0].iter().any(|j| (phi - j.to_radians()).abs() < 1e-3));
    // Cycloidal: the tip crosses its selvedge (u = 150 mm) at the same distance from 190° either way.
    let (entry, exit) = r.in_shed(0).unwrap();
    assert!(((at - entry) - (exit - at)).abs() < 1e-9, "{entry} {exit}");
    let rep = r.report(ShaftSpeed::from_rpm(400.0).unwrap()).unwrap();
    // Equal drives and reversing points: the tips meet in the middle, at rest together at the
    // transfer; overlap 2·(1100 − 150) − 1900 = 0 mm.
    assert!(rep.transfer_overlap_mm.abs() < 1e-9, "{}", rep.transfer_overlap_mm);
    // Cycloidal peak speed 2·S/φ_m per rad: 2·1.1/(120° in rad)·ω.
    let w = ShaftSpeed::from_rpm(400.0).unwrap().rad_per_s();
    assert!((rep.peak_head_speed_m_s - 2.0 * 1.1 / 120f64.to_radians() * w).abs() < 1e-9);
    // Peak acceleration 2π·S/φ_m² per rad².
    let a = TAU * 1.1 / 120f64.to_radians().powi(2) * w * w;
    assert!((rep.peak_head_acceleration_m_s2 / a - 1.0).abs() < 1e-9, "{} vs {a}", rep.peak_head_acceleration_m_s2);
}

/// A servo law with parameters (`params`, as a cycle file's segment takes them): the head's peak
/// speed and acceleration are the law's own characteristic values (`Law::metrics`, built directly
/// from the catalogue) scaled by the stroke, the motion angle and the speed, for two ramps.
#[test]
fn servo_law_takes_its_parameters() {
    let w = ShaftSpeed::from_rpm(400.0).unwrap().rad_per_s();
    let phi = 120f64.to_radians();
    let mut peaks = Vec::new();
    for ramp in [0.125, 0.2] {
        let servo = format!(
            "drive = \"servo\"\nlaw = \"modified-trapezoid\"\nparams = {{ ramp = {ramp} }}\nmotion_deg = 120\n\
             stroke_mm = 1100\nouter_mm = 150\ninner_deg = 190\n"
        );
        let rep = rapier(&servo, &servo, 1.9).unwrap().report(ShaftSpeed::from_rpm(400.0).unwrap()).unwrap();
        let law =
            loomkin_laws::LawSpec::parse("modified-trapezoid", &[("ramp", ramp.to_string())]).unwrap().build().unwrap();
        let m = law.metrics();
        assert!((rep.peak_head_speed_m_s / (m.cv * 1.1 / phi * w) - 1.0).abs() < 1e-9, "ramp {ramp}");
        let a = m.ca * 1.1 / (phi * phi) * w * w;
        assert!(
            (rep.peak_head_acceleration_m_s2 / a - 1.0).abs() < 1e-9,
            "ramp {ramp}: {} vs {a}",
            rep.peak_head_acceleration_m_s2
        );
        peaks.push(rep.peak_head_acceleration_m_s2);
    }
    assert!((peaks[0] - peaks[1]).abs() > 1.0, "the ramp changes the law: {peaks:?}");
    // A parameter the law does not take, or out of its range, is refused at `params`.
    let bad = "drive = \"servo\"\nlaw = \"cycloidal\"\nparams = { ramp = 0.2 }\nmotion_deg = 120\nstroke_mm = 1100\n";
    let e = rapier(bad, bad, 1.9).unwrap_err();
    assert!(e.starts_with("insertion.rapier.bringer.params: "), "{e}");
    let bad =
        "drive = \"servo\"\nlaw = \"modified-trapezoid\"\nparams = { ramp = 2 }\nmotion_deg = 120\nstroke_mm = 1100\n";
    let e = rapier(bad, bad, 1.9).unwrap_err();
    assert!(e.starts_with("insertion.rapier.bringer.params: ") && e.contains("ramp"), "{e}");
    let e =
        rapier("drive = \"servo\"\nlaw = \"trapezoid\"\nmotion_deg = 120\nstroke_mm = 1100\n", bad, 1.9).unwrap_err();
    assert!(e.starts_with("insertion.rapier.bringer.law: "), "{e}");
    let e = rapier(&format!("{}params = {{ ramp = 0.2 }}\n", crank(180.0)), &crank(180.0), 1.9).unwrap_err();
    assert_eq!(e, "insertion.rapier.bringer.params: does not go with drive = \"crank\"");
}

/// Equal reversing points and equal drives: the heads mirror each other, the tips meet in the
/// middle of the reed, close at twice one head's speed, and stand still together at the transfer.
#[test]
fn equal_reversing_points_are_symmetric() {
    let r = rapier(&crank(180.0), &crank(180.0), 1.9).unwrap();
    let speed = ShaftSpeed::from_rpm(500.0).unwrap();
    let rep = r.report(speed).unwrap();
    assert!((rep.transfer_position_mm - 950.0).abs() < 1e-6, "{}", rep.transfer_position_mm);
    let v = r.tip(0, rep.meet_deg.to_radians()).du * speed.rad_per_s();
    assert!((rep.transfer_relative_speed_m_s - 2.0 * v).abs() < 1e-9);
    assert!(rep.transfer_speed_m_s.abs() < 1e-6, "{}", rep.transfer_speed_m_s);
    assert!((rep.transfer_deg - 180.0).abs() < 1e-5);
    // overlap = 2·(inner position) − W.
    assert!((rep.transfer_overlap_mm - (2.0 * rep.bringer.inner_position_mm - 1900.0)).abs() < 1e-6);
}

/// Offset reversing points: at the greatest overlap its rate vanishes, so the heads move the same
/// way at the same speed; the overlap is smaller than with equal points.
#[test]
fn offset_reversing_points_hand_over_in_motion() {
    let speed = ShaftSpeed::from_rpm(500.0).unwrap();
    let equal = rapier(&crank(180.0), &crank(180.0), 1.9).unwrap().report(speed).unwrap();
    let r = rapier(&crank(182.0), &crank(178.0), 1.9).unwrap();
    let rep = r.report(speed).unwrap();
    let at = rep.transfer_deg.to_radians();
    assert!(r.overlap(at).1.abs() < 1e-6, "{}", r.overlap(at).1);
    let (b, t) = (r.tip(0, at).du, r.tip(1, at).du);
    assert!((b + t).abs() < 1e-6 && b > 0.0, "{b} {t}");
    assert!(rep.transfer_speed_m_s > 0.1, "{}", rep.transfer_speed_m_s);
    assert!(rep.transfer_overlap_mm < equal.transfer_overlap_mm);
    // A dense scan finds no greater overlap than the refined one.
    let scan = (0..36_000).map(|k| r.overlap(TAU * k as f64 / 36_000.0).0).fold(f64::NEG_INFINITY, f64::max);
    assert!(rep.transfer_overlap_mm >= scan * 1e3 - 1e-9 && rep.transfer_overlap_mm <= scan * 1e3 + 1e-3);
}

#[test]
fn bad_tables_name_their_field() {
    let e = rapier("drive = \"crank\"\nrod_mm = 400\n", &crank(180.0), 1.9).unwrap_err();
    assert_eq!(e, "insertion.rapier.bringer.crank_mm: the crank drive needs crank_mm");
    let e = rapier(&crank(180.0).replace("crank\"", "belt\""), &crank(180.0), 1.9).unwrap_err();
    assert_eq!(e, "insertion.rapier.bringer.drive: 'belt': expected crank, cam or servo");
    let e = rapier(&crank(180.0), &crank(180.0).replace("crank_mm = 100", "crank_mm = 500"), 1.9).unwrap_err();
    assert!(e.starts_with("insertion.rapier.taker.crank_mm: not a crank-rocker"), "{e}");
    let e = rapier(&format!("{}law = \"cycloidal\"\n", crank(180.0)), &crank(180.0), 1.9).unwrap_err();
    assert_eq!(e, "insertion.rapier.bringer.law: does not go with drive = \"crank\"");
    let e = rapier(&crank(360.0), &crank(180.0), 1.9).unwrap_err();
    assert!(e.starts_with("insertion.rapier.bringer.inner_deg = 360 is out of range"), "{e}");
    let e =
        rapier(&crank(180.0), &crank(180.0), 2.2).unwrap().report(ShaftSpeed::from_rpm(300.0).unwrap()).unwrap_err();
    assert!(e.to_string().starts_with("insertion.rapier: the heads never meet"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Any inner angle and offset: the inner reversing point lands where asked, and the
    /// bringer's tip is where the report says when they meet.
    #[test]
    fn inner_angles_land_where_asked(b in 100.0..260.0f64, off in -8.0..8.0f64) {
        let r = rapier(&crank(b), &crank(b + off), 1.9).unwrap();
        let rep = r.report(ShaftSpeed::from_rpm(450.0).unwrap()).unwrap();
        prop_assert!((rep.bringer.inner_deg - b).abs() < 1e-5);
        prop_assert!((rep.taker.inner_deg - (b + off)).abs() < 1e-5);
        let meet = rep.meet_deg.to_radians();
        prop_assert!(r.overlap(meet).0.abs() < 1e-9);
    }
}
