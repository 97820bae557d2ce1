//! # loomkin-eshed — electronic shedding: one servo per heald frame, the shared DC bus
//!
//! The newest looms drop the dobby: each heald frame has its own servo motor. Every frame then
//! gets its own motion for every pick from the weave (stay, rise, fall, or pass through without a
//! stop), each rest transition at least C², and the frames share a DC bus, so the peak *bus* power
//! sizes the supply and braking frames return energy that others use.
//!
//! * [`FramePlan`] — one frame's moves over the pattern repeat from its row of the lift plan
//!   (crossing angle, stagger, motion angle, pass-through), as a machine cycle of the law core
//!   ([`loomkin_laws::Cycle`]: every joint exact).
//! * [`MoveKinds`] — the law and motion angle of each kind of move (rise, fall, pass-through) a
//!   loom file gives, for all frames or some ([`moves`]).
//! * [`FramePath`] — a frame's height along its plan at any angle (what the shed geometry reads:
//!   the clear shed and the clearance to the carrier).
//! * [`ServoShedding`] — the `[shedding.servo]` table of a loom file: motor (as `loomkin servo
//!   check` takes it), transmission, winding, bus; per-frame overrides.
//! * [`FrameDrive`] — the servo axis model of loomkin-servo ([`loomkin_servo::Axis`]) moving one
//!   frame, and its electrical power `P = T·ω_m + R·(T/k_t)²`.
//! * [`analyse`] — per frame the servo check ([`loomkin_servo::check_axis`]) and the peak power,
//!   on the bus the peak and mean power, the regenerated and braking energy, all on the closed
//!   form with peaks root-found.
//! * [`frame_tables`] — one cam table per frame over the repeat for the controllers (the cam-table
//!   engine of loomkin-cams) and the manifest of the master axis.
//!
//! The loom file and the lift plan are read by loomkin-loom, which builds the [`FrameSetup`]s
//! (`loomkin_loom::servo_study`).
#![deny(missing_docs)]

mod bus;
pub mod continuity;
mod drive;
mod error;
pub mod moves;
mod path;
mod plan;
mod report;
mod spec;
mod tables;

pub use bus::{BusTotals, DriveMemo};
pub use continuity::{JointClass, joint_class};
pub use drive::{DrivePoint, FrameDrive, FrameLoad, axis};
pub use error::{EshedError, Result};
pub use loomkin_servo::CheckMemo;
pub use moves::{GivenLaw, MoveKinds, read_law};
pub use path::FramePath;
pub use plan::{FrameInput, FramePlan, MoveLaws, PlanSegment, PlannedMove};
pub use report::{
    ClearShed, Curves, FrameReport, FrameSetup, ServoReport, Study, analyse, curves, peak_bus_power_w,
    peak_bus_power_w_at, peak_bus_power_w_memo, rms_torque_n_m, rms_torque_n_m_at, worst_rms_torque_n_m,
    worst_rms_torque_n_m_at,
};
pub use spec::{Bus, FrameServo, ServoShedding, Transmission, Winding};
pub use tables::{
    FrameTables, MANIFEST_FILE, TABLE_FORMATS, TableEntry, TableFile, Tables, TablesManifest, frame_tables,
    table_file_name,
};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Transmission::TRAVEL_MM_PER_REV,
    Transmission::EFFICIENCY,
    Transmission::FRICTION_N,
    Transmission::VISCOUS_N_S_M,
    Transmission::EXTRA_INERTIA_KG_M2,
    Winding::RESISTANCE_OHM,
    Winding::TORQUE_CONSTANT_N_M_A,
    Bus::VOLTAGE_V,
    Bus::REGENERATION_EFFICIENCY,
    Bus::BRAKING_RESISTOR_OHM,
    MoveKinds::RISE_MOTION_DEG,
    MoveKinds::FALL_MOTION_DEG
];
