//! The points of a cam table: where they fall and what they hold.

use super::decimals::{Decimals, round};
use super::{Interval, Motion, tolerance};
use crate::{CamError, Result};
use loomkin_units::{Field, Range};
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

impl Spacing {
    /// `step_deg` of a table: points on every joint and every step from it; 1e-6 … 3600° (a step
    /// longer than the motion leaves the joints alone); 1° when neither it nor a tolerance is given.
    pub const STEP_DEG: Field = Field::new(
        "step_deg",
        STEP_RANGE,
        "Points on every joint and every step from it: 1e-6 … 3600° (the table holds at most 10⁶ \
         points); 1° when neither it nor tolerance is given.",
    )
    .with_default(DEFAULT_STEP_DEG);
    /// `tolerance` of a table: the re-interpolation error allowed between points, in the slave unit.
    pub const TOLERANCE: Field = Field::new(
        "tolerance",
        TOLERANCE_RANGE,
        "Re-interpolation error allowed between the points, in the slave unit (mm, or deg for a swinging \
         follower): 1e-9 … 10⁶.",
    );

    /// The spacing of a front end's options: by `tolerance` when given, else every `step_deg`
    /// (default [`Spacing::STEP_DEG`]'s 1°).
    pub fn of(step_deg: Option<f64>, tolerance: Option<f64>) -> Self {
        match tolerance {
            Some(t) => Spacing::Tolerance(t),
            None => Spacing::StepDeg(step_deg.unwrap_or(Self::STEP_DEG.default_value())),
        }
    }
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

/// The point at (rounded) master angle `x`, rounded to the decimals. At a joint of the motion (a
/// law's segment joint, a phase boundary), where A or J may jump, the point holds the values of the
/// piece that **starts** there (the right-hand limits), never a mix of the two sides; the interval
/// that ends there is then re-interpolated towards them, and its error against the piece that ends
/// there is part of the reported error. At the motion's end the one side there is.
pub(crate) fn point_at(motion: &Motion, x: f64, dec: &Decimals) -> CamPoint {
    let pieces = motion.pieces();
    let mut i = motion.piece_index(x);
    // A master rounded to its decimals may fall just before the joint it stands for.
    if i + 1 < pieces.len() && (x - pieces[i].end_deg).abs() <= 1e-9 * (1.0 + pieces[i].end_deg.abs()) {
        i += 1;
    }
    let v = pieces[i].eval(x);
    CamPoint {
        master_deg: x,
        y: round(v[0], dec.y),
        v: round(v[1], dec.v),
        a: round(v[2], dec.a),
        j: round(v[3], dec.j),
    }
}

/// `(Y, V, A)` at (rounded) master angle `x` by the formula of the piece that **ends** there, rounded
/// to the decimals: at a joint the left-hand limits (where [`point_at`] holds the right-hand ones),
/// elsewhere the same values as the point. At the motion's start the one side there is.
pub(crate) fn left_at(motion: &Motion, x: f64, dec: &Decimals) -> [f64; 3] {
    let pieces = motion.pieces();
    let mut i = motion.piece_index(x);
    if i > 0 && (x - pieces[i].start_deg).abs() <= 1e-9 * (1.0 + pieces[i].start_deg.abs()) {
        i -= 1;
    }
    let v = pieces[i].eval(x);
    [round(v[0], dec.y), round(v[1], dec.v), round(v[2], dec.a)]
}

/// The quintic Hermite intervals through consecutive points.
pub fn hermite_intervals(points: &[CamPoint]) -> Vec<Interval> {
    points.windows(2).map(|w| Interval::hermite(w[0].master_deg, w[1].master_deg, w[0].yva(), w[1].yva())).collect()
}

/// How a controller joins the points of a table.
///
/// Every format is meant for [`Interpolation::QuinticHermite`], the quintic through (Y, V, A) at
/// both ends of each interval; the two others are what a controller that reads the positions alone
/// would run, reported for comparison (`loomkin servo export`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Interpolation {
    /// Straight lines between positions (velocity piecewise constant, acceleration zero).
    Linear,
    /// The natural cubic spline through the positions (zero second derivative at both ends).
    CubicSpline,
    /// Fifth-degree Hermite polynomials matching Y, V and A at both ends (XYVA points).
    QuinticHermite,
}

impl Interpolation {
    /// Every mode.
    pub const ALL: [Interpolation; 3] = [Self::Linear, Self::CubicSpline, Self::QuinticHermite];

    /// Kebab-case name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Linear => "linear",
            Self::CubicSpline => "cubic-spline",
            Self::QuinticHermite => "quintic-hermite",
        }
    }

    /// The intervals a controller runs between `points` in this mode.
    ///
    /// The natural cubic spline's second derivatives `Mᵢ` at the points solve, with `hᵢ` the
    /// interval widths, `δᵢ = (Yᵢ₊₁ − Yᵢ)/hᵢ` and `M₀ = M_n = 0`,
    /// `hᵢ₋₁Mᵢ₋₁ + 2(hᵢ₋₁ + hᵢ)Mᵢ + hᵢMᵢ₊₁ = 6(δᵢ − δᵢ₋₁)`.
    pub fn intervals(self, points: &[CamPoint]) -> Vec<Interval> {
        match self {
            Self::QuinticHermite => hermite_intervals(points),
            Self::Linear => {
                points.windows(2).map(|w| Interval::linear(w[0].master_deg, w[1].master_deg, w[0].y, w[1].y)).collect()
            }
            Self::CubicSpline => {
                let n = points.len();
                let h: Vec<f64> = points.windows(2).map(|w| w[1].master_deg - w[0].master_deg).collect();
                let delta: Vec<f64> = points.windows(2).zip(&h).map(|(w, h)| (w[1].y - w[0].y) / h).collect();
                let (mut lo, mut di, mut up, mut m) = (vec![0.0; n], vec![1.0; n], vec![0.0; n], vec![0.0; n]);
                for i in 1..n - 1 {
                    (lo[i], di[i], up[i]) = (h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i]);
                    m[i] = 6.0 * (delta[i] - delta[i - 1]);
                }
                loomkin_numeric::solve_tridiagonal(&lo, &di, &up, &mut m);
                points
                    .windows(2)
                    .enumerate()
                    .map(|(i, w)| Interval::cubic(w[0].master_deg, w[1].master_deg, w[0].y, w[1].y, m[i], m[i + 1]))
                    .collect()
            }
        }
    }
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
