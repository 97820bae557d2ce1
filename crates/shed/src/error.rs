//! Errors of the shedding study.

use loomkin_laws::LawError;
use loomkin_study::StudyError;
use thiserror::Error;

/// Everything that can be wrong with a shedding law, its evaluation conditions or a study.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ShedError {
    /// A numeric parameter outside its allowed range.
    #[error("{field} = {} is out of range: allowed {} ≤ {field} ≤ {}{unit}", num(.value), num(.min), num(.max))]
    OutOfRange {
        /// Name of the field.
        field: String,
        /// Offending value.
        value: f64,
        /// Lowest allowed value.
        min: f64,
        /// Highest allowed value.
        max: f64,
        /// Unit suffix (with a leading space), or a note on open bounds, or empty.
        unit: String,
    },
    /// Relative lengths `k_Ti` that do not sum to one.
    #[error("{field}: relative lengths k_Ti sum to {sum}, they must sum to 1 (±1e-9)")]
    LengthsDoNotSumToOne {
        /// Name of the field.
        field: String,
        /// The sum found.
        sum: f64,
    },
    /// An unknown preset name.
    #[error("unknown shedding law '{name}': known laws are {known}")]
    UnknownPreset {
        /// The name given.
        name: String,
        /// Comma-separated list of known names.
        known: String,
    },
    /// A definition that cannot be read (TOML or text).
    #[error("{field}: {reason}")]
    Parse {
        /// Name of the field or file.
        field: String,
        /// Why.
        reason: String,
    },
    /// A law that does not make a rise between rests.
    #[error("{field}: {reason}")]
    NotARise {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
    /// A value inside its range for which the physical peaks overflow the range of numbers (a
    /// motion angle far too small for the stroke and speed).
    #[error(
        "{field} = {} makes the peak velocity, acceleration or jerk overflow at this stroke and speed: use a larger {field}",
        num(.value)
    )]
    NotFinite {
        /// Name of the field.
        field: String,
        /// Offending value.
        value: f64,
    },
    /// An error of the law core.
    #[error(transparent)]
    Law(#[from] LawError),
    /// An error of the study tools (design grids).
    #[error(transparent)]
    Study(#[from] StudyError),
}

impl ShedError {
    /// Checks `min ≤ value ≤ max` and finiteness (a non-finite value is reported as out of range).
    pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        if value.is_finite() && value >= min && value <= max {
            return Ok(value);
        }
        Err(Self::out_of_range(field, value, min, max, unit))
    }

    /// Checks `min < value ≤ max` (open at the bottom) and finiteness.
    pub fn check_open_closed(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        if value.is_finite() && value > min && value <= max {
            return Ok(value);
        }
        let note = if unit.is_empty() {
            "(exclusive of the minimum)".to_string()
        } else {
            format!("{unit}, exclusive of the minimum")
        };
        Err(Self::out_of_range(field, value, min, max, &note))
    }

    /// Shorthand for [`ShedError::OutOfRange`].
    pub fn out_of_range(field: impl Into<String>, value: f64, min: f64, max: f64, unit: &str) -> Self {
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        Self::OutOfRange { field: field.into(), value, min, max, unit }
    }
}

/// A number for an error line, in the core's compact form ([`loomkin_laws::compact`]).
pub(crate) fn num(v: &f64) -> String {
    loomkin_laws::compact(*v)
}

/// Result alias of the shedding study.
pub type Result<T, E = ShedError> = std::result::Result<T, E>;
