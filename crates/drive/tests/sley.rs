//! The sley's closed forms against independent routes: the loop solved numerically, derivatives
//! by finite differences, the crank torque by virtual work, energy over a revolution.

use std::f64::consts::{PI, TAU};

use loomkin_drive::{Assembly, FourBarSley, SleyError, SleyTable};
use loomkin_units::{FieldError, ShaftSpeed};
use proptest::prelude::*;

/// A shuttle-loom-like sley: the sword stands up from a rocking shaft below and behind the crank
/// centre, the rod about horizontal.
fn table() -> SleyTable {
    SleyTable {
        crank_mm: 50.0,
        rod_mm: 250.0,
        sword_mm: 500.0,
        pivot_x_mm: -250.0,
        pivot_y_mm: -480.0,
        reed_height_mm: 600.0,
        mass_kg: 25.0,
        gyration_mm: 450.0,
        centre_mm: Some(400.0),
        beat_up_deg: 0.0,
        beat_up_force_n: 0.0,
        beat_up_range_deg: 0.0,
        assembly: Assembly::Left,
    }
}

fn sley() -> FourBarSley {
    FourBarSley::new(table()).unwrap()
}

/// The rocker angle at main-shaft angle φ by a numerical solve of the loop: the roots in θ of
/// `|Q + c·e(θ) − A|² − b²` (every root on [θ₀, θ₀ + 2π) by sign changes and Newton,
/// loomkin_numeric::grid_roots), the one on the branch `kappa` (B to the left of Q→A for +1).
/// Independent of the closed form: no triangle angle, no atan2 of the loop.
fn theta_numeric(t: &SleyTable, phase: f64, phi: f64) -> f64 {
    let branch = FourBarSley::new(*t).unwrap().branch();
    let mm = 1e-3;
    let (r, b, c, qx, qy) = (t.crank_mm * mm, t.rod_mm * mm, t.sword_mm * mm, t.pivot_x_mm * mm, t.pivot_y_mm * mm);
    let alpha = phi + phase;
    let (ax, ay) = (r * alpha.cos(), r * alpha.sin());
    let start = 0.123;
    let f = |u: f64| {
        let th = start + u;
        let (ex, ey) = (qx + c * th.cos() - ax, qy + c * th.sin() - ay);
        (ex * ex + ey * ey - b * b, 2.0 * c * (-ex * th.sin() + ey * th.cos()))
    };
    let kappa = if branch == Assembly::Left { 1.0 } else { -1.0 };
    let mut found = None;
    loomkin_numeric::grid_roots(TAU, 64, f, |u| {
        let th = start + u;
        let (bx, by) = (qx + c * th.cos(), qy + c * th.sin());
        let cross = (ax - qx) * (by - qy) - (ay - qy) * (bx - qx);
        if cross * kappa > 0.0 {
            found = Some(th);
        }
    });
    found.expect("the loop closes")
}

/// The crank phase of a sley: its crank angle at φ = 0.
fn phase(s: &FourBarSley) -> f64 {
    s.crank_rad(0.0)
}

/// Angle difference wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

/// Five-point central difference: error h⁴·f⁽⁵⁾/30 from truncation, about 1.5·ε·|f|/h from rounding.
fn fd(f: impl Fn(f64) -> f64, x: f64, h: f64) -> f64 {
    (f(x - 2.0 * h) - 8.0 * f(x - h) + 8.0 * f(x + h) - f(x + 2.0 * h)) / (12.0 * h)
}

/// The step of the finite differences: 1e-3 rad. The rocker's rates are of order 0.1 … 1 and
/// change on the scale of a radian, so the truncation error is about (1e-3)⁴ ≈ 1e-12 of the rate
/// and the rounding error about 1.5·ε·|θ|/h ≈ 5e-13 (|θ| ≤ 2π): below 1e-9 of the rates' scale
/// with three orders of margin. A larger step raises the first, a smaller one the second.
const H: f64 = 1e-3;

#[test]
fn the_closed_form_solves_the_loop_as_a_numerical_solve_does() {
    for t in [table(), mirrored()] {
        let s = FourBarSley::new(t).unwrap();
        let mut worst: f64 = 0.0;
        for i in 0..360 {
            let phi = (i as f64 + 0.37).to_radians();
            let st = s.state(phi);
            let num = theta_numeric(&t, phase(&s), phi);
            worst = worst.max(wrap(st.rocker_rad - num).abs());
            // The rod closes the loop: |B − A| = b.
            let (r, b, c) = (t.crank_mm * 1e-3, t.rod_mm * 1e-3, t.sword_mm * 1e-3);
            let (bx, by) =
                (t.pivot_x_mm * 1e-3 + c * st.rocker_rad.cos(), t.pivot_y_mm * 1e-3 + c * st.rocker_rad.sin());
            let (ax, ay) = (r * st.crank_rad.cos(), r * st.crank_rad.sin());
            assert!(((bx - ax).hypot(by - ay) - b).abs() < 1e-15, "closure at {i}°");
            assert!((bx - ax - b * st.rod_rad.cos()).abs() < 1e-15 && (by - ay - b * st.rod_rad.sin()).abs() < 1e-15);
        }
        assert!(worst < 1e-14, "closed form vs numerical loop: {worst:e} rad");
    }
}

/// The mirror image of [`table`] about the vertical through the crank centre (rocking shaft in
/// front), assembled on the other branch; the crank still turns counter-clockwise, so the motion
/// is not simply mirrored.
fn mirrored() -> SleyTable {
    SleyTable { pivot_x_mm: 250.0, assembly: Assembly::Right, ..table() }
}

#[test]
fn rates_agree_with_finite_differences_of_the_numerical_solve() {
    for t in [table(), mirrored()] {
        let s = FourBarSley::new(t).unwrap();
        let p = phase(&s);
        let sts: Vec<_> = (0..72).map(|i| s.state((5.0 * i as f64 + 0.21).to_radians())).collect();
        let scale = |f: &dyn Fn(&loomkin_drive::SleyState) -> f64| sts.iter().map(|x| f(x).abs()).fold(0.0, f64::max);
        let (s1, s2, s3) = (scale(&|x| x.rocker_d1), scale(&|x| x.rocker_d2), scale(&|x| x.rocker_d3));
        let (r1, r2) = (scale(&|x| x.rod_d1), scale(&|x| x.rod_d2));
        for st in &sts {
            let phi = st.phi_rad;
            // θ' from the numerical loop solve: the closed form's θ is not used.
            let d1 = fd(|x| theta_numeric(&t, p, x), phi, H);
            assert!((d1 - st.rocker_d1).abs() < 1e-9 * s1, "θ' at {phi}: {d1} vs {}", st.rocker_d1);
            // Each higher rate against the difference of the one below.
            let d2 = fd(|x| s.state(x).rocker_d1, phi, H);
            assert!((d2 - st.rocker_d2).abs() < 1e-9 * s2, "θ'' at {phi}: {d2} vs {}", st.rocker_d2);
            let d3 = fd(|x| s.state(x).rocker_d2, phi, H);
            assert!((d3 - st.rocker_d3).abs() < 1e-9 * s3, "θ''' at {phi}: {d3} vs {}", st.rocker_d3);
            let b1 = fd(|x| s.state(x).rod_rad, phi, H);
            assert!((b1 - st.rod_d1).abs() < 1e-9 * r1, "β' at {phi}");
            let b2 = fd(|x| s.state(x).rod_d1, phi, H);
            assert!((b2 - st.rod_d2).abs() < 1e-9 * r2, "β'' at {phi}");
            // The reed's rates are h·σ times the rocker's, and x its arc.
            let m = s.reed(phi);
            let dx = fd(|x| s.reed(x).x_m, phi, H);
            assert!((dx - m.dx_m).abs() < 1e-9 * s1 * 0.6);
        }
    }
}

#[test]
fn dead_centres_are_where_crank_and_rod_are_collinear() {
    for t in [table(), mirrored(), SleyTable { beat_up_deg: 17.5, ..table() }] {
        let s = FourBarSley::new(t).unwrap();
        let front = s.front_dead_centre_rad();
        assert!((front - t.beat_up_deg.to_radians()).abs() < 1e-15);
        for (phi, x) in [(front, s.stroke_m()), (s.back_dead_centre_rad(), 0.0)] {
            let st = s.state(phi);
            // Collinear: sin(β − α) = 0, so θ' = 0.
            assert!(st.rocker_d1.abs() < 1e-14, "θ' = {} at {phi}", st.rocker_d1);
            assert!((s.reed(phi).x_m - x).abs() < 1e-15, "{} vs {x}", s.reed(phi).x_m);
            // The root of θ' found numerically (Newton on θ', bracketed) is the closed-form angle.
            let root = loomkin_numeric::refine_root(phi - 0.2, phi + 0.2, s.state(phi - 0.2).rocker_d1 < 0.0, |x| {
                let st = s.state(x);
                (st.rocker_d1, st.rocker_d2)
            });
            assert!((root - phi).abs() < 1e-12, "{root} vs {phi}");
        }
        // The stroke is the largest displacement, reached nowhere else.
        for i in 0..3600 {
            let x = s.reed(i as f64 * TAU / 3600.0).x_m;
            assert!(x >= -1e-15 && x <= s.stroke_m() + 1e-15);
        }
    }
}

#[test]
fn up_and_down_pick_the_branch_by_the_swords_height() {
    assert_eq!(FourBarSley::new(SleyTable { assembly: Assembly::Up, ..table() }).unwrap().branch(), Assembly::Left);
    assert_eq!(FourBarSley::new(SleyTable { assembly: Assembly::Down, ..table() }).unwrap().branch(), Assembly::Right);
    assert_eq!(FourBarSley::new(SleyTable { assembly: Assembly::Up, ..mirrored() }).unwrap().branch(), Assembly::Right);
    // Up: the sword's pin lies above the rocking shaft at both dead centres.
    for t in [table(), mirrored()] {
        let s = FourBarSley::new(SleyTable { assembly: Assembly::Up, ..t }).unwrap();
        for phi in [s.front_dead_centre_rad(), s.back_dead_centre_rad()] {
            assert!(s.state(phi).rocker_rad.sin() > 0.9);
        }
    }
}

#[test]
fn the_reference_sley_moves_as_its_dimensions_say() {
    let s = sley();
    // The sword's pin swings about 2r: a stroke of about 2r·h/c = 120 mm.
    let stroke = s.stroke_m() * 1e3;
    assert!((stroke - 120.0).abs() < 5.0, "{stroke}");
    // The back dead centre is the folded one, with the longer dwell: 180° + a few degrees after beat-up.
    let back = s.back_dead_centre_rad().to_degrees();
    assert!(back > 170.0 && back < 200.0, "{back}");
    assert!(s.min_transmission_rad().to_degrees() > 60.0);
}

#[test]
fn the_least_transmission_angle_is_the_closed_forms() {
    for t in [table(), mirrored()] {
        let s = FourBarSley::new(t).unwrap();
        let m = loomkin_numeric::scan_max(0.0, TAU, 720, |p| -s.transmission_rad(p));
        assert!((-m.value - s.min_transmission_rad()).abs() < 1e-12, "{} vs {}", -m.value, s.min_transmission_rad());
    }
}

#[test]
fn crank_torque_by_virtual_work_and_energy_over_a_revolution() {
    let t = SleyTable { beat_up_force_n: 3000.0, beat_up_range_deg: 20.0, beat_up_deg: 10.0, ..table() };
    let s = FourBarSley::new(t).unwrap();
    let w = ShaftSpeed::from_rpm(400.0).unwrap().rad_per_s();
    let h = t.reed_height_mm * 1e-3;
    let n = 4096;
    let (mut e_inertia, mut e_abs) = (0.0, 0.0);
    for i in 0..n {
        let phi = TAU * i as f64 / n as f64;
        let f = s.forces(phi, w);
        // Virtual work: the moment the sley needs about its shaft, times θ' (by finite
        // differences of the numerical loop solve), is the crank torque of the force analysis.
        let theta_d1 = fd(|x| theta_numeric(&t, phase(&s), x), phi, H);
        let st = s.state(phi);
        let sigma = (s.reed(phi).dx_m / (h * st.rocker_d1)).signum();
        // The weight's moment about the rocking shaft: m·g₀ times the centre of mass's lever arm.
        let weight = t.mass_kg * G0 * t.centre_mm.unwrap() * 1e-3 * st.rocker_rad.cos();
        let moment = s.inertia_kg_m2() * st.rocker_d2 * w * w + sigma * f.beat_up_force_n * h + weight;
        let virtual_work = moment * theta_d1;
        assert!(
            (virtual_work - f.crank_torque_n_m).abs() < 1e-9 * (1.0 + f.crank_torque_n_m.abs()),
            "{phi}: {virtual_work} vs {}",
            f.crank_torque_n_m
        );
        // The inertia torque is ½·dJ/dφ·ω², dJ/dφ by finite differences of J.
        let dj = fd(|x| s.reduced_inertia_kg_m2(x).0, phi, H);
        assert!((0.5 * dj * w * w - f.inertia_torque_n_m).abs() < 1e-9 * (1.0 + f.inertia_torque_n_m.abs()));
        assert!((s.reduced_inertia_kg_m2(phi).1 - dj).abs() < 1e-9 * (1.0 + dj.abs()));
        // The load torque is the beat-up resistance and the weight by power balance.
        assert!((f.load_torque_n_m - s.load_torque_n_m(phi)).abs() < 1e-9 * (1.0 + f.load_torque_n_m.abs()));
        e_inertia += f.inertia_torque_n_m;
        e_abs += f.inertia_torque_n_m.abs();
    }
    // The trapezoid rule on a smooth periodic integrand converges geometrically: the inertia part
    // returns every joule it takes.
    assert!(e_inertia.abs() < 1e-9 * e_abs, "{e_inertia} of {e_abs}");
}

#[test]
fn the_beat_up_resistance_does_work_and_is_the_model() {
    let t = SleyTable { beat_up_force_n: 2000.0, beat_up_range_deg: 30.0, ..table() };
    let s = FourBarSley::new(t).unwrap();
    assert_eq!(s.beat_up_force_n(0.0), 2000.0);
    assert!((s.beat_up_force_n((-15f64).to_radians()) - 1000.0).abs() < 1e-9);
    assert_eq!(s.beat_up_force_n((-31f64).to_radians()), 0.0);
    assert_eq!(s.beat_up_force_n(1e-9), 0.0);
    // The work over a revolution is ∫F dx: positive, and at most F_max times the travel in the range.
    let n = 200_000;
    let work: f64 = (0..n).map(|i| s.load_torque_n_m(TAU * (i as f64 + 0.5) / n as f64)).sum::<f64>() * TAU / n as f64;
    let travel = s.stroke_m() - s.reed((-30f64).to_radians()).x_m;
    assert!(work > 0.0 && work < 2000.0 * travel, "{work} vs {travel}");
    // Without a range there is no resistance: only the weight's torque is left.
    let none = FourBarSley::new(table()).unwrap();
    assert_eq!(none.load_torque_n_m(0.01), s.load_torque_n_m(0.01));
    assert!(none.load_torque_n_m(-0.01) < s.load_torque_n_m(-0.01));
}

/// Standard gravity, m/s².
const G0: f64 = 9.80665;

#[test]
fn the_weight_is_conservative_and_its_torque_the_rate_of_potential_energy() {
    for t in [table(), mirrored(), SleyTable { centre_mm: None, ..table() }] {
        let s = FourBarSley::new(t).unwrap();
        let g = t.centre_mm.unwrap_or(t.gyration_mm) * 1e-3;
        let p = phase(&s);
        // V(φ) = m·g₀·y_G with the centre of mass on the numerically solved sword.
        let v = |x: f64| t.mass_kg * G0 * (t.pivot_y_mm * 1e-3 + g * theta_numeric(&t, p, x).sin());
        let n = 2048;
        let (mut sum, mut abs) = (0.0, 0.0);
        for i in 0..n {
            let phi = TAU * i as f64 / n as f64;
            let load = s.load_torque_n_m(phi);
            let dv = fd(v, phi, H);
            assert!((load - dv).abs() < 1e-9 * (1.0 + dv.abs()), "{phi}: {load} vs dV/dφ {dv}");
            sum += load;
            abs += load.abs();
        }
        assert!(sum.abs() < 1e-9 * abs, "{sum} of {abs}");
        // At rest (ω → 0) the rocking shaft and the rod hold the weight alone.
        let f = s.forces(0.7, 0.0);
        let beta = s.state(0.7).rod_rad;
        assert!((f.rocking_shaft_n[0] - f.rod_force_n * beta.cos()).abs() < 1e-9 * t.mass_kg * G0);
        assert!((f.rocking_shaft_n[1] - f.rod_force_n * beta.sin() - t.mass_kg * G0).abs() < 1e-9 * t.mass_kg * G0);
    }
}

#[test]
fn the_rocking_shaft_carries_the_centre_of_mass_acceleration() {
    let t = table();
    let s = FourBarSley::new(t).unwrap();
    let w = 40.0;
    let g = t.centre_mm.unwrap() * 1e-3;
    let p = phase(&s);
    for i in 0..36 {
        let phi = (10.0 * i as f64 + 3.0).to_radians();
        let f = s.forces(phi, w);
        // Force balance of the whole mechanism (crank and rod massless): the frame's forces at the
        // crank bearing (−N·e(β)) and the rocking shaft equal m·a_G less the weight, a_G by finite
        // differences of the centre of mass on the numerically solved rocker.
        let gx = |x: f64| g * theta_numeric(&t, p, x).cos();
        let gy = |x: f64| g * theta_numeric(&t, p, x).sin();
        let dd = |f: &dyn Fn(f64) -> f64| fd(|x| fd(f, x, H), phi, H) * w * w;
        let beta = s.state(phi).rod_rad;
        let fx = f.rocking_shaft_n[0] - f.rod_force_n * beta.cos();
        let fy = f.rocking_shaft_n[1] - f.rod_force_n * beta.sin();
        let (ax, ay) = (dd(&gx), dd(&gy));
        let scale = t.mass_kg * g * w * w;
        // The frame also carries the weight, m·g₀ up.
        assert!((fx - t.mass_kg * ax).abs() < 1e-6 * scale, "{fx} vs {}", t.mass_kg * ax);
        assert!((fy - t.mass_kg * (ay + G0)).abs() < 1e-6 * scale, "{fy} vs {}", t.mass_kg * (ay + G0));
    }
}

#[test]
fn the_back_dwell_is_where_the_reed_stays_within_the_tolerance() {
    for t in [table(), mirrored(), SleyTable { beat_up_deg: 300.0, ..table() }] {
        let s = FourBarSley::new(t).unwrap();
        let tol = 1e-3;
        let (a, b) = s.back_dwell_rad(tol).unwrap();
        assert!(b > a && b - a < PI);
        assert!((s.reed(a).x_m - tol).abs() < 1e-15 && (s.reed(b).x_m - tol).abs() < 1e-15);
        // An independent route: bisection on the numerical loop solve's displacement.
        let p = phase(&s);
        let h = t.reed_height_mm * 1e-3;
        let theta_back = s.state(s.back_dead_centre_rad()).rocker_rad;
        let x = |phi: f64| h * wrap(theta_numeric(&t, p, phi) - theta_back).abs();
        let mid = s.back_dead_centre_rad() + TAU * ((a - s.back_dead_centre_rad()) / TAU).round();
        let a2 = loomkin_numeric::bisect(mid - PI / 2.0, mid, |q| x(q) > tol);
        let b2 = loomkin_numeric::bisect(mid, mid + PI / 2.0, |q| x(q) <= tol);
        assert!((a - a2).abs() < 1e-10 && (b - b2).abs() < 1e-10, "{a} {a2} {b} {b2}");
        // Tolerances outside (0, stroke) are refused with the range.
        let e = s.back_dwell_rad(s.stroke_m()).unwrap_err();
        assert_eq!(e.field(), Some("dwell_tolerance_mm"));
    }
}

#[test]
fn the_analysis_reports_exact_extremes() {
    let s = sley();
    let speed = ShaftSpeed::from_rpm(240.0).unwrap();
    let a = s.analyze(speed, 1.0).unwrap();
    let w = speed.rad_per_s();
    let n = 36_000;
    let (mut fmax, mut fmin, mut tmax, mut amax) = (f64::MIN, f64::MAX, 0.0f64, 0.0f64);
    for i in 0..n {
        let phi = TAU * i as f64 / n as f64;
        let f = s.forces(phi, w);
        fmax = fmax.max(f.inertia_force_n);
        fmin = fmin.min(f.inertia_force_n);
        tmax = tmax.max(f.crank_torque_n_m.abs());
        amax = amax.max(s.reed(phi).acceleration_m_s2(w).abs());
    }
    // A 0.01° grid never beats the located extremes, and comes within its resolution of them.
    for (got, grid) in [
        (a.max_inertia_force_n, fmax),
        (-a.min_inertia_force_n, -fmin),
        (a.peak_crank_torque_n_m, tmax),
        (a.peak_reed_acceleration_m_s2, amax),
    ] {
        assert!(got >= grid - 1e-9 * got.abs() && got - grid < 1e-6 * got.abs(), "{got} vs grid {grid}");
    }
    // The inertia force at the reed is J·θ̈·σ/h: at front dead centre the sley decelerates.
    assert!(a.min_inertia_force_n < 0.0 && a.max_inertia_force_n > 0.0);
    assert!((a.min_inertia_force_deg - 0.0).abs() < 10.0 || (a.min_inertia_force_deg - 360.0).abs() < 10.0);
    assert_eq!(a.reed_stroke_mm, s.stroke_m() * 1e3);
    assert!(a.back_dwell_deg > 15.0 && a.back_dwell_deg < 90.0, "{}", a.back_dwell_deg);
}

#[test]
fn infeasible_linkages_are_refused_naming_their_fields() {
    let cases: [(SleyTable, &str); 5] = [
        (SleyTable { crank_mm: 600.0, ..table() }, "sley.crank_mm, sley.pivot_x_mm, sley.pivot_y_mm"),
        (
            SleyTable { rod_mm: 30.0, ..table() },
            "sley.crank_mm, sley.rod_mm, sley.sword_mm, sley.pivot_x_mm, sley.pivot_y_mm",
        ),
        (
            SleyTable { rod_mm: 1000.0, ..table() },
            "sley.crank_mm, sley.rod_mm, sley.sword_mm, sley.pivot_x_mm, sley.pivot_y_mm",
        ),
        (SleyTable { crank_mm: -1.0, ..table() }, "sley.crank_mm = -1"),
        (SleyTable { centre_mm: Some(500.0), ..table() }, "sley.centre_mm = 500"),
    ];
    for (t, fields) in cases {
        let e = FourBarSley::new(t).unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with(fields), "{text}");
        assert!(!text.contains('\n'));
    }
    let e = FourBarSley::new(SleyTable { rod_mm: 30.0, ..table() }).unwrap_err();
    assert!(e.to_string().contains("pointing away from the rocking shaft"), "{e}");
    let e = FourBarSley::new(SleyTable { rod_mm: 1000.0, ..table() }).unwrap_err();
    assert!(e.to_string().contains("pointing toward the rocking shaft"), "{e}");
    assert!(matches!(e, SleyError::Infeasible { ref fields, .. } if fields.starts_with("sley.crank_mm, sley.rod_mm")));
    assert_eq!(e.field(), Some("sley.crank_mm"));
    // The loop's limit itself is refused (rod and sword collinear there): d + r = b + c exactly.
    let d = 250f64.hypot(480.0);
    let e = FourBarSley::new(SleyTable { rod_mm: d + 50.0 - 500.0, ..table() }).unwrap_err();
    assert!(e.to_string().contains("pointing"), "{e}");
    // A beat-up range beyond the forward stroke.
    let e = FourBarSley::new(SleyTable { beat_up_range_deg: 200.0, beat_up_force_n: 10.0, ..table() }).unwrap_err();
    assert_eq!(e.field(), Some("sley.beat_up_range_deg"), "{e}");
}

#[test]
fn the_table_round_trips_through_toml_and_refuses_unknown_keys() {
    let text = "crank_mm = 50\nrod_mm = 250\nsword_mm = 500\npivot_x_mm = -250\npivot_y_mm = -480\n\
                reed_height_mm = 600\nmass_kg = 25\ngyration_mm = 450\n";
    let s: FourBarSley = toml::from_str(text).unwrap();
    assert_eq!(s.table().beat_up_deg, 0.0);
    assert_eq!(s.table().assembly, Assembly::Up);
    let back: FourBarSley = toml::from_str(&toml::to_string(&s).unwrap()).unwrap();
    assert_eq!(back, s);
    let e = toml::from_str::<FourBarSley>(&format!("{text}colour = 3\n")).unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
    let e = toml::from_str::<FourBarSley>(&text.replace("crank_mm = 50", "crank_mm = 900")).unwrap_err();
    assert!(e.to_string().contains("crank_mm"), "{e}");
}

/// Random crank-rockers: lengths drawn, kept when the exact conditions hold.
fn linkage() -> impl Strategy<Value = SleyTable> {
    (10.0..100.0f64, 100.0..800.0f64, 100.0..800.0f64, -800.0..800.0f64, -800.0..800.0f64, any::<bool>(), 0.0..360.0f64)
        .prop_filter_map("a crank-rocker", |(r, b, c, px, py, left, beat)| {
            let t = SleyTable {
                crank_mm: r,
                rod_mm: b,
                sword_mm: c,
                pivot_x_mm: px,
                pivot_y_mm: py,
                reed_height_mm: 1.2 * c,
                mass_kg: 10.0,
                gyration_mm: c,
                centre_mm: None,
                beat_up_deg: beat,
                beat_up_force_n: 0.0,
                beat_up_range_deg: 0.0,
                assembly: [Assembly::Left, Assembly::Right, Assembly::Up, Assembly::Down]
                    [usize::from(left) + 2 * usize::from(beat > 180.0)],
            };
            // Keep clear of the toggle, where the rates (and their differences) blow up.
            FourBarSley::new(t).ok().filter(|s| s.min_transmission_rad() > 0.2).map(|_| t)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_crank_rockers_close_and_their_rates_match(t in linkage(), phi in 0.0..TAU) {
        let s = FourBarSley::new(t).unwrap();
        let st = s.state(phi);
        let (r, b, c) = (t.crank_mm * 1e-3, t.rod_mm * 1e-3, t.sword_mm * 1e-3);
        let (bx, by) = (t.pivot_x_mm * 1e-3 + c * st.rocker_rad.cos(), t.pivot_y_mm * 1e-3 + c * st.rocker_rad.sin());
        let (ax, ay) = (r * st.crank_rad.cos(), r * st.crank_rad.sin());
        prop_assert!(((bx - ax).hypot(by - ay) - b).abs() < 1e-12 * b);
        let num = theta_numeric(&t, phase(&s), phi);
        prop_assert!(wrap(st.rocker_rad - num).abs() < 1e-12);
        // Rates: scale is the largest over a turn.
        let sts: Vec<_> = (0..90).map(|i| s.state(i as f64 * TAU / 90.0)).collect();
        let s1 = sts.iter().map(|x| x.rocker_d1.abs()).fold(st.rocker_d1.abs(), f64::max);
        let s2 = sts.iter().map(|x| x.rocker_d2.abs()).fold(st.rocker_d2.abs(), f64::max);
        let s3 = sts.iter().map(|x| x.rocker_d3.abs()).fold(st.rocker_d3.abs(), f64::max);
        let d1 = fd(|x| theta_numeric(&t, phase(&s), x), phi, H);
        prop_assert!((d1 - st.rocker_d1).abs() < 1e-9 * s1, "θ' {} vs {}", d1, st.rocker_d1);
        let d2 = fd(|x| s.state(x).rocker_d1, phi, H);
        prop_assert!((d2 - st.rocker_d2).abs() < 1e-9 * s2, "θ'' {} vs {}", d2, st.rocker_d2);
        let d3 = fd(|x| s.state(x).rocker_d2, phi, H);
        prop_assert!((d3 - st.rocker_d3).abs() < 1e-9 * s3, "θ''' {} vs {}", d3, st.rocker_d3);
        // The dead centres: θ' = 0, the stroke between them.
        prop_assert!(s.state(s.front_dead_centre_rad()).rocker_d1.abs() < 1e-12 * s1);
        prop_assert!(s.state(s.back_dead_centre_rad()).rocker_d1.abs() < 1e-12 * s1);
        prop_assert!((s.reed(s.front_dead_centre_rad()).x_m - s.stroke_m()).abs() < 1e-12 * s.stroke_m());
    }
}

/// A published example: J. T. Taylor, *Cotton Weaving and Designing*, 6th ed. (1909; Project
/// Gutenberg #57031), the chapter on the eccentricity of the slay: with a 12-inch crank-arm and
/// (as the figures imply: 12 − √(12² − 3²) = 0·3811) a 3-inch crank, the connecting pin travels
/// 3·3811 inches while the crank turns from front to top centre and 2·6189 inches from top to back
/// centre. Taylor takes the pin along the line of centres (a slider-crank); the four-bar tends to
/// it as the sword grows, its pin's sag below the line going as 1/c, so the travel at c = 2.5, 5 and
/// 10 m extrapolated to c → ∞ (Richardson, two steps) is compared with the book's four decimals and
/// with the slider-crank's closed form.
/// A four-bar sley whose sword (`c`, mm) is long against its crank `r` and rod `b` (mm): the sword's
/// pin moves nearly on the line of centres, as a slider-crank's slider (Taylor's and the textbooks'
/// model of the slay).
fn long_sword_sley(r: f64, b: f64, c: f64) -> FourBarSley {
    let t = SleyTable {
        crank_mm: r,
        rod_mm: b,
        sword_mm: c,
        pivot_x_mm: b,
        pivot_y_mm: -c,
        reed_height_mm: c,
        mass_kg: 1.0,
        gyration_mm: c,
        centre_mm: None,
        beat_up_deg: 0.0,
        beat_up_force_n: 0.0,
        beat_up_range_deg: 0.0,
        assembly: Assembly::Up,
    };
    FourBarSley::new(t).unwrap()
}

/// `f` at c = 2.5, 5 and 10 m extrapolated to c → ∞: two Richardson steps in h = 1/c (errors
/// A·h + B·h²; the four-bar's pin sags below the line of centres as 1/c).
fn long_sword_limit(f: &dyn Fn(f64) -> f64) -> f64 {
    let (f1, f2, f4) = (f(2500.0), f(5000.0), f(10000.0));
    let (r1, r2) = (2.0 * f2 - f1, 2.0 * f4 - f2);
    (4.0 * r2 - r1) / 3.0
}

#[test]
fn taylors_slay_eccentricity_figures() {
    let inch = 25.4;
    let (r, b) = (3.0 * inch, 12.0 * inch);
    let travel = |c: f64| {
        let s = long_sword_sley(r, b, c);
        let pin_x = |phi: f64| b + c * s.state(phi).rocker_rad.cos();
        let front = s.front_dead_centre_rad();
        let (x0, x90, x180) = (pin_x(front), pin_x(front + PI / 2.0), pin_x(front + PI));
        ((x0 - x90) / inch, (x90 - x180) / inch)
    };
    let limit = long_sword_limit;
    let (front_to_top, top_to_back) = (limit(&|c| travel(c).0), limit(&|c| travel(c).1));
    let (a2, b2) = travel(10000.0);
    // One unit of the book's last place: it takes √135 as 11·6189 (4 decimals) before subtracting,
    // so its figures carry that rounding (the exact travel is 3·381050, which rounds to 3·3810).
    assert!((front_to_top - 3.3811).abs() < 1e-4, "{front_to_top} (c = 10 m: {a2})");
    assert!((top_to_back - 2.6189).abs() < 1e-4, "{top_to_back} (c = 10 m: {b2})");
    // The slider-crank's closed form, to which the four-bar tends: r + b − √(b² − r²).
    let exact = (r + b - (b * b - r * r).sqrt()) / inch;
    // Residual of the extrapolation (third order in 1/c): 2e-7 inch measured.
    assert!((front_to_top - exact).abs() < 1e-6, "{front_to_top} vs {exact}");
}

/// The textbooks' sley acceleration, `f = ω²·r·(cos θ + (r/l)·cos 2θ)` (θ the crank angle from the
/// front centre, `r` the crank, `l` the crank arm): the form given for the slay's motion in weaving
/// texts and lecture notes (e.g. "Beat up Motion", §8 "Expression of Sley Displacement, Velocity and
/// Acceleration", https://ar.scribd.com/document/307325777/Slay-Mechanism), the first two terms of
/// the slider-crank's series. On Taylor's 3-inch crank and 12-inch arm (r/l = ¼) the exact four-bar,
/// its sword long (extrapolated as for Taylor's figures), meets it at the front and back centres,
/// where the two terms are exact (`ω²r(1 ± r/l)`), and everywhere within the series' next terms,
/// `(r/l)³/4·(cos 2θ − cos 4θ)`, which leave a fifth-order rest. No published beat-up
/// *force* example with numbers was found (drive4's search: the shared papers, the reference pages);
/// the force is this acceleration times the sley's mass, which the virtual-work tests above check.
#[test]
fn the_textbook_sley_acceleration_is_the_four_bars_series() {
    let inch = 25.4;
    let (r, l) = (3.0 * inch, 12.0 * inch);
    let lambda = r / l;
    // The pin's acceleration along the line of centres per (rad of crank)², mm, toward the fell
    // positive: x = l + c·cos θ_rocker, x″ = −c·(cos θ·θ′² + sin θ·θ″).
    let accel = |c: f64, theta: f64| {
        let s = long_sword_sley(r, l, c);
        let st = s.state(s.front_dead_centre_rad() + theta);
        let th = st.rocker_rad;
        -c * (th.cos() * st.rocker_d1 * st.rocker_d1 + th.sin() * st.rocker_d2)
    };
    let mut worst: f64 = 0.0;
    for k in 0..72 {
        let theta = k as f64 * TAU / 72.0;
        let exact = long_sword_limit(&|c| accel(c, theta));
        // The textbook's two terms, decelerating toward the front (x″ = −f/ω²).
        let textbook = -r * (theta.cos() + lambda * (2.0 * theta).cos());
        let next = -r * lambda.powi(3) / 4.0 * ((2.0 * theta).cos() - (4.0 * theta).cos());
        if k == 0 || k == 36 {
            // Front and back centres: ω²r(1 + r/l) and ω²r(1 − r/l) exactly (the next terms vanish).
            assert!((exact - textbook).abs() < 1e-6 * r, "θ = {theta}: {exact} vs {textbook}");
        }
        worst = worst.max((exact - textbook - next).abs() / r);
        // Without the next terms the two-term formula is within (r/l)³/2 of r, plus the fifth-order
        // terms (~0.3·(r/l)⁵ = 0.02·(r/l)³ here).
        assert!((exact - textbook).abs() <= 0.55 * lambda.powi(3) * r, "θ = {theta}: {exact} vs {textbook}");
    }
    // What is left is fifth order in r/l (~0.3·(r/l)⁵ = 3e-4 of r) and the extrapolation's residual.
    eprintln!("largest |exact − two terms − next terms| {worst:.2e} of r");
    assert!(worst < 5e-4, "{worst:e}");
}
