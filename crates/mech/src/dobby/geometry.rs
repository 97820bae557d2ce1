//! The modulator's link lengths and lever angles.

use crate::Result;
use loomkin_units::schema::bounds;
use loomkin_units::{Field, Range};
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

/// A link length of the modulator: (0, 100] m.
const LENGTH: Range = Range::open_closed(0.0, 100.0, "m");
/// A lever angle: (0°, 180°).
const LEVER_ANGLE: Range = Range::open(0.0, 180.0, "°");

impl ModulatorGeometry {
    /// `l2_m`: the input crank OA, (0, 100] m; the paper's 0.66 m.
    pub const L2_M: Field =
        Field::new("l2_m", LENGTH, "Input crank OA: 0 < l2 ≤ 100 m; the paper's 0.66 m.").with_default(0.66);
    /// `l3_m`: the arm AB to the cam roller, (0, 100] m; the paper's 0.36 m.
    pub const L3_M: Field =
        Field::new("l3_m", LENGTH, "Arm AB to the cam roller: 0 < l3 ≤ 100 m; the paper's 0.36 m.").with_default(0.36);
    /// `l3p_m`: the arm AC to the counter-cam roller, (0, 100] m; the paper's 0.36 m.
    pub const L3P_M: Field =
        Field::new("l3p_m", LENGTH, "Arm AC to the counter-cam roller: 0 < l3′ ≤ 100 m; the paper's 0.36 m.")
            .with_default(0.36);
    /// `l6_m`: the output crank OD, (0, 100] m and below l2 (else the output turns through a dead
    /// point); the paper's 0.40 m.
    pub const L6_M: Field = Field::new(
        "l6_m",
        LENGTH,
        "Output crank OD: 0 < l6 < l2 (else the output passes a dead point), at most 100 m; the paper's 0.40 m.",
    )
    .with_default(0.40);
    /// `alpha_deg`: the angle α between the slot and the arm AB, (0°, 180°); the paper's 47°.
    pub const ALPHA_DEG: Field = Field::new(
        "alpha_deg",
        LEVER_ANGLE,
        "Angle α between the slot and the arm AB: 0 < α < 180° (the paper studies 30 … 60); 47° when left out.",
    )
    .with_default(47.0);
    /// `theta_deg`: the angle θ between the slot and the arm AC, (0°, 180°); left out, α (a
    /// symmetric lever).
    pub const THETA_DEG: Field = Field::new(
        "theta_deg",
        LEVER_ANGLE,
        "Angle θ between the slot and the arm AC: 0 < θ < 180°; left out, θ = α (a symmetric lever).",
    );

    /// The paper's geometry with α = θ = 47°.
    pub const PAPER: ModulatorGeometry = ModulatorGeometry {
        l2_m: Self::L2_M.default_value(),
        l3_m: Self::L3_M.default_value(),
        l3p_m: Self::L3P_M.default_value(),
        l6_m: Self::L6_M.default_value(),
        alpha_deg: Self::ALPHA_DEG.default_value(),
        theta_deg: Self::ALPHA_DEG.default_value(),
    };

    /// A validated geometry from a front end's inputs: α defaults to 47°, θ to α.
    pub fn from_inputs(
        l2_m: f64,
        l3_m: f64,
        l3p_m: f64,
        l6_m: f64,
        alpha_deg: Option<f64>,
        theta_deg: Option<f64>,
    ) -> Result<Self> {
        let alpha = alpha_deg.unwrap_or(Self::ALPHA_DEG.default_value());
        Self::new(l2_m, l3_m, l3p_m, l6_m, alpha, theta_deg.unwrap_or(alpha))
    }

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
        for (f, v) in
            [(Self::L2_M, self.l2_m), (Self::L3_M, self.l3_m), (Self::L3P_M, self.l3p_m), (Self::L6_M, self.l6_m)]
        {
            f.check(v)?;
        }
        Range::open(0.0, self.l2_m, "m (l6 < l2)").check("l6_m", self.l6_m)?;
        for (f, v) in [(Self::ALPHA_DEG, self.alpha_deg), (Self::THETA_DEG, self.theta_deg)] {
            f.check(v)?;
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
