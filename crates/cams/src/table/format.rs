//! The table formats: one file each, all behind [`Format`].

use super::points::{CamPoint, hermite_intervals};
use super::{CamTable, Interval};
use super::{csv, poly5, st, twincat, xyvaj};
use crate::{CamError, Result};
use serde::Serialize;

/// A cam-table file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Format {
    /// `X,Y,V,A,J` points after `#` comment lines.
    Xyvaj,
    /// Fifth-degree segments, `b₀…b₅` in the normalised master coordinate.
    Poly5,
    /// Plain CSV with a units header and no comments.
    Csv,
    /// A TwinCAT-style motion-function point list.
    Twincat,
    /// IEC 61131-3 Structured Text, an `ARRAY … OF SMC_CAMXYVA` initialiser.
    St,
    /// PLCopen-style `X,Y,V,A` points after `#` comment lines (XYVAJ without the jerk).
    Xyva,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 6] = [Format::Xyvaj, Format::Poly5, Format::Csv, Format::Twincat, Format::St, Format::Xyva];

    /// The format's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Format::Xyvaj => "xyvaj",
            Format::Poly5 => "poly5",
            Format::Csv => "csv",
            Format::Twincat => "twincat",
            Format::St => "st",
            Format::Xyva => "xyva",
        }
    }

    /// The format of a name.
    pub fn parse(name: &str) -> Result<Self> {
        Self::ALL.into_iter().find(|f| f.name() == name).ok_or_else(|| CamError::Usage {
            field: "format".into(),
            reason: format!("unknown format '{name}': use xyvaj, poly5, csv, twincat, st or xyva"),
        })
    }

    /// Writes `table` with the comment lines `header` (a format without comments drops them).
    pub fn write(self, table: &CamTable, header: &[String]) -> String {
        match self {
            Format::Xyvaj => xyvaj::write(table, header),
            Format::Poly5 => poly5::write(table, header),
            Format::Csv => csv::write(table),
            Format::Twincat => twincat::write(table, header),
            Format::St => st::write(table, header),
            Format::Xyva => xyvaj::write_xyva(table, header),
        }
    }

    /// Reads a written table back into the intervals a controller runs.
    pub fn read(self, text: &str) -> Result<Vec<Interval>> {
        match self {
            Format::Xyvaj => Ok(hermite_intervals(&xyvaj::read(text)?)),
            Format::Poly5 => poly5::read(text),
            Format::Csv => Ok(hermite_intervals(&csv::read(text)?)),
            Format::Twincat => Ok(hermite_intervals(&twincat::read(text)?)),
            Format::St => Ok(hermite_intervals(&st::read(text)?)),
            Format::Xyva => Ok(hermite_intervals(&xyvaj::read_xyva(text)?)),
        }
    }
}

/// The numbers of a comma-separated data line, naming the line in the error.
pub(crate) fn numbers(line: &str, n: usize, lineno: usize, skip: usize) -> Result<Vec<f64>> {
    let err = || CamError::Parse {
        field: format!("line {}", lineno + 1),
        reason: format!("expected {n} comma-separated numbers, found '{}'", line.trim()),
    };
    let fields: Vec<&str> = line.split(',').map(str::trim).collect();
    if fields.len() < n + skip {
        return Err(err());
    }
    let v: Vec<f64> = fields[skip..skip + n]
        .iter()
        .map(|t| t.parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|_| err())?;
    if v.iter().any(|x| !x.is_finite()) {
        return Err(err());
    }
    Ok(v)
}

/// Points from rows `X,Y,V,A,J` (after `skip` leading fields), checked to increase in X.
pub(crate) fn points_from_rows(rows: Vec<Vec<f64>>) -> Result<Vec<CamPoint>> {
    let pts: Vec<CamPoint> =
        rows.into_iter().map(|r| CamPoint { master_deg: r[0], y: r[1], v: r[2], a: r[3], j: r[4] }).collect();
    if pts.len() < 2 {
        return Err(CamError::Parse { field: "table".into(), reason: "a table needs at least two points".into() });
    }
    if let Some(i) = pts.windows(2).position(|w| w[1].master_deg <= w[0].master_deg) {
        return Err(CamError::Parse {
            field: format!("point {}", i + 1),
            reason: "master angles must increase".into(),
        });
    }
    Ok(pts)
}
