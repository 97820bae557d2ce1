//! The mechanism drawn at one input angle: the joint positions a plot or a workbench needs.

use super::geometry::ModulatorGeometry;
use super::kinematics::ModulatorState;
use serde::Serialize;

/// Joint positions (m) of the modulator at one input angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MechanismPose {
    /// Input angle φ2 (deg).
    pub phi2_deg: f64,
    /// Frame axis O.
    pub o: [f64; 2],
    /// Crank pin A (crank 2 is OA).
    pub a: [f64; 2],
    /// Roller centre B (arm AB of lever 3).
    pub b: [f64; 2],
    /// Roller centre C (arm AC of lever 3).
    pub c: [f64; 2],
    /// Slider pin D (crank 6 is OD; the slot runs from A through D).
    pub d: [f64; 2],
}

impl ModulatorState {
    /// The joint positions of this state.
    pub fn pose(&self, g: &ModulatorGeometry) -> MechanismPose {
        let p = |v: crate::planar::Vec2| [v.x, v.y];
        MechanismPose {
            phi2_deg: self.phi2.to_degrees(),
            o: [0.0, 0.0],
            a: p(self.a(g)),
            b: p(self.b[0]),
            c: p(self.c[0]),
            d: p(self.d(g)),
        }
    }
}

impl MechanismPose {
    /// The joints with their letters, as drawings label them: O, A, B, C, D.
    pub fn joints(&self) -> [(&'static str, [f64; 2]); 5] {
        [("O", self.o), ("A", self.a), ("B", self.b), ("C", self.c), ("D", self.d)]
    }

    /// The roller centres: B (in cam Γ) and C (in counter-cam Γ′).
    pub fn rollers(&self) -> [[f64; 2]; 2] {
        [self.b, self.c]
    }
}

/// The state whose input angle is nearest to `phi2_deg` modulo 360°; `None` if there is none or
/// `phi2_deg` is not finite.
pub fn nearest_state(states: &[ModulatorState], phi2_deg: f64) -> Option<&ModulatorState> {
    if !phi2_deg.is_finite() {
        return None;
    }
    let target = phi2_deg.to_radians();
    states.iter().min_by(|a, b| {
        let da = crate::planar::wrap_pi(a.phi2 - target).abs();
        let db = crate::planar::wrap_pi(b.phi2 - target).abs();
        da.total_cmp(&db)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dobby::analysis::{AnalysisOptions, analyze};
    use crate::dobby::cam::Cam;

    /// The lettered joints keep the geometry's link lengths at every drawn angle (OA = l2,
    /// OD = l6, AB = l3, AC = l3′) and its lever angles from the slot AD (α to AB, π − θ to AC),
    /// checked from the letters' points alone.
    #[test]
    fn the_joints_keep_the_links_lengths_and_angles() {
        let g = ModulatorGeometry::default();
        let r = analyze(&g, &Cam::paper(), &AnalysisOptions { step_deg: 15.0, ..AnalysisOptions::default() }).unwrap();
        let dist = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
        let angle = |p: [f64; 2], q: [f64; 2]| (p[1] - q[1]).atan2(p[0] - q[0]);
        for st in &r.states {
            let p = st.pose(&g);
            let j = p.joints();
            assert_eq!(j.map(|(l, _)| l), ["O", "A", "B", "C", "D"]);
            let at = |l: &str| j.iter().find(|(k, _)| *k == l).unwrap().1;
            assert_eq!(at("O"), [0.0, 0.0]);
            assert!((dist(at("O"), at("A")) - g.l2_m).abs() < 1e-12);
            assert!((dist(at("O"), at("D")) - g.l6_m).abs() < 1e-12);
            assert!((dist(at("A"), at("B")) - g.l3_m).abs() < 1e-9);
            assert!((dist(at("A"), at("C")) - g.l3p_m).abs() < 1e-9);
            // A − B makes α with A − D; C − A makes π − θ with A − D's direction (see the geometry).
            let slot = angle(at("A"), at("D"));
            let ab = crate::planar::wrap_pi(angle(at("A"), at("B")) - slot);
            assert!((ab - g.alpha_deg.to_radians()).abs() < 1e-9, "{ab}");
            let ac = crate::planar::wrap_pi(angle(at("C"), at("A")) - slot);
            assert!((ac - (std::f64::consts::PI - g.theta_deg.to_radians())).abs() < 1e-9, "{ac}");
            assert_eq!(p.rollers(), [at("B"), at("C")]);
        }
    }
}
