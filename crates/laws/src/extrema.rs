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
///
/// A sub-interval whose ends have the same sign can still hide a pair of close roots; where `dg`
/// changes sign inside it, the extremum of `g` there is located (bisection on `dg`) and, if `g`
/// changes sign at it, both roots are refined on either side.
pub(crate) fn roots(w: f64, n: usize, gd: impl Fn(f64) -> (f64, f64), mut found: impl FnMut(f64)) {
    let h = w / n as f64;
    let mut t0 = 0.0;
    let (mut g0, mut d0) = gd(t0);
    for i in 1..=n {
        let t1 = if i == n { w } else { i as f64 * h };
        let (g1, d1) = gd(t1);
        if g0 == 0.0 {
            found(t0);
        } else if g0.signum() != g1.signum() && g1 != 0.0 {
            found(refine(t0, t1, g0, &gd));
        } else if g1 != 0.0 && d0.signum() != d1.signum() && d0 != 0.0 && d1 != 0.0 {
            // g has an extremum inside; if g changes sign there, two roots hide in this bracket.
            if let Some(tm) = sign_flip_at_extremum(t0, t1, g0, d0, d1, &gd) {
                found(refine(t0, tm, g0, &gd));
                found(refine(tm, t1, gd(tm).0, &gd));
            }
        }
        (t0, g0, d0) = (t1, g1, d1);
    }
    if g0 == 0.0 {
        found(w);
    }
}

/// Looks for a point of `[lo, hi]` where `g` has the opposite sign of `glo`, walking towards the
/// extremum of `g` (the sign change of `g'`, from `dlo` to `dhi`) by Illinois regula falsi on `g'`.
/// Stops as soon as such a point is found, or when the extremum is located without one.
fn sign_flip_at_extremum(
    mut lo: f64,
    mut hi: f64,
    glo: f64,
    mut dlo: f64,
    mut dhi: f64,
    gd: &impl Fn(f64) -> (f64, f64),
) -> Option<f64> {
    let width = hi - lo;
    let mut side = 0;
    for _ in 0..100 {
        let t = if dhi != dlo { (lo * dhi - hi * dlo) / (dhi - dlo) } else { 0.5 * (lo + hi) };
        let t = if t > lo && t < hi { t } else { 0.5 * (lo + hi) };
        let (g, d) = gd(t);
        if g == 0.0 || g.signum() != glo.signum() {
            return (g != 0.0).then_some(t);
        }
        if hi - lo <= 1e-14 * width.max(f64::MIN_POSITIVE) || d == 0.0 {
            return None;
        }
        if d.signum() == dlo.signum() {
            (lo, dlo) = (t, d);
            if side == -1 {
                dhi *= 0.5;
            }
            side = -1;
        } else {
            (hi, dhi) = (t, d);
            if side == 1 {
                dlo *= 0.5;
            }
            side = 1;
        }
    }
    None
}

/// Newton iteration kept inside a shrinking bracket `[lo, hi]` where `g` changes sign.
fn refine(lo: f64, hi: f64, glo: f64, gd: &impl Fn(f64) -> (f64, f64)) -> f64 {
    refine_root(lo, hi, glo < 0.0, gd)
}

/// The root of `g` in a bracket `[lo, hi]` where `g` changes sign (`lo_negative`: `g(lo) < 0`),
/// by Newton's method kept inside the shrinking bracket (a step that would leave it is replaced by
/// bisection). `gd(t)` returns `(g(t), g'(t))`.
pub fn refine_root(mut lo: f64, mut hi: f64, lo_negative: bool, gd: impl Fn(f64) -> (f64, f64)) -> f64 {
    let mut t = 0.5 * (lo + hi);
    for _ in 0..100 {
        let (gt, d) = gd(t);
        if gt == 0.0 {
            return t;
        }
        if (gt < 0.0) == lo_negative {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - gt / d;
        let next = if d != 0.0 && newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        if (next - t).abs() <= 1e-15 * (1.0 + t.abs()) || hi - lo <= 4.0 * f64::EPSILON * (1.0 + hi.abs()) {
            return next;
        }
        t = next;
    }
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_close_pair_of_roots_inside_one_subinterval() {
        // g = (t − 0.5)² − 1e-6: roots 0.499 and 0.501, one sub-interval [0.25, 0.75] holds both.
        let mut got = Vec::new();
        roots(1.0, 4, |t| ((t - 0.5) * (t - 0.5) - 1e-6, 2.0 * (t - 0.5)), |r| got.push(r));
        assert_eq!(got.len(), 2, "{got:?}");
        assert!((got[0] - 0.499).abs() < 1e-12 && (got[1] - 0.501).abs() < 1e-12, "{got:?}");
    }

    #[test]
    fn finds_simple_roots() {
        let mut got = Vec::new();
        roots(4.0, 7, |t| (t.sin(), t.cos()), |r| got.push(r));
        assert_eq!(got.len(), 2, "{got:?}");
        assert_eq!(got[0], 0.0);
        assert!((got[1] - std::f64::consts::PI).abs() < 1e-14);
    }
}
