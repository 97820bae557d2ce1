//! What `loomkin servo law | torque | optimize | export --json` print and the Python module
//! returns: the reports as structs that serialise themselves, so both front ends give one value
//! one key.

use crate::InterpolationError;
use crate::drive::Drive;
use crate::error::Result;
use crate::optimize::{Objective, OptimizeReport};
use crate::points::format_points;
use crate::spline::{SplineEnd, SplineLaw};
use crate::torque::{TorqueSummary, summaries};
use loomkin_laws::Metrics;
use serde::Serialize;

/// What the values of a [`LawReport`] are (its `units` key).
pub const LAW_UNITS: &str = "d: slope of the acceleration image f (through the points) at x = 0.5; \
    d_unit = d·scale, jerk of the unit law there; cv, ca, cj, cm, ca_rms: the core's metrics \
    per unit stroke and unit motion angle (dimensionless)";

/// A spline law's shape and metrics (`servo law --json`), per unit stroke and unit motion angle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawReport {
    /// The definition points `[X, Y]`.
    pub def_points: Vec<[f64; 2]>,
    /// The spline's end condition.
    pub end: SplineEnd,
    /// [`LAW_UNITS`].
    pub units: &'static str,
    /// Slope of the acceleration image at x = 0.5 ([`SplineLaw::d`]).
    pub d: f64,
    /// `d · scale`: the unit law's jerk there.
    pub d_unit: f64,
    /// `1/F(1)` ([`SplineLaw::scale`]).
    pub scale: f64,
    /// The law core's metrics (dimensionless).
    #[serde(flatten)]
    pub metrics: Metrics,
    /// Continuity class in a dwell-rise-dwell cycle (−1: none).
    pub continuity_class: i32,
    /// Polynomial pieces of the law.
    pub intervals: usize,
    /// Cubic coefficients of the acceleration image per interval.
    pub spline_b: Vec<[f64; 4]>,
}

impl LawReport {
    /// The report of `law` (its metrics computed here).
    pub fn of(law: &SplineLaw) -> Self {
        let core = law.law();
        Self {
            def_points: law.points().to_vec(),
            end: law.end(),
            units: LAW_UNITS,
            d: law.d(),
            d_unit: law.d() * law.scale(),
            scale: law.scale(),
            metrics: core.metrics(),
            continuity_class: core.continuity().class,
            intervals: core.segments().len(),
            spline_b: law.spline_coefficients(),
        }
    }
}

/// The drive's turn in degrees of the main shaft (`layout_deg` of a [`DriveReport`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LayoutDeg {
    /// Rise.
    pub rise: f64,
    /// Dwell after the rise.
    pub dwell_after_rise: f64,
    /// Return.
    #[serde(rename = "return")]
    pub return_: f64,
    /// Dwell after the return.
    pub dwell_after_return: f64,
}

/// A drive file's values and its turn.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DriveReport {
    /// The drive's keys as in its file.
    #[serde(flatten)]
    pub drive: Drive,
    /// Rise, dwell, return, dwell (deg of the main shaft).
    pub layout_deg: LayoutDeg,
}

impl DriveReport {
    /// The drive and its layout (fails as [`Drive::layout`] does).
    pub fn of(drive: &Drive) -> Result<Self> {
        let lay = drive.layout()?;
        let layout_deg = LayoutDeg {
            rise: lay.rise_deg,
            dwell_after_rise: lay.dwell_after_rise_deg,
            return_: lay.return_deg,
            dwell_after_return: lay.dwell_after_return_deg,
        };
        Ok(Self { drive: drive.clone(), layout_deg })
    }
}

/// The motor torque of a law on a drive at each speed (`servo torque --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TorqueReport {
    /// The law's definition points.
    pub def_points: Vec<[f64; 2]>,
    /// The drive.
    pub drive: DriveReport,
    /// One summary per speed, in the order given.
    pub results: Vec<TorqueSummary>,
}

impl TorqueReport {
    /// [`summaries`] of `law` on `drive` at `speeds_rpm`, with the law and drive.
    pub fn compute(law: &SplineLaw, drive: &Drive, speeds_rpm: &[f64]) -> Result<Self> {
        let results = summaries(law.law(), drive, speeds_rpm)?;
        Ok(Self { def_points: law.points().to_vec(), drive: DriveReport::of(drive)?, results })
    }
}

/// The worst peak and RMS torque over the speeds, and the summaries per speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorstTorque {
    /// Largest peak torque (N·m).
    pub peak_torque_nm: f64,
    /// Largest RMS torque (N·m).
    pub rms_torque_nm: f64,
    /// The summaries.
    pub per_speed: Vec<TorqueSummary>,
}

impl WorstTorque {
    /// The worst of `per_speed`.
    pub fn of(per_speed: &[TorqueSummary]) -> Self {
        let peak_torque_nm = per_speed.iter().map(|s| s.peak_torque_nm).fold(0.0, f64::max);
        let rms_torque_nm = per_speed.iter().map(|s| s.rms_torque_nm).fold(0.0, f64::max);
        Self { peak_torque_nm, rms_torque_nm, per_speed: per_speed.to_vec() }
    }
}

/// An optimisation's outcome (`servo optimize --json`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptimizeSummary {
    /// What was minimised.
    pub objective: Objective,
    /// The speeds it was minimised over (rpm).
    pub speeds_rpm: Vec<f64>,
    /// The starting law.
    pub before: WorstTorque,
    /// The optimised law.
    pub after: WorstTorque,
    /// The optimised definition points.
    pub def_points: Vec<[f64; 2]>,
    /// The same as `--def` text.
    pub def: String,
    /// The end condition.
    pub end: SplineEnd,
    /// Objective evaluations spent.
    pub evaluations: usize,
}

impl OptimizeReport {
    /// The outcome as reported, with the speeds it was run at.
    pub fn summary(&self, speeds_rpm: &[f64]) -> OptimizeSummary {
        let pts = self.law.points();
        OptimizeSummary {
            objective: self.objective,
            speeds_rpm: speeds_rpm.to_vec(),
            before: WorstTorque::of(&self.before),
            after: WorstTorque::of(&self.after),
            def_points: pts.to_vec(),
            def: format_points(pts),
            end: self.law.end(),
            evaluations: self.evaluations,
        }
    }
}

/// One re-interpolation row of a cam table's report, the same in `servo export --json` (array
/// `reinterpolation`), the workbench's `/api/servo/export` (array `interpolation`) and Python: an
/// [`InterpolationError`] with its mode under both names it has been published with,
/// `interpolation` (the CLI's) and `mode` (the API's), so a script written against either front
/// end reads the other.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReinterpolationRow {
    /// The interpolation's kebab-case name.
    pub interpolation: &'static str,
    /// The same name under the API's key.
    pub mode: &'static str,
    /// Table step (deg).
    pub step_deg: f64,
    /// Largest position error (m).
    pub max_position_error_m: f64,
    /// Largest velocity error (m/deg).
    pub max_velocity_error_m_per_deg: f64,
    /// Largest acceleration error (m/deg²).
    pub max_accel_error_m_per_deg2: f64,
    /// Position error relative to the stroke.
    pub rel_position_error: f64,
    /// Velocity error relative to the peak velocity.
    pub rel_velocity_error: f64,
    /// Acceleration error relative to the peak acceleration.
    pub rel_accel_error: f64,
}

impl From<&InterpolationError> for ReinterpolationRow {
    fn from(e: &InterpolationError) -> Self {
        Self {
            interpolation: e.mode.name(),
            mode: e.mode.name(),
            step_deg: e.step_deg,
            max_position_error_m: e.max_position_error_m,
            max_velocity_error_m_per_deg: e.max_velocity_error_m_per_deg,
            max_accel_error_m_per_deg2: e.max_accel_error_m_per_deg2,
            rel_position_error: e.rel_position_error,
            rel_velocity_error: e.rel_velocity_error,
            rel_accel_error: e.rel_accel_error,
        }
    }
}
