//! The maximum of a function known by its values only: a grid's local maxima, each refined.

use crate::{Max, golden_max_from};

/// The largest value of `f` on `[lo, hi]` and where it is: `f` on a grid of `n` intervals (at
/// least 2), then every local maximum of the grid (the ends included) refined by golden-section
/// search ([`golden_max_from`]) in its two neighbouring intervals. So the result is the
/// function's maximum, not the grid's, whenever each peak is resolved by the grid (one peak per
/// bracket); a finer grid only finds the same peaks.
///
/// A plateau of equal grid values is refined once, from its first point: on a flat stretch (a
/// narrow band, where neighbouring values round to the same number) every point is a local
/// maximum, and each search costs dozens of evaluations.
pub fn scan_max(lo: f64, hi: f64, n: usize, f: impl Fn(f64) -> f64) -> Max {
    let n = n.max(2);
    let x = |j: usize| if j == n { hi } else { lo + (hi - lo) * j as f64 / n as f64 };
    let v: Vec<f64> = (0..=n).map(|j| f(x(j))).collect();
    let mut best = Max { at: lo, value: f64::NEG_INFINITY };
    for j in 0..=n {
        let left = if j > 0 { v[j - 1] } else { f64::NEG_INFINITY };
        let right = if j < n { v[j + 1] } else { f64::NEG_INFINITY };
        let on_plateau = j > 0 && v[j] == left;
        if v[j] >= left && v[j] >= right && !on_plateau {
            let (a, b) = (x(j.saturating_sub(1)), x((j + 1).min(n)));
            let m = golden_max_from(&f, a, b, (x(j), v[j]));
            if m.value > best.value {
                best = m;
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_narrow_band_far_from_zero_ends() {
        // ±0.2 % around 300: the grid's intervals are 3e-2 wide, 1e-12 of that is below an ulp of 300.
        let m = scan_max(299.4, 300.6, 40, |x| -(x - 300.1).powi(2));
        assert!((m.at - 300.1).abs() < 1e-6 && m.value <= 0.0, "{m:?}");
    }

    #[test]
    fn a_flat_band_is_refined_once() {
        // Every grid point of a constant is a local maximum; one search, not 41.
        let calls = std::cell::Cell::new(0);
        let m = scan_max(1.0, 2.0, 40, |_| {
            calls.set(calls.get() + 1);
            3.0
        });
        assert_eq!((m.value, m.at), (3.0, 1.0));
        assert!(calls.get() < 41 + 80, "{} evaluations", calls.get());
    }

    #[test]
    fn the_higher_of_two_peaks_between_grid_points() {
        let f = |x: f64| (-(x - 1.0).powi(2) * 50.0).exp() + 2.0 * (-(x - 2.37).powi(2) * 50.0).exp();
        for n in [7usize, 13, 40, 1000] {
            let m = scan_max(0.0, 3.0, n, f);
            assert!((m.value - 2.0).abs() < 1e-12 && (m.at - 2.37).abs() < 1e-6, "n = {n}: {m:?}");
        }
    }
}
