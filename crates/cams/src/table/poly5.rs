//! Fifth-degree segments: one polynomial per interval in the normalised master coordinate,
//! `Y = b₀ + b₁u + … + b₅u⁵`, `u = (X − start)/(end − start)`, every `bₖ` in the slave unit.
//!
//! The segments are the quintic Hermite interpolants of the table's points (so the position and
//! its first two derivatives join at every point up to the coefficients' rounding); a controller
//! that takes polynomial segments runs them as written.
//!
//! ```text
//! # loomkin cam table: …
//! master_start_deg,master_end_deg,b0_mm,b1_mm,b2_mm,b3_mm,b4_mm,b5_mm
//! ```

use super::decimals::{fixed, round};
use super::format::numbers;
use super::points::hermite_intervals;
use super::{CamTable, Interval};
use crate::{CamError, Result};

/// The column header for a slave unit.
pub fn header(unit: &str) -> String {
    let b: Vec<String> = (0..6).map(|k| format!("b{k}_{unit}")).collect();
    format!("master_start_deg,master_end_deg,{}", b.join(","))
}

/// The segments as written: the Hermite intervals of the points, coefficients rounded.
pub fn segments(table: &CamTable) -> Vec<Interval> {
    let dc = table.decimals().coeffs();
    hermite_intervals(table.points()).into_iter().map(|iv| Interval { b: iv.b.map(|c| round(c, dc)), ..iv }).collect()
}

/// Writes the segments.
pub fn write(table: &CamTable, head: &[String]) -> String {
    let d = table.decimals();
    let dc = d.coeffs();
    let mut s: String = head.iter().map(|l| format!("# {l}\n")).collect();
    s.push_str(&header(table.unit_name()));
    s.push('\n');
    for iv in segments(table) {
        let b: Vec<String> = iv.b.iter().map(|&c| fixed(c, dc)).collect();
        s.push_str(&format!("{},{},{}\n", fixed(iv.start_deg, d.master), fixed(iv.end_deg, d.master), b.join(",")));
    }
    s
}

/// Reads the segments back; they must follow one another without gap.
pub fn read(text: &str) -> Result<Vec<Interval>> {
    let mut out: Vec<Interval> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let l = line.trim();
        if l.is_empty() || l.starts_with('#') || l.starts_with("master_") {
            continue;
        }
        let v = numbers(l, 8, i, 0)?;
        let iv = Interval { start_deg: v[0], end_deg: v[1], b: std::array::from_fn(|k| v[2 + k]) };
        let joined = out.last().is_none_or(|p| p.end_deg == iv.start_deg);
        if iv.end_deg <= iv.start_deg || !joined {
            return Err(CamError::Parse {
                field: format!("line {}", i + 1),
                reason: "segments must follow one another, each with end > start".into(),
            });
        }
        out.push(iv);
    }
    if out.is_empty() {
        return Err(CamError::Parse { field: "table".into(), reason: "no segments".into() });
    }
    Ok(out)
}
