//! Checks shared by analysis and synthesis: pressure angles, curvature, closure, self-intersection.

use super::kinematics::ModulatorState;
use super::refine::{Extreme, Revolution, first_failure};
use crate::planar::{Vec2, cross, wrap_pi};
use serde::Serialize;
use std::f64::consts::PI;

/// What a [`Warning`] is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum WarningCode {
    /// A pressure angle above the limit set in the options.
    PressureAngle,
    /// The roller radius exceeds a cam's smallest radius of curvature: the groove wall is undercut.
    Undercut,
    /// A roller-centre curve or a groove wall crosses itself.
    SelfIntersection,
    /// A roller-centre curve has a stationary point (cusp).
    Cusp,
    /// The counter-cam roller's arm becomes normal to its cam (pressure angle 90°): Γ′ cannot hold
    /// the lever there, though cam Γ still drives it.
    CounterCamFold,
}

/// A condition the user can still go on with, located at an input angle where it applies.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Warning {
    /// Kind.
    pub code: WarningCode,
    /// Input angle φ2 (deg) of the worst point, if located (absent from JSON otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phi2_deg: Option<f64>,
    /// The condition with its numbers and the admissible range.
    pub message: String,
}

/// Pressure angle (deg, 0…90) at a roller: the angle between the cam normal (the line of the
/// contact force) and the roller centre's velocity relative to the input crank, which is normal to
/// the lever arm. `cos μ = |t̂ · û|` with `t̂` the cam tangent and `û` the arm direction; below
/// 45° computed as `μ = arcsin |t̂ × û|` (the arccosine loses digits near 0°, where `cos μ` is
/// flat; the arcsine near 90°), so that μ is exact to rounding at every size. A stationary tangent
/// (cusp) gives 90°.
pub fn roller_pressure_angle_deg(tangent: Vec2, arm: Vec2) -> f64 {
    let (nt, na) = (tangent.norm(), arm.norm());
    let usable = nt > 1e-300 && na > 1e-300 && nt.is_finite() && na.is_finite();
    if !usable {
        return 90.0;
    }
    let n = nt * na;
    let (c, s) = (tangent.dot(&arm).abs() / n, cross(tangent, arm).abs() / n);
    if s < c { s.asin() } else { c.min(1.0).acos() }.to_degrees()
}

/// `tan μ` of [`roller_pressure_angle_deg`] (+∞ where μ is 90°): `|t × u| / |t · u|`, in the order of
/// μ and without its inverse sine or cosine, for choosing the grid's largest pressure angles.
pub(crate) fn roller_pressure_order(tangent: Vec2, arm: Vec2) -> f64 {
    let (nt, na) = (tangent.norm(), arm.norm());
    let usable = nt > 1e-300 && na > 1e-300 && nt.is_finite() && na.is_finite();
    let r = cross(tangent, arm).abs() / tangent.dot(&arm).abs();
    if usable && !r.is_nan() { r } else { f64::INFINITY }
}

/// Pressure angle (deg, 0…90) at the output: the slot pushes slider 5 normal to the slot,
/// direction `e⊥(φ3)`, while D moves along `e⊥(φ6)`: `μ6 = arccos |cos(φ3 − φ6)|`, the distance
/// from `φ3 − φ6` to the nearest multiple of π, computed as that distance (no cosine and
/// arccosine of it).
pub fn output_pressure_angle_deg(phi3: f64, phi6: f64) -> f64 {
    let d = phi3 - phi6;
    let r = d - PI * crate::planar::round(d / PI);
    r.abs().min(std::f64::consts::FRAC_PI_2).to_degrees()
}

/// The slot deviation `δ = φ3 − φ2` (rad, wrapped to (−π, π]) of a state.
pub(crate) fn slot_deviation(s: &ModulatorState) -> f64 {
    wrap_pi(s.phi3[0] - s.phi2)
}

/// The refined extremes `[min δ, max δ]` of the slot deviation over a revolution.
pub(crate) fn deviation_range(rev: &Revolution<'_>) -> [Extreme; 2] {
    [rev.min(&slot_deviation), rev.max(&slot_deviation)]
}

/// Where an arm at angle `arm_rad` from the slot (`+α` for AB, `−θ` for AC, as `arm + sign·δ`) first
/// becomes normal to its cam: the first input angle (deg) at which `sign·δ + arm` leaves (0, π),
/// refined between grid points; `None` if it never does. `dev` are the refined extremes of δ.
pub(crate) fn fold_at(rev: &Revolution<'_>, arm_rad: f64, sign: f64, dev: [Extreme; 2]) -> Option<f64> {
    let margin = |d: f64| {
        let v = arm_rad + sign * d;
        v.min(PI - v)
    };
    let worst = dev.into_iter().min_by(|a, b| margin(a.value).total_cmp(&margin(b.value)))?;
    if margin(worst.value) > 0.0 {
        return None;
    }
    let ok = |x: f64| (rev.eval)(x).map_or(-1.0, |s| margin(slot_deviation(&s)));
    Some(first_failure(&rev.xs, &ok).unwrap_or(worst.at).to_degrees())
}

/// Warns where the counter-cam arm AC becomes normal to Γ′: `C′·(C − A) = l2 sin(θ − δ)` vanishes,
/// `δ = φ3 − φ2`; `dev` are the refined extremes of δ.
pub(crate) fn counter_cam_fold(
    g: &super::geometry::ModulatorGeometry,
    rev: &Revolution<'_>,
    dev: [Extreme; 2],
    theta_range: [f64; 2],
    warnings: &mut Vec<Warning>,
) {
    if let Some(at) = fold_at(rev, g.theta_rad(), -1.0, dev) {
        let d = (rev.eval)(at.to_radians()).map_or(dev[1].value.to_degrees(), |s| slot_deviation(&s).to_degrees());
        warnings.push(Warning {
            code: WarningCode::CounterCamFold,
            phi2_deg: Some(at),
            message: format!(
                "fold at roller C at φ2 = {:.3}°: the arm AC is normal to counter-cam Γ′ (φ3 − φ2 = {}°, θ = {:.3}°), \
                 Γ′ cannot hold the lever there; admissible θ ∈ ({:.3}, {:.3})°",
                at,
                loomkin_units::fixed(d, 3),
                g.theta_deg,
                theta_range[0],
                theta_range[1]
            ),
        });
    }
}

/// A crossing of a polyline with itself.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Crossing {
    /// Index of the first segment (from point i to i+1).
    pub segment_a: usize,
    /// Index of the second segment.
    pub segment_b: usize,
    /// Crossing point x (m).
    pub x_m: f64,
    /// Crossing point y (m).
    pub y_m: f64,
}

/// Proper crossings of a polyline with itself (closed: the last point joins the first), at most
/// `limit`. Neighbouring segments are not compared. A sweep over the segments sorted by their
/// leftmost x keeps the cost near `n log n` for cam-like curves; a closed polyline that winds once
/// about the origin with every segment turning the same way is simple and needs no sweep.
pub fn self_intersections(points: &[Vec2], closed: bool, limit: usize) -> Vec<Crossing> {
    let n = points.len();
    let nseg = if closed { n } else { n.saturating_sub(1) };
    if nseg < 3 || (closed && winds_once_about_origin(points)) {
        return Vec::new();
    }
    sweep(points, closed, limit)
}

/// The sweep of [`self_intersections`].
fn sweep(points: &[Vec2], closed: bool, limit: usize) -> Vec<Crossing> {
    let n = points.len();
    let nseg = if closed { n } else { n.saturating_sub(1) };
    if nseg < 3 {
        return Vec::new();
    }
    // The segments' ends and x-extents in one contiguous table, and the sweep order as
    // (leftmost x, index) pairs: a stable sort on x keeps equal keys in index order, and the
    // runs a traced curve is made of are merged in about linear time.
    let segs: Vec<(Vec2, Vec2, f64)> = (0..nseg)
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % n]);
            (a, b, a.x.max(b.x))
        })
        .collect();
    let mut order: Vec<(f64, usize)> = segs.iter().enumerate().map(|(i, s)| (s.0.x.min(s.1.x), i)).collect();
    order.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut active: Vec<usize> = Vec::new();
    let mut out = Vec::new();
    for &(x0, i) in &order {
        let (a, b, _) = segs[i];
        active.retain(|&j| segs[j].2 >= x0);
        for &j in &active {
            let adjacent = i.abs_diff(j) <= 1 || (closed && i.abs_diff(j) == nseg - 1);
            if adjacent {
                continue;
            }
            let (c, d, _) = segs[j];
            if let Some(p) = segment_crossing(a, b, c, d) {
                out.push(Crossing { segment_a: i.min(j), segment_b: i.max(j), x_m: p.x, y_m: p.y });
                if out.len() >= limit {
                    return out;
                }
            }
        }
        active.push(i);
    }
    out
}

/// Whether the closed polyline `points` is star-shaped about the origin O: seen from O, every
/// segment `pᵢpᵢ₊₁` turns the same way by a clear margin, `±(pᵢ × pᵢ₊₁) > 10⁻¹²·|pᵢ||pᵢ₊₁|` (far
/// above the rounding of the cross product, so the sign is exact), and the polyline goes round O
/// exactly once. Then each segment lies in its own angular sector `[θᵢ, θᵢ₊₁]` (less than a half
/// turn, O excluded), the sectors tile the turn once, and segments that are not neighbours lie in
/// disjoint sectors: the polyline does not cross itself. The turns are counted exactly from the
/// signs of y: turning anticlockwise by less than a half turn, a segment leaves the upper half
/// plane (y ≥ 0) for the lower one only across the negative x axis (clockwise: the reverse).
/// The roller-centre curves of a modulator go round O (cam Γ and Γ′ surround the crank axis), so
/// this answers for them in one pass; anything else is left to the sweep.
pub(crate) fn winds_once_about_origin(points: &[Vec2]) -> bool {
    winds_once_about(points.len(), |i| points[i])
}

/// [`winds_once_about_origin`] of the closed polyline `point(0..n)`.
pub(crate) fn winds_once_about(n: usize, point: impl Fn(usize) -> Vec2) -> bool {
    if n < 3 {
        return false;
    }
    let (mut sign, mut wraps) = (0.0f64, 0usize);
    let mut p = point(0);
    let mut np = p.norm();
    for i in 0..n {
        let q = point(if i + 1 == n { 0 } else { i + 1 });
        let nq = q.norm();
        let c = cross(p, q);
        let margin = 1e-12 * (np * nq);
        if c.abs().partial_cmp(&margin) != Some(std::cmp::Ordering::Greater) {
            return false;
        }
        let s = c.signum();
        if sign == 0.0 {
            sign = s;
        } else if s != sign {
            return false;
        }
        let (upper_p, upper_q) = (p.y >= 0.0, q.y >= 0.0);
        if (sign > 0.0 && upper_p && !upper_q) || (sign < 0.0 && !upper_p && upper_q) {
            wraps += 1;
        }
        (p, np) = (q, nq);
    }
    wraps == 1
}

/// The proper crossing point of segments `ab` and `cd`, if any.
fn segment_crossing(a: Vec2, b: Vec2, c: Vec2, d: Vec2) -> Option<Vec2> {
    if a.y.max(b.y) < c.y.min(d.y) || c.y.max(d.y) < a.y.min(b.y) {
        return None;
    }
    let (r, s) = (b - a, d - c);
    let den = cross(r, s);
    if den == 0.0 {
        return None;
    }
    let t = cross(c - a, s) / den;
    let u = cross(c - a, r) / den;
    ((0.0..1.0).contains(&t) && (0.0..1.0).contains(&u)).then(|| a + t * r)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::planar::e;

    #[test]
    fn a_figure_eight_crosses_once_and_a_circle_never() {
        let n = 400;
        let eight: Vec<Vec2> = (0..n)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / n as f64;
                Vec2::new(t.sin(), (2.0 * t).sin() / 2.0)
            })
            .collect();
        let x = self_intersections(&eight, true, 10);
        assert_eq!(x.len(), 1, "{x:?}");
        assert!(x[0].x_m.abs() < 1e-3 && x[0].y_m.abs() < 1e-3);
        let circle: Vec<Vec2> = (0..n).map(|i| e(std::f64::consts::TAU * i as f64 / n as f64)).collect();
        assert!(self_intersections(&circle, true, 10).is_empty());
    }

    /// Independent route for the star-shaped shortcut: the sweep. Random closed polylines (most
    /// cross themselves) never pass the winding test while the sweep finds a crossing; random
    /// star-shaped ones (sorted angles, any radii, either direction) pass it; a curve going twice
    /// round O crosses itself and does not pass.
    #[test]
    fn winding_once_about_the_origin_means_no_crossing() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let mut runner = TestRunner::new(Config { cases: 400, ..Config::default() });
        // Points round O with jittered angles: some out of order (crossing), some not.
        let jittered = prop::collection::vec((-0.8f64..0.8, 0.2f64..1.0), 3..40);
        let (passed, crossed) = (std::cell::Cell::new(0), std::cell::Cell::new(0));
        runner
            .run(&jittered, |p| {
                let n = p.len() as f64;
                let p: Vec<Vec2> = p
                    .iter()
                    .enumerate()
                    .map(|(k, &(jit, r))| r * e(std::f64::consts::TAU * (k as f64 + jit) / n))
                    .collect();
                let found = sweep(&p, true, 1000);
                crossed.set(crossed.get() + usize::from(!found.is_empty()));
                if winds_once_about_origin(&p) {
                    passed.set(passed.get() + 1);
                    prop_assert!(found.is_empty(), "{p:?}");
                }
                Ok(())
            })
            .unwrap();
        assert!(passed.get() > 10 && crossed.get() > 10, "{} passed, {} crossed", passed.get(), crossed.get());
        let star = (prop::collection::vec((0.0f64..1.0, 0.2f64..1.0), 3..200), any::<bool>());
        runner
            .run(&star, |(mut p, ccw)| {
                p.sort_by(|a, b| a.0.total_cmp(&b.0));
                let mut q: Vec<Vec2> = p
                    .iter()
                    .enumerate()
                    .map(|(k, &(_, r))| r * e(std::f64::consts::TAU * (k as f64 + 0.5) / p.len() as f64 + 0.1))
                    .collect();
                if !ccw {
                    q.reverse();
                }
                prop_assert!(winds_once_about_origin(&q));
                prop_assert!(sweep(&q, true, 1000).is_empty());
                Ok(())
            })
            .unwrap();
        let twice: Vec<Vec2> = (0..400)
            .map(|i| {
                let t = 2.0 * std::f64::consts::TAU * f64::from(i) / 400.0;
                (1.0 + 0.3 * (0.5 * t).cos()) * e(t)
            })
            .collect();
        assert!(!winds_once_about_origin(&twice));
        assert!(!sweep(&twice, true, 1000).is_empty());
        // A cam-like curve: the shortcut and the sweep agree (none).
        let cam: Vec<Vec2> = (0..1440)
            .map(|i| {
                let t = std::f64::consts::TAU * f64::from(i) / 1440.0;
                Vec2::new(0.366 * t.cos(), 0.577 * t.sin())
            })
            .collect();
        assert!(winds_once_about_origin(&cam) && sweep(&cam, true, 1000).is_empty());
    }

    /// Independent route for the pressure angles: the arccosine forms they stand for, where those
    /// are well conditioned (μ away from 0°: the arccosine's error there is ε/sin μ), and known
    /// small angles, which the arccosine loses and these keep to rounding.
    #[test]
    fn pressure_angles_match_the_arccosine_forms() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        let acos_roller = |t: Vec2, u: Vec2| (t.dot(&u).abs() / (t.norm() * u.norm())).min(1.0).acos().to_degrees();
        let acos_out = |a: f64, b: f64| (a - b).cos().abs().min(1.0).acos().to_degrees();
        let angle = -20.0f64..20.0;
        TestRunner::new(Config { cases: 2000, ..Config::default() })
            .run(&(angle.clone(), angle, 1e-3f64..10.0, 1e-3f64..10.0), |(a, b, lt, lu)| {
                let (t, u) = (lt * e(a), lu * e(b));
                for (new, old) in [
                    (roller_pressure_angle_deg(t, u), acos_roller(t, u)),
                    (output_pressure_angle_deg(a, b), acos_out(a, b)),
                ] {
                    prop_assert!((0.0..=90.0).contains(&new));
                    // The arccosine's own error: ε·|a − b|-sized rounding of the cosine over sin μ.
                    let tol = 1e-13
                        + (4.0 * f64::EPSILON * (1.0 + a.abs() + b.abs()) / new.to_radians().sin().max(1e-300))
                            .to_degrees();
                    prop_assert!((new - old).abs() <= tol, "{new} vs {old} (a = {a}, b = {b})");
                }
                Ok(())
            })
            .unwrap();
        // Small angles: μ = 1e-9 rad exactly between a tangent and an arm, and between slot and crank.
        let t = Vec2::new(1.0, 0.0);
        let u = Vec2::new(1e-9f64.cos(), 1e-9f64.sin());
        let mu = roller_pressure_angle_deg(t, u).to_radians();
        assert!((mu - 1e-9).abs() < 1e-24, "{mu:e}");
        assert!((output_pressure_angle_deg(1e-9, 0.0).to_radians() - 1e-9).abs() < 1e-24);
        assert!((output_pressure_angle_deg(PI + 1e-9, -PI).to_radians() - 1e-9).abs() < 1e-15);
    }

    /// The order of the roller pressure angles is tan μ: its arctangent is μ (to the rounding of
    /// μ's own forms), a cusp or an unusable vector gives +∞ as μ gives 90°.
    #[test]
    fn roller_pressure_order_is_tan_mu() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        TestRunner::new(Config { cases: 2000, ..Config::default() })
            .run(&(-20.0f64..20.0, -20.0f64..20.0, 1e-3f64..10.0, 1e-3f64..10.0), |(a, b, lt, lu)| {
                let (t, u) = (lt * e(a), lu * e(b));
                let (mu, r) = (roller_pressure_angle_deg(t, u), roller_pressure_order(t, u));
                prop_assert!(r >= 0.0);
                prop_assert!((r.atan().to_degrees() - mu).abs() <= 1e-12 * mu.max(1.0), "{mu} vs tan⁻¹ {r}");
                Ok(())
            })
            .unwrap();
        for (t, u) in [(Vec2::zeros(), Vec2::new(1.0, 0.0)), (Vec2::new(0.0, 2.0), Vec2::new(1.0, 0.0))] {
            assert_eq!((roller_pressure_order(t, u), roller_pressure_angle_deg(t, u)), (f64::INFINITY, 90.0));
        }
        assert_eq!(roller_pressure_order(Vec2::new(f64::NAN, 1.0), Vec2::new(1.0, 0.0)), f64::INFINITY);
    }

    #[test]
    fn pressure_angles_are_in_range() {
        assert!((roller_pressure_angle_deg(Vec2::new(1.0, 0.0), Vec2::new(1.0, 0.0))).abs() < 1e-12);
        assert!((roller_pressure_angle_deg(Vec2::new(0.0, 2.0), Vec2::new(1.0, 0.0)) - 90.0).abs() < 1e-12);
        assert_eq!(roller_pressure_angle_deg(Vec2::zeros(), Vec2::new(1.0, 0.0)), 90.0);
        assert!((output_pressure_angle_deg(0.3, 0.3)).abs() < 1e-6);
        assert!((output_pressure_angle_deg(0.0, 2.0) - (180.0 - 2.0f64.to_degrees())).abs() < 1e-9);
    }
}
