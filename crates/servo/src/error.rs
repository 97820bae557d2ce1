//! Errors of the servo crate.

use loomkin_laws::LawError;
use thiserror::Error;

/// Everything that can be wrong with definition points, a drive or an export request.
///
/// Every variant names the offending field (or definition point, numbered from 1 as in the paper)
/// and, where there is one, the allowed range and unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ServoError {
    /// A definition point that breaks a rule (order, range, end values, finiteness).
    #[error("definition point {index} [{}, {}]: {reason}", num(*x), num(*y))]
    Point {
        /// Number of the point, 1-based (the paper's `j`).
        index: usize,
        /// Its X (fraction of the motion angle).
        x: f64,
        /// Its Y (relative acceleration).
        y: f64,
        /// What is wrong and what is allowed.
        reason: String,
    },
    /// Fewer definition points than the spline needs.
    #[error("def_points: {count} definition points given, at least {min} are needed")]
    TooFewPoints {
        /// Number given.
        count: usize,
        /// Minimum number.
        min: usize,
    },
    /// Points that define no rise (e.g. every Y zero, or a net motion backwards).
    #[error("def_points: {reason}")]
    NoRise {
        /// Why.
        reason: String,
    },
    /// A numeric value outside its allowed range.
    #[error("{field} = {} is out of range: allowed {} ≤ {field} ≤ {}{unit}", num(*value), num(*min), num(*max))]
    OutOfRange {
        /// Name of the field.
        field: String,
        /// Offending value.
        value: f64,
        /// Lowest allowed value.
        min: f64,
        /// Highest allowed value.
        max: f64,
        /// Unit suffix with a leading space, or empty.
        unit: String,
    },
    /// A value that is not a finite number.
    #[error("{field} is not a finite number")]
    NotFinite {
        /// Name of the field.
        field: String,
    },
    /// Text that could not be read.
    #[error("{field}: cannot read '{text}': expected {expected}")]
    Parse {
        /// Name of the field.
        field: String,
        /// Text given.
        text: String,
        /// What was expected.
        expected: String,
    },
    /// Angles of the machine cycle that do not fit in one turn.
    #[error("{field}: {reason}")]
    Cycle {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
    /// An error of the law core.
    #[error(transparent)]
    Law(#[from] LawError),
}

impl ServoError {
    /// Checks `min ≤ value ≤ max` and finiteness; `unit` is appended to the message.
    pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        if !value.is_finite() {
            return Err(Self::NotFinite { field: field.into() });
        }
        if value < min || value > max {
            let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
            return Err(Self::OutOfRange { field: field.into(), value, min, max, unit });
        }
        Ok(value)
    }
}

/// A number for a message: shortest round-trip form for ordinary magnitudes, scientific notation
/// for very large or small ones, and at most 12 significant digits (so `0.1 + 1e-4` reads
/// `0.1001`, not `0.10010000000000001`).
pub(crate) fn num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    // Round to 12 significant digits through the exponent form, then print the shorter of the
    // plain and the scientific form.
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    if a == 0.0 || (1e-4..1e9).contains(&a) { format!("{rounded}") } else { format!("{rounded:e}") }
}

/// Result alias of the servo crate.
pub type Result<T, E = ServoError> = std::result::Result<T, E>;
