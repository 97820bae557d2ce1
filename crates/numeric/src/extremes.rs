//! The extremes of smooth functions known with their first two derivatives, located exactly: the
//! sign changes of the derivative bracketed on a grid (refined where the grid does not resolve the
//! derivative) and each root refined by Newton inside its bracket ([`refine_root_from`]). The one
//! peak scan of loomkin: cam profiles (pressure angle, curvature), follower responses and the
//! two-mass train take their extremes from here.

use crate::refine_root_from;

/// The least and greatest value of a function on an interval, each with where it is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Least value and its location.
    pub min: (f64, f64),
    /// Greatest value and its location.
    pub max: (f64, f64),
}

impl Extremes {
    /// Nothing taken yet (to be merged into): `min` is +∞ and `max` −∞.
    pub const EMPTY: Extremes = Extremes { min: (f64::INFINITY, 0.0), max: (f64::NEG_INFINITY, 0.0) };

    /// Takes a candidate value `v` at `at`; of equal values the first taken stays.
    pub fn take(&mut self, v: f64, at: f64) {
        if v < self.min.0 {
            self.min = (v, at);
        }
        if v > self.max.0 {
            self.max = (v, at);
        }
    }

    /// Takes another set's extremes, their locations shifted by `shift`.
    pub fn merge(&mut self, o: &Extremes, shift: f64) {
        self.take(o.min.0, o.min.1 + shift);
        self.take(o.max.0, o.max.1 + shift);
    }

    /// The largest magnitude `max(|min|, |max|)` and its location (the maximum's on a tie).
    pub fn peak_abs(&self) -> (f64, f64) {
        if self.max.0.abs() >= self.min.0.abs() {
            (self.max.0.abs(), self.max.1)
        } else {
            (self.min.0.abs(), self.min.1)
        }
    }

    /// True when nothing was taken.
    pub fn is_empty(&self) -> bool {
        !self.max.0.is_finite() && !self.min.0.is_finite()
    }
}

/// The extremes of `f` on `[a, b]`, `f(t) = [q, q′, q″]`: both ends and every root of `q′`
/// (see [`extremes_of`]).
pub fn extremes(a: f64, b: f64, n: usize, f: impl Fn(f64) -> [f64; 3]) -> Extremes {
    let [e] = extremes_of(a, b, n, |t| [f(t)]);
    e
}

/// The extremes of `K` functions at once on `[a, b]` (each evaluation of `f` gives all of them):
/// `f(t)[i] = [q_i, q_i′, q_i″]`. Candidates are both ends and every root of each `q_i′`, taken in
/// order along the interval, so of equal values the leftmost is reported.
///
/// The grid of `n` intervals (at least 2) is sized by the caller to the function's own scale (a
/// law's degree and half-periods); the function may be far sharper somewhere. An interval is halved
/// while `q″` at its ends does not account for the change of `q′` across it (the trapezoid rule off
/// by more than a tenth of the change): a resolved interval costs nothing, an unresolved one is
/// refined until it is resolved (at most 40 halvings, 64·n evaluations in all). Where a curve meets
/// a rest, `q′` vanishes at an end and its computed value is rounding of either sign; its sign just
/// inside is that of `q″` after the start (of `−q″` before the end), and a root between the last
/// grid point and such an end is bracketed against a point near the end where `q′` has that sign.
/// (Judged by the rounded value alone the bracket is missed: a cam's largest pressure angle 0.051°
/// before the end of a return was reported at 0°, 2.3e-7° too small.)
pub fn extremes_of<const K: usize>(a: f64, b: f64, n: usize, f: impl Fn(f64) -> [[f64; 3]; K]) -> [Extremes; K] {
    let mut e = [Extremes::EMPTY; K];
    let first = f(a);
    if b <= a {
        for (ei, v) in e.iter_mut().zip(&first) {
            ei.take(v[0], a);
        }
        return e;
    }
    let n = n.max(2);
    let h = (b - a) / n as f64;
    let last = f(b);
    let grid: Vec<(f64, [[f64; 3]; K])> = (0..=n)
        .map(|j| match j {
            0 => (a, first),
            j if j == n => (b, last),
            j => {
                let t = a + j as f64 * h;
                (t, f(t))
            }
        })
        .collect();
    let resolved = |p: &(f64, [[f64; 3]; K]), q: &(f64, [[f64; 3]; K])| {
        (0..K).all(|i| {
            let (u, v) = (p.1[i], q.1[i]);
            let dq = v[1] - u[1];
            let trapezoid = 0.5 * (u[2] + v[2]) * (q.0 - p.0);
            let size = dq.abs().max(0.5 * (u[2].abs() + v[2].abs()) * (q.0 - p.0));
            (dq - trapezoid).abs() <= 0.1 * size || size == 0.0
        })
    };
    let mut pts: Vec<(f64, [[f64; 3]; K])> = Vec::with_capacity(grid.len());
    let mut budget = 64 * n;
    // Scratch reused across the grid's intervals (most are resolved at once and push nothing).
    let (mut stack, mut inner) = (Vec::new(), Vec::new());
    for w in grid.windows(2) {
        pts.push(w[0]);
        stack.push((w[0], w[1], 0u32));
        while let Some((p, q, depth)) = stack.pop() {
            if depth >= 40 || budget == 0 || resolved(&p, &q) {
                inner.push(q);
                continue;
            }
            budget -= 1;
            let m = 0.5 * (p.0 + q.0);
            let mid = (m, f(m));
            // The right half at the stack's bottom: the left half is taken (and pushed) first.
            stack.push((mid, q, depth + 1));
            stack.push((p, mid, depth + 1));
        }
        // `inner` holds the right ends of the accepted intervals in order, the last being w[1].
        inner.pop();
        pts.append(&mut inner);
    }
    pts.push(grid[n]);
    let sign = |d: f64| {
        if d > 0.0 {
            1
        } else if d < 0.0 {
            -1
        } else {
            0
        }
    };
    for (i, ei) in e.iter_mut().enumerate() {
        let scale = pts.iter().fold(0.0f64, |m, p| m.max(p.1[i][1].abs()));
        let vanishes = |d: f64| d.abs() <= 1e-9 * scale;
        // A point between `end` and `other`, as close to `end` as needed, where q′ has the sign `want`.
        let inside = |end: f64, other: f64, want: i32| {
            (1..=40).map(|k| end + (other - end) * 0.5f64.powi(k)).find(|&t| sign(f(t)[i][1]) == want)
        };
        ei.take(pts[0].1[i][0], pts[0].0);
        for w in pts.windows(2) {
            let ((t0, v0), (t1, v1)) = (w[0], w[1]);
            let (v0, v1) = (v0[i], v1[i]);
            let at_start = t0 == a && vanishes(v0[1]);
            let at_end = t1 == b && vanishes(v1[1]);
            let s0 = if at_start { sign(v0[2]) } else { sign(v0[1]) };
            let s1 = if at_end { -sign(v1[2]) } else { sign(v1[1]) };
            if s0 != 0 && s1 != 0 && s0 != s1 {
                let lo = if at_start { inside(t0, t1, s0) } else { Some(t0) };
                let hi = if at_end { inside(t1, t0, s1) } else { Some(t1) };
                if let (Some(lo), Some(hi)) = (lo, hi) {
                    // Start from the secant point of q′ across the bracket (within O(h²) of the root).
                    let (g0, g1) =
                        (if at_start { f(lo)[i][1] } else { v0[1] }, if at_end { f(hi)[i][1] } else { v1[1] });
                    let start = if g1 != g0 { (lo * g1 - hi * g0) / (g1 - g0) } else { 0.5 * (lo + hi) };
                    let start = if start > lo && start < hi { start } else { 0.5 * (lo + hi) };
                    let r = refine_root_from(lo, hi, start, s0 < 0, |t| {
                        let d = f(t)[i];
                        (d[1], d[2])
                    });
                    ei.take(f(r)[i][0], r);
                }
            }
            ei.take(v1[0], t1);
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn interior_extremes_exactly() {
        // sin(3t) + 0.1 t on [0, 4]: maxima where 3 cos(3t) = −0.1.
        let e = extremes(0.0, 4.0, 12, |t| {
            [(3.0 * t).sin() + 0.1 * t, 3.0 * (3.0 * t).cos() + 0.1, -9.0 * (3.0 * t).sin()]
        });
        // The maxima in [0, 4]: 3t = acos(−1/30) + 2πk, k = 0, 1 (k = 2 lies past the end).
        let candidates = [0.0, 2.0 * PI].map(|k| ((-0.1f64 / 3.0).acos() + k) / 3.0);
        let best = candidates
            .into_iter()
            .map(|t| ((3.0 * t).sin() + 0.1 * t, t))
            .fold((f64::MIN, 0.0), |m, c| if c.0 > m.0 { c } else { m });
        assert!((e.max.0 - best.0).abs() < 1e-15, "{:?} vs {best:?}", e.max);
        assert!((e.max.1 - best.1).abs() < 1e-9);
    }

    #[test]
    fn an_extremum_next_to_the_end_is_found() {
        // q = t²(1 − t)·(t − 0.999) on [0, 1]: its maximum (2.5e-7) lies 5e-4 before the end, its
        // minimum mid-way, on a 4-interval grid; q′(0) = 0 at the start (a rest).
        let q = |t: f64| t * t * (1.0 - t) * (t - 0.999);
        let dq = |t: f64| {
            let h = 1e-6;
            (q(t + h) - q(t - h)) / (2.0 * h)
        };
        // Analytic derivatives of the quartic −t⁴ + 1.999 t³ − 0.999 t².
        let f = |t: f64| {
            [
                q(t),
                -4.0 * t.powi(3) + 3.0 * 1.999 * t * t - 2.0 * 0.999 * t,
                -12.0 * t * t + 6.0 * 1.999 * t - 2.0 * 0.999,
            ]
        };
        assert!((f(0.5)[1] - dq(0.5)).abs() < 1e-8);
        let e = extremes(0.0, 1.0, 4, f);
        // The dense scan's best is never above the located maximum, and lies within its resolution.
        let scan = (0..=1_000_000)
            .map(|k| k as f64 * 1e-6)
            .map(|t| (q(t), t))
            .fold((f64::MIN, 0.0), |m, c| if c.0 > m.0 { c } else { m });
        assert!(e.max.0 >= scan.0, "{:?} below the scan's {scan:?}", e.max);
        // The scan's points are 1e-6 apart: its best lies within 5e-7 of the peak, below it by at most
        // |q″|·(5e-7)²/2 = 2.5e-13 (|q″| ≈ 2 there).
        assert!(e.max.0 - scan.0 < 2.5e-13 && (e.max.1 - scan.1).abs() < 5e-7, "{:?} vs {scan:?}", e.max);
    }

    #[test]
    fn sharp_peaks_between_grid_points_at_any_magnitude() {
        use proptest::prelude::*;
        use proptest::test_runner::{Config, TestRunner};
        // A narrow Gaussian bump on a slope, scaled by 10^k and placed anywhere, on a grid as wide as
        // the bump (the caller sizes the grid to the function's scale): located exactly at every
        // magnitude, and no scan point above the maximum or below the minimum.
        let mut runner = TestRunner::new(Config { cases: 200, ..Config::default() });
        runner
            .run(&(-9i32..=9, 0.05f64..0.95, 1e-3f64..1e-2), |(k, c, w)| {
                let s = 10f64.powi(k);
                let f = |t: f64| {
                    let g = (-((t - c) / w).powi(2)).exp();
                    let d = -2.0 * (t - c) / (w * w);
                    [s * (g + 0.01 * t), s * (g * d + 0.01), s * g * (d * d - 2.0 / (w * w))]
                };
                let e = extremes(0.0, 1.0, (1.0 / w).ceil() as usize, f);
                let tmax = e.max.1;
                prop_assert!((tmax - c).abs() < 1e-3 * w + 1e-12, "peak at {tmax}, expected near {c}");
                for j in 0..=20_000 {
                    let t = j as f64 / 20_000.0;
                    prop_assert!(f(t)[0] <= e.max.0 + 1e-15 * s, "scan {t}: {} above {:?}", f(t)[0], e.max);
                    prop_assert!(f(t)[0] >= e.min.0 - 1e-15 * s, "scan {t}: {} below {:?}", f(t)[0], e.min);
                }
                Ok(())
            })
            .unwrap();
    }

    #[test]
    fn leftmost_of_equal_values() {
        let e = extremes(0.0, 2.0, 8, |_| [1.0, 0.0, 0.0]);
        assert_eq!((e.min, e.max), ((1.0, 0.0), (1.0, 0.0)));
        let mut m = Extremes::EMPTY;
        assert!(m.is_empty());
        m.merge(&e, 5.0);
        assert_eq!(m.max, (1.0, 5.0));
        assert_eq!(m.peak_abs(), (1.0, 5.0));
    }
}
