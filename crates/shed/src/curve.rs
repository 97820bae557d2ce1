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
}

/// The frame over two picks (720° of the main shaft; one up-and-down period in plain weave): the
/// rise over `[0, φ_дв]`, the dwell up to 360°, the return `1 − s` over `[360°, 360° + φ_дв]`, the
/// dwell up to 720°. `points ≥ 2` evenly spaced angles, both ends included.
pub fn cycle_curve(law: &ShedLaw, conditions: &Conditions, points: usize) -> Result<Vec<CurvePoint>> {
    Range::closed(2.0, 1e6, "").check("points", points as f64)?;
    crate::criteria::check_scales(law.motion_deg(), conditions)?;
    let built = law.build()?;
    let phi = law.motion_deg();
    let (h, sv, sa) = (conditions.stroke_m(), conditions.scale(phi, 1), conditions.scale(phi, 2));
    let step = 720.0 / (points - 1) as f64;
    Ok((0..points)
        .map(|i| {
            let angle = i as f64 * step;
            let (pick, local) = if angle < 360.0 { (0, angle) } else { (1, angle - 360.0) };
            let k = built.eval(local / phi);
            let moving = local < phi;
            let (s, v, a) = if pick == 0 { (k.s, k.v, k.a) } else { (1.0 - k.s, -k.v, -k.a) };
            let (v, a) = if moving { (v, a) } else { (0.0, 0.0) };
            CurvePoint { angle_deg: angle, s_m: h * s, v_m_s: sv * v, a_m_s2: sa * a }
        })
        .collect())
}
