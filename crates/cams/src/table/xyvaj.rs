//! XYVA points with an added jerk column: `X,Y,V,A,J` after `#` comment lines; and the plain
//! PLCopen-style XYVA points `X,Y,V,A` ([`write_xyva`], [`read_xyva`]).
//!
//! ```text
//! # loomkin cam table: master X in deg, slave Y in mm, …
//! X,Y,V,A,J
//! 0,0.0000,0.000000,0.00000000,0.004112
//! ```

use super::decimals::fixed;
use super::format::{numbers, points_from_rows};
use super::{CamPoint, CamTable};
use crate::Result;
use loomkin_io::csv::CsvText;

/// Writes the points.
pub fn write(table: &CamTable, header: &[String]) -> String {
    let comments: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut t = CsvText::new(&comments, &["X", "Y", "V", "A", "J"]);
    super::csv::push_points(&mut t, table);
    t.finish()
}

/// Reads the points back (comment lines and the header skipped).
pub fn read(text: &str) -> Result<Vec<CamPoint>> {
    read_columns(text, 5)
}

/// Rows of `n` numbers (`X,Y,V,A[,J]`) after the comment lines and the header; a missing J is 0.
fn read_columns(text: &str, n: usize) -> Result<Vec<CamPoint>> {
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') || l.starts_with("X,") {
            continue;
        }
        let mut v = numbers(l, n, i, 0)?;
        v.resize(5, 0.0);
        rows.push(v);
    }
    points_from_rows(rows)
}

/// Writes the points without the jerk: `X,Y,V,A` after the comment lines.
pub fn write_xyva(table: &CamTable, header: &[String]) -> String {
    let comments: Vec<&str> = header.iter().map(String::as_str).collect();
    let mut t = CsvText::new(&comments, &["X", "Y", "V", "A"]);
    let d = table.decimals();
    for p in table.points() {
        t.push([fixed(p.master_deg, d.master), fixed(p.y, d.y), fixed(p.v, d.v), fixed(p.a, d.a)]);
    }
    t.finish()
}

/// Reads `X,Y,V,A` points back (comment lines and the header skipped; J, not written, is 0).
pub fn read_xyva(text: &str) -> Result<Vec<CamPoint>> {
    read_columns(text, 4)
}
