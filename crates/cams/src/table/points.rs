//! The points of a cam table: where they fall and what they hold.

use super::decimals::{Decimals, round};
use super::{Interval, Motion, tolerance};
use crate::{CamError, Result};
use loomkin_units::Range;
use serde::Serialize;

/// One point of a cam table: the master angle and the slave's position and derivatives with
/// respect to the master angle, each rounded to its column's decimals.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CamPoint {
    /// Master angle X (deg).
    pub master_deg: f64,
    /// Slave position Y (mm or deg).
    pub y: f64,
    /// V = dY/dX (slave unit per deg).
    pub v: f64,
    /// A = d²Y/dX² (slave unit per deg²).
    pub a: f64,
    /// J = d³Y/dX³ (slave unit per deg³).
    pub j: f64,
}

impl CamPoint {
    /// `(Y, V, A)`, what the controller interpolates from.
    pub fn yva(&self) -> [f64; 3] {
        [self.y, self.v, self.a]
    }
}

/// How the points are placed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Spacing {
    /// On every joint of the motion, and from each joint onwards every `step` degrees; where the
    /// step does not divide the span between two joints, the last step before the next joint is
    /// shorter (the step is honoured exactly, never rounded to fit).
    StepDeg(f64),
    /// On every joint, and in between as few points as the greedy placement needs to keep the
    /// re-interpolation error of every interval at most this tolerance (slave unit).
    Tolerance(f64),
}

/// The allowed step (deg).
pub const STEP_RANGE: Range = Range::closed(1e-6, 3600.0, "deg");
/// The step when neither a step nor a tolerance is given (deg).
pub const DEFAULT_STEP_DEG: f64 = 1.0;
/// The allowed tolerance (slave unit).
pub const TOLERANCE_RANGE: Range = Range::closed(1e-9, 1e6, "");
/// The most points a table may hold.
pub const MAX_POINTS: usize = 1_000_000;

/// The master angles planned for a step: every joint, and `joint + k·step` inside each span.
pub(crate) fn step_masters(motion: &Motion, step: f64) -> Result<Vec<f64>> {
    let joints = motion.joints();
    let span = motion.end_deg() - motion.start_deg();
    if span / step > MAX_POINTS as f64 {
        return Err(CamError::Usage {
            field: "step_deg".into(),
            reason: format!(
                "a step of {}° over {}° makes more than {MAX_POINTS} points: use a larger step",
                loomkin_units::compact(step),
                loomkin_units::compact(span)
            ),
        });
    }
    let mut out = Vec::new();
    for w in joints.windows(2) {
        let (a, b) = (w[0], w[1]);
        out.push(a);
        let mut k = 1.0;
        // A point closer than 1e-9 of the step to the next joint is that joint.
        while a + k * step < b - 1e-9 * step {
            out.push(a + k * step);
            k += 1.0;
        }
    }
    out.push(motion.end_deg());
    Ok(out)
}

/// Rounded masters, in order, without repeats.
pub(crate) fn rounded_masters(masters: &[f64], d: usize) -> Vec<f64> {
    let mut out: Vec<f64> = masters.iter().map(|&x| round(x, d)).collect();
    out.dedup();
    out
}

/// The point at (rounded) master angle `x`, rounded to the decimals. At a joint of the motion the
/// values are the mean of the two sides' limits (they differ where the acceleration or the jerk
/// jumps); at the motion's ends the one side there is.
pub(crate) fn point_at(motion: &Motion, x: f64, dec: &Decimals) -> CamPoint {
    let pieces = motion.pieces();
    let i = motion.piece_index(x);
    let p = &pieces[i];
    let near = |j: f64| (x - j).abs() <= 1e-9 * (1.0 + j.abs());
    let v = if near(p.start_deg) && i > 0 {
        let (l, r) = (pieces[i - 1].eval(x), p.eval(x));
        std::array::from_fn(|k| 0.5 * (l[k] + r[k]))
    } else if near(p.end_deg) && i + 1 < pieces.len() {
        let (l, r) = (p.eval(x), pieces[i + 1].eval(x));
        std::array::from_fn(|k| 0.5 * (l[k] + r[k]))
    } else {
        p.eval(x)
    };
    CamPoint {
        master_deg: x,
        y: round(v[0], dec.y),
        v: round(v[1], dec.v),
        a: round(v[2], dec.a),
        j: round(v[3], dec.j),
    }
}

/// The quintic Hermite intervals through consecutive points.
pub fn hermite_intervals(points: &[CamPoint]) -> Vec<Interval> {
    points.windows(2).map(|w| Interval::hermite(w[0].master_deg, w[1].master_deg, w[0].yva(), w[1].yva())).collect()
}

/// The points of a table for a spacing, with the decimals they are rounded to.
pub(crate) fn place(motion: &Motion, spacing: Spacing) -> Result<(Vec<CamPoint>, Decimals)> {
    let peaks = column_peaks(motion);
    match spacing {
        Spacing::StepDeg(step) => {
            let step = STEP_RANGE.check("step_deg", step)?;
            let planned = step_masters(motion, step)?;
            let dec = Decimals::choose(&planned, motion.stroke(), peaks, None);
            let masters = rounded_masters(&planned, dec.master);
            Ok((masters.iter().map(|&x| point_at(motion, x, &dec)).collect(), dec))
        }
        Spacing::Tolerance(t) => {
            // The range in the slave unit the tolerance is given in (`TOLERANCE_RANGE` has none).
            let unit = match motion.unit() {
                loomkin_laws::StrokeUnit::Mm => "mm",
                loomkin_laws::StrokeUnit::Deg => "deg",
            };
            let t = Range { unit, ..TOLERANCE_RANGE }.check("tolerance", t)?;
            let dec = Decimals::choose(&motion.joints(), motion.stroke(), peaks, Some(t));
            Ok((tolerance::greedy(motion, t, &dec)?, dec))
        }
    }
}

/// The largest |V|, |A|, |J| over the motion, from 65 points per piece and its ends (only to
/// choose the columns' decimals).
fn column_peaks(motion: &Motion) -> [f64; 3] {
    let mut out = [0.0f64; 3];
    for p in motion.pieces() {
        for i in 0..=64 {
            let x = p.start_deg + (p.end_deg - p.start_deg) * i as f64 / 64.0;
            let e = p.eval(x);
            for k in 0..3 {
                out[k] = out[k].max(e[k + 1].abs());
            }
        }
    }
    out
}
