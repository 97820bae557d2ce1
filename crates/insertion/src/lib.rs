//! # loomkin-insertion — weft insertion beyond the shuttle
//!
//! Today's looms insert the weft with rapiers, projectiles and air jets. For each carrier the
//! designer asks the same questions: how fast can the loom run for this reed width, does the
//! carrier pass the shed without touching the warp on every pick, and when must each element act.
//! This crate holds the carriers' models as library types with their own bounds: the time budget
//! every carrier shares, the rapier drives, torsion-bar projectile picking and the air-jet yarn
//! flight. It sits below `loomkin-loom`, which puts a carrier's path on the main-shaft angle of the
//! shed it computes (the clearance over a pattern repeat, the timing diagram).
//!
//! * [`budget`] — the time budget `n = v̄·θ/(6·(W + L))`, its converse, energy and power per pick.
//! * [`rapier`] — the double rapier: bringer and taker drives (crank, cam, servo), the transfer.
#![deny(missing_docs)]

pub mod budget;
pub mod rapier;

pub use budget::{BudgetReport, PickBudget, WindowSource, max_speed_rpm, required_speed_m_s, window_needed_deg};
pub use rapier::{DriveTable, HeadDrive, HeadMotion, HeadReport, Rapier, RapierError, RapierReport, RapierTable};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    PickBudget::REED_WIDTH_MM,
    PickBudget::CARRIER_LENGTH_MM,
    PickBudget::WINDOW_DEG,
    PickBudget::SPEED_M_S,
    PickBudget::CARRIER_MASS_G,
    DriveTable::OUTER_MM,
    DriveTable::INNER_DEG,
    DriveTable::CRANK_MM,
    DriveTable::ROD_MM,
    DriveTable::ROCKER_MM,
    DriveTable::PIVOT_MM,
    DriveTable::SECTOR_MM,
    DriveTable::PINION_MM,
    DriveTable::WHEEL_MM,
    DriveTable::STROKE_MM,
    DriveTable::MOTION_DEG,
];
