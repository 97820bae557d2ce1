//! Points placed for a tolerance: as few as the greedy placement needs.

use super::decimals::{Decimals, round};
use super::points::{CamPoint, MAX_POINTS, point_at};
use super::reinterpolation::interval_error;
use super::{Interval, Motion};
use crate::{CamError, Result};

/// The share of the tolerance the greedy placement aims at, leaving room for the rounding of the
/// poly5 coefficients (at most `3·10⁻²` of the position resolution, itself at most `T/100`).
pub const TOLERANCE_MARGIN: f64 = 0.999;

/// Greedy placement: every joint of the motion is a point; from each point the next one is the
/// farthest master angle on the `10^−master` grid, up to the next joint, whose interval's exact
/// re-interpolation error (quintic Hermite from the rounded points) is at most `0.999·T`, found
/// by bisection on the grid (the error of an interval grows with its length except in rare
/// wiggles, so bisection finds the longest admissible interval up to such a wiggle). An interval
/// of one grid step is taken even if it exceeds the tolerance; the reported error then says so.
pub(crate) fn greedy(motion: &Motion, tol: f64, dec: &Decimals) -> Result<Vec<CamPoint>> {
    let target = TOLERANCE_MARGIN * tol;
    let grid = 10f64.powi(-(dec.master as i32));
    let joints: Vec<f64> = motion.joints().iter().map(|&j| round(j, dec.master)).collect();
    let mut pts = vec![point_at(motion, joints[0], dec)];
    for w in joints.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a {
            continue;
        }
        let mut p = pts[pts.len() - 1];
        let end = point_at(motion, b, dec);
        loop {
            let ok = |q: &CamPoint| {
                let iv = Interval::hermite(p.master_deg, q.master_deg, p.yva(), q.yva());
                interval_error(motion, &iv, false).max_position_error <= target
            };
            if ok(&end) {
                pts.push(end);
                break;
            }
            // Bisection on the number of grid steps from p: lo admissible (or the least step), hi not.
            let steps = ((b - p.master_deg) / grid).round() as u64;
            let (mut lo, mut hi) = (1u64, steps);
            let at = |k: u64| point_at(motion, round(p.master_deg + k as f64 * grid, dec.master), dec);
            while hi - lo > 1 {
                let mid = lo + (hi - lo) / 2;
                if ok(&at(mid)) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            p = at(lo);
            pts.push(p);
            if lo >= steps {
                break;
            }
            if pts.len() > MAX_POINTS {
                return Err(CamError::Usage {
                    field: "tolerance".into(),
                    reason: format!("more than {MAX_POINTS} points are needed: use a larger tolerance"),
                });
            }
        }
    }
    Ok(pts)
}
