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

pub mod cam_sley;
pub mod fourbar;
pub mod motor;
pub mod ripple;
pub mod sley;
pub mod timetrue;

pub use cam_sley::{CamContact, CamSley, CamSleyTable, Sley, SleyClosure, SleyDrive};
pub use fourbar::{CrankRocker, LoopState};
pub use motor::{Induction, Motor, MotorCurve, MotorKind, MotorSpec, Servo};
pub use ripple::{RippleError, RippleReport, Shaft, Solution, Table, flywheel_for, solve};
pub use sley::synth::{SleySynthesis, SleyTarget};
pub use timetrue::{CorrectedMove, Span, TimeMap, correct_move, time_excitation};

pub use sley::{
    Assembly, FourBarSley, ReedMotion, SleyAnalysis, SleyError, SleyForces, SleyJoints, SleyRow, SleyState, SleyTable,
};

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
    CamSleyTable::BACK_ANGLE_DEG,
    SleyAnalysis::DWELL_TOLERANCE_MM,
    SleyAnalysis::POINTS,
    SleyTarget::STROKE_MM,
    SleyTarget::BACK_DWELL_DEG,
    SleyTarget::REED_HEIGHT_MM,
    SleyTarget::SWORD_MM,
    ripple::STEP_DEG,
    ripple::FLYWHEEL_KG_M2,
    ripple::TARGET_RIPPLE_PCT,
    Induction::SYNCHRONOUS_RPM,
    Induction::RATED_RPM,
    Induction::RATED_POWER_KW,
    Induction::BREAKDOWN_RATIO,
    Induction::GEAR_RATIO,
    Servo::GAIN_N_M_S,
    Servo::INTEGRAL_S,
    Servo::TORQUE_LIMIT_N_M,
];
