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
//! * [`airjet`] — the air jet: the jets along the reed, Uno's drag, the tip's flight, the relay plan.
//! * [`projectile`] — torsion-bar picking: the bar's energy, the launch, the flight, the brake.
#![deny(missing_docs)]

pub mod airjet;
pub mod budget;
pub mod projectile;
pub mod rapier;

pub use airjet::{Airjet, AirjetReport, AirjetTable, RelayOpen, TipPoint};
pub use budget::{
    BudgetInputs, BudgetReport, MissingInput, PickBudget, WindowSource, max_speed_rpm, required_speed_m_s,
    window_needed_deg,
};
pub use projectile::{
    CarrierError, Flight, Projectile, ProjectilePath, ProjectileReport, ProjectileTable, torsion_stiffness,
};
pub use rapier::{DriveTable, HeadDrive, HeadMotion, HeadReport, Rapier, RapierError, RapierReport, RapierTable};

/// A wrong carrier description (any kind: the rapier's drives, the projectile, the air jet), or a
/// carrier that cannot do what is asked of it; every variant names the field at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InsertionError {
    /// A number outside its range.
    #[error(transparent)]
    Range(#[from] loomkin_units::RangeError),
    /// A field missing, given twice, one that does not go with the rest, or a carrier that cannot
    /// do what is asked of it.
    #[error("{field}: {reason}")]
    Field {
        /// The field (`insertion.rapier.bringer.crank_mm`, `insertion.projectile.twist_deg`).
        field: String,
        /// Why.
        reason: String,
    },
    /// A law or cycle the laws crate refuses (a rapier's cam or servo drive).
    #[error("{field}: {reason}")]
    Law {
        /// The drive's table.
        field: String,
        /// The laws crate's message.
        reason: String,
    },
}

impl InsertionError {
    pub(crate) fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Field { field: field.into(), reason: reason.into() }
    }

    /// The field at fault.
    pub fn field_name(&self) -> &str {
        match self {
            Self::Range(e) => &e.field,
            Self::Field { field, .. } | Self::Law { field, .. } => field,
        }
    }
}

/// The air the carriers move through, and gravity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Atmosphere;

impl Atmosphere {
    /// `air_density_kg_m3`: 0.5 ≤ ρ ≤ 2 kg/m³, default 1.2 kg/m³.
    pub const AIR_DENSITY_KG_M3: loomkin_units::Field = loomkin_units::Field::new(
        "air_density_kg_m3",
        loomkin_units::Range::closed(0.5, 2.0, "kg/m³"),
        "Density of the air in the weaving room: 0.5 ≤ ρ ≤ 2 kg/m³; 1.2 kg/m³ (20 °C at sea level) when left \
         out.",
    )
    .with_default(1.2);
    /// Standard gravity, m/s².
    pub const GRAVITY_M_S2: f64 = 9.806_65;
}

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
    Atmosphere::AIR_DENSITY_KG_M3,
    ProjectileTable::BAR_DIAMETER_MM,
    ProjectileTable::BAR_LENGTH_MM,
    ProjectileTable::SHEAR_MODULUS_GPA,
    ProjectileTable::BAR_STIFFNESS_N_M_PER_RAD,
    ProjectileTable::TWIST_DEG,
    ProjectileTable::EFFICIENCY,
    ProjectileTable::PROJECTILE_MASS_G,
    ProjectileTable::LEVER_MASS_G,
    ProjectileTable::GUIDE_FRICTION,
    ProjectileTable::DRAG_AREA_MM2,
    ProjectileTable::RUN_IN_MM,
    ProjectileTable::RUN_OUT_MM,
    ProjectileTable::BRAKE_MM,
    ProjectileTable::LAUNCH_DEG,
    AirjetTable::YARN_TEX,
    AirjetTable::YARN_DIAMETER_MM,
    AirjetTable::TAIL_MM,
    AirjetTable::DRAW_OFF,
    AirjetTable::MAIN_SPEED_M_S,
    AirjetTable::MAIN_CORE_MM,
    AirjetTable::REED_ENTRY_MM,
    AirjetTable::RELAY_SPEED_M_S,
    AirjetTable::RELAY_CORE_MM,
    AirjetTable::RELAY_PITCH_MM,
    AirjetTable::FIRST_RELAY_MM,
    AirjetTable::NOZZLES_PER_GROUP,
    AirjetTable::GROUPS,
    AirjetTable::CF_FLOOR,
    AirjetTable::CF_SCALE_M_S,
    AirjetTable::CF_OFFSET_M_S,
    AirjetTable::LAUNCH_DEG,
];
