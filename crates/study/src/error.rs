//! Errors of the study tools.

use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can be wrong with an experiment design or a study request.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum StudyError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
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
    /// A distribution or limit of a Monte-Carlo study that cannot be drawn from.
    #[error("{field}: {reason}")]
    Distribution {
        /// The input (or result) it was given for.
        field: String,
        /// What is wrong, with the allowed values.
        reason: String,
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

impl FieldError for StudyError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::TooLarge { field, .. } | Self::Shape { field, .. } | Self::Distribution { field, .. } => Some(field),
        }
    }
}

/// Result alias of the study tools.
pub type Result<T, E = StudyError> = std::result::Result<T, E>;
