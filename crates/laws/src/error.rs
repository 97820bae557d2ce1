//! Errors of the law core.

use thiserror::Error;

/// Everything that can be wrong with a law or a cycle definition.
///
/// Each variant names the offending field and, where there is one, the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LawError {
    /// A numeric parameter outside its allowed range.
    #[error("{field} = {value} is out of range: allowed {min} {} {field} ≤ {max}{unit}", if *.min_exclusive { "<" } else { "≤" })]
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
    #[error("{field}: relative lengths sum to {sum}, they must sum to 1 (±1e-9)")]
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

/// Result alias of the law core.
pub type Result<T, E = LawError> = std::result::Result<T, E>;
