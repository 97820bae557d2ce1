//! The frame's motion over its full cycle, for plots: up over one pick, down over the next.

use crate::{Conditions, Result, ShedLaw};
use loomkin_units::Range;
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

/// The frame over two picks (720° of the main shaft; one up-and-down period in plain weave): the
/// rise over `[0, φ_дв]`, the dwell up to 360°, the return `1 − s` over `[360°, 360° + φ_дв]`, the
/// dwell up to 720°. `points ≥ 2` evenly spaced angles, both ends included.
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

/// The steps of the frame acceleration over the two picks of [`cycle_curve`]: at the joints of
/// the law's segments and at its ends against the dwells, where the law's acceleration jumps
/// (by more than rounding, 1e-9 of the unit law's peak). On the way down (the second pick) the
/// motion is `1 − s`, so each step changes sign. Sorted by angle.
pub fn cycle_accel_jumps(law: &ShedLaw, conditions: &Conditions) -> Result<Vec<AccelJump>> {
    crate::criteria::check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let phi = law.motion_deg();
    let sa = conditions.scale(phi, 2);
    let c = built.continuity();
    let joints: Vec<_> = std::iter::once(&c.start).chain(&c.joints).chain(std::iter::once(&c.end)).collect();
    let peak = joints.iter().fold(1.0f64, |m, j| m.max(j.da.abs()));
    let mut out = Vec::new();
    for (offset, sign) in [(0.0, 1.0), (360.0, -1.0)] {
        for j in joints.iter().filter(|j| j.da.abs() > 1e-9 * peak) {
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
