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
