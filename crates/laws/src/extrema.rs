//! Locating extrema of closed-form segment functions: bracket sign changes of the derivative on a
//! grid sized to the segment's polynomial degree and sine frequency, then refine by safeguarded Newton.

use crate::Segment;
use std::f64::consts::PI;

/// Number of bracketing sub-intervals for a function on `seg` whose derivative has polynomial
/// degree at most `deg`: enough to separate the roots of a degree-`deg` polynomial plus a sinusoid.
pub(crate) fn brackets(seg: &Segment, deg: usize) -> usize {
    let osc = seg.sine().map_or(0.0, |s| (s.omega.abs() * seg.width() / PI).ceil());
    2 * (deg + 1) + 3 * osc as usize
}

/// Roots in `[0, w]` of `g`, whose derivative is `dg`, found by sign changes on `n` sub-intervals.
/// Calls `found` with every root.
pub(crate) fn roots(w: f64, n: usize, g: impl Fn(f64) -> f64, dg: impl Fn(f64) -> f64, mut found: impl FnMut(f64)) {
    let h = w / n as f64;
    let mut t0 = 0.0;
    let mut g0 = g(t0);
    for i in 1..=n {
        let t1 = if i == n { w } else { i as f64 * h };
        let g1 = g(t1);
        if g0 == 0.0 {
            found(t0);
        } else if g0.signum() != g1.signum() && g1 != 0.0 {
            found(refine(t0, t1, g0, &g, &dg));
        }
        t0 = t1;
        g0 = g1;
    }
    if g0 == 0.0 {
        found(w);
    }
}

/// Newton iteration kept inside a shrinking bracket `[lo, hi]` where `g` changes sign.
fn refine(mut lo: f64, mut hi: f64, glo: f64, g: &impl Fn(f64) -> f64, dg: &impl Fn(f64) -> f64) -> f64 {
    let neg_lo = glo < 0.0;
    let mut t = 0.5 * (lo + hi);
    for _ in 0..60 {
        let gt = g(t);
        if gt == 0.0 {
            return t;
        }
        if (gt < 0.0) == neg_lo {
            lo = t;
        } else {
            hi = t;
        }
        let d = dg(t);
        let newton = t - gt / d;
        let next = if d != 0.0 && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        if (next - t).abs() <= 1e-15 * (1.0 + t.abs()) || hi - lo <= 4.0 * f64::EPSILON * (1.0 + hi.abs()) {
            return next;
        }
        t = next;
    }
    t
}
