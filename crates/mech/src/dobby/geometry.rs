//! The modulator's link lengths and lever angles.

use crate::Result;
use loomkin_units::Range;
use loomkin_units::schema::bounds;
use serde::{Deserialize, Serialize};

/// Geometry of the modulator of a Stäubli-type rotary dobby (series 2600).
///
/// O is the frame axis, common to the input crank 2 (`OA = l2`, angle φ2) and the output crank 6
/// (`OD = l6`, angle φ6). Lever 3 is pivoted at A; it carries roller 4 (centre B, `AB = l3`) in cam
/// Γ, roller 4′ (centre C, `AC = l3′`) in counter-cam Γ′, and a slot through A of direction φ3 in
/// which slider 5, pinned to crank 6 at D, slides (`S53 = |AD|`):
///
/// * `A − B = l3·e(φ3 + α)`, `A − D = S53·e(φ3)`, `C = A + l3′·e(φ3 + π − θ)`.
///
/// [`ModulatorGeometry::default`] is the paper's, eq. (10): `l2 = 0.66 m`, `l3 = l3′ = 0.36 m`,
/// `l6 = 0.40 m`, `α = θ = 47°` (the angle of its figures; the paper sweeps α over 30…60°).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
pub struct ModulatorGeometry {
    /// Input crank OA (m).
    #[schemars(transform = bounds(Self::LENGTH_M_RANGE))]
    pub l2_m: f64,
    /// Lever arm AB to the cam roller (m).
    #[schemars(transform = bounds(Self::LENGTH_M_RANGE))]
    pub l3_m: f64,
    /// Lever arm AC to the counter-cam roller (m).
    #[schemars(transform = bounds(Self::LENGTH_M_RANGE))]
    pub l3p_m: f64,
    /// Output crank OD (m); must be shorter than `l2`.
    #[schemars(transform = bounds(Self::LENGTH_M_RANGE))]
    pub l6_m: f64,
    /// Angle α between the slot and the arm AB (deg).
    #[schemars(transform = bounds(Self::ANGLE_DEG_RANGE))]
    pub alpha_deg: f64,
    /// Angle θ between the slot and the arm AC (deg), on the other side of the slot.
    #[schemars(transform = bounds(Self::ANGLE_DEG_RANGE))]
    pub theta_deg: f64,
}

impl Default for ModulatorGeometry {
    fn default() -> Self {
        Self::PAPER
    }
}

impl ModulatorGeometry {
    /// The paper's geometry with α = θ = 47°.
    pub const PAPER: ModulatorGeometry =
        ModulatorGeometry { l2_m: 0.66, l3_m: 0.36, l3p_m: 0.36, l6_m: 0.40, alpha_deg: 47.0, theta_deg: 47.0 };

    /// A validated geometry.
    pub fn new(l2_m: f64, l3_m: f64, l3p_m: f64, l6_m: f64, alpha_deg: f64, theta_deg: f64) -> Result<Self> {
        let g = Self { l2_m, l3_m, l3p_m, l6_m, alpha_deg, theta_deg };
        g.validate()?;
        Ok(g)
    }

    /// The same geometry with a symmetric lever of angle `alpha_deg` (θ = α).
    pub fn with_alpha_deg(self, alpha_deg: f64) -> Result<Self> {
        let g = Self { alpha_deg, theta_deg: alpha_deg, ..self };
        g.validate()?;
        Ok(g)
    }

    /// The allowed link length (m): above 0, at most 100 m.
    pub const LENGTH_M_RANGE: Range = Range::open_closed(0.0, 100.0, "m");
    /// The allowed angles α and θ (deg): strictly between 0° and 180° (the arm would lie on the slot).
    pub const ANGLE_DEG_RANGE: Range = Range::open(0.0, 180.0, "°");

    /// Checks every field: lengths in [`ModulatorGeometry::LENGTH_M_RANGE`], `l6 < l2`, α and θ in
    /// [`ModulatorGeometry::ANGLE_DEG_RANGE`].
    pub fn validate(&self) -> Result<()> {
        for (f, v) in [("l2_m", self.l2_m), ("l3_m", self.l3_m), ("l3p_m", self.l3p_m), ("l6_m", self.l6_m)] {
            Self::LENGTH_M_RANGE.check(f, v)?;
        }
        Range::open(0.0, self.l2_m, "m (l6 < l2)").check("l6_m", self.l6_m)?;
        for (f, v) in [("alpha_deg", self.alpha_deg), ("theta_deg", self.theta_deg)] {
            Self::ANGLE_DEG_RANGE.check(f, v)?;
        }
        Ok(())
    }

    /// α in rad.
    pub fn alpha_rad(&self) -> f64 {
        self.alpha_deg.to_radians()
    }

    /// θ in rad.
    pub fn theta_rad(&self) -> f64 {
        self.theta_deg.to_radians()
    }

    /// Largest lag `|φ6 − φ2|` (deg) at which the slot still crosses the output circle at a
    /// positive pressure margin: `arccos(l6/l2)` (52.7° for the paper). There the slot is normal to
    /// OD and the output pressure angle reaches 90°.
    pub fn max_lag_deg(&self) -> f64 {
        (self.l6_m / self.l2_m).acos().to_degrees()
    }

    /// Largest slot deviation `|φ3 − φ2|` (deg): `arcsin(l6/l2)` (37.3° for the paper); beyond it the
    /// slot misses the output crank's circle.
    pub fn max_slot_deviation_deg(&self) -> f64 {
        (self.l6_m / self.l2_m).asin().to_degrees()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_geometry_is_valid_and_bad_ones_are_named() {
        ModulatorGeometry::PAPER.validate().unwrap();
        let g = ModulatorGeometry { l6_m: 0.7, ..ModulatorGeometry::PAPER };
        let e = g.validate().unwrap_err().to_string();
        assert!(e.contains("l6_m") && e.contains("0.66"), "{e}");
        let e = ModulatorGeometry::PAPER.with_alpha_deg(190.0).unwrap_err().to_string();
        assert!(e.contains("alpha_deg"), "{e}");
        // The two limits are complementary: arcsin k + arccos k = 90°.
        let g = ModulatorGeometry::PAPER;
        assert!((g.max_lag_deg() + g.max_slot_deviation_deg() - 90.0).abs() < 1e-12);
    }
}
