//! One exporter per file format of a servo law; the CLI (`servo export`) and the workbench
//! (`POST /api/servo/export`) both call [`export`].

use crate::{
    CamTable, Drive, Interpolation, InterpolationError, Result, SplineLaw, export_coeffs_text, export_json,
    format_points, poly5_csv, poly5_segments, spline_cycle,
};
use serde::{Deserialize, Serialize};

/// The file formats of [`export`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum ExportFormat {
    /// The spline coefficients per interval as documented text.
    Coeffs,
    /// The coefficients as JSON (`intervals` with `x_start`, `x_end`, `accel`, `velocity`, `position`).
    Json,
    /// Cam table over one turn as CSV (master deg → slave m, m/deg, m/deg²).
    Csv,
    /// Cam table as PLCopen-style XYVA points.
    Xyva,
    /// The exact law as fifth-degree polynomial segments in master degrees (CSV).
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

/// A cam table's size and what re-interpolating it loses.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TableReport {
    /// Points of the table (both ends of the turn included).
    pub points: usize,
    /// Step between points (deg of the main shaft).
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

/// Writes `spline` on `drive` in `format`; cam tables have a step of about `step_deg` (deg of the
/// main shaft, see [`CamTable::new`]).
pub fn export(spline: &SplineLaw, drive: &Drive, format: ExportFormat, step_deg: f64) -> Result<Export> {
    let file = |filename, media_type, text| Export { format, filename, media_type, text, table: None };
    Ok(match format {
        ExportFormat::Coeffs => file("servo-coefficients.txt", "text/plain", export_coeffs_text(spline)),
        ExportFormat::Json => file("servo-coefficients.json", "application/json", export_json(spline)),
        ExportFormat::Poly5 => {
            file("servo-cam-poly5.csv", "text/csv", poly5_csv(&poly5_segments(spline.law(), drive)?))
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
            let table = CamTable::new(spline.law(), drive, step_deg)?;
            let reinterpolation = Interpolation::ALL
                .iter()
                .map(|&m| table.interpolation_error(spline.law(), drive, m))
                .collect::<Result<Vec<_>>>()?;
            let (filename, text) = if format == ExportFormat::Csv {
                ("servo-cam.csv", table.to_csv())
            } else {
                ("servo-cam-xyva.csv", table.to_xyva())
            };
            let report = TableReport { points: table.points.len(), step_deg: table.step_deg(), reinterpolation };
            Export { table: Some(report), ..file(filename, "text/csv", text) }
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
        assert_eq!((t.points, csv.text.lines().count()), (73, 74));
        assert_eq!(t.reinterpolation.len(), 3);
        assert!(x(ExportFormat::Xyva).table.is_some() && x(ExportFormat::Poly5).table.is_none());
        let cycle = x(ExportFormat::Cycle);
        let spec: loomkin_laws::CycleSpec = toml::from_str(&cycle.text).unwrap();
        assert_eq!(spec.period_deg, crate::CYCLE_DEG);
        assert!(export(&spline, &drive, ExportFormat::Csv, 1e-9).is_err());
    }
}
