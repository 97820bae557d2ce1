//! Errors of the loom model.

use loomkin_laws::LawError;
use loomkin_picking::PickError;
use loomkin_shed::ShedError;
use loomkin_units::{FieldError, RangeError};
use thiserror::Error;

/// Everything that can be wrong with a loom file, a weave pattern or a study of them.
///
/// Each variant names the field of the loom file (`geometry.back_rest_mm`) or the section of a
/// pattern file (`[TIEUP]`) at fault.
#[derive(Debug, Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum LoomError {
    /// A number outside its allowed range, or not a finite number.
    #[error(transparent)]
    Range(#[from] RangeError),
    /// A loom file that cannot be read, or a field that is missing, unknown or contradicts another.
    #[error("{field}: {reason}")]
    Field {
        /// The field (`section.key`).
        field: String,
        /// Why.
        reason: String,
    },
    /// A weave pattern (WIF or lift plan) that cannot be read or whose sections disagree.
    #[error("{section}: {reason}")]
    Pattern {
        /// The section (`[TIEUP]`) or line (`line 3`).
        section: String,
        /// Why.
        reason: String,
    },
    /// A requirement no setting can meet (a window no stagger can give, a carrier taller than the shed).
    #[error("{field}: {reason}")]
    Infeasible {
        /// The field whose requirement cannot be met.
        field: String,
        /// Why, with the best that can be had.
        reason: String,
    },
    /// An error of the law core (a law or cycle in the loom file).
    #[error("shedding: {0}")]
    Law(#[from] LawError),
    /// An error of the shedding laws (a preset or piecewise law in the loom file).
    #[error("shedding: {0}")]
    Shed(#[from] ShedError),
    /// An error of the picking study (the shuttle of the loom file).
    #[error("insertion.shuttle: {0}")]
    Pick(#[from] PickError),
    /// The computation was stopped through its [`loomkin_units::StopFlag`] before it finished.
    #[error(transparent)]
    Stopped(#[from] loomkin_units::Stopped),
    /// An error of electronic shedding (`[shedding.servo]`, a frame's plan or drive).
    #[error(transparent)]
    Eshed(#[from] loomkin_eshed::EshedError),
}

impl LoomError {
    pub(crate) fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field { field: field.into(), reason: reason.into() }
    }

    pub(crate) fn pattern(section: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Pattern { section: section.into(), reason: reason.into() }
    }

    /// Whether the error is about the loom file: it names one of the file's keys
    /// (`insertion.carrier_height_mm`, [`LOOM_FILE_KEYS`]) or comes from a law, shuttle or servo
    /// drive the file gives, whether it was found while the file was read or while a study ran
    /// (a carrier taller than the shed). `false` for a weave pattern's error, an option of a study
    /// (`min_clearance_mm`) and a stop: a front end that read the file from a path names the path
    /// before the first kind only.
    pub fn in_loom_file(&self) -> bool {
        match self {
            Self::Law(_) | Self::Shed(_) | Self::Pick(_) | Self::Eshed(_) => true,
            Self::Pattern { .. } | Self::Stopped(_) => false,
            Self::Range(RangeError { field, .. }) | Self::Field { field, .. } | Self::Infeasible { field, .. } => {
                let key = field.split(['.', '[', ' ', ':', ',']).next().unwrap_or("");
                LOOM_FILE_KEYS.contains(&key)
            }
        }
    }
}

/// The keys at the top of a loom file: its numbers and its tables (a test checks them against
/// the file reader and the examples).
pub const LOOM_FILE_KEYS: [&str; 12] = [
    "name",
    "speed_rpm",
    "efficiency",
    "motor_torque_n_m",
    "geometry",
    "frames",
    "warp",
    "shedding",
    "insertion",
    "beat_up",
    "sley",
    "drive",
];

impl FieldError for LoomError {
    fn field(&self) -> Option<&str> {
        match self {
            Self::Range(e) => Some(&e.field),
            Self::Field { field, .. } | Self::Infeasible { field, .. } => Some(field),
            Self::Pattern { section, .. } => Some(section),
            Self::Law(e) => e.field(),
            Self::Shed(e) => e.field(),
            Self::Pick(e) => e.field(),
            Self::Stopped(_) => None,
            Self::Eshed(e) => e.field(),
        }
    }
}

/// Result alias of the loom model.
pub type Result<T, E = LoomError> = std::result::Result<T, E>;
