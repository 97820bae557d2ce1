//! Extremes of a smooth quantity over a span of cam angle, located exactly: sign changes of the
//! exact derivative bracketed on a grid and refined by `loomkin_numeric::refine_root`.

use super::lift::Span;

/// The least and greatest value of a quantity and where (cam angle, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Least value.
    pub min: f64,
    /// Where it is least (rad).
    pub min_at: f64,
    /// Greatest value.
    pub max: f64,
    /// Where it is greatest (rad).
    pub max_at: f64,
}

impl Extremes {
    /// No values yet.
    pub fn empty() -> Self {
        Self { min: f64::INFINITY, min_at: f64::NAN, max: f64::NEG_INFINITY, max_at: f64::NAN }
    }

    /// Takes a value into account.
    pub fn push(&mut self, at: f64, v: f64) {
        if v < self.min {
            (self.min, self.min_at) = (v, at);
        }
        if v > self.max {
            (self.max, self.max_at) = (v, at);
        }
    }

    /// Takes another set of extremes into account.
    pub fn merge(&mut self, o: Extremes) {
        self.push(o.min_at, o.min);
        self.push(o.max_at, o.max);
    }
}

/// The extremes over a span of `f`, which returns `[q, q′, q″]` at a cam angle: the span's ends and
/// every root of `q′` (bracketed on the span's grid, refined by Newton inside the bracket). On a
/// dwell every quantity of the geometry is constant and only the ends are taken.
///
/// Where a motion meets a dwell, `s′ = s″ = 0`, and with them the derivative of the pressure angle,
/// of the curvature and of most of the geometry vanishes at the span's end: its computed value is
/// rounding of either sign. Its sign just inside the span is that of `q″` (after the start) or `−q″`
/// (before the end), and a root of `q′` between the last grid point and such an end is bracketed
/// against a point near the end where `q′` has that sign. (Judged by the rounded value alone, the
/// bracket was missed: a translating follower offset 10 mm on a prime circle of 10.000001 mm, whose
/// largest pressure angle lies 0.051° before the end of the heald cycle's return, had it reported
/// at 0°, 2.3e-7° too small, below its own printed points.)
pub(crate) fn extremes(sp: Span, f: impl Fn(f64) -> [f64; 3]) -> Extremes {
    let mut ext = Extremes::empty();
    let fa = f(sp.a);
    let fb = f(sp.b);
    ext.push(sp.a, fa[0]);
    ext.push(sp.b, fb[0]);
    if sp.dwell {
        return ext;
    }
    let n = sp.grid.max(2);
    let h = (sp.b - sp.a) / n as f64;
    let grid: Vec<(f64, [f64; 3])> = (0..=n)
        .map(|i| match i {
            0 => (sp.a, fa),
            i if i == n => (sp.b, fb),
            i => {
                let t = sp.a + i as f64 * h;
                (t, f(t))
            }
        })
        .collect();
    // The grid is sized to the law (its degree and sine half-periods); the geometry can be far
    // sharper. Where a cam is steep (ds/dψ ≫ the radius: a 40 mm rise over 0.01°) the curvature of
    // the pitch curve peaks within 3e-4 of the motion's end, between grid points, next to a lower
    // peak that the grid does see. An interval is halved while q″ at its ends does not account for
    // the change of q′ across it (trapezoid rule off by more than 1/10 of the change's size): a
    // resolved interval costs no evaluation, an unresolved one is refined until it is resolved.
    let mut pts: Vec<(f64, [f64; 3])> = Vec::with_capacity(grid.len());
    let mut budget = 64 * n;
    let resolved = |a: &(f64, [f64; 3]), b: &(f64, [f64; 3])| {
        let dq = b.1[1] - a.1[1];
        let trapezoid = 0.5 * (a.1[2] + b.1[2]) * (b.0 - a.0);
        let size = dq.abs().max(0.5 * (a.1[2].abs() + b.1[2].abs()) * (b.0 - a.0));
        (dq - trapezoid).abs() <= 0.1 * size || size == 0.0
    };
    // Scratch reused across the grid's intervals (most are resolved at once and push nothing).
    let (mut stack, mut inner) = (Vec::new(), Vec::new());
    for w in grid.windows(2) {
        pts.push(w[0]);
        stack.push((w[0], w[1], 0u32));
        while let Some((a, b, depth)) = stack.pop() {
            if depth >= 40 || budget == 0 || resolved(&a, &b) {
                inner.push(b);
                continue;
            }
            budget -= 1;
            let m = 0.5 * (a.0 + b.0);
            let mid = (m, f(m));
            // Right half first on the stack's bottom: the left half is taken (and pushed) first.
            stack.push((mid, b, depth + 1));
            stack.push((a, mid, depth + 1));
        }
        // `inner` holds the right ends of the accepted intervals in order, the last being w[1].
        inner.pop();
        pts.append(&mut inner);
    }
    pts.push(grid[grid.len() - 1]);
    let scale = pts.iter().fold(0.0f64, |m, p| m.max(p.1[1].abs()));
    let vanishes = |d: f64| d.abs() <= 1e-9 * scale;
    let sign = |d: f64| {
        if d > 0.0 {
            1
        } else if d < 0.0 {
            -1
        } else {
            0
        }
    };
    // A point between `end` and `other`, as close to `end` as needed, where q′ has the sign `want`.
    let inside = |end: f64, other: f64, want: i32| {
        (1..=40).map(|k| end + (other - end) * 0.5f64.powi(k)).find(|&t| sign(f(t)[1]) == want)
    };
    for w in pts.windows(2) {
        let ((t0, v0), (t1, v1)) = (w[0], w[1]);
        ext.push(t1, v1[0]);
        let at_start = t0 == sp.a && vanishes(v0[1]);
        let at_end = t1 == sp.b && vanishes(v1[1]);
        let s0 = if at_start { sign(v0[2]) } else { sign(v0[1]) };
        let s1 = if at_end { -sign(v1[2]) } else { sign(v1[1]) };
        if s0 == 0 || s1 == 0 || s0 == s1 {
            continue;
        }
        let lo = if at_start { inside(t0, t1, s0) } else { Some(t0) };
        let hi = if at_end { inside(t1, t0, s1) } else { Some(t1) };
        if let (Some(lo), Some(hi)) = (lo, hi) {
            let t = loomkin_numeric::refine_root(lo, hi, s0 < 0, |t| {
                let v = f(t);
                (v[1], v[2])
            });
            ext.push(t, f(t)[0]);
        }
    }
    ext
}
