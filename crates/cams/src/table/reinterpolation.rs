//! The exact error of a re-interpolated table against the motion it was made from.

use super::{Interval, Motion};
use loomkin_units::{StopFlag, Stopped};
use serde::Serialize;

/// The largest differences between a re-interpolated table and the exact motion, in the slave
/// unit (`unit`) and per master degree.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReinterpolationError {
    /// Largest |Y_table − Y_exact| (slave unit).
    pub max_position_error: f64,
    /// Master angle where it occurs (deg).
    pub max_position_error_at_deg: f64,
    /// Largest |V_table − V_exact| (slave unit per deg).
    pub max_velocity_error: f64,
    /// Largest |A_table − A_exact| (slave unit per deg²).
    pub max_accel_error: f64,
}

impl ReinterpolationError {
    fn merge(&mut self, o: &Self) {
        if o.max_position_error > self.max_position_error {
            self.max_position_error = o.max_position_error;
            self.max_position_error_at_deg = o.max_position_error_at_deg;
        }
        self.max_velocity_error = self.max_velocity_error.max(o.max_velocity_error);
        self.max_accel_error = self.max_accel_error.max(o.max_accel_error);
    }
}

/// The exact errors of `intervals` against `motion`.
///
/// Every interval is cut at the motion's joints inside it; on each piece the difference
/// `e(X) = Y_table(X) − Y_exact(X)` is smooth (a quintic minus one closed-form law segment), and
/// the largest `|e|`, `|e'|` and `|e''|` are located by bracketing the sign changes of the next
/// derivative on a grid sized to the degree and the sine frequency and refining each root by
/// safeguarded Newton ([`loomkin_numeric::refine_root`]); the ends of every piece are included.
pub fn reinterpolation_error(motion: &Motion, intervals: &[Interval]) -> ReinterpolationError {
    loomkin_units::to_the_end(|stop| reinterpolation_error_until(motion, intervals, stop))
}

/// Intervals compared between two looks at the stop flag (well under a millisecond of work).
const STOP_CHECK_INTERVALS: usize = 256;

/// [`reinterpolation_error`] that ends with [`Stopped`] once `stop` is set (a client gone, a time
/// budget spent), looked at every few hundred intervals; run to its end it gives
/// the same errors bit for bit.
pub fn reinterpolation_error_until(
    motion: &Motion,
    intervals: &[Interval],
    stop: &StopFlag,
) -> Result<ReinterpolationError, Stopped> {
    let mut out = ReinterpolationError {
        max_position_error: 0.0,
        max_position_error_at_deg: intervals.first().map_or(0.0, |i| i.start_deg),
        max_velocity_error: 0.0,
        max_accel_error: 0.0,
    };
    for (i, iv) in intervals.iter().enumerate() {
        if i % STOP_CHECK_INTERVALS == 0 {
            stop.check()?;
        }
        out.merge(&interval_error(motion, iv, true));
    }
    Ok(out)
}

/// The errors on one interval (`all`: velocity and acceleration errors too, else position only).
pub(crate) fn interval_error(motion: &Motion, iv: &Interval, all: bool) -> ReinterpolationError {
    let (x0, x1) = (iv.start_deg, iv.end_deg);
    let mut cuts = vec![x0];
    cuts.extend(motion.joints().into_iter().filter(|&j| j > x0 && j < x1));
    cuts.push(x1);
    let mut out = ReinterpolationError {
        max_position_error: 0.0,
        max_position_error_at_deg: x0,
        max_velocity_error: 0.0,
        max_accel_error: 0.0,
    };
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a {
            continue;
        }
        let piece = &motion.pieces()[motion.piece_index(0.5 * (a + b))];
        let n = 2 * (piece.wiggles(a, b).max(5) + 1) + 6;
        let diff = |x: f64| {
            let t = iv.derivs(x - x0);
            let e = piece.derivs(x);
            std::array::from_fn::<f64, 6, _>(|k| t[k] - e[k])
        };
        let orders: &[usize] = if all { &[0, 1, 2] } else { &[0] };
        // The scan's grid is the same for every order: its differences once (the values, and so
        // the result, are those of evaluating them per order).
        let h = (b - a) / n as f64;
        let grid: Vec<[f64; 6]> = (0..=n).map(|i| diff(if i == n { b } else { a + i as f64 * h })).collect();
        for &k in orders {
            let (m, at) = abs_max(a, b, n, &grid, k, |x| {
                let d = diff(x);
                (d[k], d[k + 1], d[k + 2])
            });
            match k {
                0 if m > out.max_position_error => {
                    out.max_position_error = m;
                    out.max_position_error_at_deg = at;
                }
                1 => out.max_velocity_error = out.max_velocity_error.max(m),
                2 => out.max_accel_error = out.max_accel_error.max(m),
                _ => {}
            }
        }
    }
    out
}

/// Largest `|g|` on `[a, b]` and where, for `f(x) = (g, g', g'')` = orders `k, k+1, k+2` of the
/// differences: the ends, and every root of `g'` bracketed on `n` equal sub-intervals (the
/// differences at their ends given in `grid`, `n + 1` of them) and refined by Newton inside the bracket.
fn abs_max(a: f64, b: f64, n: usize, grid: &[[f64; 6]], k: usize, f: impl Fn(f64) -> (f64, f64, f64)) -> (f64, f64) {
    let (g0, mut d0) = (grid[0][k], grid[0][k + 1]);
    let mut best = (g0.abs(), a);
    let h = (b - a) / n as f64;
    let mut x0 = a;
    for (i, gi) in grid.iter().enumerate().skip(1) {
        let x1 = if i == n { b } else { a + i as f64 * h };
        let (g1, d1) = (gi[k], gi[k + 1]);
        if g1.abs() > best.0 {
            best = (g1.abs(), x1);
        }
        if d0 != 0.0 && d1 != 0.0 && (d0 < 0.0) != (d1 < 0.0) {
            let r = loomkin_numeric::refine_root(x0, x1, d0 < 0.0, |x| {
                let (_, d, dd) = f(x);
                (d, dd)
            });
            let g = f(r).0.abs();
            if g > best.0 {
                best = (g, r);
            }
        }
        x0 = x1;
        d0 = d1;
    }
    best
}
