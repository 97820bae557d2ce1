//! The frame's motion over its full cycle, for plots: up over one pick, down over the next.

use crate::{Conditions, Result, ShedLaw};
use loomkin_units::{Field, Range};
use serde::Serialize;

/// One point of the cycle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurvePoint {
    /// Main-shaft angle, deg (0 … 720: two picks).
    pub angle_deg: f64,
    /// Frame position from its lower extreme, m.
    pub s_m: f64,
    /// Frame velocity, m/s.
    pub v_m_s: f64,
    /// Frame acceleration, m/s².
    pub a_m_s2: f64,
    /// Frame jerk, m/s³ (inside the law's segments; at a jump of the acceleration, see
    /// [`cycle_accel_jumps`], the jerk is unbounded and the value is the one-sided limit).
    pub j_m_s3: f64,
}

/// A step of the frame acceleration over the cycle, where the jerk is unbounded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AccelJump {
    /// Main-shaft angle, deg (0 … 720, as [`cycle_curve`]).
    pub angle_deg: f64,
    /// Acceleration after the step less the acceleration before it, m/s².
    pub jump_m_s2: f64,
}

/// `points` per curve of a shedding plot: 2 … 10⁵ (a plot holds every curve); 1441 (every half
/// degree of the frame's 720° cycle).
pub const PLOT_POINTS: Field = loomkin_laws::Law::PLOT_POINTS
    .within(
        Range::closed(2.0, 1e5, ""),
        "Points per plotted curve over the frame's 720° cycle: 2 … 10⁵; 1441 (every half degree) when left out.",
    )
    .with_default(1441.0);

/// The frame over two picks (720° of the main shaft; one up-and-down period in plain weave): the
/// rise over `[0, φ_дв]`, the dwell up to 360°, the return `1 − s` over `[360°, 360° + φ_дв]`, the
/// dwell up to 720°. `points ≥ 2` evenly spaced angles, both ends included.
///
/// (A plot of several laws takes [`PLOT_POINTS`].)
pub fn cycle_curve(law: &ShedLaw, conditions: &Conditions, points: usize) -> Result<Vec<CurvePoint>> {
    Range::closed(2.0, 1e6, "").check("points", points as f64)?;
    crate::criteria::check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let phi = law.motion_deg();
    let (h, sv, sa, sj) =
        (conditions.stroke_m(), conditions.scale(phi, 1), conditions.scale(phi, 2), conditions.scale(phi, 3));
    let step = 720.0 / (points - 1) as f64;
    Ok((0..points)
        .map(|i| {
            let angle = i as f64 * step;
            let (pick, local) = if angle < 360.0 { (0, angle) } else { (1, angle - 360.0) };
            let k = built.eval(local / phi);
            let moving = local < phi;
            let (s, v, a, j) = if pick == 0 { (k.s, k.v, k.a, k.j) } else { (1.0 - k.s, -k.v, -k.a, -k.j) };
            let (v, a, j) = if moving { (v, a, j) } else { (0.0, 0.0, 0.0) };
            CurvePoint { angle_deg: angle, s_m: h * s, v_m_s: sv * v, a_m_s2: sa * a, j_m_s3: sj * j }
        })
        .collect())
}

/// What a plot of the frame's cycle ([`cycle_curve`]) marks, all located on the closed form (root
/// finding and the law's metrics, not the samples).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CycleMarks {
    /// The threshold `T`.
    pub threshold: f64,
    /// Width of the threshold band, m: the frame counts as still within `(1 − T)·h` of an extreme,
    /// i.e. below `(1 − T)·h` or above `T·h`.
    pub band_m: f64,
    /// The angles (deg, within 0 … 720) over which the frame is in the band around an extreme:
    /// the weft-insertion window of each pick, `[φ_m·x_arrive, 360° + φ_m·x_depart]` around the
    /// top dwell and the same 360° later around the bottom dwell (cut at 0° and 720°). Each
    /// pick's window is `window_deg` of [`crate::Criteria`] long.
    pub windows_deg: Vec<[f64; 2]>,
    /// Largest frame acceleration over the cycle: angle (deg) and value (m/s²).
    pub accel_max: (f64, f64),
    /// Most negative frame acceleration over the cycle: angle (deg) and value (m/s²).
    pub accel_min: (f64, f64),
}

/// The threshold band, the windows and the acceleration peaks of a law over the two picks of
/// [`cycle_curve`] at `conditions` (its threshold, stroke and speed).
///
/// The rise's extremes `a_max` at `φ_m·x_a+`, `a_min` at `φ_m·x_a−` come from the law's exact
/// metrics; the return runs `1 − s`, so its extremes are `−a_min` at `360° + φ_m·x_a−` and
/// `−a_max` at `360° + φ_m·x_a+`. The largest of the cycle is reported (the rise's on a tie).
pub fn cycle_marks(law: &ShedLaw, conditions: &Conditions) -> Result<CycleMarks> {
    crate::criteria::check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let phi = law.motion_deg();
    let t = conditions.threshold();
    let d = crate::Dimensionless::of_law(&built, t)?;
    let m = built.metrics();
    let sa = conditions.scale(phi, 2);
    let (arrive, depart) = (phi * d.x_arrive, phi * d.x_depart);
    let windows_deg = vec![[0.0, depart], [arrive, 360.0 + depart], [360.0 + arrive, 720.0]];
    let rise_max = (phi * m.x_ca_pos, sa * m.ca_pos);
    let return_max = (360.0 + phi * m.x_ca_neg, -sa * m.ca_neg);
    let rise_min = (phi * m.x_ca_neg, sa * m.ca_neg);
    let return_min = (360.0 + phi * m.x_ca_pos, -sa * m.ca_pos);
    Ok(CycleMarks {
        threshold: t,
        band_m: (1.0 - t) * conditions.stroke_m(),
        windows_deg,
        accel_max: if return_max.1 > rise_max.1 { return_max } else { rise_max },
        accel_min: if return_min.1 < rise_min.1 { return_min } else { rise_min },
    })
}

/// The steps of the frame acceleration over the two picks of [`cycle_curve`]: at the joints of
/// the law's segments and at its ends against the dwells, where the law's acceleration jumps
/// (as [`loomkin_laws::Law::continuity`] judges it). On the way down (the second pick) the
/// motion is `1 − s`, so each step changes sign. Sorted by angle.
pub fn cycle_accel_jumps(law: &ShedLaw, conditions: &Conditions) -> Result<Vec<AccelJump>> {
    crate::criteria::check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let phi = law.motion_deg();
    let sa = conditions.scale(phi, 2);
    let c = built.continuity();
    let joints: Vec<_> = std::iter::once(&c.start).chain(&c.joints).chain(std::iter::once(&c.end)).collect();
    let mut out = Vec::new();
    for (offset, sign) in [(0.0, 1.0), (360.0, -1.0)] {
        for j in joints.iter().filter(|j| !j.flags()[2]) {
            out.push(AccelJump { angle_deg: offset + j.x * phi, jump_m_s2: sign * j.da * sa });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Template;

    fn law(t: &Template, lengths: &[f64]) -> ShedLaw {
        t.law(220.0, lengths).expect("law")
    }

    /// The jerk is the derivative of the acceleration in time: centred differences of a over a
    /// fine grid, away from the steps, give the jerk (dθ/dt = ω = 2πn/60).
    #[test]
    fn jerk_is_the_time_derivative_of_the_acceleration() {
        let cond = Conditions::new(0.95, 0.1, 300.0).expect("conditions");
        let l = law(&Template::trapezoid(), &[0.25, 0.5, 0.25]);
        let n = 72_001;
        let c = cycle_curve(&l, &cond, n).expect("curve");
        let dt = (720.0f64 / (n - 1) as f64).to_radians() / cond.omega_rad_s();
        let jumps = cycle_accel_jumps(&l, &cond).expect("jumps");
        let jmax = c.iter().fold(0.0f64, |m, p| m.max(p.j_m_s3.abs()));
        assert!(jmax > 0.0);
        let mut checked = 0;
        for i in 1..n - 1 {
            let near = |x: f64| (c[i].angle_deg - x).abs() < 0.05;
            if jumps.iter().any(|j| near(j.angle_deg)) || near(220.0) || near(360.0) || near(580.0) || near(0.0) {
                continue;
            }
            let fd = (c[i + 1].a_m_s2 - c[i - 1].a_m_s2) / (2.0 * dt);
            assert!((fd - c[i].j_m_s3).abs() < 1e-3 * jmax, "at {}°: {} vs {}", c[i].angle_deg, fd, c[i].j_m_s3);
            checked += 1;
        }
        assert!(checked > n / 2);
    }

    /// The windows hold exactly the angles at which the frame is within the band (checked on a
    /// dense sample, away from the located edges), each pick's window is the criteria's
    /// `window_deg`, and the located peaks bound the sampled acceleration and are reached by it.
    #[test]
    fn marks_agree_with_the_sampled_cycle() {
        for (t, lengths, thr) in [
            (Template::trapezoid(), vec![0.25, 0.5, 0.25], 0.95),
            (Template::trapezoid(), vec![0.1, 0.3, 0.6], 0.85),
            (Template::trapezoid(), vec![0.0, 0.6, 0.4], 0.9),
        ] {
            let cond = Conditions::new(thr, 0.08, 450.0).expect("conditions");
            let l = law(&t, &lengths);
            let marks = cycle_marks(&l, &cond).expect("marks");
            let crit = crate::evaluate(&l, &cond).expect("criteria");
            let w = &marks.windows_deg;
            let total: f64 = w.iter().map(|[a, b]| b - a).sum();
            assert!((total - 2.0 * crit.window_deg).abs() < 1e-9, "{total} vs 2 × {}", crit.window_deg);
            assert!((marks.band_m - (1.0 - thr) * 0.08).abs() < 1e-15);
            let n = 144_001;
            let c = cycle_curve(&l, &cond, n).expect("curve");
            let (h, band) = (cond.stroke_m(), marks.band_m);
            let (mut amax, mut amin) = (f64::NEG_INFINITY, f64::INFINITY);
            for p in &c {
                amax = amax.max(p.a_m_s2);
                amin = amin.min(p.a_m_s2);
                let edge = w.iter().flatten().any(|e| (p.angle_deg - e).abs() < 0.02);
                if edge {
                    continue;
                }
                let still = p.s_m <= band || p.s_m >= h - band;
                let inside = w.iter().any(|[a, b]| p.angle_deg >= *a && p.angle_deg <= *b);
                assert_eq!(still, inside, "at {}°: s = {} m, band {band} m", p.angle_deg, p.s_m);
            }
            let scale = marks.accel_max.1.abs().max(marks.accel_min.1.abs());
            assert!(marks.accel_max.1 >= amax - 1e-12 * scale && marks.accel_max.1 - amax < 1e-4 * scale);
            assert!(marks.accel_min.1 <= amin + 1e-12 * scale && amin - marks.accel_min.1 < 1e-4 * scale);
            assert!((marks.accel_max.1.max(-marks.accel_min.1) - crit.peak_accel_m_s2).abs() < 1e-9 * scale);
            // The value at the reported angle is the reported value (a one-point cycle evaluation).
            for (at, v) in [marks.accel_max, marks.accel_min] {
                let (pick, local) = if at < 360.0 { (1.0, at) } else { (-1.0, at - 360.0) };
                let k = l.build().expect("law").eval(local / l.motion_deg());
                let a = pick * k.a * cond.scale(l.motion_deg(), 2);
                assert!((a - v).abs() < 1e-9 * scale, "{a} vs {v} at {at}°");
            }
        }
    }

    /// Every step reported is the difference of the acceleration just after and just before its
    /// angle, the largest equals the criteria's `accel_jump_m_s2`, and a law without steps has none.
    #[test]
    fn steps_of_the_acceleration_are_where_the_curve_jumps() {
        let cond = Conditions::new(0.95, 0.1, 300.0).expect("conditions");
        let l = law(&Template::trapezoid(), &[0.0, 0.6, 0.4]);
        let jumps = cycle_accel_jumps(&l, &cond).expect("jumps");
        let crit = crate::evaluate(&l, &cond).expect("criteria");
        assert!(crit.accel_jump_m_s2 > 0.0, "a trapezoid without its rising ramp steps up at once");
        assert!(!jumps.is_empty() && jumps.len().is_multiple_of(2));
        let biggest = jumps.iter().fold(0.0f64, |m, j| m.max(j.jump_m_s2.abs()));
        assert!((biggest - crit.accel_jump_m_s2).abs() <= 1e-9 * biggest, "{biggest} vs {}", crit.accel_jump_m_s2);
        let built = l.build().expect("law");
        let sa = cond.scale(220.0, 2);
        // a(θ) from the law directly: 0 in the dwells, ±a of the law during the motion.
        let a_at = |deg: f64| {
            let (sign, local) = if deg < 360.0 { (1.0, deg) } else { (-1.0, deg - 360.0) };
            if !(0.0..220.0).contains(&local) { 0.0 } else { sign * sa * built.eval(local / 220.0).a }
        };
        for j in &jumps {
            let e = 1e-7;
            let step = a_at(j.angle_deg + e) - a_at(j.angle_deg - e);
            assert!((step - j.jump_m_s2).abs() < 1e-4 * biggest, "at {}°: {step} vs {}", j.angle_deg, j.jump_m_s2);
        }
        let smooth = law(&Template::trapezoid(), &[0.25, 0.5, 0.25]);
        assert_eq!(crate::evaluate(&smooth, &cond).expect("criteria").accel_jump_m_s2, 0.0);
        assert!(cycle_accel_jumps(&smooth, &cond).expect("jumps").is_empty());
    }
}
