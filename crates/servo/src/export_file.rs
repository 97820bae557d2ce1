//! One exporter per file format of a servo law; the CLI (`servo export`), the workbench
//! (`POST /api/servo/export`) and Python all call [`export`]. The cam tables (csv, xyva, poly5) are
//! written by the one cam-table engine of the workspace, [`loomkin_cams::table`], on the drive's
//! turn as a [`Motion`] in mm ([`spline_motion`]): the same file `loomkin cam table` writes from
//! the cycle file of `--format cycle`.

use crate::{Drive, Result, SplineLaw, export_coeffs_text, export_json, format_points, spline_cycle};
use loomkin_cams::table::{CamTable, Format, Interpolation, Motion, ReinterpolationError, Spacing};
use loomkin_laws::Cycle;
use loomkin_units::StopFlag;
use serde::{Deserialize, Serialize};

/// The file formats of [`export`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ExportFormat {
    /// The spline coefficients per interval as documented text.
    Coeffs,
    /// The coefficients as JSON (`intervals` with `x_start`, `x_end`, `accel`, `velocity`, `position`).
    Json,
    /// Cam table over one turn as CSV (master deg → slave mm, mm/deg, mm/deg², mm/deg³).
    Csv,
    /// Cam table as PLCopen-style XYVA points (mm, mm/deg, mm/deg²).
    Xyva,
    /// The exact law as fifth-degree polynomial segments between its joints (`loomkin cam table
    /// --format poly5`: `b0…b5` in mm in the normalised master coordinate).
    Poly5,
    /// The drive's turn as a cycle file of the law core (for `loomkin cycle`, `cam table`, `servo check`).
    Cycle,
}

impl ExportFormat {
    /// Lower-case name, as in files and requests.
    pub fn name(self) -> &'static str {
        match self {
            Self::Coeffs => "coeffs",
            Self::Json => "json",
            Self::Csv => "csv",
            Self::Xyva => "xyva",
            Self::Poly5 => "poly5",
            Self::Cycle => "cycle",
        }
    }

    /// Whether the format is a cam table of points (re-interpolated by a controller).
    pub fn is_cam_table(self) -> bool {
        matches!(self, Self::Csv | Self::Xyva)
    }
}

/// The worst errors of a table re-interpolated in one mode against the exact law, in the units
/// these reports have been published with (m, m/deg, m/deg²) and relative to the law's peaks.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct InterpolationError {
    /// Interpolation mode.
    pub mode: Interpolation,
    /// The table's step (deg) as asked; points also fall on every joint of the law.
    pub step_deg: f64,
    /// Largest position error (m).
    pub max_position_error_m: f64,
    /// Largest velocity error (m/deg).
    pub max_velocity_error_m_per_deg: f64,
    /// Largest acceleration error (m/deg²).
    pub max_accel_error_m_per_deg2: f64,
    /// Position error relative to the stroke.
    pub rel_position_error: f64,
    /// Velocity error relative to the peak velocity `H·Cv/φ_min`.
    pub rel_velocity_error: f64,
    /// Acceleration error relative to the peak acceleration `H·Ca/φ_min²`.
    pub rel_accel_error: f64,
}

impl InterpolationError {
    /// The engine's error (mm) of `mode` on `drive`'s turn of `law`, converted and made relative.
    fn of(
        e: &ReinterpolationError,
        mode: Interpolation,
        step_deg: f64,
        spline: &SplineLaw,
        drive: &Drive,
    ) -> Result<Self> {
        let lay = drive.layout()?;
        let met = spline.law().metrics();
        let h = drive.stroke_m;
        let phi = lay.rise_deg.min(lay.return_deg);
        let (pv, pa) = (h * met.cv / phi, h * met.ca / (phi * phi));
        let rel = |e: f64, p: f64| if p > 0.0 { e / p } else { 0.0 };
        // The engine works in the cycle's unit, mm.
        let (ep, ev, ea) = (e.max_position_error / 1e3, e.max_velocity_error / 1e3, e.max_accel_error / 1e3);
        Ok(Self {
            mode,
            step_deg,
            max_position_error_m: ep,
            max_velocity_error_m_per_deg: ev,
            max_accel_error_m_per_deg2: ea,
            rel_position_error: rel(ep, h),
            rel_velocity_error: rel(ev, pv),
            rel_accel_error: rel(ea, pa),
        })
    }
}

/// A cam table's size and what re-interpolating it loses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TableReport {
    /// Points of the table (both ends of the turn included).
    pub points: usize,
    /// Step between points (deg of the main shaft) as asked: the table also has a point on every
    /// joint of the law, with a shorter step before it.
    pub step_deg: f64,
    /// Worst errors per interpolation mode ([`Interpolation::ALL`] order).
    pub reinterpolation: Vec<InterpolationError>,
}

/// An exported file.
#[derive(Debug, Clone, PartialEq)]
pub struct Export {
    /// The format.
    pub format: ExportFormat,
    /// Suggested file name.
    pub filename: &'static str,
    /// Media type.
    pub media_type: &'static str,
    /// The file's text.
    pub text: String,
    /// For cam tables ([`ExportFormat::is_cam_table`]): size and re-interpolation errors.
    pub table: Option<TableReport>,
}

/// The drive's turn of the spline law (rise, dwell, return, dwell; see [`Drive::layout`]) as the
/// cam-table engine's motion, in mm: the cycle of [`spline_cycle`], as `loomkin cam table` reads it.
pub fn spline_motion(spline: &SplineLaw, drive: &Drive) -> Result<Motion> {
    let cycle = Cycle::new(&spline_cycle(spline, drive, None)?)?;
    Ok(Motion::from_cycle(&cycle))
}

/// Writes `spline` on `drive` in `format`. The cam tables csv and xyva have a point on every joint
/// of the law and, from each joint onwards, every `step_deg` (deg of the main shaft; see
/// [`Spacing::StepDeg`]); poly5 has its segments between the law's joints, where each is the law
/// itself (the spline law is piecewise quintic), and takes no step.
pub fn export(spline: &SplineLaw, drive: &Drive, format: ExportFormat, step_deg: f64) -> Result<Export> {
    export_until(spline, drive, format, step_deg, &StopFlag::default())
}

/// [`export`] that ends with [`crate::ServoError::Stopped`] once `stop` is set (a client gone, a
/// time budget spent): the tables' error comparisons look at it as they go. Run to its end it
/// writes the same file.
pub fn export_until(
    spline: &SplineLaw,
    drive: &Drive,
    format: ExportFormat,
    step_deg: f64,
    stop: &StopFlag,
) -> Result<Export> {
    let file = |filename, media_type, text| Export { format, filename, media_type, text, table: None };
    Ok(match format {
        ExportFormat::Coeffs => file("servo-coefficients.txt", "text/plain", export_coeffs_text(spline)),
        ExportFormat::Json => file("servo-coefficients.json", "application/json", export_json(spline)),
        ExportFormat::Poly5 => {
            // A step of a whole turn: the points are the law's joints alone.
            let table = CamTable::new(spline_motion(spline, drive)?, Spacing::StepDeg(crate::CYCLE_DEG))?;
            file("servo-cam-poly5.csv", "text/csv", table.export_until(Format::Poly5, stop)?.text)
        }
        ExportFormat::Cycle => file(
            "servo-cycle.toml",
            "application/toml",
            format!(
                "# The spline law on the drive's turn (rise, dwell, return, dwell): a cycle file for loomkin cycle,\n\
                 # cam profile, cam table and servo check. Definition points: {}\n{}",
                format_points(spline.points()),
                spline_cycle(spline, drive, None)?.to_toml()?
            ),
        ),
        ExportFormat::Csv | ExportFormat::Xyva => {
            crate::ServoInputs::EXPORT_STEP_DEG.check(step_deg)?;
            let table = CamTable::new(spline_motion(spline, drive)?, Spacing::StepDeg(step_deg))?;
            let (filename, written) = if format == ExportFormat::Csv {
                ("servo-cam.csv", Format::Csv)
            } else {
                ("servo-cam-xyva.csv", Format::Xyva)
            };
            let out = table.export_until(written, stop)?;
            let reinterpolation = Interpolation::ALL
                .iter()
                .map(|&m| {
                    // The quintic's error is the one of the file as written and re-read.
                    let e = if m == Interpolation::QuinticHermite {
                        out.error
                    } else {
                        table.reinterpolation_until(m, stop)?
                    };
                    InterpolationError::of(&e, m, step_deg, spline, drive)
                })
                .collect::<Result<Vec<_>>>()?;
            let report = TableReport { points: out.points, step_deg, reinterpolation };
            Export { table: Some(report), ..file(filename, "text/csv", out.text) }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_format_reads_back_or_has_its_shape() {
        let spline = SplineLaw::default_law();
        let drive = Drive::needle_rack_default();
        let x = |f| export(&spline, &drive, f, 5.0).unwrap();
        let json = x(ExportFormat::Json);
        assert_eq!(crate::read_json(&json.text).unwrap().def_points, spline.points());
        let coeffs = x(ExportFormat::Coeffs);
        assert_eq!(crate::read_coeffs_text(&coeffs.text).unwrap().len(), 2 * (spline.points().len() - 1));
        let csv = x(ExportFormat::Csv);
        let t = csv.table.as_ref().unwrap();
        // Every 5° from each joint of the law (12.5° apart in the 150° rise and return): 0, 5, 10,
        // 12.5, 17.5, 22.5, 25, … — 5 points per two joints' 25° in the moving phases.
        assert_eq!(t.points + 1, csv.text.lines().count());
        assert_eq!(t.reinterpolation.len(), 3);
        assert!(x(ExportFormat::Xyva).table.is_some() && x(ExportFormat::Poly5).table.is_none());
        let cycle = x(ExportFormat::Cycle);
        let spec: loomkin_laws::CycleSpec = toml::from_str(&cycle.text).unwrap();
        assert_eq!(spec.period_deg, crate::CYCLE_DEG);
        assert!(export(&spline, &drive, ExportFormat::Csv, 1e-9).is_err());
    }
}
