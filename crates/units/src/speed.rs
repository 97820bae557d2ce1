//! The main-shaft speed, with every conversion a loom needs named once.

use std::f64::consts::PI;

use serde::Serialize;

use crate::field::Field;
use crate::range::{Range, RangeError};

/// A main-shaft (or input-shaft) speed. Loom speeds are given in rpm (revolutions per minute);
/// loomkin computes with rad/s.
///
/// The range (1e-3 … 1e5 rpm) keeps every derived quantity finite: one cycle lasts at most 6·10⁴ s and
/// ω² at most about 1.1·10⁸ s⁻².
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize)]
#[serde(transparent)]
pub struct ShaftSpeed {
    rpm: f64,
}

impl ShaftSpeed {
    /// The allowed speeds.
    pub const RANGE: Range = Range::closed(1e-3, 1e5, "rpm");

    /// The main-shaft speed as an input, `speed_rpm`: [`ShaftSpeed::RANGE`], and 300 rpm where a
    /// command, a cycle file or a study leaves it out (a mid-range speed of a shuttle or rapier loom,
    /// the speed the shedding tables and the dynamics examples are given at).
    pub const SPEED: Field = Field::new(
        "speed_rpm",
        Self::RANGE,
        "Main-shaft speed. 0.001 … 100000 rpm keeps every derived quantity finite (a cycle of at most \
         6·10⁴ s, ω² at most about 1.1·10⁸ s⁻²); 300 rpm when left out.",
    )
    .with_default(300.0);

    /// The default main-shaft speed, rpm ([`ShaftSpeed::SPEED`]'s).
    pub const DEFAULT_RPM: f64 = Self::SPEED.default_value();

    /// A speed from rpm, checked against [`ShaftSpeed::RANGE`] under the field name `speed_rpm`.
    pub fn from_rpm(rpm: f64) -> Result<Self, RangeError> {
        Self::from_rpm_field("speed_rpm", rpm)
    }

    /// A speed from rpm, checked under the given field name (e.g. `input_rpm`).
    pub fn from_rpm_field(field: &str, rpm: f64) -> Result<Self, RangeError> {
        Self::RANGE.check(field, rpm).map(|rpm| Self { rpm })
    }

    /// Revolutions per minute.
    pub fn rpm(self) -> f64 {
        self.rpm
    }

    /// Revolutions per second (the shaft frequency in Hz).
    pub fn hz(self) -> f64 {
        self.rpm / 60.0
    }

    /// Angular speed ω in rad/s.
    pub fn rad_per_s(self) -> f64 {
        self.rpm * (2.0 * PI / 60.0)
    }

    /// Angular speed in degrees of shaft angle per second.
    pub fn deg_per_s(self) -> f64 {
        self.rpm * 6.0
    }

    /// Time of one revolution (360° of shaft angle) in s.
    pub fn cycle_time_s(self) -> f64 {
        60.0 / self.rpm
    }

    /// Time in s the shaft takes to turn `angle_deg` degrees.
    pub fn time_of_deg_s(self, angle_deg: f64) -> f64 {
        angle_deg / self.deg_per_s()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_agree() {
        let n = ShaftSpeed::from_rpm(750.0).unwrap();
        assert_eq!(n.hz(), 12.5);
        assert!((n.rad_per_s() - 25.0 * PI).abs() < 1e-12);
        assert_eq!(n.deg_per_s(), 4500.0);
        assert_eq!(n.cycle_time_s(), 0.08);
        assert!((n.time_of_deg_s(360.0) - n.cycle_time_s()).abs() < 1e-17);
    }

    #[test]
    fn the_speed_field_is_the_range_and_300_rpm() {
        assert_eq!(ShaftSpeed::SPEED.range, ShaftSpeed::RANGE);
        assert_eq!(ShaftSpeed::DEFAULT_RPM, 300.0);
        assert_eq!(ShaftSpeed::from_rpm(ShaftSpeed::DEFAULT_RPM).unwrap().cycle_time_s(), 0.2);
    }

    #[test]
    fn bounds_keep_everything_finite() {
        assert!(ShaftSpeed::from_rpm(5e-324).is_err());
        assert!(ShaftSpeed::from_rpm(0.0).is_err());
        assert!(ShaftSpeed::from_rpm(1.1e5).is_err());
        let e = ShaftSpeed::from_rpm_field("input_rpm", -1.0).unwrap_err();
        assert_eq!(e.to_string(), "input_rpm = -1 is out of range: allowed 0.001 ≤ input_rpm ≤ 100000 rpm");
        for rpm in [1e-3, 1e5] {
            let n = ShaftSpeed::from_rpm(rpm).unwrap();
            assert!(n.cycle_time_s().is_finite() && (n.rad_per_s() * n.rad_per_s()).is_finite());
        }
    }
}
