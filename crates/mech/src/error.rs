//! Errors of the mechanisms crate.

use loomkin_laws::LawError;
use thiserror::Error;

/// Everything that can go wrong when a mechanism is defined, assembled or traced.
///
/// Every variant names the offending field or the input angle, the condition that failed and,
/// where one exists, the admissible range with its unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MechError {
    /// A numeric parameter outside its allowed range.
    #[error("{field} = {} is out of range: allowed {min} ≤ {field} ≤ {max}{unit}", short_number(*value))]
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
    /// A value that is not a finite number.
    #[error("{field} is not a finite number")]
    NotFinite {
        /// Name of the field.
        field: String,
    },
    /// A structurally invalid definition (wrong number of equations, bad index, …).
    #[error("{field}: {reason}")]
    Invalid {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
    /// Newton's method did not converge at an input value.
    #[error("no assembly at input {input:.6}: Newton stopped after {iterations} iterations with residual {residual:e}")]
    NoConvergence {
        /// Input coordinate (rad for an angle input).
        input: f64,
        /// Iterations used.
        iterations: usize,
        /// Residual norm reached (m for a vector loop).
        residual: f64,
    },
    /// The loop Jacobian is singular: a fold (dead point) of the mechanism.
    #[error(
        "singular position at input {input:.6}: the loop Jacobian is singular (|det| = {det:e}), a fold or dead point"
    )]
    Singular {
        /// Input coordinate (rad for an angle input).
        input: f64,
        /// Determinant of the Jacobian found.
        det: f64,
    },
    /// Continuation could not follow the branch (a fold passed between two steps).
    #[error("the branch ends between input {from:.6} and {to:.6}: {reason}")]
    BranchLost {
        /// Last input coordinate solved.
        from: f64,
        /// Input coordinate that could not be reached.
        to: f64,
        /// Why.
        reason: String,
    },
    /// Two circles or a line and a circle that do not meet (a dyad that cannot assemble).
    #[error("{what} cannot assemble: {reason}")]
    NoIntersection {
        /// The dyad.
        what: String,
        /// The failed condition with numbers.
        reason: String,
    },
    /// The mechanism cannot be built at an input angle (the dobby's named conditions).
    #[error("at φ2 = {phi2_deg:.3}°: {condition}{}", admissible.as_deref().map(|a| format!("; {a}")).unwrap_or_default())]
    CannotBuild {
        /// Input angle φ2 (degrees) where the condition fails.
        phi2_deg: f64,
        /// The condition, with its numbers.
        condition: String,
        /// The admissible range of a design parameter, where it can be given.
        admissible: Option<String>,
    },
    /// A point table that cannot be read or fitted.
    #[error("point table, {location}: {reason}")]
    PointTable {
        /// Line or point index.
        location: String,
        /// Why.
        reason: String,
    },
    /// An error of the law core.
    #[error(transparent)]
    Law(#[from] LawError),
}

/// A number as a user typed it: plain for ordinary magnitudes, in exponent form outside
/// 1e-4…1e9 (so that `1e308` does not print as 309 digits).
fn short_number(v: f64) -> String {
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) { format!("{v}") } else { format!("{v:e}") }
}

impl MechError {
    /// Shorthand for [`MechError::OutOfRange`].
    pub fn out_of_range(field: impl Into<String>, value: f64, min: f64, max: f64, unit: &str) -> Self {
        let unit = if unit.is_empty() { String::new() } else { format!(" {unit}") };
        Self::OutOfRange { field: field.into(), value, min, max, unit }
    }

    /// Checks `min ≤ value ≤ max` and finiteness; returns the value.
    pub fn check_range(field: &str, value: f64, min: f64, max: f64, unit: &str) -> Result<f64> {
        if !value.is_finite() {
            return Err(Self::NotFinite { field: field.into() });
        }
        if value < min || value > max {
            return Err(Self::out_of_range(field, value, min, max, unit));
        }
        Ok(value)
    }
}

/// Result alias of the mechanisms crate.
pub type Result<T, E = MechError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn huge_values_print_short() {
        let e = MechError::check_range("alpha_deg", 1e308, 0.0, 180.0, "°").unwrap_err().to_string();
        assert!(e.starts_with("alpha_deg = 1e308 is out of range"), "{e}");
        let e = MechError::check_range("l2_m", -0.5, 0.0, 100.0, "m").unwrap_err().to_string();
        assert!(e.starts_with("l2_m = -0.5 is out"), "{e}");
    }
}
