//! A cam table: the points, their decimals, and the written file with its exact error.

use super::decimals::Decimals;
use super::format::Format;
use super::points::{CamPoint, Spacing, left_at, place};
use super::reinterpolation::{ReinterpolationError, reinterpolation_error};
use super::{Interval, Motion};
use crate::Result;
use loomkin_laws::StrokeUnit;
use loomkin_units::{StopFlag, compact};
use serde::Serialize;

/// The interpolation a controller runs between two points of every point format.
pub const INTERPOLATION: &str = "quintic Hermite from (Y, V, A) at both ends of each interval (XYVA; \
TwinCAT MOTIONFUNCTYPE_POLYNOM5_MM; CODESYS SMC_CAM_TYPE.XYVA)";

/// A number with six significant digits (`3.46994e-6`), for the comment lines: stable against
/// rounding-level changes of the root finder.
fn sig6(x: f64) -> String {
    if x == 0.0 { "0".into() } else { format!("{x:.5e}") }
}

/// A cam table of a motion: points with fixed decimals (see [`Decimals`]).
///
/// ```
/// use loomkin_cams::table::{CamTable, Format, Motion, Spacing};
/// use loomkin_laws::{LawSpec, StrokeUnit};
///
/// let law = LawSpec::Cycloidal.build()?;
/// let motion = Motion::rise(&law, 40.0, 120.0, StrokeUnit::Mm)?;   // 40 mm over 120°
/// let table = CamTable::new(motion, Spacing::StepDeg(5.0))?;
/// let out = table.export(Format::Csv)?;
/// assert!(out.text.starts_with("master_deg,slave_mm,slave_v_mm_per_deg,"));
/// assert!(out.error.max_position_error < 1e-3);                    // mm, exact
/// # Ok::<(), loomkin_cams::CamError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct CamTable {
    motion: Motion,
    spacing: Spacing,
    points: Vec<CamPoint>,
    /// `(Y, V, A)` of the piece that ends at each point (the left-hand limits at a joint).
    left: Vec<[f64; 3]>,
    decimals: Decimals,
}

/// A written table: the text, and the exact re-interpolation error of what it holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Export {
    /// The file's text.
    pub text: String,
    /// The exact error of the table as written, re-read and re-interpolated as the controller does.
    pub error: ReinterpolationError,
    /// Number of points (poly5: segments + 1).
    pub points: usize,
}

/// A written table's report (`loomkin cam table --json`): source, format, points, spacing and
/// decimals, and the exact re-interpolation error with the slave unit `U` (`mm` or `deg`) in its
/// keys: `max_position_error_U`, `max_position_error_at_deg`, `max_velocity_error_U_per_deg`,
/// `max_accel_error_U_per_deg2`.
#[derive(Debug, Clone, PartialEq)]
pub struct TableReport {
    /// What the motion came from (a file name, `law cycloidal`).
    pub source: String,
    /// The format written.
    pub format: Format,
    /// Number of points (poly5: segments + 1).
    pub points: usize,
    /// The slave unit, `mm` or `deg`.
    pub unit: &'static str,
    /// The spacing of the points.
    pub spacing: Spacing,
    /// The exact error of the table as written.
    pub error: ReinterpolationError,
    /// The decimals of each column.
    pub decimals: Decimals,
}

impl Serialize for TableReport {
    fn serialize<S: serde::Serializer>(&self, ser: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let (u, e) = (self.unit, &self.error);
        let interpolation = if self.format == Format::Poly5 { "poly5 segments as written" } else { INTERPOLATION };
        let mut m = ser.serialize_map(Some(11))?;
        m.serialize_entry("source", &self.source)?;
        m.serialize_entry("format", self.format.name())?;
        m.serialize_entry("points", &self.points)?;
        m.serialize_entry("unit", u)?;
        m.serialize_entry("spacing", &self.spacing)?;
        m.serialize_entry("interpolation", interpolation)?;
        m.serialize_entry(&format!("max_position_error_{u}"), &e.max_position_error)?;
        m.serialize_entry("max_position_error_at_deg", &e.max_position_error_at_deg)?;
        m.serialize_entry(&format!("max_velocity_error_{u}_per_deg"), &e.max_velocity_error)?;
        m.serialize_entry(&format!("max_accel_error_{u}_per_deg2"), &e.max_accel_error)?;
        m.serialize_entry("decimals", &self.decimals)?;
        m.end()
    }
}

impl CamTable {
    /// Places the points of `motion` for `spacing` and rounds them to their decimals.
    pub fn new(motion: Motion, spacing: Spacing) -> Result<Self> {
        let (points, decimals) = place(&motion, spacing)?;
        // Rates per degree grow as the motion angle shrinks: a motion of 1e-300° inside its range
        // overflows them. Refuse it naming the input instead of writing NaN.
        if points.iter().any(|p| ![p.master_deg, p.y, p.v, p.a, p.j].iter().all(|v| v.is_finite())) {
            return Err(crate::CamError::Law {
                field: "motion_deg".into(),
                reason: "the table's slave position or its rates per degree are not finite numbers (an overflow): \
                         the motion angle is too small for its stroke"
                    .into(),
            });
        }
        let left = points.iter().map(|p| left_at(&motion, p.master_deg, &decimals)).collect();
        Ok(Self { motion, spacing, points, left, decimals })
    }

    /// The points.
    pub fn points(&self) -> &[CamPoint] {
        &self.points
    }

    /// `(Y, V, A)` at each point by the formula of the piece that ends there: at a joint where A
    /// jumps the left-hand limits (the points hold the right-hand ones), elsewhere the points'
    /// own values. A format that carries both sides of a joint (poly5) ends each segment on them.
    pub fn left_limits(&self) -> &[[f64; 3]] {
        &self.left
    }

    /// The decimals of each column.
    pub fn decimals(&self) -> Decimals {
        self.decimals
    }

    /// The motion the table was made from.
    pub fn motion(&self) -> &Motion {
        &self.motion
    }

    /// The spacing of the points.
    pub fn spacing(&self) -> Spacing {
        self.spacing
    }

    /// The slave unit's name, `mm` or `deg`.
    pub fn unit_name(&self) -> &'static str {
        match self.motion.unit() {
            StrokeUnit::Mm => "mm",
            StrokeUnit::Deg => "deg",
        }
    }

    /// Writes the table in a format and reports the exact re-interpolation error of what was
    /// written: the text is read back ([`Format::read`]), re-interpolated as the controller does,
    /// and compared with the motion ([`super::reinterpolation_error`]).
    pub fn export(&self, format: Format) -> Result<Export> {
        self.export_until(format, &StopFlag::default())
    }

    /// [`CamTable::export`] that ends with [`crate::CamError::Stopped`] once `stop` is set (a
    /// client gone, a time budget spent): the error's comparison looks at it as it goes
    /// ([`super::reinterpolation_error_until`]). Run to its end it writes the same text.
    pub fn export_until(&self, format: Format, stop: &StopFlag) -> Result<Export> {
        let body = format.write(self, &[]);
        let intervals: Vec<Interval> = format.read(&body)?;
        let error = super::reinterpolation_error_until(&self.motion, &intervals, stop)?;
        let text = format.write(self, &self.header(format, &error));
        Ok(Export { text, error, points: intervals.len() + 1 })
    }

    /// The exact re-interpolation error of the table's points (as rounded) joined in `mode`.
    pub fn reinterpolation(&self, mode: super::Interpolation) -> ReinterpolationError {
        reinterpolation_error(&self.motion, &mode.intervals(&self.points))
    }

    /// [`CamTable::reinterpolation`] that ends with [`crate::CamError::Stopped`] once `stop` is set.
    pub fn reinterpolation_until(&self, mode: super::Interpolation, stop: &StopFlag) -> Result<ReinterpolationError> {
        Ok(super::reinterpolation_error_until(&self.motion, &mode.intervals(&self.points), stop)?)
    }

    /// The report of `export`, written in `format` from a motion that came from `source`.
    pub fn report(&self, source: impl Into<String>, format: Format, export: &Export) -> TableReport {
        TableReport {
            source: source.into(),
            format,
            points: export.points,
            unit: self.unit_name(),
            spacing: self.spacing,
            error: export.error,
            decimals: self.decimals,
        }
    }

    /// The comment lines that head a file (without comment markers).
    fn header(&self, format: Format, e: &ReinterpolationError) -> Vec<String> {
        let u = self.unit_name();
        let d = self.decimals;
        let spacing = match self.spacing {
            // A step as long as every span between joints: the joints alone.
            Spacing::StepDeg(s) if self.motion.joints().windows(2).all(|w| w[1] - w[0] <= s) => {
                "points on every joint of the law only".to_string()
            }
            Spacing::StepDeg(s) => format!(
                "points on every joint of the law and every {} deg from each joint (shorter last step before a joint)",
                compact(s)
            ),
            Spacing::Tolerance(t) => {
                format!(
                    "points on every joint of the law, between them as few as keep the error within {} {u}",
                    compact(t)
                )
            }
        };
        let (interp, joints) = if format == Format::Poly5 {
            (
                format!("slave Y = b0 + b1*u + ... + b5*u^5 ({u}), u = (X - start)/(end - start) in [0, 1]"),
                "at a joint of the law (where A or J may jump) each segment starts and ends on the values of its own side"
                    .to_string(),
            )
        } else {
            (
                format!("interpolation between points: {INTERPOLATION}"),
                "at a joint of the law (where A or J may jump) a point holds the values of the segment that starts there"
                    .to_string(),
            )
        };
        vec![
            format!(
                "loomkin cam table: master X in deg, slave Y in {u}, V = dY/dX in {u}/deg, A in {u}/deg^2, J in {u}/deg^3"
            ),
            spacing,
            interp,
            joints,
            format!(
                "re-interpolation error (exact, of the values as written): position {} {u} at X = {} deg, velocity {} {u}/deg, acceleration {} {u}/deg^2",
                sig6(e.max_position_error),
                super::decimals::fixed(e.max_position_error_at_deg, 4),
                sig6(e.max_velocity_error),
                sig6(e.max_accel_error)
            ),
            format!(
                "decimals: X {}, Y {}, V {}, A {}, J {}{} (chosen from the resolution each column needs)",
                d.master,
                d.y,
                d.v,
                d.a,
                d.j,
                if format == Format::Poly5 {
                    let dc = super::poly5::coeff_decimals(self, &super::poly5::two_sided(self));
                    format!(", b0..b5 {}", dc.map(|n| n.to_string()).join(" "))
                } else {
                    String::new()
                }
            ),
        ]
    }
}
