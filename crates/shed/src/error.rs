//! Errors of the shedding study.

use loomkin_laws::LawError;
use loomkin_study::StudyError;
use loomkin_units::{FieldError, RangeError, compact};
use thiserror::Error;

/// Everything that can be wrong with a shedding law, its evaluation conditions or a study.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ShedError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
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
        compact(*.value)
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
    /// The computation was stopped through its [`loomkin_units::StopFlag`] before it finished.
    #[error(transparent)]
    Stopped(#[from] loomkin_units::Stopped),
}

impl FieldError for ShedError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::LengthsDoNotSumToOne { field, .. }
            | Self::Parse { field, .. }
            | Self::NotARise { field, .. }
            | Self::NotFinite { field, .. } => Some(field),
            Self::UnknownPreset { .. } => Some("law"),
            Self::Law(e) => e.field(),
            Self::Study(e) => e.field(),
            Self::Stopped(_) => None,
        }
    }
}

/// Result alias of the shedding study.
pub type Result<T, E = ShedError> = std::result::Result<T, E>;
