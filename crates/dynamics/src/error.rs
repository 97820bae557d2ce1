//! The error type of the crate.

use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can go wrong in a dynamics computation.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum DynError {
    /// A number outside its allowed range.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// The cycle or law could not be read or built.
    #[error("{field}: {reason}")]
    Input {
        /// The offending field.
        field: String,
        /// Why.
        reason: String,
    },
    /// The periodic steady state does not exist (or is not representable in double precision).
    #[error(
        "speed_rpm = {speed_rpm}: no periodic steady state — undamped and the natural frequency is {ratio} × the \
         shaft frequency (an integer multiple resonates with a harmonic of the cycle); give damping_ratio > 0 or \
         another speed"
    )]
    NoSteadyState {
        /// Shaft speed (rpm).
        speed_rpm: String,
        /// f_n / f_shaft.
        ratio: String,
    },
    /// The compensating input law does not exist.
    #[error("{field}: no compensating input — {reason}")]
    NoCompensation {
        /// The offending field (a cycle segment).
        field: String,
        /// Why.
        reason: String,
    },
    /// The optimiser failed.
    #[error("optimizer: {reason}")]
    Optimizer {
        /// Why.
        reason: String,
    },
}

impl FieldError for DynError {
    fn field(&self) -> Option<&str> {
        match self {
            DynError::Range(e) => Some(&e.field),
            DynError::Input { field, .. } | DynError::NoCompensation { field, .. } => Some(field),
            DynError::NoSteadyState { .. } => Some("speed_rpm"),
            DynError::Optimizer { .. } => None,
        }
    }
}

impl From<loomkin_laws::LawError> for DynError {
    fn from(e: loomkin_laws::LawError) -> Self {
        DynError::Input { field: "cycle".into(), reason: e.to_string() }
    }
}

/// Result with [`DynError`].
pub type Result<T> = std::result::Result<T, DynError>;
