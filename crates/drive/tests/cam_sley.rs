//! The cam-driven sley against independent routes: the reed's rates against finite differences of
//! the sampled law, the cam shaft's torque against the rate of the sley's energy (kinetic and
//! potential, from sampled positions only) plus the beat-up's power, the peak acceleration against
//! the modified-sine law's closed-form coefficient, the phase against a cycle written elsewhere on
//! the turn, and the dwell against a dense scan.

use std::f64::consts::{PI, TAU};

use loomkin_drive::{CamSley, CamSleyTable, Sley, SleyError};
use loomkin_units::{FieldError, STANDARD_GRAVITY_M_S2, ShaftSpeed};

/// The projectile example's cam sley: a 23° swing, back over 80° by modified sine, a dwell, forward
/// over the last 80°.
const TABLE: &str = r#"
drive = "cam"
reed_height_mm = 280
back_angle_deg = 100
mass_kg = 30
gyration_mm = 230
centre_mm = 200
beat_up_force_n = 2000
beat_up_range_deg = 15
arm_mm = 200
pivot_mm = 250
roller_radius_mm = 20
max_pressure_deg = 35

[cycle]
unit = "deg"
stroke = 23

[[cycle.segment]]
kind = "return"
to_deg = 80
law = "modified-sine"

[[cycle.segment]]
kind = "dwell"
to_deg = 280

[[cycle.segment]]
kind = "rise"
to_deg = 360
law = "modified-sine"
"#;

fn table() -> CamSleyTable {
    toml::from_str(TABLE).unwrap()
}

fn sley() -> CamSley {
    CamSley::new(table()).unwrap()
}

/// Central differences of `f` at `x`: first and second derivative, O(h⁴) (5 points).
fn diff(f: &dyn Fn(f64) -> f64, x: f64, h: f64) -> (f64, f64) {
    let (m2, m1, p1, p2) = (f(x - 2.0 * h), f(x - h), f(x + h), f(x + 2.0 * h));
    let d1 = (m2 - 8.0 * m1 + 8.0 * p1 - p2) / (12.0 * h);
    let d2 = (-m2 + 16.0 * m1 - 30.0 * f(x) + 16.0 * p1 - p2) / (12.0 * h * h);
    (d1, d2)
}

/// The angles where the law is smooth (off its joints by more than the stencil's reach).
fn smooth_angles() -> Vec<f64> {
    (0..720)
        .map(|k| (k as f64 * 0.5 + 0.25).to_radians())
        .filter(|p| [0.0_f64, 80.0, 280.0, 360.0].iter().all(|j| (p.to_degrees() - j).abs() > 0.1))
        .collect()
}

#[test]
fn rates_match_finite_differences_of_the_sampled_law() {
    let s = sley();
    let h = s.stroke_m();
    // h = 1e-3 rad: the 5-point stencil's truncation (h⁴·x⁽⁵⁾/30 ≈ 1e-13 of the stroke) is below
    // its rounding (ε·x/h ≈ 1e-13), so 1e-8 of each rate's scale is a safe bound for both.
    let step = 1e-3;
    let x = |p: f64| s.reed(p).x_m;
    let dx = |p: f64| s.reed(p).dx_m;
    let (mut e1, mut e2, mut e3) = (0.0_f64, 0.0_f64, 0.0_f64);
    for p in smooth_angles() {
        let m = s.reed(p);
        let (d1, d2) = diff(&x, p, step);
        let (_, d3) = diff(&dx, p, step);
        e1 = e1.max((d1 - m.dx_m).abs());
        e2 = e2.max((d2 - m.d2x_m).abs());
        e3 = e3.max((d3 - m.d3x_m).abs());
    }
    // Scales: the stroke over the move's angle, to the power of the rate.
    let beta = 80f64.to_radians();
    assert!(e1 < 1e-8 * h / beta, "dx/dφ off by {e1}");
    assert!(e2 < 1e-6 * h / beta.powi(2), "d²x/dφ² off by {e2}");
    assert!(e3 < 1e-6 * h / beta.powi(3), "d³x/dφ³ off by {e3}");
}

#[test]
fn reduced_inertia_and_its_rate_match_the_sampled_swing() {
    let s = sley();
    let j_q = 30.0 * 0.23 * 0.23;
    let h = 0.28;
    for p in smooth_angles() {
        // The sword's angular rate from differences of its sampled angle (not from the law's rates).
        let (w, _) = diff(&|q| s.rocker_rad(q), p, 1e-3);
        let (j, dj) = s.reduced_inertia_kg_m2(p);
        assert!((j - j_q * w * w).abs() < 1e-9 * j_q, "{p}: {j} vs {}", j_q * w * w);
        let (dj_num, _) = diff(&|q| s.reduced_inertia_kg_m2(q).0, p, 1e-3);
        assert!((dj - dj_num).abs() < 1e-7 * j_q, "{p}: {dj} vs {dj_num}");
        // The reed's travel is the arc of the beating point.
        assert!((s.reed(p).dx_m.abs() - h * w.abs()).abs() < 1e-9 * h);
    }
}

/// At constant speed the cam shaft gives the rate of the sley's energy per radian, plus the power
/// the beat-up takes: `T = d/dφ(½·J_Q·θ̇² + m·g₀·y_G) + F·dx/dφ`, every term here from sampled
/// positions (θ(φ) and x(φ)) by differences.
#[test]
fn cam_torque_is_the_rate_of_the_sleys_energy() {
    let s = sley();
    let w = ShaftSpeed::from_rpm(300.0).unwrap().rad_per_s();
    let j_q = 30.0 * 0.23 * 0.23;
    let g = 0.2;
    let step = 1e-3;
    let kinetic = |p: f64| {
        let (th, _) = diff(&|q| s.rocker_rad(q), p, step);
        0.5 * j_q * (th * w).powi(2)
    };
    let potential = |p: f64| 30.0 * STANDARD_GRAVITY_M_S2 * g * s.rocker_rad(p).sin();
    let mut worst = 0.0_f64;
    let mut peak = 0.0_f64;
    for p in smooth_angles() {
        let (dk, _) = diff(&kinetic, p, step);
        let (dv, _) = diff(&potential, p, step);
        let (dx, _) = diff(&|q| s.reed(q).x_m, p, step);
        let expected = dk + dv + s.beat_up_force_n(p) * dx;
        let t = s.forces(p, w).crank_torque_n_m;
        worst = worst.max((t - expected).abs());
        peak = peak.max(t.abs());
    }
    assert!(worst < 1e-6 * peak, "torque off by {worst} N·m of {peak}");
    // Over a turn the inertia and weight terms give back what they take: the net work is the
    // beat-up's (Gauss–Legendre would be exact on the pieces; 0.01° trapezoids on a periodic
    // integrand are within 1e-9 here).
    let n = 36_000;
    let work: f64 =
        (0..n).map(|k| s.forces(k as f64 * TAU / n as f64, w).crank_torque_n_m).sum::<f64>() * TAU / n as f64;
    let beat: f64 = (0..n)
        .map(|k| {
            let p = k as f64 * TAU / n as f64;
            s.beat_up_force_n(p) * s.reed(p).dx_m
        })
        .sum::<f64>()
        * TAU
        / n as f64;
    assert!((work - beat).abs() < 1e-6 * beat.abs().max(1.0), "{work} vs beat-up {beat}");
}

/// The modified sine's peak acceleration coefficient is 4π²/(π + 4) (its eighth-sine ramps): the
/// reed's largest acceleration is that times stroke·ω²/β², at an eighth of the move from its start.
#[test]
fn peak_acceleration_is_the_modified_sines() {
    let s = sley();
    let speed = ShaftSpeed::from_rpm(300.0).unwrap();
    let a = s.analyze(speed, 1.0).unwrap();
    let beta = 80f64.to_radians();
    let ca = 4.0 * PI * PI / (PI + 4.0);
    let expected = ca * s.stroke_m() * speed.rad_per_s().powi(2) / (beta * beta);
    assert!((a.peak_reed_acceleration_m_s2 - expected).abs() < 1e-9 * expected, "{a:?} vs {expected}");
    assert!((a.peak_reed_acceleration_deg - 10.0).abs() < 1e-6 || (a.peak_reed_acceleration_deg - 350.0).abs() < 1e-6);
    // The swing's stroke is the cycle's 23°, the reed's its arc.
    assert!((a.reed_stroke_mm - 280.0 * 23f64.to_radians()).abs() < 1e-9);
    assert_eq!(a.front_dead_centre_deg, 0.0);
    assert!((a.back_dead_centre_deg - 180.0).abs() < 1e-6, "the dwell's middle: {}", a.back_dead_centre_deg);
    assert!((a.min_transmission_angle_deg - (90.0 - a.max_pressure_angle_deg.unwrap())).abs() < 1e-12);
    assert!(a.peak_rod_force_n.is_none() && a.peak_rocking_shaft_force_n.is_some());
}

/// The same law written with its peak at 290° (sley-cycle.toml's layout) is put at the beat-up: the
/// motion is the same at every main-shaft angle.
#[test]
fn the_front_position_is_put_at_the_beat_up() {
    let a = sley();
    let cycle_at = TABLE.find("[[cycle.segment]]").unwrap();
    let shifted = format!(
        "{}{}",
        &TABLE[..cycle_at],
        r#"[[cycle.segment]]
kind = "dwell"
from_deg = 10
to_deg = 210

[[cycle.segment]]
kind = "rise"
to_deg = 290
law = "modified-sine"

[[cycle.segment]]
kind = "return"
to_deg = 370
law = "modified-sine"
"#
    );
    let b = CamSley::new(toml::from_str(&shifted).unwrap()).unwrap();
    assert!((b.phase_deg() - 70.0).abs() < 1e-9, "{}", b.phase_deg());
    for k in 0..360 {
        let p = (k as f64 + 0.3).to_radians();
        let (ma, mb) = (a.reed(p), b.reed(p));
        assert!((ma.x_m - mb.x_m).abs() < 1e-12 && (ma.d2x_m - mb.d2x_m).abs() < 1e-9, "{k}: {ma:?} {mb:?}");
    }
    // A beat-up at 30° moves everything by 30°.
    let mut t = table();
    t.beat_up_deg = 30.0;
    let c = CamSley::new(t).unwrap();
    for k in 0..360 {
        let p = (k as f64 + 0.3).to_radians();
        assert!((c.reed(p + 30f64.to_radians()).x_m - a.reed(p).x_m).abs() < 1e-12);
    }
}

#[test]
fn back_dwell_against_a_dense_scan() {
    let s = sley();
    let tol = 1e-3;
    let (start, end) = s.back_dwell_rad(tol).unwrap();
    for (edge, inside) in [(start, 1.0), (end, -1.0)] {
        assert!((s.reed(edge).x_m - tol).abs() < 1e-15, "{}", s.reed(edge).x_m);
        assert!(s.reed(edge + inside * 1e-9).x_m <= tol && s.reed(edge - inside * 1e-9).x_m > tol);
    }
    // Every point of a 0.001° scan between the ends is within the tolerance.
    let n = ((end - start).to_degrees() * 1000.0) as usize;
    assert!((0..=n).all(|k| s.reed(start + (end - start) * k as f64 / n as f64).x_m <= tol + 1e-15));
    // The exact dwell (200°) and the near-dwell of the two ramps: symmetric about 180°.
    assert!(((start + end) / 2.0 - PI).abs() < 1e-9 && end - start > 200f64.to_radians());
}

#[test]
fn refusals_name_the_field() {
    let bad = |from: &str, to: &str| {
        let t: CamSleyTable = toml::from_str(&TABLE.replacen(from, to, 1)).unwrap();
        CamSley::new(t).unwrap_err()
    };
    let field = |e: &SleyError| e.field().unwrap().to_string();
    assert_eq!(field(&bad("unit = \"deg\"", "unit = \"mm\"")), "sley.cycle.unit");
    assert_eq!(field(&bad("[cycle]\n", "[cycle]\nperiod_deg = 720\n")), "sley.cycle.period_deg");
    assert_eq!(field(&bad("mass_kg = 30", "mass_kg = -1")), "sley.mass_kg");
    assert_eq!(field(&bad("arm_mm = 200", "arm_mm = 0")), "sley.arm_mm");
    assert_eq!(field(&bad("back_angle_deg = 100", "back_angle_deg = 10")), "sley.back_angle_deg");
    assert_eq!(field(&bad("beat_up_range_deg = 15", "beat_up_range_deg = 81")), "sley.beat_up_range_deg");
    let e = bad("to_deg = 360", "to_deg = 350");
    assert!(e.field().unwrap().starts_with("sley.cycle"), "{e}");
    assert!(toml::from_str::<CamSleyTable>(&TABLE.replace("drive = \"cam\"", "drive = \"crank\"")).is_err());
}

#[test]
fn the_sley_enum_is_either() {
    let s: Sley = sley().into();
    assert_eq!(s.kind(), "cam");
    assert!(s.cam().is_some() && s.four_bar().is_none());
    let p = 0.4;
    assert_eq!(s.reduced_inertia_kg_m2(p), sley().reduced_inertia_kg_m2(p));
    assert_eq!(s.load_torque_n_m(p), sley().load_torque_n_m(p));
    // The law's joints and the beat-up model's ends, in the main shaft's turn.
    let mut b: Vec<f64> = s.breaks_rad().iter().map(|x| x.to_degrees()).collect();
    b.sort_by(f64::total_cmp);
    for want in [0.0, 80.0, 280.0, 345.0] {
        assert!(b.iter().any(|x| (x - want).abs() < 1e-9 || (x - want - 360.0).abs() < 1e-9), "{want} in {b:?}");
    }
}

/// The cam's contact force against the sley's balance, every check from sampled positions and the
/// cam's own pitch curve (loomkin-cams), not from the contact's formulas:
/// * the force lies along the pitch curve's normal (the tangent by differences of the cam's points
///   in its own frame, turned into the fixed frame);
/// * the roller stays on the arm, rigid with the sword;
/// * about the rocking shaft, the contact, the beat-up resistance (against the reed's sampled
///   velocity) and the weight give `J_Q·θ̈` (θ̈ by differences of the sword's angle);
/// * the bearing, the contact, the resistance and the weight give `m·a_G` (a_G by differences of
///   the centre of mass's position);
/// * the cam shaft's torque from the contact (`q × F`) is the sley's power over ω (to 1e-9);
/// * the force's sign follows the closure: a conjugate pair's return cam and a groove's outer wall
///   carry the negative part, which a single cam cannot (it loses contact there).
#[test]
fn the_cams_contact_force_balances_the_sley() {
    use loomkin_cams::profile::Curve;
    let w = ShaftSpeed::from_rpm(300.0).unwrap().rad_per_s();
    let (m, j_q, g, h, arm, d) = (30.0, 30.0 * 0.23 * 0.23, 0.2, 0.28, 0.2, 0.25);
    let gravity = [0.0, -m * STANDARD_GRAVITY_M_S2];
    let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
    for closure in ["conjugate", "groove", "single"] {
        let t: CamSleyTable =
            toml::from_str(&TABLE.replace("max_pressure_deg", &format!("closure = \"{closure}\"\nmax_pressure_deg")))
                .unwrap();
        let s = CamSley::new(t).unwrap();
        let q = [d, 0.0];
        let step = 1e-3;
        let peak = smooth_angles().iter().map(|p| s.forces(*p, w).crank_torque_n_m.abs()).fold(0.0, f64::max);
        let (mut most, mut least) = (f64::NEG_INFINITY, f64::INFINITY);
        // Each roller's arm against the sword, at its first angle.
        let mut arm_angle: [Option<f64>; 2] = [None, None];
        for p in smooth_angles() {
            let c = s.contact(p, w);
            let f = s.forces(p, w);
            most = most.max(c.force_n);
            least = least.min(c.force_n);
            assert!(
                (c.on_roller_n[0].hypot(c.on_roller_n[1]) - c.force_n.abs()).abs() <= 1e-9 * c.force_n.abs().max(1.0)
            );
            // The normal: perpendicular to the pitch curve's tangent (differences in the cam frame).
            let cycle_deg = (p.to_degrees() - s.phase_deg()).rem_euclid(360.0);
            let at = |dd: f64| s.cam().point(Curve::Pitch(c.track), cycle_deg + dd);
            let psi = cycle_deg.to_radians();
            let tc = [diff(&|x| at(x)[0], 0.0, 0.01).0, diff(&|x| at(x)[1], 0.0, 0.01).0];
            let tf = [psi.cos() * tc[0] - psi.sin() * tc[1], psi.sin() * tc[0] + psi.cos() * tc[1]];
            if c.force_n.abs() > 1.0 {
                let along =
                    (tf[0] * c.on_roller_n[0] + tf[1] * c.on_roller_n[1]) / (tf[0].hypot(tf[1]) * c.force_n.abs());
                assert!(along.abs() < 1e-8, "{closure} {p}: the force leans {along:e} along the pitch curve");
            }
            // The roller on its arm, the arm rigid with the sword.
            let r = [c.roller_m[0] - q[0], c.roller_m[1] - q[1]];
            assert!((r[0].hypot(r[1]) - arm).abs() < 1e-12);
            let rel = r[1].atan2(r[0]) - s.rocker_rad(p);
            let turn = (rel - *arm_angle[c.track].get_or_insert(rel) + PI).rem_euclid(TAU) - PI;
            assert!(turn.abs() < 1e-9, "{closure} {p}: the arm turned {turn} rad against the sword");
            // Moments about the rocking shaft.
            let (_, th_dd) = diff(&|x| s.rocker_rad(x), p, step);
            let reed = |x: f64| s.joints_m(x).reed;
            let (vx, _) = diff(&|x| reed(x)[0], p, step);
            let (vy, _) = diff(&|x| reed(x)[1], p, step);
            let speed = vx.hypot(vy);
            let resist = if speed > 0.0 {
                [-f.beat_up_force_n * vx / speed, -f.beat_up_force_n * vy / speed]
            } else {
                [0.0, 0.0]
            };
            let rq = [reed(p)[0] - q[0], reed(p)[1] - q[1]];
            let th = s.rocker_rad(p);
            let gq = [g * th.cos(), g * th.sin()];
            let moments = cross(r, c.on_roller_n) + cross(rq, resist) + cross(gq, gravity);
            let need = j_q * th_dd * w * w;
            assert!((moments - need).abs() < 1e-6 * peak, "{closure} {p}: moments {moments} vs J·θ̈ {need}");
            // Forces: the bearing closes m·a_G.
            let centre = |x: f64| {
                let th = s.rocker_rad(x);
                [q[0] + g * th.cos(), q[1] + g * th.sin()]
            };
            let (_, ax) = diff(&|x| centre(x)[0], p, step);
            let (_, ay) = diff(&|x| centre(x)[1], p, step);
            for i in 0..2 {
                let sum = f.rocking_shaft_n[i] + c.on_roller_n[i] + resist[i] + gravity[i];
                let ma = m * [ax, ay][i] * w * w;
                assert!((sum - ma).abs() < 1e-6 * (peak / h), "{closure} {p}: force {i} {sum} vs m·a {ma}");
            }
            // Power: the contact's torque is the sley's.
            assert!(
                (c.cam_torque_n_m - f.crank_torque_n_m).abs() <= 1e-9 * peak,
                "{closure} {p}: {} vs {}",
                c.cam_torque_n_m,
                f.crank_torque_n_m
            );
            assert!((f.crank_bearing_n - c.force_n.abs()).abs() == 0.0);
            if closure == "conjugate" {
                assert_eq!(c.track, usize::from(c.force_n < 0.0), "{p}: {c:?}");
            } else {
                assert_eq!(c.track, 0);
            }
        }
        // The sley is thrown forward and pulled back: both signs occur.
        assert!(most > 0.0 && least < 0.0, "{closure}: {least} … {most}");
        let a = s.analyze(ShaftSpeed::from_rpm(300.0).unwrap(), 1.0).unwrap();
        let (peak_c, min_c) = (a.peak_contact_force_n.unwrap(), a.min_contact_force_n.unwrap());
        // The located extremes reach at least the samples' and are the force where they are said to be.
        assert!(peak_c >= most.max(-least), "{closure}: {peak_c} vs {most} {least}");
        assert!(min_c <= least, "{closure}: {min_c} vs {least}");
        assert!(a.max_contact_force_n.unwrap() >= most && peak_c == a.max_contact_force_n.unwrap().max(-min_c));
        let force_at = |deg: f64| s.contact(deg.to_radians(), w).force_n;
        assert!((force_at(a.peak_contact_force_deg.unwrap()).abs() - peak_c).abs() <= 1e-9 * peak_c);
        assert!((force_at(a.min_contact_force_deg.unwrap()) - min_c).abs() <= 1e-9 * peak_c);
        assert!(a.peak_rocking_shaft_force_n.unwrap() > 0.0);
        assert!(a.contact_force_sign.unwrap().contains(match closure {
            "conjugate" => "return cam",
            "groove" => "outer wall",
            _ => "lifts off",
        }));
    }
}
