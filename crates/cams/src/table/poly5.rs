//! Fifth-degree segments: one polynomial per interval in the normalised master coordinate,
//! `Y = b₀ + b₁u + … + b₅u⁵`, `u = (X − start)/(end − start)`, every `bₖ` in the slave unit.
//!
//! The segments are the quintic Hermite interpolants of the table's points (so the position and
//! its first two derivatives join at every point up to the coefficients' rounding), each from the
//! values of its own side of a joint: a segment starts on the point (the right-hand limits) and
//! ends on the left-hand limits of the piece that ends there ([`CamTable::left_limits`]), so where
//! A jumps at a joint both segments follow the law up to it. A controller that takes polynomial
//! segments runs them as written.
//!
//! ```text
//! # loomkin cam table: …
//! master_start_deg,master_end_deg,b0_mm,b1_mm,b2_mm,b3_mm,b4_mm,b5_mm
//! ```

use super::decimals::{fixed, round};
use super::format::numbers;
use super::{CamTable, Interval};
use crate::{CamError, Result};
use loomkin_io::csv::CsvText;

/// The column header for a slave unit.
pub fn header(unit: &str) -> String {
    let b: Vec<String> = (0..6).map(|k| format!("b{k}_{unit}")).collect();
    format!("master_start_deg,master_end_deg,{}", b.join(","))
}

/// The decimals of the columns `b₀…b₅`, from the resolutions of Y, V and A (`r_y`, `r_v`, `r_a`:
/// one unit of their last digit) and the shortest interval `h`: since `dᵏY/dXᵏ = Y⁽ᵏ⁾(u)/hᵏ`, a
/// coefficient's rounding moves V by `k·δb/h` and A by `k(k−1)·δb/h²`, so
/// `δb₀ ≤ r_y/10`, `δb₁ ≤ min(r_y/10, r_v·h/10)`, `δb₂ ≤ min(r_y/10, r_v·h/10, r_a·h²/20)`,
/// `δb₃…₅ ≤ min(r_y/30, r_v·h/120, r_a·h²/380)` (a tenth of a last digit of each column, summed
/// over the three high coefficients). Each is also held to 15 significant digits of the column's
/// largest magnitude, the precision of a double.
pub fn coeff_decimals(table: &CamTable, intervals: &[Interval]) -> [usize; 6] {
    let d = table.decimals();
    let r = |n: usize| 10f64.powi(-(n as i32));
    let (ry, rv, ra) = (r(d.y), r(d.v), r(d.a));
    let h = intervals.iter().map(Interval::width).fold(f64::INFINITY, f64::min);
    let bounds = [
        ry / 10.0,
        (ry / 10.0).min(rv * h / 10.0),
        (ry / 10.0).min(rv * h / 10.0).min(ra * h * h / 20.0),
        (ry / 30.0).min(rv * h / 120.0).min(ra * h * h / 380.0),
    ];
    std::array::from_fn(|k| {
        let want = decimals_up_to(bounds[k.min(3)], 20);
        let peak = intervals.iter().map(|iv| iv.b[k].abs()).fold(0.0, f64::max);
        let digits = if peak > 0.0 { (15.0 - peak.log10().floor() - 1.0).max(0.0) as usize } else { 20 };
        want.min(digits)
    })
}

/// The fewest decimals `d ≤ max` with `10⁻ᵈ ≤ resolution`.
fn decimals_up_to(resolution: f64, max: usize) -> usize {
    if !(resolution.is_finite() && resolution > 0.0) {
        return max;
    }
    ((-resolution.log10() - 1e-9).ceil().max(0.0) as usize).min(max)
}

/// The quintic Hermite intervals from each point to the left-hand limits at the next (unrounded
/// coefficients).
pub(crate) fn two_sided(table: &CamTable) -> Vec<Interval> {
    let (pts, left) = (table.points(), table.left_limits());
    pts.windows(2)
        .zip(&left[1..])
        .map(|(w, &end)| Interval::hermite(w[0].master_deg, w[1].master_deg, w[0].yva(), end))
        .collect()
}

/// The segments as written: from each point to the left-hand limits at the next, coefficients rounded.
pub fn segments(table: &CamTable) -> Vec<Interval> {
    let ivs = two_sided(table);
    let dc = coeff_decimals(table, &ivs);
    ivs.into_iter().map(|iv| Interval { b: std::array::from_fn(|k| round(iv.b[k], dc[k])), ..iv }).collect()
}

/// Writes the segments.
pub fn write(table: &CamTable, head: &[String]) -> String {
    let d = table.decimals();
    let dc = coeff_decimals(table, &two_sided(table));
    let comments: Vec<&str> = head.iter().map(String::as_str).collect();
    let columns = header(table.unit_name());
    let mut t = CsvText::new(&comments, &columns.split(',').collect::<Vec<_>>());
    for iv in segments(table) {
        let b = iv.b.iter().zip(dc).map(|(&c, n)| fixed(c, n));
        t.push([fixed(iv.start_deg, d.master), fixed(iv.end_deg, d.master)].into_iter().chain(b));
    }
    t.finish()
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
