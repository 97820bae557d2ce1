//! Cam profiles checked by independent routes: the follower motion re-derived from the working
//! profile alone (roller–profile contact solved numerically), pressure angle and curvature against
//! finite differences of the pitch curve, textbook formulas, sizing against its definition, and
//! proptests over laws and geometries.

use loomkin_cams::profile::{CamDesign, CamProfile, Closure, Curve, Follower, Size};
use loomkin_cams::table::Motion;
use loomkin_laws::{Cycle, CycleSpec, LawSpec, StrokeUnit};
use proptest::prelude::*;

const HEALD: &str = include_str!("../../../examples/heald-frame-cycle.toml");

fn heald() -> Motion {
    Motion::from_cycle(&Cycle::from_toml(HEALD).unwrap())
}

fn rise_return(law: &str, unit: StrokeUnit, stroke: f64, motion_deg: f64) -> Motion {
    let spec =
        CycleSpec::rise_return(&LawSpec::parse::<&str, &str>(law, &[]).unwrap(), unit, stroke, motion_deg).unwrap();
    Motion::from_cycle(&Cycle::new(&spec).unwrap())
}

fn design(follower: Follower, closure: Closure, r: f64, size: Size) -> CamDesign {
    CamDesign { follower, closure, roller_radius_mm: r, size }
}

fn rot(psi: f64, p: [f64; 2]) -> [f64; 2] {
    let (s, c) = psi.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

/// Maximum of a unimodal function near `x0` by golden sections on `[x0 − w, x0 + w]` (values only:
/// independent of the profile's Newton refinement of the derivative's roots).
fn golden_max(f: impl Fn(f64) -> f64, x0: f64, w: f64) -> (f64, f64) {
    let m = loomkin_numeric::golden_max(f, x0 - w, x0 + w);
    (m.at, m.value)
}

/// A profile wall sampled once (in the cam frame), with its parameter (main-shaft deg).
struct Sampled {
    u: Vec<f64>,
    pts: Vec<[f64; 2]>,
    step: f64,
}

fn sample_wall(cam: &CamProfile, wall: usize, n: usize) -> Sampled {
    let (a, b) = cam.range_deg();
    let step = (b - a) / n as f64;
    let u: Vec<f64> = (0..n).map(|i| a + i as f64 * step).collect();
    let pts = u.iter().map(|&x| cam.point(Curve::Wall(wall), x)).collect();
    Sampled { u, pts, step }
}

/// The translating roller's centre height on the line `x = ε` when the cam has turned by `psi`,
/// from the profile alone: the lowest centre whose circle of radius `r` does not cut the profile,
/// `y = max_u [Y(u) + √(r² − (X(u) − ε)²)]` over the rotated profile points `(X, Y)`.
fn roller_height(cam: &CamProfile, wall: usize, sm: &Sampled, psi: f64, eps: f64, r: f64, below: bool) -> f64 {
    let sign = if below { -1.0 } else { 1.0 };
    let f = |p: [f64; 2]| {
        let q = rot(psi, p);
        let dx = q[0] - eps;
        if dx.abs() >= r { f64::NEG_INFINITY } else { sign * q[1] + (r * r - dx * dx).sqrt() }
    };
    let (i, _) = sm
        .pts
        .iter()
        .enumerate()
        .map(|(i, p)| (i, f(*p)))
        .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
    let (_, v) = golden_max(|u| f(cam.point(Curve::Wall(wall), u)), sm.u[i], 1.5 * sm.step);
    sign * v
}

/// Re-derives the lift of a translating roller follower from the profile and compares it with the law.
fn check_translating_contact(cam: &CamProfile, eps: f64, r: f64) -> f64 {
    let rp = cam.prime_radius_mm();
    let d0 = (rp * rp - eps * eps).sqrt();
    let h = cam.stroke();
    let (a, b) = cam.range_deg();
    let sm = sample_wall(cam, 0, 4000);
    let sm2 = (cam.track_count() == 2).then(|| sample_wall(cam, 1, 4000));
    let mut worst: f64 = 0.0;
    for k in 0..73 {
        let deg = a + (b - a) * (k as f64 + 0.37) / 73.0;
        let psi = (deg * 360.0 / (b - a)).to_radians();
        let s_law = cam.lift_at(deg);
        let s = roller_height(cam, 0, &sm, psi, eps, r, false) - d0;
        worst = worst.max((s - s_law).abs() / h);
        if let Some(sm2) = &sm2 {
            // The counter-roller hangs below the centre at y = d0 + s − (2 d0 + H).
            let s2 = roller_height(cam, 1, sm2, psi, eps, r, true) + d0 + h;
            worst = worst.max((s2 - s_law).abs() / h);
        }
    }
    worst
}

#[test]
fn translating_motion_rederived_from_the_profile() {
    for (eps, closure) in [(0.0, Closure::Single), (12.0, Closure::Single), (-7.5, Closure::Conjugate)] {
        let d = design(Follower::Translating { offset_mm: eps }, closure, 10.0, Size::PrimeRadiusMm(80.0));
        let cam = CamProfile::new(&heald(), &d).unwrap();
        let worst = check_translating_contact(&cam, eps, 10.0);
        assert!(worst < 1e-9, "ε = {eps}: lift from the profile off by {worst:e} of the stroke");
    }
}

#[test]
fn oscillating_motion_rederived_from_the_profile() {
    // Swing 20° (cycloidal rise and return over 120° each), arm 100 mm, pivot 120 mm.
    let m = rise_return("cycloidal", StrokeUnit::Deg, 20.0, 120.0);
    let (l, dp, r) = (100.0, 120.0, 8.0);
    for closure in [Closure::Single, Closure::Conjugate] {
        let d = design(Follower::Oscillating { arm_mm: l, pivot_mm: dp }, closure, r, Size::PrimeRadiusMm(45.0));
        let cam = CamProfile::new(&m, &d).unwrap();
        let rp = cam.prime_radius_mm();
        let g0 = ((dp * dp + l * l - rp * rp) / (2.0 * dp * l)).acos();
        let h = 20f64.to_radians();
        let mut worst: f64 = 0.0;
        for wall in 0..cam.walls().len() {
            let sm = sample_wall(&cam, wall, 4000);
            let sigma = if wall == 0 { 1.0 } else { -1.0 };
            for k in 0..37 {
                let deg = 360.0 * (k as f64 + 0.29) / 37.0;
                let psi = deg.to_radians();
                // Roller centre for arm angle γ; its least distance to the rotated profile minus r.
                let gap = |g: f64| {
                    let c = [dp - l * g.cos(), sigma * l * g.sin()];
                    let dist = |p: [f64; 2]| {
                        let q = rot(psi, p);
                        -((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2)).sqrt()
                    };
                    let (i, _) = sm
                        .pts
                        .iter()
                        .enumerate()
                        .map(|(i, p)| (i, dist(*p)))
                        .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
                    let (_, v) = golden_max(|u| dist(cam.point(Curve::Wall(wall), u)), sm.u[i], 1.5 * sm.step);
                    -v - r
                };
                // Bracket around the expected arm angle (of the arm carrying this roller); which γ touches is decided by the contact alone.
                let s_law = cam.lift_at(deg).to_degrees().to_radians();
                let g_law = if wall == 0 { g0 + s_law } else { g0 + h - s_law };
                let (lo, hi) = (g_law - 0.02, g_law + 0.02);
                // g is the angle of the arm that carries this roller: a larger g moves it away from the centre.
                let inward = gap;
                assert!(
                    inward(lo) < 0.0 && inward(hi) > 0.0,
                    "no contact bracket at {deg}°: {} {} {}",
                    inward(lo),
                    inward(g_law),
                    inward(hi)
                );
                let g = loomkin_numeric::bisect(lo, hi, |m| inward(m) < 0.0);
                let s = if wall == 0 { g - g0 } else { g0 + h - g };
                worst = worst.max((s - s_law).abs() / h);
            }
        }
        assert!(worst < 1e-9, "{closure:?}: swing from the profile off by {worst:e} of the stroke");
    }
}

#[test]
fn flat_face_motion_rederived_from_the_profile() {
    let d = design(Follower::Flat, Closure::Single, 0.0, Size::PrimeRadiusMm(120.0));
    let cam = CamProfile::new(&heald(), &d).unwrap();
    let sm = sample_wall(&cam, 0, 4000);
    let mut worst: f64 = 0.0;
    for k in 0..73 {
        let deg = 360.0 * (k as f64 + 0.37) / 73.0;
        let psi = deg.to_radians();
        let f = |p: [f64; 2]| rot(psi, p)[1];
        let (i, _) = sm
            .pts
            .iter()
            .enumerate()
            .map(|(i, p)| (i, f(*p)))
            .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
        let (_, y) = golden_max(|u| f(cam.point(Curve::Wall(0), u)), sm.u[i], 1.5 * sm.step);
        worst = worst.max((y - 120.0 - cam.lift_at(deg)).abs() / cam.stroke());
    }
    assert!(worst < 1e-9, "face height from the profile off by {worst:e} of the stroke");
}

/// Pressure angle and curvature against finite differences of the pitch curve (points only), and
/// the translating formula of the convention, `atan((s′ − ε)/(s + √(R_p² − ε²)))`, with s′ by
/// finite differences of the lift.
#[test]
fn pressure_angle_and_curvature_against_finite_differences() {
    let cases = [
        (heald(), Follower::Translating { offset_mm: 9.0 }, Closure::Conjugate, 6.0, 70.0),
        (
            rise_return("modified-sine", StrokeUnit::Deg, 25.0, 100.0),
            Follower::Oscillating { arm_mm: 90.0, pivot_mm: 110.0 },
            Closure::Conjugate,
            6.0,
            40.0,
        ),
        (heald(), Follower::Flat, Closure::Single, 0.0, 90.0),
    ];
    for (m, f, c, r, rp) in cases {
        let cam = CamProfile::new(&m, &design(f, c, r, Size::PrimeRadiusMm(rp))).unwrap();
        let h = 1e-3; // deg
        for t in 0..cam.track_count() {
            for k in 0..90 {
                let deg = 4.0 * k as f64 + 1.3;
                let e = cam.eval(t, deg);
                let pt = |x: f64| cam.point(Curve::Pitch(t), x);
                let (pm, p0, pp) = (pt(deg - h), pt(deg), pt(deg + h));
                let hr = h.to_radians();
                let d1 = [(pp[0] - pm[0]) / (2.0 * hr), (pp[1] - pm[1]) / (2.0 * hr)];
                let d2 = [(pp[0] - 2.0 * p0[0] + pm[0]) / (hr * hr), (pp[1] - 2.0 * p0[1] + pm[1]) / (hr * hr)];
                let kappa = -(d1[0] * d2[1] - d1[1] * d2[0]) / (d1[0].hypot(d1[1])).powi(3);
                assert!(
                    (kappa - e.curvature_pitch_per_mm).abs() < 1e-6 * (1.0 + kappa.abs()) * 10.0,
                    "{f:?} track {t} at {deg}°: κ {kappa} vs {}",
                    e.curvature_pitch_per_mm
                );
                // the profile's curvature from its own points
                let pr = |x: f64| cam.point(Curve::Wall(cam.walls().iter().position(|w| w.track == t).unwrap()), x);
                let (qm, q0, qp) = (pr(deg - h), pr(deg), pr(deg + h));
                let e1 = [(qp[0] - qm[0]) / (2.0 * hr), (qp[1] - qm[1]) / (2.0 * hr)];
                let e2 = [(qp[0] - 2.0 * q0[0] + qm[0]) / (hr * hr), (qp[1] - 2.0 * q0[1] + qm[1]) / (hr * hr)];
                let kq = -(e1[0] * e2[1] - e1[1] * e2[0]) / (e1[0].hypot(e1[1])).powi(3);
                assert!(
                    (kq - e.curvature_profile_per_mm).abs() < 1e-5 * (1.0 + kq.abs()),
                    "{f:?} at {deg}°: profile κ {kq} vs {}",
                    e.curvature_profile_per_mm
                );
                // the pressure angle from the finite-difference tangent, rotated into the fixed frame
                let psi = deg.to_radians();
                let tf = rot(psi, d1);
                let q = rot(psi, p0);
                let (ev, av) = match f {
                    Follower::Oscillating { arm_mm: l, pivot_mm: d } => {
                        // the direction of the roller's motion: perpendicular to the arm from the pivot (d, 0)
                        let arm = [(q[0] - d) / l, q[1] / l];
                        let sign = if t == 0 { 1.0 } else { -1.0 };
                        let ev = [-arm[1] * -sign, arm[0] * -sign];
                        (ev, [ev[1], -ev[0]])
                    }
                    _ => ([0.0, 1.0], [1.0, 0.0]),
                };
                if f != Follower::Flat {
                    let phi = ((tf[0] * ev[0] + tf[1] * ev[1]) / (tf[0] * av[0] + tf[1] * av[1])).atan().to_degrees();
                    assert!(
                        (phi - e.pressure_angle_deg).abs() < 1e-6,
                        "{f:?} track {t} at {deg}°: φ {phi} vs {}",
                        e.pressure_angle_deg
                    );
                }
                if let Follower::Translating { offset_mm: eps } = f {
                    let ds = (cam.lift_at(deg + h) - cam.lift_at(deg - h)) / (2.0 * hr);
                    let y = (rp * rp - eps * eps).sqrt();
                    let den = if t == 0 { cam.lift_at(deg) + y } else { cam.lift_at(deg) - y - cam.stroke() };
                    let phi = ((ds - eps) / den).atan().to_degrees();
                    assert!(
                        (phi - e.pressure_angle_deg).abs() < 1e-6,
                        "at {deg}°: convention {phi} vs {}",
                        e.pressure_angle_deg
                    );
                }
            }
        }
    }
}

/// The located extremes are never beaten by a dense sample, and a dense sample comes close to them.
#[test]
fn extremes_bound_a_dense_sample() {
    let d = design(Follower::Translating { offset_mm: 5.0 }, Closure::Single, 10.0, Size::PrimeRadiusMm(60.0));
    let cam = CamProfile::new(&heald(), &d).unwrap();
    let (pmax, pat, _) = cam.max_pressure_angle();
    let (rmin, rat) = cam.min_convex_radius_pitch();
    let pts = cam.sample(0, 0.01);
    let smax = pts.iter().map(|p| p.pressure_angle_deg.abs()).fold(0.0, f64::max);
    let kmax = pts.iter().map(|p| p.curvature_pitch_per_mm).fold(0.0, f64::max);
    assert!(smax <= pmax + 1e-12 && pmax - smax < 1e-6, "{pmax} vs {smax}");
    assert!(kmax <= 1.0 / rmin + 1e-15 && 1.0 / rmin - kmax < 1e-8, "{rmin} vs {}", 1.0 / kmax);
    assert!((cam.eval(0, pat).pressure_angle_deg.abs() - pmax).abs() < 1e-12);
    assert!((1.0 / cam.eval(0, rat).curvature_pitch_per_mm - rmin).abs() < 1e-9);
}

/// Textbook formulas, evaluated independently from the law: radial roller follower
/// `ρ = (R² + s′²)^{3/2} / (R² + 2s′² − R s″)`, `R = R_p + s` (Shigley & Uicker, Theory of Machines
/// and Mechanisms, ch. 6; Norton, Design of Machinery, ch. 8); flat-faced follower
/// `ρ = R_b + s + s″` (same sources).
#[test]
fn textbook_curvature_formulas() {
    let m = heald();
    let radial = CamProfile::new(
        &m,
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, 0.0, Size::PrimeRadiusMm(50.0)),
    )
    .unwrap();
    let flat = CamProfile::new(&m, &design(Follower::Flat, Closure::Single, 0.0, Size::PrimeRadiusMm(150.0))).unwrap();
    let h = 1e-3f64;
    for k in 0..120 {
        let deg = 3.0 * k as f64 + 0.7;
        let hr = h.to_radians();
        let (sm, s, sp) = (radial.lift_at(deg - h), radial.lift_at(deg), radial.lift_at(deg + h));
        let (d1, d2) = ((sp - sm) / (2.0 * hr), (sp - 2.0 * s + sm) / (hr * hr));
        let r = 50.0 + s;
        let rho = (r * r + d1 * d1).powf(1.5) / (r * r + 2.0 * d1 * d1 - r * d2);
        let k_lib = radial.eval(0, deg).curvature_pitch_per_mm;
        assert!((1.0 / rho - k_lib).abs() < 1e-6 / 50.0, "radial at {deg}°: {rho} vs {}", 1.0 / k_lib);
        let k_flat = flat.eval(0, deg).curvature_profile_per_mm;
        // s″ by central differences over ±0.01° (rounding ~3e-7 mm, truncation ~3e-5 mm): radii to 1e-4 mm.
        let hf = 0.01f64.to_radians();
        let d2 = (flat.lift_at(deg + 0.01) - 2.0 * s + flat.lift_at(deg - 0.01)) / (hf * hf);
        assert!((150.0 + s + d2 - 1.0 / k_flat).abs() < 1e-4, "flat at {deg}°: {} vs {}", 150.0 + s + d2, 1.0 / k_flat);
    }
}

/// Sizing against its definition: at the least prime radius the largest pressure angle is A, and a
/// hair less radius exceeds it.
#[test]
fn least_prime_radius_meets_the_pressure_angle() {
    let cases = [
        (heald(), Follower::Translating { offset_mm: 0.0 }, Closure::Single, 30.0),
        (heald(), Follower::Translating { offset_mm: 15.0 }, Closure::Conjugate, 25.0),
        (
            rise_return("cycloidal", StrokeUnit::Deg, 20.0, 120.0),
            Follower::Oscillating { arm_mm: 100.0, pivot_mm: 120.0 },
            Closure::Single,
            30.0,
        ),
    ];
    for (m, f, c, a) in cases {
        let cam = CamProfile::new(&m, &design(f, c, 5.0, Size::MaxPressureDeg(a))).unwrap();
        let rp = cam.prime_radius_mm();
        let (pmax, _, _) = cam.max_pressure_angle();
        assert!((pmax - a).abs() < 1e-9, "{f:?}: {pmax}° at R_p {rp}");
        let smaller = CamProfile::new(&m, &design(f, c, 5.0, Size::PrimeRadiusMm(rp * (1.0 - 1e-6)))).unwrap();
        assert!(smaller.max_pressure_angle().0 > a, "{f:?}");
    }
}

/// A target just above the least pressure angle an oscillating follower can reach: the feasible
/// radii are a band narrower than the sizing grid around a minimum of the largest pressure angle.
/// The radius found meets the target (not the rounding of a bracket's midpoint past it), and a
/// hair less radius does not.
#[test]
fn least_prime_radius_in_a_narrow_band() {
    let m = Motion::from_cycle(&Cycle::from_toml(include_str!("../../../examples/sley-cycle.toml")).unwrap());
    let f = Follower::Oscillating { arm_mm: 150.0, pivot_mm: 180.0 };
    // The least largest pressure angle over the prime radius (37.5846732521° at 86.4985905099 mm,
    // as `cam profile` reports when a target below it is refused).
    let least = 37.584_673_252_1;
    for a in [least + 1e-6, least + 1e-4, least + 1e-2] {
        let cam = CamProfile::new(&m, &design(f, Closure::Single, 15.0, Size::MaxPressureDeg(a))).unwrap();
        let rp = cam.prime_radius_mm();
        let (pmax, _, _) = cam.max_pressure_angle();
        assert!(pmax <= a, "{a}°: {pmax}° at R_p {rp}");
        let smaller = CamProfile::new(&m, &design(f, Closure::Single, 15.0, Size::PrimeRadiusMm(rp * (1.0 - 1e-9))));
        if let Ok(smaller) = smaller {
            assert!(smaller.max_pressure_angle().0 > a, "{a}°: a smaller radius meets it too");
        }
    }
    let below = CamProfile::new(&m, &design(f, Closure::Single, 15.0, Size::MaxPressureDeg(least - 1e-6)));
    assert!(below.is_err(), "{least}° − 1e-6 is below the least reachable");
}

#[test]
fn undercut_and_the_largest_roller() {
    // A steep rise (50 mm in 60°) on a small cam: the pitch curve is sharper than the prime circle.
    let m = rise_return("cycloidal", StrokeUnit::Mm, 50.0, 60.0);
    let base = CamProfile::new(
        &m,
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, 1.0, Size::PrimeRadiusMm(40.0)),
    )
    .unwrap();
    let rmax = base.roller_max_mm().unwrap();
    let (rmin, at) = base.min_convex_radius_pitch();
    assert!(rmax == rmin && rmax < 40.0, "{rmax} {rmin}");
    let ok = CamProfile::new(
        &m,
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, rmax * 0.999, Size::PrimeRadiusMm(40.0)),
    )
    .unwrap();
    assert_eq!(ok.undercut_at_deg(), None);
    {
        let bad = CamProfile::new(
            &m,
            &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, rmax * 1.001, Size::PrimeRadiusMm(40.0)),
        )
        .unwrap();
        assert_eq!(bad.undercut_at_deg(), Some(at));
        // Independently: beyond the largest roller the working profile folds back on itself —
        // its tangent reverses where the pitch curve is most curved.
        let t = |x: f64| {
            let (a, b) = (bad.point(Curve::Wall(0), x - 1e-4), bad.point(Curve::Wall(0), x + 1e-4));
            let p = (bad.point(Curve::Pitch(0), x + 1e-4), bad.point(Curve::Pitch(0), x - 1e-4));
            (b[0] - a[0]) * (p.0[0] - p.1[0]) + (b[1] - a[1]) * (p.0[1] - p.1[1])
        };
        assert!(t(at) < 0.0, "the profile should run backwards at the undercut");
    }
}

#[test]
fn groove_walls_are_a_roller_diameter_apart() {
    let cam = CamProfile::new(
        &heald(),
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Groove, 8.0, Size::PrimeRadiusMm(70.0)),
    )
    .unwrap();
    let outer: Vec<[f64; 2]> = (0..36000).map(|i| cam.point(Curve::Wall(1), i as f64 * 0.01)).collect();
    for k in 0..60 {
        let p = cam.point(Curve::Wall(0), 6.0 * k as f64 + 0.5);
        let d = outer.iter().map(|q| (q[0] - p[0]).hypot(q[1] - p[1])).fold(f64::INFINITY, f64::min);
        assert!((d - 16.0).abs() < 1e-4, "{d}");
    }
}

#[test]
fn bad_input_names_the_field() {
    use loomkin_units::FieldError;
    let m = heald();
    let e = |f, c, r, s| CamProfile::new(&m, &design(f, c, r, s)).unwrap_err();
    assert_eq!(
        e(Follower::Translating { offset_mm: 50.0 }, Closure::Single, 5.0, Size::PrimeRadiusMm(40.0)).field(),
        Some("prime_radius_mm")
    );
    assert_eq!(
        e(Follower::Translating { offset_mm: 0.0 }, Closure::Single, 45.0, Size::PrimeRadiusMm(40.0)).field(),
        Some("roller_radius_mm")
    );
    assert_eq!(
        e(Follower::Oscillating { arm_mm: 100.0, pivot_mm: 120.0 }, Closure::Single, 5.0, Size::PrimeRadiusMm(40.0))
            .field(),
        Some("unit")
    );
    assert_eq!(e(Follower::Flat, Closure::Single, 0.0, Size::MaxPressureDeg(30.0)).field(), Some("max_pressure_deg"));
    assert_eq!(
        e(Follower::Translating { offset_mm: 0.0 }, Closure::Single, -1.0, Size::PrimeRadiusMm(40.0)).field(),
        Some("roller_radius_mm")
    );
    let swing = rise_return("cycloidal", StrokeUnit::Deg, 60.0, 120.0);
    let err = CamProfile::new(
        &swing,
        &design(
            Follower::Oscillating { arm_mm: 50.0, pivot_mm: 60.0 },
            Closure::Single,
            2.0,
            Size::PrimeRadiusMm(100.0),
        ),
    )
    .unwrap_err();
    assert_eq!(err.field(), Some("prime_radius_mm"), "{err}");
    let open = Motion::rise(
        &LawSpec::parse::<&str, &str>("cycloidal", &[]).unwrap().build().unwrap(),
        10.0,
        90.0,
        StrokeUnit::Mm,
    )
    .unwrap();
    let err =
        CamProfile::new(&open, &design(Follower::Flat, Closure::Single, 0.0, Size::PrimeRadiusMm(40.0))).unwrap_err();
    assert_eq!(err.field(), Some("segment"), "{err}");
}

const LAWS: [&str; 6] = ["cycloidal", "modified-sine", "modified-trapezoid", "poly345", "poly4567", "harmonic"];

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    /// Any catalogue law, stroke, motion angle, offset and roller: the lift re-derived from the
    /// profile is the law's, and the sized prime circle meets its pressure angle.
    #[test]
    fn any_law_any_geometry(law in 0usize..6, stroke in 5.0f64..60.0, motion in 60.0f64..180.0,
                           eps_frac in -0.3f64..0.3, a in 20.0f64..40.0, r_frac in 0.05f64..0.5) {
        let m = rise_return(LAWS[law], StrokeUnit::Mm, stroke, motion);
        let sized = CamProfile::new(&m, &design(Follower::Translating { offset_mm: eps_frac * stroke }, Closure::Single, 0.0, Size::MaxPressureDeg(a))).unwrap();
        prop_assert!((sized.max_pressure_angle().0 - a).abs() < 1e-9);
        let rp = sized.prime_radius_mm();
        let r = r_frac * sized.roller_max_mm().unwrap();
        let eps = eps_frac * stroke;
        let cam = CamProfile::new(&m, &design(Follower::Translating { offset_mm: eps }, Closure::Conjugate, r, Size::PrimeRadiusMm(rp))).unwrap();
        prop_assert!(cam.undercut_at_deg().is_none());
        let worst = check_translating_contact(&cam, eps, r);
        prop_assert!(worst < 1e-9, "lift off by {:e} of the stroke", worst);
    }
}

/// The drawing through the DXF writer and back through the `dxf` crate: every curve closed, units
/// stated, and the curve within the chord tolerance of its polyline everywhere (a 0.005° sample of
/// the curve against the polyline's segments).
#[test]
fn dxf_drawing_is_closed_within_tolerance_and_in_mm() {
    let cam = CamProfile::new(
        &heald(),
        &design(Follower::Translating { offset_mm: 8.0 }, Closure::Conjugate, 12.0, Size::PrimeRadiusMm(85.0)),
    )
    .unwrap();
    for tol in [0.01, 0.001] {
        let text = cam.dxf(tol, 30.0).unwrap();
        let back = dxf::Drawing::load(&mut text.as_bytes()).unwrap();
        assert_eq!(back.header.default_drawing_units, dxf::enums::Units::Millimeters);
        let curves = [
            ("CAM_PITCH", Curve::Pitch(0)),
            ("CAM_PROFILE", Curve::Wall(0)),
            ("COUNTER_PITCH", Curve::Pitch(1)),
            ("COUNTER_PROFILE", Curve::Wall(1)),
        ];
        for (layer, curve) in curves {
            let e = back.entities().find(|e| e.common.layer == layer).unwrap();
            let dxf::entities::EntityType::LwPolyline(p) = &e.specific else { panic!("{layer} not a polyline") };
            assert!(p.is_closed(), "{layer}");
            let v: Vec<[f64; 2]> = p.vertices.iter().map(|q| [q.x, q.y]).collect();
            let n = v.len();
            let seg_dist = |c: [f64; 2], j: usize| {
                let (a, b) = (v[j % n], v[(j + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let t = (((c[0] - a[0]) * dx + (c[1] - a[1]) * dy) / (dx * dx + dy * dy)).clamp(0.0, 1.0);
                (c[0] - a[0] - t * dx).hypot(c[1] - a[1] - t * dy)
            };
            let mut j = 0;
            let mut worst: f64 = 0.0;
            for i in 0..72_000 {
                let c = cam.point(curve, i as f64 * 0.005);
                while j + 1 < 2 * n && seg_dist(c, j + 1) < seg_dist(c, j) {
                    j += 1;
                }
                worst = worst.max(seg_dist(c, j));
            }
            assert!(worst <= tol * (1.0 + 1e-9), "{layer}: {worst} mm > {tol} mm");
            assert!(worst > 0.2 * tol, "{layer}: {worst} mm — far more points than the tolerance needs");
        }
    }
}

/// Shigley & Uicker, *Theory of Machines and Mechanisms* (cam design chapter, exercise on a radial
/// flat-faced follower): "a disk cam drives a radial flat-faced follower with simple harmonic
/// motion; the follower moves out and back in one revolution; total displacement 50 mm, minimum
/// radius 25 mm — find the contour and the theoretical length of the follower face". The answer
/// in closed form: s = 25 (1 − cos θ) makes the contour the circle of radius 50 mm about
/// (0, −25 mm) — an eccentric, eccentricity 25 mm — of constant radius of curvature 50 mm, and the
/// face must reach 25 mm either side of the line of motion (50 mm).
#[test]
fn textbook_eccentric_flat_faced_cam() {
    let m = rise_return("harmonic", StrokeUnit::Mm, 50.0, 180.0);
    let cam = CamProfile::new(&m, &design(Follower::Flat, Closure::Single, 0.0, Size::PrimeRadiusMm(25.0))).unwrap();
    for k in 0..360 {
        let p = cam.point(Curve::Wall(0), k as f64 + 0.5);
        assert!((p[0].hypot(p[1] + 25.0) - 50.0).abs() < 1e-9, "{p:?}");
    }
    let f = cam.flat_extremes_report().unwrap();
    assert!((f.min_radius_profile_mm - 50.0).abs() < 1e-9);
    assert!((f.face_min_mm + 25.0).abs() < 1e-9 && (f.face_max_mm - 25.0).abs() < 1e-9, "{f:?}");
    assert_eq!(f.least_prime_radius_mm, 0.0);
}

/// The circumcentre of three points.
fn circumcentre(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> [f64; 2] {
    let d = 2.0 * (a[0] * (b[1] - c[1]) + b[0] * (c[1] - a[1]) + c[0] * (a[1] - b[1]));
    let (a2, b2, c2) = (a[0] * a[0] + a[1] * a[1], b[0] * b[0] + b[1] * b[1], c[0] * c[0] + c[1] * c[1]);
    [
        (a2 * (b[1] - c[1]) + b2 * (c[1] - a[1]) + c2 * (a[1] - b[1])) / d,
        (a2 * (c[0] - b[0]) + b2 * (a[0] - c[0]) + c2 * (b[0] - a[0])) / d,
    ]
}

/// The circular-arc cam with a flat-faced follower, a cam "of specified contour" in the textbooks
/// (S. S. Rattan, *Theory of Machines*, and R. S. Khurmi & J. K. Gupta, *Theory of Machines*, cams
/// chapter: circular-arc cam, flat-faced follower). The cam is a base circle of radius r₁, two
/// circular flanks of radius R and a nose of radius r₂; the textbooks state the follower's lift as
/// `x = (R − r₁)(1 − cos θ)` while the face touches the flank and `x = d·cos(α − θ) + r₂ − r₁` while
/// it touches the nose (d: cam centre to nose centre, α: angle of lift), velocity `ω(R − r₁) sin θ`
/// on the flank. Here the two stated lifts are given to loomkin as a law (each piece a pure
/// sinusoidal acceleration, integrated from rest), and the flat-faced cam loomkin synthesises from
/// it must be that very cam: its profile over the flank a circle of radius R whose centre lies
/// R − r₁ from the cam axis, over the nose a circle of radius r₂ centred d from the axis, its radius
/// of curvature R and r₂ there, and the face reaching ±(R − r₁)·sin θ_f (the largest x′, at the
/// flank–nose junction θ_f).
///
/// Geometry (triangle cam axis O, flank centre P, nose centre Q): OP = R − r₁, OQ = d = r₁ + L − r₂,
/// PQ = R − r₂ (the nose touches the flank inside), ∠POQ = 180° − α, so
/// `R = (r₁² + d² − r₂² − 2·d·r₁·cos α) / (2·(r₁ − r₂ − d·cos α))`, and at the junction the face is
/// normal to PQ: `tan θ_f = d·sin α / (R − r₁ + d·cos α)`. Inputs: r₁ = 30 mm, lift L = 20 mm,
/// r₂ = 5 mm, α = 75° (then R = 82.42 mm, θ_f = 34.15°).
#[test]
fn textbook_circular_arc_cam_flat_faced() {
    use loomkin_laws::{AccelPiece, EndCondition, Law, Sine};
    use std::f64::consts::FRAC_PI_2;
    let (r1, lift, r2, alpha_deg) = (30.0f64, 20.0f64, 5.0f64, 75.0f64);
    let alpha = alpha_deg.to_radians();
    let d = r1 + lift - r2;
    let big_r = (r1 * r1 + d * d - r2 * r2 - 2.0 * d * r1 * alpha.cos()) / (2.0 * (r1 - r2 - d * alpha.cos()));
    let theta_f = (d * alpha.sin()).atan2(big_r - r1 + d * alpha.cos());
    let xf = theta_f / alpha;
    // Lift against x = θ/α ∈ [0, 1]: d²x/dx² = α²·d²x/dθ². Flank: (R − r₁)·cos θ; nose: −d·cos(α − θ).
    let rise = Law::from_accel_pieces(
        &[
            AccelPiece::with_sine(
                xf,
                &[0.0],
                Sine { amp: alpha * alpha * (big_r - r1), omega: alpha, phase: FRAC_PI_2 },
            ),
            AccelPiece::with_sine(
                1.0 - xf,
                &[0.0],
                Sine { amp: -alpha * alpha * d, omega: alpha, phase: FRAC_PI_2 - alpha * (1.0 - xf) },
            ),
        ],
        EndCondition::Rest,
        "circular-arc rise",
    )
    .unwrap();
    // The return is the rise mirrored (a symmetric cam): r(x) = 1 − rise(1 − x), nose first.
    let back = Law::from_accel_pieces(
        &[
            AccelPiece::with_sine(1.0 - xf, &[0.0], Sine { amp: alpha * alpha * d, omega: alpha, phase: FRAC_PI_2 }),
            AccelPiece::with_sine(
                xf,
                &[0.0],
                Sine { amp: -alpha * alpha * (big_r - r1), omega: alpha, phase: FRAC_PI_2 - alpha * xf },
            ),
        ],
        EndCondition::Rest,
        "circular-arc return",
    )
    .unwrap();
    // The stated lifts themselves, before any cam is made (the law is normalised to s(1) = 1).
    for k in 0..=200 {
        let th = alpha * k as f64 / 200.0;
        let stated = if th <= theta_f { (big_r - r1) * (1.0 - th.cos()) } else { d * (alpha - th).cos() + r2 - r1 };
        assert!((lift * rise.eval(th / alpha).s - stated).abs() < 1e-9, "lift at {th} rad");
    }
    let m = Motion::from_parts(
        StrokeUnit::Mm,
        &[
            (0.0, alpha_deg, Some(&rise), 0.0, lift),
            (alpha_deg, 2.0 * alpha_deg, Some(&back), lift, -lift),
            (2.0 * alpha_deg, 360.0, None, 0.0, 0.0),
        ],
    )
    .unwrap();
    let cam = CamProfile::new(&m, &design(Follower::Flat, Closure::Single, 0.0, Size::PrimeRadiusMm(r1))).unwrap();
    let tf = theta_f.to_degrees();
    // One arc per contact region, on each side of the nose; its centre from three of its points.
    let arcs = [
        (0.0, tf, big_r, big_r - r1),
        (tf, 2.0 * alpha_deg - tf, r2, d),
        (2.0 * alpha_deg - tf, 2.0 * alpha_deg, big_r, big_r - r1),
    ];
    for (a, b, radius, centre_dist) in arcs {
        let at = |f: f64| cam.point(Curve::Wall(0), a + f * (b - a));
        let c = circumcentre(at(0.01), at(0.5), at(0.99));
        assert!((c[0].hypot(c[1]) - centre_dist).abs() < 1e-9, "arc {a}…{b}°: centre {c:?}");
        for k in 0..=100 {
            let p = at(k as f64 / 100.0);
            assert!(((p[0] - c[0]).hypot(p[1] - c[1]) - radius).abs() < 1e-9, "arc {a}…{b}° at {k}: {p:?}");
            let q = cam.eval(0, a + (k as f64 / 100.0).clamp(1e-6, 1.0 - 1e-6) * (b - a));
            assert!((1.0 / q.curvature_profile_per_mm - radius).abs() < 1e-8 * radius, "ρ at {}°", q.angle_deg);
        }
    }
    // The base circle between the lifts.
    for k in 0..=50 {
        let p = cam.point(Curve::Wall(0), 2.0 * alpha_deg + (360.0 - 2.0 * alpha_deg) * k as f64 / 50.0);
        assert!((p[0].hypot(p[1]) - r1).abs() < 1e-9);
    }
    let f = cam.flat_extremes_report().unwrap();
    let reach = (big_r - r1) * theta_f.sin();
    assert!((f.face_max_mm - reach).abs() < 1e-9 && (f.face_min_mm + reach).abs() < 1e-9, "{f:?} vs ±{reach}");
    assert!((f.min_radius_profile_mm - r2).abs() < 1e-9, "{f:?}");
    assert!((big_r - 82.42).abs() < 5e-3 && (tf - 34.15).abs() < 5e-3, "R = {big_r}, θ_f = {tf}");
}

/// An extreme next to a dwell joint, where the derivative of the pressure angle vanishes with s′ and s″:
/// a translating follower offset 10 mm on a prime circle of 10.000001 mm has its largest |φ| 0.051°
/// before the end of the heald cycle's return. Against the textbook formula
/// `φ = arctan((s′ − ε)/(√(R_p² − ε²) + s))` evaluated from the law (`Cycle::eval`, at 1 rad/s so
/// that the velocity is ds/dθ) and maximised by golden sections: the same value and place. (The
/// rounded derivative at the joint hid the bracket: 89.97437655° at 0° was reported.)
#[test]
fn pressure_angle_peak_next_to_a_dwell_joint() {
    let cycle = Cycle::from_toml(HEALD).unwrap();
    let (eps, rp) = (10.0, 10.000001);
    let d = design(Follower::Translating { offset_mm: eps }, Closure::Single, 0.0, Size::PrimeRadiusMm(rp));
    let cam = CamProfile::new(&heald(), &d).unwrap();
    let (pmax, pat, _) = cam.max_pressure_angle();
    let y0 = (rp * rp - eps * eps).sqrt();
    let rpm = 60.0 / std::f64::consts::TAU;
    let phi = |deg: f64| {
        let k = cycle.eval(deg.to_radians(), rpm);
        ((k.v * 1e3 - eps) / (y0 + k.s * 1e3)).atan().to_degrees().abs()
    };
    let (at, want) = golden_max(phi, 359.95, 0.04);
    assert!((pmax - want).abs() < 1e-9 * want, "{pmax} at {pat}° vs {want} at {at}°");
    assert!((pat - at).abs() < 1e-4, "{pmax} at {pat}° vs {want} at {at}°");
    let sampled = cam.sample(0, 0.001).iter().map(|p| p.pressure_angle_deg.abs()).fold(0.0, f64::max);
    assert!(sampled <= pmax, "{sampled} sampled above the located {pmax}");
}

/// A steep cam: a 40 mm cycloidal rise over 0.01° on a 70 mm prime circle (ds/dψ up to 4.6e5 mm/rad).
/// The pitch curve's sharpest convex bend lies 3e-4 of the motion before its end, between the law's
/// grid points and next to a milder one the grid does see. Against the textbook radial-follower
/// radius `ρ = (R² + s′²)^{3/2}/(R² + 2s′² − R·s″)`, R = R_p + s, from the law (`Cycle::eval` at 1 rad/s)
/// on a 4000-point scan of the rise's last 5 % and golden sections: the same least radius and place.
/// (The grid alone gave 0.0514 mm at 0.0098°; the least is 9.305e-5 mm at 0.009967°.)
#[test]
fn steep_cam_sharpest_bend_is_found() {
    let spec = CycleSpec::rise_return(&LawSpec::Cycloidal, StrokeUnit::Mm, 40.0, 0.01).unwrap();
    let cycle = Cycle::new(&spec).unwrap();
    let cam = CamProfile::new(
        &Motion::from_cycle(&cycle),
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, 0.0, Size::PrimeRadiusMm(70.0)),
    )
    .unwrap();
    let (rmin, at) = cam.min_convex_radius_pitch();
    let rpm = 60.0 / std::f64::consts::TAU;
    let kappa = |deg: f64| {
        let k = cycle.eval(deg.to_radians(), rpm);
        let (s, d1, d2) = (k.s * 1e3, k.v * 1e3, k.a * 1e3);
        let r = 70.0 + s;
        (r * r + 2.0 * d1 * d1 - r * d2) / (r * r + d1 * d1).powf(1.5)
    };
    let (lo, hi) = (0.0095, 0.01);
    let step = (hi - lo) / 4000.0;
    let best = (0..4000).map(|i| lo + step * (i as f64 + 0.5)).max_by(|a, b| kappa(*a).total_cmp(&kappa(*b))).unwrap();
    let (x, kmax) = golden_max(kappa, best, step);
    let want = 1.0 / kmax;
    // The return (from 180°) is the rise mirrored in time: the least radius is reached on both.
    let at_rise = if at >= 180.0 { 0.01 - (at - 180.0) } else { at };
    assert!((rmin - want).abs() < 1e-9 * want, "{rmin} mm at {at}° vs {want} mm at {x}°");
    assert!((at_rise - x).abs() < 1e-7, "{rmin} mm at {at}° vs {want} mm at {x}°");
}

/// A conjugate pair reports each cam's own extremes (issue 27: an asymmetric cycle's pair
/// reported the counter-cam's 26.25° as its one pressure angle, the cam's own 23.30° nowhere):
/// each against the cam's points sampled every 0.01° (an independent route: the grid's largest
/// |pressure angle| and least convex radius), and the pair's keys as the larger / smaller of the two.
#[test]
fn a_conjugate_pair_reports_each_cam() {
    let asymmetric = Cycle::from_toml(
        "unit = \"mm\"\nstroke = 60\n[[segment]]\nkind = \"rise\"\nto_deg = 100\nlaw = \"cycloidal\"\n\
         [[segment]]\nkind = \"dwell\"\nto_deg = 150\n[[segment]]\nkind = \"return\"\nto_deg = 330\n\
         law = \"poly345\"\n[[segment]]\nkind = \"dwell\"\nto_deg = 360\n",
    )
    .unwrap();
    let cases = [
        (Motion::from_cycle(&asymmetric), Follower::Translating { offset_mm: 10.0 }, 80.0),
        (heald(), Follower::Translating { offset_mm: 9.0 }, 70.0),
        (
            rise_return("modified-sine", StrokeUnit::Deg, 25.0, 100.0),
            Follower::Oscillating { arm_mm: 90.0, pivot_mm: 110.0 },
            40.0,
        ),
    ];
    for (m, f, rp) in cases {
        let cam = CamProfile::new(&m, &design(f, Closure::Conjugate, 6.0, Size::PrimeRadiusMm(rp))).unwrap();
        let report = cam.report("t", 1.0);
        let cams = report.cams.clone().unwrap();
        assert_eq!(cams.iter().map(|c| c.cam).collect::<Vec<_>>(), ["cam", "counter"]);
        for (t, c) in cams.iter().enumerate() {
            let pts = cam.sample(t, 0.01);
            let (p, at) = pts
                .iter()
                .map(|q| (q.pressure_angle_deg.abs(), q.angle_deg))
                .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
            assert!(
                c.max_pressure_angle_deg >= p - 1e-9 && c.max_pressure_angle_deg - p < 1e-4,
                "track {t}: {} vs {p}",
                c.max_pressure_angle_deg
            );
            assert!(
                (c.max_pressure_angle_at_deg - at).abs() < 0.02,
                "track {t}: at {} vs {at}",
                c.max_pressure_angle_at_deg
            );
            let kmax = pts.iter().map(|q| q.curvature_pitch_per_mm).fold(f64::NEG_INFINITY, f64::max);
            assert!(
                c.min_convex_radius_pitch_mm <= 1.0 / kmax + 1e-9
                    && (c.min_convex_radius_pitch_mm * kmax - 1.0).abs() < 1e-4,
                "track {t}"
            );
            assert_eq!(c.min_convex_radius_profile_mm, Some(c.min_convex_radius_pitch_mm - 6.0));
        }
        let e = report.extremes;
        assert_eq!(e.max_pressure_angle_deg, cams[0].max_pressure_angle_deg.max(cams[1].max_pressure_angle_deg));
        assert_eq!(
            e.min_convex_radius_pitch_mm,
            cams[0].min_convex_radius_pitch_mm.min(cams[1].min_convex_radius_pitch_mm)
        );
        assert_eq!(report.counter_max_pressure_angle_deg, Some(cams[1].max_pressure_angle_deg));
    }
    // An oscillating pair of an asymmetric cycle: each cam's largest angle is at its own place
    // (the pair's, before the only one reported, is the counter-cam's).
    let swing = Cycle::from_toml(
        "unit = \"deg\"\nstroke = 25\n[[segment]]\nkind = \"rise\"\nto_deg = 100\nlaw = \"cycloidal\"\n\
         [[segment]]\nkind = \"dwell\"\nto_deg = 150\n[[segment]]\nkind = \"return\"\nto_deg = 330\n\
         law = \"poly345\"\n[[segment]]\nkind = \"dwell\"\nto_deg = 360\n",
    )
    .unwrap();
    let cam = CamProfile::new(
        &Motion::from_cycle(&swing),
        &design(
            Follower::Oscillating { arm_mm: 90.0, pivot_mm: 110.0 },
            Closure::Conjugate,
            6.0,
            Size::PrimeRadiusMm(40.0),
        ),
    )
    .unwrap();
    let cams = cam.cam_reports().unwrap();
    assert!((cams[0].max_pressure_angle_at_deg - cams[1].max_pressure_angle_at_deg).abs() > 1.0, "{cams:?}");
    assert_eq!(cam.max_pressure_angle().0, cams[0].max_pressure_angle_deg.max(cams[1].max_pressure_angle_deg));
    // A single cam has no `cams`.
    let single = CamProfile::new(
        &heald(),
        &design(Follower::Translating { offset_mm: 0.0 }, Closure::Single, 6.0, Size::PrimeRadiusMm(70.0)),
    )
    .unwrap();
    assert!(single.cam_reports().is_none() && single.report("t", 1.0).cams.is_none());
}

/// Each cam's extremes from the written points alone: the pressure angle from the pitch curve's
/// tangent (central differences of the points) and the follower's direction of motion at the
/// trace point, the least convex radius from the circle through three consecutive points.
/// `(max |φ| deg, at deg, least convex radius mm, at deg)` of one track's points, `dir(q)` the
/// direction of motion of a trace point at `q` in the fixed frame.
fn extremes_from_points(pts: &[loomkin_cams::profile::PointReport], dir: impl Fn([f64; 2]) -> [f64; 2]) -> [f64; 4] {
    // One turn, the last point (360°) repeating the first.
    let n =
        if (pts[pts.len() - 1].angle_deg - pts[0].angle_deg - 360.0).abs() < 1e-9 { pts.len() - 1 } else { pts.len() };
    let p = |i: usize| [pts[i % n].x_mm, pts[i % n].y_mm];
    let (mut phi, mut phi_at, mut rmin, mut rmin_at) = (0.0f64, 0.0, f64::INFINITY, 0.0);
    for i in 0..n {
        let (a, b, c) = (p(i + n - 1), p(i), p(i + 1));
        let psi = pts[i].angle_deg.to_radians();
        // The tangent and the trace point in the fixed frame (the cam frame turned back by ψ).
        let t = rot(psi, [c[0] - a[0], c[1] - a[1]]);
        let q = rot(psi, b);
        let e = dir(q);
        let en = e[0].hypot(e[1]);
        let sin = ((t[0] * e[0] + t[1] * e[1]) / (t[0].hypot(t[1]) * en)).abs();
        let deg = sin.min(1.0).asin().to_degrees();
        if deg > phi {
            (phi, phi_at) = (deg, pts[i].angle_deg);
        }
        // Circumradius of a, b, c; convex where the clockwise-traced curve turns clockwise.
        let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
        let cross = u[0] * v[1] - u[1] * v[0];
        if cross < 0.0 {
            let w = [c[0] - a[0], c[1] - a[1]];
            let r = u[0].hypot(u[1]) * v[0].hypot(v[1]) * w[0].hypot(w[1]) / (2.0 * cross.abs());
            if r < rmin {
                (rmin, rmin_at) = (r, pts[i].angle_deg);
            }
        }
    }
    [phi, phi_at, rmin, rmin_at]
}

/// A conjugate pair whose two cams differ (issue 27: the pair reported one angle, the counter-cam's):
/// an asymmetric rise (acceleration over the first 30 %, deceleration over 70 %) makes the cam's
/// and the counter-cam's pressure angles and least radii differ, for a translating offset follower
/// and for a swinging arm. Each cam's reported maximum pressure angle, least convex pitch radius
/// and their places are checked against [`extremes_from_points`], from the written points alone.
/// Tolerances: the points are h = 0.01° apart, so a place is found to the grid: within half a step
/// of the library's refined place, checked to one step (measured: at most 0.0039°). The central
/// difference's error in the tangent is O(h²) ≈ 1e-8 rad and the grid's maximum lies within
/// (h/2)²·|φ''| of the true one, so the angle is checked to 1e-5° (measured: at most 2.2e-6°, the
/// grid's maximum below the refined one); the three-point radius has an O(h²) relative error,
/// checked to 1e-6 (measured: at most 4.2e-8). Measured values: translating, cam 30.3206° at
/// 230.25°, counter-cam 34.5039° at 212.87°, radii 51.720 and 48.707 mm; swinging arm, 33.8311° at
/// 244.50° and 40.5475° at 209.52°, radii 33.520 and 34.686 mm.
#[test]
fn each_cam_of_an_asymmetric_conjugate_pair_has_its_own_extremes() {
    let level = format!("{}", -0.3 / 0.7);
    let segments = format!("0.3:sine-arc:1,0.7:sine-arc:{level}");
    let law = LawSpec::parse("piecewise", &[("segments", segments.as_str())]).unwrap();
    let motion = |unit, stroke| {
        Motion::from_cycle(&Cycle::new(&CycleSpec::rise_return(&law, unit, stroke, 120.0).unwrap()).unwrap())
    };
    let (eps, arm, pivot) = (10.0, 90.0, 110.0);
    let cases = [
        (motion(StrokeUnit::Mm, 40.0), Follower::Translating { offset_mm: eps }, 60.0),
        (motion(StrokeUnit::Deg, 20.0), Follower::Oscillating { arm_mm: arm, pivot_mm: pivot }, 40.0),
    ];
    for (m, f, rp) in cases {
        let cam = CamProfile::new(&m, &design(f, Closure::Conjugate, 6.0, Size::PrimeRadiusMm(rp))).unwrap();
        let report = cam.report("asymmetric", 0.01);
        let cams = report.cams.clone().unwrap();
        let tracks = [&report.points, report.counter_points.as_ref().unwrap()];
        let mut found = Vec::new();
        for (c, pts) in cams.iter().zip(tracks) {
            let x = match f {
                Follower::Translating { .. } => {
                    // The trace point runs on the line x = ε.
                    assert!(
                        pts.iter().all(|p| (rot(p.angle_deg.to_radians(), [p.x_mm, p.y_mm])[0] - eps).abs() < 1e-9)
                    );
                    extremes_from_points(pts, |_| [0.0, 1.0])
                }
                _ => {
                    // The trace point runs on the circle of the arm about the pivot (d, 0); it moves
                    // at right angles to the arm.
                    for p in pts.iter() {
                        let q = rot(p.angle_deg.to_radians(), [p.x_mm, p.y_mm]);
                        assert!(((q[0] - pivot).hypot(q[1]) - arm).abs() < 1e-9);
                    }
                    extremes_from_points(pts, |q| [-q[1], q[0] - pivot])
                }
            };
            assert!(
                (c.max_pressure_angle_deg - x[0]).abs() < 1e-5,
                "{f:?} {}: {} vs {}",
                c.cam,
                c.max_pressure_angle_deg,
                x[0]
            );
            assert!(
                (c.max_pressure_angle_at_deg - x[1]).abs() < 0.01,
                "{f:?} {}: at {} vs {}",
                c.cam,
                c.max_pressure_angle_at_deg,
                x[1]
            );
            assert!(
                ((c.min_convex_radius_pitch_mm - x[2]) / x[2]).abs() < 1e-6,
                "{f:?} {}: {} vs {}",
                c.cam,
                c.min_convex_radius_pitch_mm,
                x[2]
            );
            assert!(
                (c.min_convex_radius_pitch_at_deg - x[3]).abs() < 0.01,
                "{f:?} {}: at {} vs {}",
                c.cam,
                c.min_convex_radius_pitch_at_deg,
                x[3]
            );
            found.push(x);
        }
        // The two cams differ: the point of reporting each.
        assert!((found[0][0] - found[1][0]).abs() > 1.0, "{f:?}: pressure angles {found:?}");
        assert!((found[0][2] - found[1][2]).abs() > 1.0, "{f:?}: radii {found:?}");
        // The pair's figures are the worse cam's, and the counter-cam's own are reported as such.
        assert_eq!(
            report.extremes.max_pressure_angle_deg,
            cams[0].max_pressure_angle_deg.max(cams[1].max_pressure_angle_deg)
        );
        assert_eq!(report.counter_max_pressure_angle_deg, Some(cams[1].max_pressure_angle_deg));
        assert_eq!(report.counter_max_pressure_angle_at_deg, Some(cams[1].max_pressure_angle_at_deg));
    }
}
