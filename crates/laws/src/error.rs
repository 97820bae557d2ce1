//! Errors of the law core.

use thiserror::Error;

/// Everything that can be wrong with a law or a cycle definition.
///
/// Each variant names the offending field and, where there is one, the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LawError {
    /// A numeric parameter outside its allowed range.
    #[error(
        "{field} = {} is out of range: allowed {} {} {field} ≤ {}{unit}",
        compact(*.value), compact(*.min), if *.min_exclusive { "<" } else { "≤" }, compact(*.max)
    )]
    OutOfRange {
        /// Name of the field.
        field: String,
        /// Offending value.
        value: f64,
        /// Lowest allowed value.
        min: f64,
        /// Highest allowed value.
        max: f64,
        /// Unit suffix (with a leading space) or empty.
        unit: String,
        /// Whether the lower bound itself is excluded.
        min_exclusive: bool,
    },
    /// A value that is not a finite number.
    #[error("{field} is not a finite number")]
    NotFinite {
        /// Name of the field.
        field: String,
    },
    /// Relative lengths that do not sum to one.
    #[error("{field}: relative lengths sum to {}, they must sum to 1 (±1e-9)", compact(*.sum))]
    LengthsDoNotSumToOne {
        /// Name of the field.
        field: String,
        /// The sum found.
        sum: f64,
    },
    /// An unknown law name.
    #[error("unknown law '{name}': known laws are {known}")]
    UnknownLaw {
        /// The name given.
        name: String,
        /// Comma-separated list of known names.
        known: String,
    },
    /// An unknown parameter key for a law.
    #[error("law '{law}' has no parameter '{key}': allowed {allowed}")]
    UnknownParam {
        /// Law name.
        law: String,
        /// Key given.
        key: String,
        /// Allowed keys.
        allowed: String,
    },
    /// A textual value that could not be parsed.
    #[error("{field}: cannot read '{text}': expected {expected}")]
    Parse {
        /// Name of the field.
        field: String,
        /// Text given.
        text: String,
        /// What was expected.
        expected: String,
    },
    /// An acceleration shape that does not bring the follower to rest or makes no rise.
    #[error("{field}: {reason}")]
    NotARise {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
    /// Cycle segments that do not close the cycle.
    #[error("{field}: {reason}")]
    Cycle {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
}

impl LawError {
    /// Shorthand for [`LawError::OutOfRange`].
    pub fn out_of_range(field: impl Into<String>, value: f64, min: f64, max: f64, unit: &str) -> Self {
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        Self::OutOfRange { field: field.into(), value, min, max, unit, min_exclusive: false }
    }

    /// Shorthand for [`LawError::OutOfRange`] with an excluded lower bound (`min < value ≤ max`).
    pub fn out_of_open_range(field: impl Into<String>, value: f64, min: f64, max: f64, unit: &str) -> Self {
        match Self::out_of_range(field, value, min, max, unit) {
            Self::OutOfRange { field, value, min, max, unit, .. } => {
                Self::OutOfRange { field, value, min, max, unit, min_exclusive: true }
            }
            other => other,
        }
    }

    /// Checks `min ≤ value ≤ max` and finiteness.
    pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64, Self> {
        if !value.is_finite() {
            return Err(Self::NotFinite { field: field.into() });
        }
        if value < min || value > max {
            return Err(Self::out_of_range(field, value, min, max, unit));
        }
        Ok(value)
    }
}

/// A number for a message: plain for ordinary magnitudes, in exponent form for huge or tiny ones, so
/// that `1e308` is not written out in 309 digits.
pub fn compact(v: f64) -> String {
    if v.is_nan() {
        return "not-a-number".into();
    }
    // The largest finite values stand for open bounds.
    if v >= f64::MAX {
        return "∞".into();
    }
    if v <= f64::MIN {
        return "-∞".into();
    }
    // At most 12 significant digits, so representation noise (0.1 + 0.2) does not show.
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) { format!("{}", rounded + 0.0) } else { format!("{rounded:e}") }
}

/// Result alias of the law core.
pub type Result<T, E = LawError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_keep_numbers_short() {
        assert_eq!(compact(1e308), "1e308");
        assert_eq!(compact(0.25), "0.25");
        assert_eq!(compact(0.1 + 0.2), "0.3");
        assert_eq!(compact(-2.5e-7), "-2.5e-7");
        assert_eq!(compact(f64::NAN), "not-a-number");
        assert_eq!(compact(f64::NEG_INFINITY), "-∞");
        let e = LawError::out_of_range("ramp", 1e300, 0.0, 0.25, "").to_string();
        assert_eq!(e, "ramp = 1e300 is out of range: allowed 0 ≤ ramp ≤ 0.25");
    }
}
