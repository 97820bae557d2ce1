//! Errors of the study tools.

use thiserror::Error;

/// Everything that can be wrong with an experiment design or a study request.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum StudyError {
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
        /// Unit suffix (with a leading space) or empty.
        unit: String,
    },
    /// A grid that would hold more points than allowed.
    #[error("{field}: the design would hold {points} points, more than the limit of {limit}")]
    TooLarge {
        /// Name of the design or axis.
        field: String,
        /// Number of points it would hold.
        points: u128,
        /// The limit.
        limit: usize,
    },
    /// Rows or objective vectors of inconsistent length.
    #[error("{field}: expected {expected} values per row, found {found}")]
    Shape {
        /// Name of the input.
        field: String,
        /// Values expected per row.
        expected: usize,
        /// Values found.
        found: usize,
    },
}

impl StudyError {
    /// Checks `min ≤ value ≤ max` and finiteness (a non-finite value is reported as out of range).
    pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64, Self> {
        if value.is_finite() && value >= min && value <= max {
            return Ok(value);
        }
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        Err(Self::OutOfRange { field: field.into(), value, min, max, unit })
    }
}

/// A number for an error line: `∞` for the largest finite value (an open upper bound), plain
/// text for ordinary magnitudes, the exponent form for very large or small ones, at most 12
/// significant digits (so that `f64::MAX` or `1e300` do not print as hundreds of digits).
pub(crate) fn num(v: &f64) -> String {
    let v = *v;
    if v.is_nan() {
        return "NaN".into();
    }
    if v >= f64::MAX {
        return "∞".into();
    }
    if v <= f64::MIN {
        return "−∞".into();
    }
    let rounded: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) { format!("{}", rounded + 0.0) } else { format!("{rounded:e}") }
}

/// Result alias of the study tools.
pub type Result<T, E = StudyError> = std::result::Result<T, E>;
