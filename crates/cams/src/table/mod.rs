//! Cam tables for a motion controller from any law or cycle: points on the law's joints plus a
//! step, or as few as a tolerance allows; five formats with fixed decimals; and the exact error of
//! each table as written, re-read and re-interpolated the way the controller does.

mod camtable;
pub mod csv;
mod decimals;
mod format;
mod interp;
mod motion;
mod points;
pub mod poly5;
mod reinterpolation;
pub mod st;
mod tolerance;
pub mod twincat;
pub mod xyvaj;

pub use camtable::{CamTable, Export, INTERPOLATION, TableReport};
pub use decimals::{Decimals, RELATIVE_RESOLUTION, decimals_exact, decimals_for, fixed, round};
pub use format::Format;
pub use interp::Interval;
pub use motion::{MOTION_DEG_RANGE, Motion, Piece, STROKE_RANGE, SlaveMap};
pub use points::{
    CamPoint, DEFAULT_STEP_DEG, Interpolation, MAX_POINTS, STEP_RANGE, Spacing, TOLERANCE_RANGE, hermite_intervals,
};
pub use reinterpolation::{ReinterpolationError, reinterpolation_error, reinterpolation_error_until};
pub use tolerance::TOLERANCE_MARGIN;
