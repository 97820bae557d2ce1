//! # loomkin-servo — servo motion functions from definition points
//!
//! After M. Sivčák, *Generation of a motion function for optimal needle rack motion of a CAM-EL
//! weaving machine* (2017). The acceleration of a normalised rise is the cubic spline through a
//! few definition points `[X_j, Y_j]` on `[0, 0.5]`, mirrored odd about `(0.5, 0)`; integrated
//! twice and scaled to a unit stroke it is a [`loomkin_laws::Law`], so every metric, sample and
//! plot of the law core works on it. On top: the motor torque of a rack-and-pinion servo drive
//! ([`Drive`], [`summary`], [`torque_curve`]), export of the coefficients and cam tables for the
//! controller ([`export_coefficients`], and cam tables by [`loomkin_cams::table`] through [`export`]) and an optimiser that
//! moves the points to lower the peak or RMS torque ([`optimize`]).
//!
//! ```
//! use loomkin_servo::{Drive, SplineEnd, SplineLaw, parse_points, summary};
//!
//! let pts = parse_points("0:0, 0.08:0.6, 0.17:0.95, 0.25:1, 0.33:0.9, 0.42:0.5, 0.5:0")?;
//! let spline = SplineLaw::new(&pts, SplineEnd::Natural)?;
//! let law = spline.law();                       // a law of the core: u°(x) on x ∈ [0, 1]
//! assert!((law.eval(1.0).s - 1.0).abs() < 1e-12);
//! assert!((law.eval(0.3).s + law.eval(0.7).s - 1.0).abs() < 1e-12); // odd symmetry
//! let m = law.metrics();                        // Cv, Ca, Cj, Cm, …
//! assert!(m.ca > 4.0 && m.ca < 8.0);
//!
//! let drive = Drive::needle_rack_default();
//! let s = summary(law, &drive, 600.0)?;         // peak / RMS torque (N·m), peak power (W)
//! assert!(s.peak_torque_nm > s.rms_torque_nm && s.peak_power_w > 0.0);
//! # Ok::<(), loomkin_servo::ServoError>(())
//! ```
#![deny(missing_docs)]

mod axis;
mod axis_check;
pub mod crank_lever;
mod cycle_file;
mod design;
mod drive;
mod error;
mod export;
mod export_file;
mod linear_drive;
mod optimize;
mod points;
mod poly;
mod report;
mod spline;
mod torque;

pub use axis::{Axis, Limits, Load, Motor};
pub use axis_check::{
    AxisReport, Check, CheckMemo, OperatingPoint, Polyline, check_axis, check_axis_memo, envelope_lines,
    operating_point_at, operating_points, torque_squared_by_segment, torque_squared_by_segment_memo,
};
pub use crank_lever::{CrankBranch, CrankLever, DeadCentre, Linkage, MotorMotion, Reach};
pub use cycle_file::spline_cycle;
pub use design::{DesignFormat, MAX_DEF_POINTS, MAX_SPEEDS, ServoDesign};
pub use drive::{CYCLE_DEG, CycleLayout, DESIGN_KEYS, Drive};
pub use error::{Result, ServoError};
pub use export::{
    CoefficientExport, IntervalCoeffs, export_coefficients, export_coeffs_text, export_json, read_coeffs_text,
    read_json,
};
pub use export_file::{Export, ExportFormat, InterpolationError, TableReport, export, export_until, spline_motion};
pub use linear_drive::LinearDrive;
/// The cam-table engine the exports use (re-exported: one engine for `servo export` and `cam table`).
pub use loomkin_cams::table::{CamTable, Interpolation};
pub use optimize::{Counter, EVAL_S_PER_POINT_SPEED, Objective, OptimizeOptions, OptimizeReport, StopFlag, optimize};
pub use points::{
    DEFAULT_DEF, END_TOL, MIN_GAP, MIN_POINTS, MIN_Y_MAX, check_points, default_points, format_points, parse_points,
};

use loomkin_units::{Field, Range};

/// The inputs of the servo commands that belong to no one type.
pub struct ServoInputs;

impl ServoInputs {
    /// The speeds `servo torque` evaluates when none are given (rpm, comma separated): the paper's two.
    pub const TORQUE_SPEEDS_RPM: &'static str = "600,750";
    /// The speed `servo optimize` and `servo plot` work at when none is given (rpm): the paper's.
    pub const DESIGN_SPEEDS_RPM: &'static str = "600";
    /// `starts`: Nelder–Mead starts of `servo optimize`, at least one (the time budget, from
    /// [`OptimizeOptions::cost`], bounds how many; Python's run stops on Ctrl-C); 6 (the given
    /// points, then five pseudo-random ones).
    pub const STARTS: Field = Field::count(
        "starts",
        Range::at_least(1.0, ""),
        "Nelder–Mead starts (the given points, then pseudo-random ones): at least 1, the time budget bounds          how many; 6 when left out.",
    )
    .with_default(6.0);
    /// `points`: samples of a torque curve over one turn, 2 … 10⁷; 721 (every half degree).
    pub const CURVE_POINTS: Field = Field::count(
        "points",
        Range::closed(2.0, 1e7, ""),
        "Samples of the torque curve over one turn: 2 … 10⁷; 721 (every half degree) when left out.",
    )
    .with_default(721.0);
    /// `step_deg`: the cam table resolution of an export, 360°/10⁶ … 90°; 1°.
    pub const EXPORT_STEP_DEG: Field = Field::new(
        "step_deg",
        Range::closed(CYCLE_DEG / 1e6, CYCLE_DEG / 4.0, "deg"),
        "Cam table resolution in degrees of the main shaft: 360°/10⁶ … 90° (at least four points a turn); \
         1° when left out.",
    )
    .with_default(1.0);

    /// The speeds of a comma-separated default ([`ServoInputs::TORQUE_SPEEDS_RPM`]) as numbers.
    pub fn speeds(text: &str) -> Vec<f64> {
        text.split(',').filter_map(|v| v.trim().parse().ok()).collect()
    }
}

/// The descriptors of this crate's inputs.
pub const FIELDS: loomkin_units::FieldList = loomkin_units::field_list![
    ServoInputs::STARTS,
    ServoInputs::CURVE_POINTS,
    ServoInputs::EXPORT_STEP_DEG,
    Drive::STROKE_M,
    Drive::MOTION_ANGLE_DEG,
    Drive::RETURN_ANGLE_DEG,
    Drive::MOVING_MASS_KG,
    Drive::PINION_RADIUS_M,
    Drive::GEAR_RATIO,
    Drive::MOTOR_INERTIA_KG_M2,
    Drive::SPRING_N_M,
    Drive::SPRING_PRELOAD_N,
    Drive::DAMPING_N_S_M,
    Drive::CONSTANT_FORCE_N,
    Drive::EFFICIENCY,
    Drive::DWELL_AFTER_RISE_DEG,
    Motor::RATED_TORQUE_NM,
    Motor::PEAK_TORQUE_NM,
    Motor::RATED_SPEED_RPM,
    Motor::MAX_SPEED_RPM,
    Motor::ROTOR_INERTIA_KG_M2,
    Motor::TORQUE_AT_MAX_SPEED_NM,
    Load::MOVING_MASS_KG,
    Load::LOAD_INERTIA_KG_M2,
    Load::TRAVEL_MM_PER_REV,
    Load::GEAR_RATIO,
    Load::EFFICIENCY,
    Load::FRICTION_N,
    Load::VISCOUS_N_S_M,
    Load::SPRING_N_M,
    Load::CONSTANT_FORCE_N,
    Load::EXTRA_INERTIA_KG_M2,
    Limits::MAX_INERTIA_RATIO,
    CrankLever::CRANK_RADIUS_MM,
    CrankLever::ROD_LENGTH_MM,
    CrankLever::LEVER_INPUT_ARM_MM,
    CrankLever::LEVER_OUTPUT_ARM_MM,
    CrankLever::LEVER_ANGLE_DEG,
    CrankLever::ROCKING_SHAFT_X_MM,
    CrankLever::ROCKING_SHAFT_Y_MM,
    CrankLever::FRAME_LINK_MM,
    CrankLever::LEVER_INERTIA_KG_M2,
    CrankLever::GEAR_RATIO,
    CrankLever::MID_STROKE_MM,
];
pub use report::{
    DriveReport, LAW_UNITS, LawReport, LayoutDeg, OptimizeSummary, ReinterpolationRow, TorqueReport, WorstTorque,
};
pub use spline::{SplineEnd, SplineLaw, slope_at_middle};
pub use torque::{DrivePoint, Phase, TorqueSummary, summaries, summary, torque_curve};
