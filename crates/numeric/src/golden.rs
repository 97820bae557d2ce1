//! Golden-section search for a maximum, keeping the best point evaluated.

use std::convert::Infallible;

/// A maximum found by a search: where, and the value there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Max {
    /// Where the largest value was found.
    pub at: f64,
    /// The largest value found (−∞ when no value was above −∞, e.g. every value NaN).
    pub value: f64,
}

/// How narrow [`golden_max`] closes its bracket, relative to the bracket it was given: 10⁻¹²
/// (58 golden steps). The value at a smooth maximum is then exact to rounding: it falls off as the
/// square of the distance, (10⁻¹²)² of the bracket's curvature.
pub const GOLDEN_REL: f64 = 1e-12;

/// 1/φ = (√5 − 1)/2 to 16 digits (one ulp below the nearest double; the golden steps of
/// loomkin-dynamics were taken with this value, and a search's reduction ratio does not notice).
const INV_PHI: f64 = 0.618_033_988_749_894_8;

/// Most golden steps: 0.618²⁰⁰ ≈ 10⁻⁴² of the bracket, never reached before [`GOLDEN_REL`] or the
/// ulps; a guard only.
const MAX_ROUNDS: usize = 200;

/// The largest value of `f` on `[a, b]` by golden-section search, and where it is: the best point
/// evaluated (a search that stepped past the maximum in rounding noise still reports the best
/// value it saw). The bracket is closed to [`GOLDEN_REL`] of its first width or to 4 ulps of its
/// ends ([`crate::ulps`]), whichever is wider, so the search ends at any magnitude of `a`, `b`
/// after at most 58 steps (60 evaluations). The ends themselves are not evaluated.
///
/// For a function with one maximum in the bracket this is that maximum; with several, one of them.
pub fn golden_max(mut f: impl FnMut(f64) -> f64, a: f64, b: f64) -> Max {
    match try_golden_max(|x| Ok::<_, Infallible>(f(x)), a, b, None) {
        Ok(m) => m,
    }
}

/// [`golden_max`] with a point `start = (x, f(x))` already known (a grid point), kept as a
/// candidate: a value there at least as large as every probe is the answer.
pub fn golden_max_from(mut f: impl FnMut(f64) -> f64, a: f64, b: f64, start: (f64, f64)) -> Max {
    match try_golden_max(|x| Ok::<_, Infallible>(f(x)), a, b, Some(start)) {
        Ok(m) => m,
    }
}

/// [`golden_max_from`] (or [`golden_max`] when `start` is `None`) with a function that can fail:
/// the first error ends the search and is returned.
pub fn try_golden_max<E>(
    mut f: impl FnMut(f64) -> Result<f64, E>,
    mut a: f64,
    mut b: f64,
    start: Option<(f64, f64)>,
) -> Result<Max, E> {
    let tol = (GOLDEN_REL * (b - a).abs()).max(crate::ulps(a, b, 4.0));
    let mut best = start.map_or(Max { at: a, value: f64::NEG_INFINITY }, |(at, value)| Max { at, value });
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (f(c)?, f(d)?);
    for (at, value) in [(c, fc), (d, fd)] {
        if value > best.value {
            best = Max { at, value };
        }
    }
    let mut rounds = 0;
    while (b - a).abs() > tol && rounds < MAX_ROUNDS {
        rounds += 1;
        if fc >= fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - INV_PHI * (b - a);
            fc = f(c)?;
            if fc > best.value {
                best = Max { at: c, value: fc };
            }
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + INV_PHI * (b - a);
            fd = f(d)?;
            if fd > best.value {
                best = Max { at: d, value: fd };
            }
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inv_phi_is_the_golden_ratio_s_inverse() {
        assert_eq!(INV_PHI.next_up(), (5f64.sqrt() - 1.0) / 2.0);
    }

    #[test]
    fn a_narrow_bracket_far_from_zero_ends() {
        // 5·10⁵ wide 10⁻² (the loom's torque peak past pick 1,389): 10⁻¹⁴ is below the ulps there.
        let calls = std::cell::Cell::new(0);
        let m = golden_max(
            |x| {
                calls.set(calls.get() + 1);
                -(x - 500_000.003).powi(2)
            },
            499_999.99,
            500_000.01,
        );
        assert!((m.at - 500_000.003).abs() < 1e-9, "{m:?}");
        assert!(calls.get() <= 60, "{} evaluations", calls.get());
    }

    #[test]
    fn start_is_kept_and_errors_end_the_search() {
        let m = golden_max_from(|x| x, 0.0, 1.0, (1.0, 1.0));
        assert_eq!(m, Max { at: 1.0, value: 1.0 });
        let r = try_golden_max(|x| if x < 0.5 { Ok(x) } else { Err(x) }, 0.0, 1.0, None);
        assert!(r.is_err());
        let nan = golden_max(|_| f64::NAN, 0.0, 1.0);
        assert_eq!(nan.value, f64::NEG_INFINITY);
    }
}
