//! Bisection of a boundary between two sides of a bracket, down to adjacent doubles.

use std::convert::Infallible;

/// Most halvings of a bisection. From any bracket whose ends are normal doubles of one sign, the
/// ends are adjacent after at most 64 halvings of the exponent's range plus 52 of the mantissa's;
/// a bracket reaching to 0 could halve on through the subnormals (1,074 more), which no caller
/// wants: after 200 halvings the bracket is 2⁻²⁰⁰ of its first width.
pub const MAX_HALVINGS: usize = 200;

/// The midpoint of `lo` and `hi`, finite whenever both are (`0.5·(lo + hi)` overflows near `f64::MAX`).
fn midpoint(lo: f64, hi: f64) -> f64 {
    let m = 0.5 * (lo + hi);
    if m.is_finite() { m } else { 0.5 * lo + 0.5 * hi }
}

/// The boundary between `lo` and `hi` (either may be the larger) between the points on `lo`'s
/// side (`on_lo_side(t)`) and those on `hi`'s, by bisection down to adjacent doubles (at most [`MAX_HALVINGS`]): the midpoint
/// of the last bracket. For roots with no derivative at hand (a level crossing, an inverse found
/// by its monotone forward function); with a derivative, [`crate::refine_root`] takes fewer steps.
pub fn bisect(lo: f64, hi: f64, on_lo_side: impl FnMut(f64) -> bool) -> f64 {
    let (lo, hi) = bisect_bracket(lo, hi, on_lo_side);
    midpoint(lo, hi)
}

/// [`bisect`]'s last bracket `(lo, hi)`: `lo` the last point found on `lo`'s side (or the first
/// end), `hi` the last on `hi`'s side; adjacent doubles unless the halvings ran out first.
pub fn bisect_bracket(lo: f64, hi: f64, mut on_lo_side: impl FnMut(f64) -> bool) -> (f64, f64) {
    match try_bisect_bracket(lo, hi, |t| Ok::<_, Infallible>(on_lo_side(t))) {
        Ok(b) => b,
    }
}

/// [`bisect`] that stops as soon as the bracket is no wider than `rel` of its ends' magnitudes
/// ([`try_bisect_bracket_within`]): the midpoint of the last bracket.
pub fn bisect_within(lo: f64, hi: f64, rel: f64, mut on_lo_side: impl FnMut(f64) -> bool) -> f64 {
    match try_bisect_bracket_within(lo, hi, rel, |t| Ok::<_, Infallible>(on_lo_side(t))) {
        Ok((lo, hi)) => midpoint(lo, hi),
    }
}

/// [`bisect_bracket`] with a side test that can fail (a simulation at each point): the first
/// error ends the search and is returned.
pub fn try_bisect_bracket<E>(
    lo: f64,
    hi: f64,
    on_lo_side: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64), E> {
    try_bisect_bracket_within(lo, hi, 0.0, on_lo_side)
}

/// [`try_bisect_bracket`] that stops as soon as the bracket is no wider than `rel` of the larger
/// of its ends' magnitudes (`|hi − lo| ≤ rel·max(|lo|, |hi|)`), for a side test so costly (a whole
/// simulation) that the last bits are not worth it; `rel = 0` bisects to adjacent doubles. The
/// test is relative, so it is met at any magnitude in a bounded number of halvings
/// (`log₂(1/rel)` past the first bracket's own relative width).
pub fn try_bisect_bracket_within<E>(
    mut lo: f64,
    mut hi: f64,
    rel: f64,
    mut on_lo_side: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64), E> {
    for _ in 0..MAX_HALVINGS {
        if (hi - lo).abs() <= rel * lo.abs().max(hi.abs()) {
            break;
        }
        let mid = midpoint(lo, hi);
        // The midpoint of adjacent doubles is one of them (it lies between the ends, rounded).
        if mid == lo || mid == hi {
            break;
        }
        if on_lo_side(mid)? { lo = mid } else { hi = mid }
    }
    Ok((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ends_on_adjacent_doubles() {
        let (lo, hi) = bisect_bracket(1.0, 2.0, |t| t * t < 2.0);
        assert_eq!(lo.next_up(), hi);
        assert!(lo * lo < 2.0 && hi * hi >= 2.0);
        assert_eq!(bisect(1.0, 2.0, |t| t * t < 2.0), 0.5 * (lo + hi));
    }

    #[test]
    fn a_boundary_at_zero_stops_after_the_cap() {
        let n = std::cell::Cell::new(0);
        let (lo, hi) = bisect_bracket(0.0, 1.0, |_| {
            n.set(n.get() + 1);
            false
        });
        assert_eq!(n.get(), MAX_HALVINGS);
        assert_eq!(lo, 0.0);
        assert!(hi > 0.0 && hi <= 2f64.powi(-199));
    }

    #[test]
    fn the_relative_stop_and_errors() {
        let calls = std::cell::Cell::new(0);
        let (lo, hi) = try_bisect_bracket_within(1e9, 2e9, 1e-9, |t| {
            calls.set(calls.get() + 1);
            Ok::<_, ()>(t < 1.5e9 + 0.3)
        })
        .unwrap();
        assert!(hi - lo <= 1e-9 * hi && lo < 1.5e9 + 0.3 && hi >= 1.5e9 + 0.3, "{lo} {hi}");
        // 10⁹ wide at first, ≤ 1.5 (1e-9 of ~1.5e9) after 30 halvings (10⁹/2²⁹ = 1.86, 10⁹/2³⁰ = 0.93).
        assert_eq!(calls.get(), 30);
        let side = |t: f64| {
            if t < 0.3 {
                Ok(true)
            } else if t > 0.4 {
                Ok(false)
            } else {
                Err(t)
            }
        };
        assert_eq!(try_bisect_bracket(0.0, 1.0, side), Err(0.375));
    }

    #[test]
    fn a_bracket_given_from_its_upper_end() {
        let (lo, hi) = bisect_bracket(2.0, 1.0, |t| t * t >= 2.0);
        assert_eq!(hi.next_up(), lo);
        assert!(lo * lo >= 2.0 && hi * hi < 2.0);
        let (lo, hi) = try_bisect_bracket_within(70.0, 30.0, 1e-12, |t| Ok::<_, ()>(t > 41.3)).unwrap();
        assert!(lo > 41.3 && hi <= 41.3 && lo - hi <= 1e-12 * 41.4, "{lo} {hi}");
    }

    #[test]
    fn ends_near_the_largest_double_do_not_overflow() {
        let r = bisect(f64::MAX / 2.0, f64::MAX, |t| t < 0.75 * f64::MAX);
        assert!((r / f64::MAX - 0.75).abs() < 1e-15, "{r}");
    }
}
