//! The root of a function in a bracket where it changes sign, by Newton's method kept inside the
//! bracket.

/// The root of `g` in a bracket `[lo, hi]` where `g` changes sign (`lo_negative`: `g(lo) < 0`),
/// by Newton's method kept inside the shrinking bracket. A Newton step that would leave the bracket
/// is replaced by a secant step between the bracket's ends (their values fetched once when not yet
/// known), and by bisection only when that fails too, so a root sitting on an end of the first
/// bracket is reached in a few steps rather than by halving. `gd(t)` returns `(g(t), g'(t))`.
///
/// Stops when a step moves the estimate by at most 10⁻¹⁵ of its magnitude (about 4 ulps) or the
/// bracket is down to 4 ulps of its ends, after at most 100 steps: relative tests, met at any
/// magnitude.
pub fn refine_root(lo: f64, hi: f64, lo_negative: bool, gd: impl Fn(f64) -> (f64, f64)) -> f64 {
    refine_root_from(lo, hi, 0.5 * (lo + hi), lo_negative, gd)
}

/// [`refine_root`] from a first guess `start` inside `[lo, hi]` (e.g. the secant point of values the
/// caller already has), which saves the steps from the bracket's middle.
pub fn refine_root_from(lo: f64, hi: f64, start: f64, lo_negative: bool, gd: impl Fn(f64) -> (f64, f64)) -> f64 {
    match try_refine_root_from::<std::convert::Infallible>(lo, hi, start, lo_negative, |t| Ok(gd(t))) {
        Ok(t) => t,
        Err(never) => match never {},
    }
}

/// [`refine_root_from`] of a function whose evaluation can fail (the first error is returned).
pub fn try_refine_root_from<E>(
    mut lo: f64,
    mut hi: f64,
    start: f64,
    lo_negative: bool,
    mut gd: impl FnMut(f64) -> Result<(f64, f64), E>,
) -> Result<f64, E> {
    let (mut g_lo, mut g_hi): (Option<f64>, Option<f64>) = (None, None);
    let mut t = if start > lo && start < hi { start } else { 0.5 * (lo + hi) };
    for _ in 0..100 {
        let (gt, d) = gd(t)?;
        if gt == 0.0 {
            return Ok(t);
        }
        if (gt < 0.0) == lo_negative {
            (lo, g_lo) = (t, Some(gt));
        } else {
            (hi, g_hi) = (t, Some(gt));
        }
        let newton = t - gt / d;
        let next = if d != 0.0 && newton > lo && newton < hi {
            newton
        } else {
            let gl = match g_lo {
                Some(g) => g,
                None => *g_lo.insert(gd(lo)?.0),
            };
            let gh = match g_hi {
                Some(g) => g,
                None => *g_hi.insert(gd(hi)?.0),
            };
            if gl == 0.0 || gh == 0.0 {
                return Ok(if gl == 0.0 { lo } else { hi });
            }
            let secant = (lo * gh - hi * gl) / (gh - gl);
            if secant > lo && secant < hi { secant } else { 0.5 * (lo + hi) }
        };
        if (next - t).abs() <= 1e-15 * t.abs() || hi - lo <= crate::ulps(lo, hi, 4.0) {
            return Ok(next);
        }
        t = next;
    }
    Ok(t)
}

/// A root of `d` in `[a, b]` where `d(a) = da` and `d(b) = db` have opposite signs, without its
/// derivative: regula falsi with the Illinois modification (superlinear, always bracketed), until
/// a step is below 1e-14 of the first bracket plus 4 ulps of its ends (met at any magnitude), after
/// at most 100 steps.
pub fn illinois_root(mut a: f64, mut b: f64, mut da: f64, mut db: f64, d: impl Fn(f64) -> f64) -> f64 {
    let tol = 1e-14 * (b - a).abs() + 4.0 * f64::EPSILON * a.abs().max(b.abs());
    let mut side = 0i8;
    let mut prev = a;
    for _ in 0..100 {
        let c = (a * db - b * da) / (db - da);
        let c = if c > a.min(b) && c < a.max(b) { c } else { 0.5 * (a + b) };
        let dc = d(c);
        if dc == 0.0 || (c - prev).abs() <= tol {
            return c;
        }
        prev = c;
        if (dc < 0.0) == (db < 0.0) {
            b = c;
            db = dc;
            if side == -1 {
                da *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            da = dc;
            if side == 1 {
                db *= 0.5;
            }
            side = 1;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_root_on_the_end_of_its_bracket_takes_few_steps() {
        // sin(2π(t − 0.5)) on [0.5, 0.625]: the root is the bracket's end (up to rounding), where
        // Newton from the right overshoots out of the bracket at every step.
        let calls = std::cell::Cell::new(0);
        let gd = |t: f64| {
            calls.set(calls.get() + 1);
            let w = 2.0 * std::f64::consts::PI;
            ((w * (t - 0.5)).sin(), w * (w * (t - 0.5)).cos())
        };
        let r = refine_root(0.5, 0.625, true, gd);
        assert!((r - 0.5).abs() < 1e-15, "{r}");
        assert!(calls.get() <= 10, "{} evaluations", calls.get());
    }

    #[test]
    fn illinois_on_a_steep_exponential() {
        let f = |t: f64| (20.0 * t).exp() - 2.0;
        // To its stop: a step of at most 1e-14 of the bracket (superlinear, so the error is below it).
        let r = illinois_root(0.0, 1.0, f(0.0), f(1.0), f);
        assert!((r - 2f64.ln() / 20.0).abs() < 1e-14, "{r}");
    }

    #[test]
    fn a_root_at_zero_ends() {
        // Both relative tests shrink with the root; the root itself (g = 0) ends the search.
        let r = refine_root(-1.0, 2.0, true, |t| (t * (1.0 + t * t), 1.0 + 3.0 * t * t));
        assert!(r.abs() < 1e-300, "{r}");
    }
}
