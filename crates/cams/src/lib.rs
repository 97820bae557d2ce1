//! # loomkin-cams — from a law to a part
//!
//! Controller cam tables for any law or machine cycle ([`table`]); disc cam profiles, their
//! pressure angle, curvature, undercut and sizing ([`profile`]).
#![deny(missing_docs)]

mod error;
pub mod profile;
pub mod table;

pub use error::{CamError, Result};
use profile::{CamDesign, CamProfile};
use table::{Motion, Spacing};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    CamDesign::ROLLER_RADIUS_MM,
    CamDesign::OFFSET_MM,
    CamDesign::PRIME_RADIUS_MM,
    CamDesign::MAX_PRESSURE_DEG,
    CamDesign::ARM_MM,
    CamDesign::PIVOT_MM,
    CamProfile::STEP_DEG,
    CamProfile::CHORD_TOL_MM,
    CamProfile::BORE_MM,
    Spacing::STEP_DEG,
    Spacing::TOLERANCE,
    Motion::MOTION_DEG,
    Motion::STROKE_MM,
    Motion::STROKE_DEG,
];
