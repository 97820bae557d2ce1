//! Errors of electronic shedding.

use loomkin_laws::LawError;
use loomkin_servo::ServoError;
use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can be wrong with a servo-shedding table, a lift plan or a plan of moves.
///
/// Each variant names the field at fault, as the loom file spells it (`shedding.servo.bus.voltage_v`).
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum EshedError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// A table that cannot be read, or a field that is missing, unknown or contradicts another.
    #[error("{field}: {reason}")]
    Field {
        /// The field (`shedding.servo.motor`).
        field: String,
        /// Why.
        reason: String,
    },
    /// An error of the law core (a frame's cycle of moves).
    #[error("{0}")]
    Law(#[from] LawError),
    /// An error of the servo axis model (a motor or transmission out of range).
    #[error("{0}")]
    Servo(#[from] ServoError),
}

impl EshedError {
    pub(crate) fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field { field: field.into(), reason: reason.into() }
    }
}

impl FieldError for EshedError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::Field { field, .. } => Some(field),
            Self::Law(e) => e.field(),
            Self::Servo(e) => e.field(),
        }
    }
}

/// Result alias of electronic shedding.
pub type Result<T, E = EshedError> = std::result::Result<T, E>;
