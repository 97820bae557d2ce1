//! The conditions a law is judged under: the dwell threshold, the frame's stroke and the
//! main-shaft speed.

use crate::Result;
use loomkin_units::{Field, Range, ShaftSpeed};
use serde::Serialize;

/// Allowed range of the dwell threshold `T` (the paper's 0.75 … 0.99 of the stroke).
pub const THRESHOLD_RANGE: (f64, f64) = (0.75, 0.99);

/// The threshold that reproduces the paper's Table 3 (see [`crate::table3`]): the frame counts as
/// still while it is within 5 % of the stroke from its extreme position.
pub const TABLE3_THRESHOLD: f64 = 0.95;

/// Conditions of evaluation.
///
/// * `threshold` `T` — the frame counts as still (conditional dwell) while its displacement is at
///   least `T` of the stroke from the other extreme, `0.75 ≤ T ≤ 0.99`;
/// * `stroke_m` `h` — the frame's stroke, m, `0 < h ≤ 1`;
/// * `speed_rpm` `n` — main-shaft speed, rpm, `0 < n ≤ 5000` (one pick per turn).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Conditions {
    threshold: f64,
    stroke_m: f64,
    speed_rpm: f64,
}

impl Default for Conditions {
    /// `T = 0.95`, `h = 0.1 m`, `n = 300 rpm`: the descriptors' defaults.
    fn default() -> Self {
        Self {
            threshold: Self::THRESHOLD_FIELD.default_value(),
            stroke_m: loomkin_units::m_from_mm(Self::STROKE_MM.default_value()),
            speed_rpm: ShaftSpeed::DEFAULT_RPM,
        }
    }
}

impl Conditions {
    /// The allowed dwell threshold `T` ([`THRESHOLD_RANGE`]), a fraction of the stroke.
    pub const THRESHOLD: Range = Range::closed(THRESHOLD_RANGE.0, THRESHOLD_RANGE.1, "(fraction of the stroke)");
    /// The allowed frame stroke `h` (m): above 0, at most a metre.
    pub const STROKE_M: Range = Range::open_closed(0.0, 1.0, "m");
    /// `threshold`: T, the share of the stroke within which the frame counts as still: the paper's
    /// 0.75 … 0.99; 0.95 ([`TABLE3_THRESHOLD`], which reproduces Table 3).
    pub const THRESHOLD_FIELD: Field = Field::new(
        "threshold",
        Self::THRESHOLD,
        "Dwell threshold T: the frame counts as still within (1 − T) of its stroke from an extreme; the \
         paper's 0.75 … 0.99; 0.95 (reproduces the paper's Table 3) when left out.",
    )
    .with_default(TABLE3_THRESHOLD);
    /// `stroke_mm`: the frame's stroke as front ends take it, 0 < h ≤ 1000 mm (a metre, above any
    /// heald frame); 100 mm.
    pub const STROKE_MM: Field = Field::new(
        "stroke_mm",
        Range::open_closed(0.0, 1000.0, "mm"),
        "Heald-frame stroke: 0 < h ≤ 1000 mm (a metre, above any frame); 100 mm when left out.",
    )
    .with_default(100.0);

    /// The conditions of a front end's `threshold`, `stroke_mm` (checked in mm, [`Conditions::STROKE_MM`])
    /// and `speed_rpm`.
    pub fn from_stroke_mm(threshold: f64, stroke_mm: f64, speed_rpm: f64) -> Result<Self> {
        Self::STROKE_MM.check(stroke_mm)?;
        Self::new(threshold, loomkin_units::m_from_mm(stroke_mm), speed_rpm)
    }

    /// Validating constructor.
    pub fn new(threshold: f64, stroke_m: f64, speed_rpm: f64) -> Result<Self> {
        check_threshold(threshold)?;
        Self::STROKE_M.check("stroke_m", stroke_m)?;
        ShaftSpeed::from_rpm(speed_rpm)?;
        Ok(Self { threshold, stroke_m, speed_rpm })
    }

    /// The dwell threshold `T`.
    pub fn threshold(&self) -> f64 {
        self.threshold
    }

    /// The frame's stroke `h`, m.
    pub fn stroke_m(&self) -> f64 {
        self.stroke_m
    }

    /// Main-shaft speed `n`, rpm.
    pub fn speed_rpm(&self) -> f64 {
        self.speed_rpm
    }

    /// Main-shaft angular speed `ω = 2πn/60`, rad/s.
    pub fn omega_rad_s(&self) -> f64 {
        loomkin_units::rad_per_s_from_rpm(self.speed_rpm)
    }

    /// The factor `h·(ω/Φ)^order` that turns the dimensionless derivative of order `order` of a
    /// normalised law (per unit stroke, per unit motion angle) into SI units (m, m/s, m/s², m/s³)
    /// for a motion angle `Φ = motion_deg·π/180` rad.
    pub fn scale(&self, motion_deg: f64, order: i32) -> f64 {
        let rate = self.omega_rad_s() / motion_deg.to_radians();
        self.stroke_m * rate.powi(order)
    }
}

/// Checks a dwell threshold: `0.75 ≤ T ≤ 0.99`.
pub fn check_threshold(threshold: f64) -> Result<f64> {
    Ok(Conditions::THRESHOLD.check("threshold", threshold)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_and_scales() {
        assert!(Conditions::new(0.7, 0.1, 300.0).is_err());
        assert!(Conditions::new(0.995, 0.1, 300.0).is_err());
        assert!(Conditions::new(0.9, 0.0, 300.0).is_err());
        assert!(Conditions::new(0.9, 0.1, f64::NAN).is_err());
        let c = Conditions::new(0.9, 0.1, 300.0).unwrap();
        // 300 rpm → ω = 10π rad/s; over Φ = π (180°): ω/Φ = 10 s⁻¹; a-factor = 0.1·100 = 10 m/s².
        assert!((c.scale(180.0, 2) - 10.0).abs() < 1e-12);
        assert!((c.scale(180.0, 1) - 1.0).abs() < 1e-12);
    }
}
