//! # loomkin-shed — heald-frame motion laws and the two-criterion choice
//!
//! After Makarov, Khozina and Lebzak (2004). A heald frame moves over the motion angle `φ_дв` and
//! dwells over `φ_вр = 360° − φ_дв` of each pick. Its acceleration is piecewise: the positive phase
//! is split into parts of relative length `k_Ti` with shapes (zero, linear, sine or cosine ramp,
//! constant, …), the negative phase mirrors it or is given separately. Such a law trades peak
//! acceleration against the window in which the weft carrier may cross the shed,
//! `φ_пп* = φ_вр + φ_ув`, where the conditional dwell `φ_ув` counts the angle over which the frame
//! is within `1 − T` of its extreme position.
//!
//! ```
//! use loomkin_shed::{Conditions, evaluate, preset};
//!
//! // The "dobby" law of Table 3 (300° motion, modified trapezoid k_r = 0.25) at T = 0.95,
//! // a 100 mm stroke and 300 rpm.
//! let law = preset("dobby")?;
//! let c = evaluate(&law, &Conditions::new(0.95, 0.1, 300.0)?)?;
//! assert!((c.ca - 4.888).abs() < 1e-3);                 // the classical modified trapezoid
//! assert!((c.conditional_dwell_deg - 111.2).abs() < 0.1); // Table 3 prints 115°
//! assert!((c.window_deg - (c.dwell_deg + c.conditional_dwell_deg)).abs() < 1e-12);
//! assert!((c.peak_accel_m_s2 - 4.888 * 0.1 * (10.0 * std::f64::consts::PI / (300f64).to_radians()).powi(2)).abs() < 0.01);
//! # Ok::<(), loomkin_shed::ShedError>(())
//! ```
//!
//! For large tables, [`Template`] fixes the shapes and leaves the lengths free; its criteria come
//! from a fast closed-form path ([`Template::evaluate_fast`], checked against the generic path in
//! the tests). [`grid_design`], [`evaluate_rows`], [`pareto`] and [`best`] run the study.
#![deny(missing_docs)]

mod conditions;
mod criteria;
mod curve;
mod dwell;
mod error;
mod experiment;
mod fast;
mod frame_cycle;
mod paper;
mod presets;
mod report;
mod requirement;
mod shedlaw;
mod study;
mod template;

pub use conditions::{Conditions, TABLE3_THRESHOLD, THRESHOLD_RANGE, check_threshold};
pub use criteria::{Criteria, Dimensionless, evaluate};
pub use curve::{AccelJump, CurvePoint, CycleMarks, PLOT_POINTS, cycle_accel_jumps, cycle_curve, cycle_marks};
pub use error::{Result, ShedError};
pub use experiment::{
    CRITERIA_COLUMNS, DesignKind, Family, GridSpec, STUDY_BYTES_PER_LAW, STUDY_S_PER_LAW, Study, StudyEstimate,
    StudyRow, StudyTable, csv_header, csv_line, front_of_table, preset_table, preset_table_in,
};
pub use frame_cycle::{FRAME_PERIOD_DEG, FRAME_STROKE_MM_RANGE, frame_cycle, frame_cycle_toml};
pub use paper::{TABLE3, Table3Check, Table3Row, table3, table3_minimax_threshold};
pub use presets::{PRESETS, Preset, preset, preset_names};
pub use report::{
    BestReport, BestSearch, CriteriaReport, Definition, LawReport, PresetReport, RowReport, WindowReport,
};
pub use requirement::LoomRequirement;
pub use shedlaw::{MOTION_DEG, MOTION_DEG_FIELD, NegativePhase, ShedLaw, check_motion_deg, mirror};
pub use study::{
    Candidate, JERK_LIMIT_RANGE, PARETO_MOTION_DEG, TABLE_MOTION_DEG, WINDOW_DEG, best, check_window_deg, dominates_in,
    evaluate_rows, evaluate_rows_in, evaluate_rows_until, fig1_design, grid_design, grid_design_rows, pareto,
    pareto_indices, pareto_within, parse_motion_angles, table, table1_design, within_jerk_limit,
};
pub use template::{MAX_PARTS, Template};

pub use loomkin_study::{Design, Progress};

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    Conditions::THRESHOLD_FIELD,
    Conditions::STROKE_MM,
    LoomRequirement::CARRIER_SPEED_M_S,
    LoomRequirement::REED_WIDTH_M,
    LoomRequirement::CLOTH_WIDTH_M,
    LoomRequirement::CARRIER_LENGTH_M,
    LoomRequirement::CROSSING_RANGE_DEG,
    LoomRequirement::SHED_EXCESS,
    PLOT_POINTS,
    MOTION_DEG_FIELD,
    WINDOW_DEG,
];
