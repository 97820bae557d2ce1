//! Plain CSV, one header line with units and no comments:
//! `master_deg,slave_mm,slave_v_mm_per_deg,slave_a_mm_per_deg2,slave_j_mm_per_deg3`
//! (`slave_deg,slave_v_deg_per_deg,…` for a swinging follower).

use super::decimals::fixed;
use super::format::{numbers, points_from_rows};
use super::{CamPoint, CamTable};
use crate::{CamError, Result};
use loomkin_io::csv::CsvText;

/// The header for a slave unit (`mm` or `deg`).
pub fn header(unit: &str) -> String {
    format!("master_deg,slave_{unit},slave_v_{unit}_per_deg,slave_a_{unit}_per_deg2,slave_j_{unit}_per_deg3")
}

/// Writes the points.
pub fn write(table: &CamTable) -> String {
    let head = header(table.unit_name());
    let columns: Vec<&str> = head.split(',').collect();
    let mut t = CsvText::new(&[], &columns);
    push_points(&mut t, table);
    t.finish()
}

/// Appends the points as rows of X, Y, V, A, J with the table's fixed decimals (CSV and XYVAJ).
pub(super) fn push_points(t: &mut CsvText, table: &CamTable) {
    let d = table.decimals();
    for p in table.points() {
        t.push([fixed(p.master_deg, d.master), fixed(p.y, d.y), fixed(p.v, d.v), fixed(p.a, d.a), fixed(p.j, d.j)]);
    }
}

/// Reads the points back.
pub fn read(text: &str) -> Result<Vec<CamPoint>> {
    let mut lines = text.lines().enumerate();
    match lines.next() {
        Some((_, h)) if h.trim() == header("mm") || h.trim() == header("deg") => {}
        _ => {
            return Err(CamError::Parse {
                field: "line 1".into(),
                reason: format!("expected the header '{}'", header("mm")),
            });
        }
    }
    let rows = lines.filter(|(_, l)| !l.trim().is_empty()).map(|(i, l)| numbers(l, 5, i, 0)).collect::<Result<_>>()?;
    points_from_rows(rows)
}
