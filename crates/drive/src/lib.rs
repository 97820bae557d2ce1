//! # loomkin-drive — the sley and the main-shaft drive
//!
//! Every other study in loomkin assumes the main shaft turns at a constant speed. This crate is
//! where that assumption is dropped: the sley (batten) linkage the main shaft drives, the moment
//! of inertia the loom's mechanisms present to the shaft as it turns (J(φ)), the periodic motion
//! of the shaft under a motor and a load (speed ripple, flywheel sizing), and cam laws corrected
//! for the shaft's real speed (time-true cams).
//!
//! It sits below `loomkin-loom`: the mechanisms and the solvers live here, as library types with
//! their own bounds; the whole loom (its file, its frames over a pattern repeat) assembles them.
#![deny(missing_docs)]

pub mod sley;

pub use sley::synth::{SleySynthesis, SleyTarget};
pub use sley::{Assembly, FourBarSley, ReedMotion, SleyAnalysis, SleyError, SleyForces, SleyRow, SleyState, SleyTable};

/// The descriptors this crate declares.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    SleyTable::CRANK_MM,
    SleyTable::ROD_MM,
    SleyTable::SWORD_MM,
    SleyTable::PIVOT_X_MM,
    SleyTable::PIVOT_Y_MM,
    SleyTable::REED_HEIGHT_MM,
    SleyTable::MASS_KG,
    SleyTable::GYRATION_MM,
    SleyTable::CENTRE_MM,
    SleyTable::BEAT_UP_DEG,
    SleyTable::BEAT_UP_FORCE_N,
    SleyTable::BEAT_UP_RANGE_DEG,
    SleyAnalysis::DWELL_TOLERANCE_MM,
    SleyAnalysis::POINTS,
    SleyTarget::STROKE_MM,
    SleyTarget::BACK_DWELL_DEG,
    SleyTarget::REED_HEIGHT_MM,
    SleyTarget::SWORD_MM,
];
