//! Errors of the cam crate.

use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can be wrong with a cam, its input or its output.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum CamError {
    /// A number outside its allowed range.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// A law or cycle that cannot be used.
    #[error("{field}: {reason}")]
    Law {
        /// The field at fault.
        field: String,
        /// Why.
        reason: String,
    },
    /// A combination of options that cannot be honoured.
    #[error("{field}: {reason}")]
    Usage {
        /// The field (option) at fault.
        field: String,
        /// Why.
        reason: String,
    },
    /// A written file that cannot be read back.
    #[error("{field}: {reason}")]
    Parse {
        /// The file or line at fault.
        field: String,
        /// Why.
        reason: String,
    },
    /// The computation was stopped through its [`loomkin_units::StopFlag`] before it finished.
    #[error(transparent)]
    Stopped(#[from] loomkin_units::Stopped),
}

impl FieldError for CamError {
    fn field(&self) -> Option<&str> {
        match self {
            CamError::Range(e) => e.field(),
            CamError::Law { field, .. } | CamError::Usage { field, .. } | CamError::Parse { field, .. } => Some(field),
            CamError::Stopped(_) => None,
        }
    }
}

impl From<loomkin_laws::LawError> for CamError {
    fn from(e: loomkin_laws::LawError) -> Self {
        CamError::Law { field: "law".into(), reason: e.to_string() }
    }
}

/// Result of the cam crate.
pub type Result<T, E = CamError> = std::result::Result<T, E>;
