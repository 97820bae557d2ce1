//! Errors of the servo crate.

use loomkin_laws::LawError;
use loomkin_units::{FieldError, RangeError, compact};
use thiserror::Error;

/// Everything that can be wrong with definition points, a drive or an export request.
///
/// Every variant names the offending field (or definition point, numbered from 1 as in the paper)
/// and, where there is one, the allowed range and unit.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ServoError {
    /// A definition point that breaks a rule (order, range, end values, finiteness).
    #[error("definition point {index} [{}, {}]: {reason}", compact(*x), compact(*y))]
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
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
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
    /// A cam table that cannot be written (the engine of `loomkin_cams::table`).
    #[error("{field}: {reason}")]
    Table {
        /// Name of the field.
        field: String,
        /// Why.
        reason: String,
    },
    /// The computation was stopped through its [`loomkin_units::StopFlag`] before it finished.
    #[error(transparent)]
    Stopped(#[from] loomkin_units::Stopped),
}

impl From<loomkin_cams::CamError> for ServoError {
    fn from(e: loomkin_cams::CamError) -> Self {
        use loomkin_units::FieldError;
        match e {
            loomkin_cams::CamError::Range(r) => Self::Range(r),
            loomkin_cams::CamError::Stopped(s) => Self::Stopped(s),
            e => Self::Table {
                field: e.field().unwrap_or("table").to_string(),
                // The message without its leading "field: ".
                reason: e.to_string().split_once(": ").map_or_else(|| e.to_string(), |(_, r)| r.to_string()),
            },
        }
    }
}

impl FieldError for ServoError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Point { .. } | Self::TooFewPoints { .. } | Self::NoRise { .. } => Some("def_points"),
            Self::Range(e) => Some(&e.field),
            Self::Parse { field, .. } | Self::Cycle { field, .. } | Self::Table { field, .. } => Some(field),
            Self::Law(e) => e.field(),
            Self::Stopped(_) => None,
        }
    }
}

/// Result alias of the servo crate.
pub type Result<T, E = ServoError> = std::result::Result<T, E>;
