//! # loomkin-loom — the whole loom
//!
//! A loom designer never sets one heald frame alone: the frames sit at different distances behind
//! the cloth fell and must lift different heights for a clean shed, the weave pattern decides at
//! every pick which frames rise, fall or stay, the shedding drive carries all of them at once, and
//! the weft carrier must pass a shed that is open enough while it flies.
//!
//! * [`Loom`] — a loom file (TOML): geometry, frames, warp, shedding law with crossing angle and
//!   stagger, weft insertion, beat-up, speed; every field range-checked.
//! * [`Pattern`] — the weave: a WIF 1.1 file or a plain lift plan.
//! * [`Motion`] — every frame's motion over the repeat, in closed form (a machine cycle of the law
//!   core per frame, [`Motion::cycle_spec`]).
//! * [`geometry`] — clean-shed lifts, shed angles and depths, warp strain.
//! * [`insertion`] — the weft carrier on the loom: the time budget, the clearance in the shed.
//!
//! ```
//! use loomkin_loom::{Loom, Pattern, Motion};
//!
//! let loom = Loom::from_toml(include_str!("../../../examples/rapier-loom.toml"))?;
//! let pattern = Pattern::from_wif(include_str!("../../../examples/twill-2-2.wif"))?;
//! let motion = Motion::new(&loom, &pattern)?;
//! assert_eq!(motion.picks(), 4);
//! // Frame 2 stays up from the first pick to the second: it dwells at the top of its stroke.
//! let top = motion.stroke_m(1) / 2.0;
//! assert_eq!(motion.frame(1, 360.0 + 180.0).y_m, top);
//! assert_eq!(motion.frame(1, 360.0 - 10.0).dy, 0.0);
//! # Ok::<(), loomkin_loom::LoomError>(())
//! ```
#![deny(missing_docs)]

mod check;
mod diagram;
mod drive;
mod error;
mod file;
pub mod geometry;
mod inertia;
pub mod insertion;
pub mod insertion_air;
pub mod insertion_timing;
mod law;
mod motion;
mod pattern;
mod servo_shedding;
mod stagger;
mod timetrue;
mod timing;
mod turn_rows;
mod turns;

pub use check::{CheckReport, FrameCheck, check, check_with};
pub use diagram::{
    DEFAULT_TIMING_PICKS, DEFAULT_TIMING_STEP_DEG, TIMING_STEP_RANGE, TimingCurves, timing_curves, timing_diagram,
    torque_figure,
};
pub use drive::{Drive, FrameForce, MAX_RMS_SPLITS, Peak, TableCache, TorquePoint, TorquePoints, TorqueReport};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Drive::STEP_DEG,
    DriveSpec::ROTATING_INERTIA_KG_M2,
    DriveSpec::FRICTION_TORQUE_N_M,
    StaggerOptions::MIN_CLEARANCE_MM
];
pub use error::{LOOM_FILE_KEYS, LoomError, Result};
pub use file::{
    CarrierSpeed, FrameProps, G_M_S2, Geometry, Insertion, InsertionKind, Lifts, Loom, MAX_FRAMES, Shedding, Warp,
};
pub use inertia::{
    DriveSpec, InertiaReport, InertiaStats, LoomShaft, MechanismInertia, SideView, SleySide, ripple_figure,
};
pub use law::FrameLaw;
pub use motion::{FrameKin, Motion, Move, crossing_offset_deg};
pub use pattern::{MAX_PICKS, MAX_SHAFTS, Pattern, WIF_CODE_PAGE_NOTE, check_weavable, wif_text};
pub use servo_shedding::{
    Reduced, SERVO_PLOT_POINTS, ServoMotion, ServoOptimum, ServoOptions, frame_laws, optimise_servo,
    optimise_servo_with, reduced_pattern, servo_curves, servo_curves_of, servo_figure, servo_figure_of, servo_laws,
    servo_setups, servo_study, servo_study_of, servo_tables, servo_tables_of, servo_timing,
};
pub use stagger::{
    Objective, StaggerCase, StaggerOptions, StaggerResult, optimise_stagger, optimise_stagger_until,
    optimise_stagger_with,
};
pub use timetrue::{
    CorrectedFrames, Correction, CorrectionReport, FrameCorrection, MAX_ROUNDS, SleyCorrection, SleyTiming,
    TIMING_TOL_DEG, correct,
};
pub use timing::{PickWindow, ShedMotion, Timing, TimingReport, max_speed_rpm};
