//! The one range error: a field, its value, a closed or open bound on each side, a unit.

use std::fmt;

use serde::Serialize;

use crate::format::{compact, exact, to_12_digits};

/// One side of an allowed range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(tag = "kind", content = "value", rename_all = "snake_case")]
pub enum Bound {
    /// No bound on this side (any finite number).
    Unbounded,
    /// The bound itself is allowed (`≤`).
    Closed(f64),
    /// The bound itself is excluded (`<`).
    Open(f64),
}

/// An allowed range of a quantity with its unit: `lo ≤ x ≤ hi`, either side open or absent.
/// Every range admits finite numbers only.
///
/// Ranges are `const`, so a quantity's bound is declared once beside the type that owns it and
/// read by the library, the CLI and the workbench alike.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Range {
    /// Lower side.
    pub lo: Bound,
    /// Upper side.
    pub hi: Bound,
    /// Unit of the bounds and the value (`""` for a dimensionless quantity).
    pub unit: &'static str,
}

impl Range {
    /// `lo ≤ x ≤ hi`.
    pub const fn closed(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Closed(lo), hi: Bound::Closed(hi), unit }
    }
    /// `lo < x < hi`.
    pub const fn open(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Open(lo), hi: Bound::Open(hi), unit }
    }
    /// `lo < x ≤ hi`.
    pub const fn open_closed(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Open(lo), hi: Bound::Closed(hi), unit }
    }
    /// `lo ≤ x < hi`.
    pub const fn closed_open(lo: f64, hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Closed(lo), hi: Bound::Open(hi), unit }
    }
    /// `x ≥ lo`.
    pub const fn at_least(lo: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Closed(lo), hi: Bound::Unbounded, unit }
    }
    /// `x > lo`.
    pub const fn above(lo: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Open(lo), hi: Bound::Unbounded, unit }
    }
    /// `x ≤ hi`.
    pub const fn at_most(hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Unbounded, hi: Bound::Closed(hi), unit }
    }
    /// `x < hi`.
    pub const fn below(hi: f64, unit: &'static str) -> Self {
        Self { lo: Bound::Unbounded, hi: Bound::Open(hi), unit }
    }
    /// Any finite number.
    pub const fn finite(unit: &'static str) -> Self {
        Self { lo: Bound::Unbounded, hi: Bound::Unbounded, unit }
    }

    /// Whether `v` is finite and inside the range.
    pub const fn contains(&self, v: f64) -> bool {
        let lo_ok = match self.lo {
            Bound::Unbounded => true,
            Bound::Closed(b) => v >= b,
            Bound::Open(b) => v > b,
        };
        let hi_ok = match self.hi {
            Bound::Unbounded => true,
            Bound::Closed(b) => v <= b,
            Bound::Open(b) => v < b,
        };
        v.is_finite() && lo_ok && hi_ok
    }

    /// `Ok(v)` when `v` is inside, else the error naming `field`.
    pub fn check(&self, field: &str, v: f64) -> Result<f64, RangeError> {
        if self.contains(v) { Ok(v) } else { Err(RangeError::new(field, v, *self)) }
    }

    /// The range in words for `field`, e.g. `0 < ramp ≤ 0.25` or `speed_rpm ≥ 1 rpm`.
    pub fn describe(&self, field: &str) -> String {
        let unit = if self.unit.is_empty() { String::new() } else { format!(" {}", self.unit) };
        let lo = match self.lo {
            Bound::Unbounded => None,
            Bound::Closed(b) => Some((compact(b), "≤")),
            Bound::Open(b) => Some((compact(b), "<")),
        };
        let hi = match self.hi {
            Bound::Unbounded => None,
            Bound::Closed(b) => Some(("≤", compact(b))),
            Bound::Open(b) => Some(("<", compact(b))),
        };
        match (lo, hi) {
            (Some((l, ls)), Some((hs, h))) => format!("{l} {ls} {field} {hs} {h}{unit}"),
            (Some((l, ls)), None) => format!("{field} {} {l}{unit}", if ls == "<" { ">" } else { "≥" }),
            (None, Some((hs, h))) => format!("{field} {hs} {h}{unit}"),
            (None, None) => format!("{field} any finite number{unit}"),
        }
    }
}

/// Checks a count `min ≤ n ≤ max` under `field` (a number of samples, laws or points a caller
/// bounds by the size of its answer): the one count check every front end calls.
pub fn check_count(field: &str, n: usize, min: usize, max: usize) -> Result<usize, RangeError> {
    Range::closed(min as f64, max as f64, "").check(field, n as f64).map(|_| n)
}

/// A number outside its allowed range, or not a finite number.
///
/// The message is one line naming the field, the value and the allowed range with its unit:
/// `ramp = 0.3 is out of range: allowed 0 < ramp ≤ 0.25`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RangeError {
    /// Name of the field: the key in files and JSON (`speed_rpm`); a CLI flag is the same words with `-`.
    pub field: String,
    /// The value given.
    pub value: f64,
    /// The allowed range.
    pub range: Range,
}

impl RangeError {
    /// The error for `value` given as `field` against `range`.
    pub fn new(field: impl Into<String>, value: f64, range: Range) -> Self {
        Self { field: field.into(), value, range }
    }

    /// The same error under another field name (a front end naming its own flag or key).
    pub fn renamed(mut self, field: impl Into<String>) -> Self {
        self.field = field.into();
        self
    }

    /// The same error for a front end that takes the quantity in another unit (`--distance-cm`
    /// for a length the library keeps in m): the value and the bounds multiplied by `factor`
    /// (> 0, the size of the library's unit in the new one), under `field` and `unit`.
    pub fn in_unit(self, field: impl Into<String>, factor: f64, unit: &'static str) -> Self {
        let scale = |b: Bound| match b {
            Bound::Unbounded => Bound::Unbounded,
            Bound::Closed(v) => Bound::Closed(v * factor),
            Bound::Open(v) => Bound::Open(v * factor),
        };
        Self {
            field: field.into(),
            // The value was typed in the new unit: the conversion's own rounding is taken off.
            value: to_12_digits(self.value * factor),
            range: Range { lo: scale(self.range.lo), hi: scale(self.range.hi), unit },
        }
    }
}

impl fmt::Display for RangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let allowed = self.range.describe(&self.field);
        if self.value.is_finite() {
            write!(f, "{} = {} is out of range: allowed {allowed}", self.field, exact(self.value))
        } else {
            write!(f, "{} is not a finite number: allowed {allowed}", self.field)
        }
    }
}

impl std::error::Error for RangeError {}

/// An error that can say which input field it is about, so a front end maps it to its own flag or
/// request key from data, never from message text.
pub trait FieldError: std::error::Error {
    /// The input field at fault, if the error is about one.
    fn field(&self) -> Option<&str>;
}

impl FieldError for RangeError {
    fn field(&self) -> Option<&str> {
        Some(&self.field)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_in_another_unit_scales_value_and_bounds() {
        let e = Range::open_closed(0.0, 100.0, "m").check("distance_m", -0.01).unwrap_err();
        let cm = e.in_unit("distance_cm", 100.0, "cm");
        assert_eq!(cm.to_string(), "distance_cm = -1 is out of range: allowed 0 < distance_cm ≤ 10000 cm");
        assert!(!cm.range.contains(cm.value));
        // A one-sided range keeps its open side.
        let e = Range::below(0.22, "m").check("first_stage_m", 0.3).unwrap_err();
        assert_eq!(
            e.in_unit("first_stage_cm", 100.0, "cm").to_string(),
            "first_stage_cm = 30 is out of range: allowed first_stage_cm < 22 cm"
        );
        // Not a number stays not a number.
        let e = Range::closed(0.0, 1.0, "m").check("x_m", f64::NAN).unwrap_err();
        assert_eq!(e.in_unit("x_mm", 1e3, "mm").to_string(), "x_mm is not a finite number: allowed 0 ≤ x_mm ≤ 1000 mm");
    }

    #[test]
    fn messages_name_field_range_and_unit() {
        let r = Range::closed(0.0, 0.25, "");
        assert_eq!(
            r.check("ramp", 1e300).unwrap_err().to_string(),
            "ramp = 1e300 is out of range: allowed 0 ≤ ramp ≤ 0.25"
        );
        let s = Range::open_closed(0.0, 1e5, "rpm");
        assert_eq!(
            s.check("speed_rpm", -5.0).unwrap_err().to_string(),
            "speed_rpm = -5 is out of range: allowed 0 < speed_rpm ≤ 100000 rpm"
        );
        assert_eq!(
            s.check("speed_rpm", f64::NAN).unwrap_err().to_string(),
            "speed_rpm is not a finite number: allowed 0 < speed_rpm ≤ 100000 rpm"
        );
        assert_eq!(Range::above(0.0, "kg").describe("mass_kg"), "mass_kg > 0 kg");
        assert_eq!(Range::at_least(1.0, "").describe("points"), "points ≥ 1");
        assert_eq!(Range::below(90.0, "deg").describe("pressure_deg"), "pressure_deg < 90 deg");
        assert_eq!(Range::finite("mm").describe("offset_mm"), "offset_mm any finite number mm");
    }

    #[test]
    fn bounds_are_exact() {
        let r = Range::open_closed(0.0, 1.0, "");
        assert!(!r.contains(0.0) && r.contains(5e-324) && r.contains(1.0) && !r.contains(1.0 + f64::EPSILON));
        let c = Range::closed_open(0.0, 1.0, "");
        assert!(c.contains(0.0) && !c.contains(1.0));
        assert!(!Range::finite("").contains(f64::INFINITY));
        assert!(!Range::finite("").contains(f64::NAN));
    }

    #[test]
    fn the_field_is_data() {
        let e = Range::closed(1.0, 2.0, "").check("alpha_deg", 3.0).unwrap_err();
        assert_eq!(FieldError::field(&e), Some("alpha_deg"));
        assert_eq!(e.renamed("alpha").field, "alpha");
    }
}
