//! Errors of the mechanisms crate.

use loomkin_laws::LawError;
use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can go wrong when a mechanism is defined, assembled or traced.
///
/// Every variant names the offending field or the input angle, the condition that failed and,
/// where one exists, the admissible range with its unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum MechError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
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
        /// The design parameter that range is about (`alpha_deg`, `l3_m`, `dwell_deg`), as the input
        /// field a front end should point at; `None` when no single parameter is at fault.
        parameter: Option<&'static str>,
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

impl FieldError for MechError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::Invalid { field, .. } => Some(field),
            Self::CannotBuild { parameter, .. } => *parameter,
            Self::PointTable { .. } => Some("cam"),
            Self::Law(e) => e.field(),
            _ => None,
        }
    }
}

/// Result alias of the mechanisms crate.
pub type Result<T, E = MechError> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;
    use loomkin_units::Range;

    #[test]
    fn huge_values_print_short() {
        let e: MechError = Range::closed(0.0, 180.0, "°").check("alpha_deg", 1e308).unwrap_err().into();
        assert!(e.to_string().starts_with("alpha_deg = 1e308 is out of range"), "{e}");
        assert_eq!(e.field(), Some("alpha_deg"));
    }
}
