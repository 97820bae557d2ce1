//! Brent's method for a maximum: parabolic steps where the function is smooth, golden-section
//! steps where it is not, the best point evaluated kept.

use crate::Max;

/// (3 − √5)/2, the golden section of a bracket from its nearer end.
const GOLD: f64 = 0.381_966_011_250_105_2;

/// Most steps; never reached on a bracket that narrows (each golden step takes 38 % off).
const MAX_STEPS: usize = 200;

fn finite_or_neg_inf(v: f64) -> f64 {
    if v.is_nan() { f64::NEG_INFINITY } else { v }
}

/// The largest value of `f` on the bracket `[a, b]` whose end values are known (`(a, f(a))` and
/// `(b, f(b))`, e.g. a grid's, not evaluated again), closed to a width of `4·tol` where `tol` is
/// `xtol` or 4 ulps of the bracket's ends ([`crate::ulps`]), whichever is larger; the best point
/// evaluated is returned, the ends included, so a maximum at a jump or at an end of the bracket is
/// found too. A NaN counts as −∞.
///
/// Brent's method: a parabola through the three best points proposes the next probe when it
/// falls well inside the bracket and shrinks the step, a golden-section step is taken otherwise.
/// On a smooth maximum the parabolic steps converge superlinearly; on a kink or a jump it falls
/// back to the golden-section steps and their guaranteed reduction. No probe is closer than `tol`
/// to another or to an end, so the search ends at any magnitude: the ulps floor keeps `tol`
/// above the spacing of the doubles.
///
/// **Early end.** At the first parabolic step below `s/1000`, `s = 4·10⁸·tol` (for the dobby's
/// `tol` of 2.5·10⁻¹⁴ rad: below 10⁻⁸ rad, `s` = 10⁻⁵ rad), the function is probed at `±s` and
/// `±2s` from the best interior point x. If it falls off quadratically on both sides (the drop at
/// `2s` more than three times the drop at `s`; a kink gives twice) the maximum is taken as found:
/// the four drops fit `f* − c(t − t*)²` and give the vertex `t*` (the two one-sided drops differ
/// by `4c·s·(x − t*)`), and where the value at x falls short of `f*` by more than its own rounding
/// (`c(x − t*)² > ε|f(x)|`) the vertex is evaluated too. The value is then exact to rounding;
/// before this end, parabolic steps this small meet values that are flat to rounding, and the
/// search went on by golden steps without changing the value beyond its last bits. At a kink, or
/// a maximum at an end of the bracket, the search goes on to the tolerance.
///
/// **Flat bracket.** When both ends and the first two probes (at 0.38 and about 0.62 of the
/// bracket) have the same value to the bit, the function is taken as constant there (a dwell) and
/// the left end returned: what the full search returns on a constant function (only a strictly
/// larger value replaces the best point), in two evaluations instead of ~50.
pub fn brent_max_from(mut f: impl FnMut(f64) -> f64, (a, fa): (f64, f64), (b, fb): (f64, f64), xtol: f64) -> Max {
    let mut best = Max { at: a, value: f64::NEG_INFINITY };
    let mut keep = |x: f64, v: f64| {
        if v > best.value {
            best = Max { at: x, value: v };
        }
        // Minimise the negated value; a value that could not be computed is the worst.
        -v
    };
    let ((mut lo, flo), (mut hi, fhi)) = if a <= b { ((a, fa), (b, fb)) } else { ((b, fb), (a, fa)) };
    let tol = xtol.max(crate::ulps(lo, hi, 4.0));
    // The early end's probe offset and the parabolic step that triggers it.
    let (probe, trigger) = (4e8 * tol, 4e5 * tol);
    keep(lo, finite_or_neg_inf(flo));
    keep(hi, finite_or_neg_inf(fhi));
    // x: best interior point so far, w: second best, v: the previous w.
    let mut x = lo + GOLD * (hi - lo);
    let mut fx = keep(x, finite_or_neg_inf(f(x)));
    let (mut w, mut fw, mut v, mut fv) = (x, fx, x, fx);
    // d: the last step, e: the step before it.
    let (mut d, mut e) = (0.0f64, 0.0f64);
    let mut checked = false;
    // Interior probes so far, while every value equals both ends'.
    let level = (flo == fhi && flo.is_finite()).then_some(-flo);
    let mut flat = usize::from(level == Some(fx));
    for _ in 0..MAX_STEPS {
        if flat >= 2 {
            break;
        }
        let m = 0.5 * (lo + hi);
        if hi - lo <= 4.0 * tol {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol {
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let last = e;
            if p.abs() < (0.5 * q * last).abs() && p > q * (lo - x) && p < q * (hi - x) {
                e = d;
                d = p / q;
                let u = x + d;
                // Not closer than the tolerance to an end of the bracket.
                if u - lo < 2.0 * tol || hi - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < m { hi - x } else { lo - x };
            d = GOLD * e;
        }
        if parabolic && d.abs() <= trigger && !checked {
            checked = true;
            let s = probe;
            let mut drop = |t: f64| -fx - finite_or_neg_inf(f(t));
            // The drops at s and 2s on one side, if the fall-off there is quadratic.
            let mut side = |sign: f64| {
                let d1 = drop(x + sign * s);
                (d1 >= 0.0).then(|| (d1, drop(x + sign * 2.0 * s))).filter(|&(d1, d2)| d2 > 3.0 * d1).map(|p| p.0)
            };
            if let Some(left) = side(-1.0)
                && let Some(right) = side(1.0)
            {
                // f(x ± s) = f* − c(x ± s − t*)²: right + left = 2cs², right − left = 4cs(x − t*).
                let sum = right + left;
                let offset = s * (right - left) / (2.0 * sum);
                let deficit = sum / (2.0 * s * s) * offset * offset;
                let vertex = x - offset;
                if deficit > f64::EPSILON * fx.abs() && vertex > lo && vertex < hi {
                    keep(vertex, finite_or_neg_inf(f(vertex)));
                }
                break;
            }
        }
        let u = if d.abs() >= tol { x + d } else { x + tol.copysign(d) };
        let fu = keep(u, finite_or_neg_inf(f(u)));
        flat = if flat > 0 && level == Some(fu) { flat + 1 } else { 0 };
        if fu <= fx {
            if u < x {
                hi = x;
            } else {
                lo = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn brent(f: &dyn Fn(f64) -> f64, a: f64, b: f64) -> Max {
        brent_max_from(f, (a, f(a)), (b, f(b)), 2.5e-14)
    }

    #[test]
    fn a_smooth_maximum_a_kink_and_an_end() {
        let e = brent(&|x: f64| -(x - 0.3).powi(2) + 2.0, 0.0, 1.0);
        assert!((e.at - 0.3).abs() < 1e-7 && (e.value - 2.0).abs() < 1e-14, "{e:?}");
        let e = brent(&|x: f64| 1.0 - (x - 0.123_456_789).abs(), 0.0, 1.0);
        assert!((e.value - 1.0).abs() < 1e-12, "{e:?}");
        let e = brent(&|x: f64| x, 0.0, 1.0);
        assert_eq!(e.value, 1.0);
    }

    #[test]
    fn a_smooth_maximum_converges_fast_and_a_flat_bracket_costs_two() {
        let calls = std::cell::Cell::new(0);
        let g = |x: f64| {
            calls.set(calls.get() + 1);
            40.0 * (3.0 * (x - 1.234_567)).cos() + 7.0
        };
        let h = 0.25f64.to_radians();
        // A smooth maximum in a bracket of 0.5° costs far fewer evaluations than golden-section
        // search (52 down to 1e-13 rad).
        let e = brent(&g, 1.234 - h, 1.234 + h);
        assert!((e.value - 47.0).abs() < 1e-13 && (e.at - 1.234_567).abs() < 1e-7, "{e:?}");
        assert!(calls.get() <= 16, "{} evaluations", calls.get());
        let count = |v: f64| {
            calls.set(calls.get() + 1);
            v
        };
        // A constant bracket costs two evaluations and returns its left end, as the full search
        // did.
        calls.set(0);
        let e = brent_max_from(|_| count(5.0), (1.0, 5.0), (2.0, 5.0), 2.5e-14);
        assert_eq!((e.value, e.at, calls.get()), (5.0, 1.0, 2));
        // Ends that differ in the last bit: the full search, which finds the maximum at the end.
        calls.set(0);
        let e = brent_max_from(|_| count(5.0), (1.0, 5.0), (2.0, 5.0 + 1e-15), 2.5e-14);
        assert_eq!((e.value, e.at), (5.0 + 1e-15, 2.0));
        assert!(calls.get() > 20, "{}", calls.get());
        // A kink in the same bracket is still located to 1e-12.
        let e = brent(&|x: f64| 1.0 - (x - 1.234_567_891_2).abs(), 1.234 - h, 1.234 + h);
        assert!((e.value - 1.0).abs() < 1e-12, "{e:?}");
    }

    #[test]
    fn a_tolerance_below_the_ulps_still_ends() {
        // At 10⁹ the doubles are 1.2e-7 apart: a tolerance of 1e-20 is raised to 4 ulps.
        let calls = std::cell::Cell::new(0);
        let f = |x: f64| {
            calls.set(calls.get() + 1);
            1.0 - (x - 1e9 - 0.37).abs()
        };
        let e = brent_max_from(f, (1e9, f(1e9)), (1e9 + 1.0, f(1e9 + 1.0)), 1e-20);
        assert!((e.at - (1e9 + 0.37)).abs() < 1e-6, "{e:?}");
        assert!(calls.get() < MAX_STEPS, "{} evaluations", calls.get());
    }
}
