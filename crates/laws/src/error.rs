//! Errors of the law core.

pub use loomkin_units::compact;
use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can be wrong with a law or a cycle definition.
///
/// Each variant names the offending field and, where there is one, the allowed range.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LawError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
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

impl FieldError for LawError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::LengthsDoNotSumToOne { field, .. }
            | Self::Parse { field, .. }
            | Self::NotARise { field, .. }
            | Self::Cycle { field, .. } => Some(field),
            Self::UnknownLaw { .. } => Some("law"),
            Self::UnknownParam { key, .. } => Some(key),
        }
    }
}

/// Result alias of the law core.
pub type Result<T, E = LawError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_errors_name_the_field_as_data() {
        let e: LawError = crate::RAMP.check("ramp", 1e300).unwrap_err().into();
        assert_eq!(e.to_string(), "ramp = 1e300 is out of range: allowed 1e-6 ≤ ramp ≤ 0.25");
        assert_eq!(e.field(), Some("ramp"));
        assert_eq!(compact(1e308), "1e308");
    }
}
