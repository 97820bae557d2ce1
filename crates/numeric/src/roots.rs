//! Every root of a function on an interval: sign changes of the function on a grid, each refined
//! by [`crate::refine_root`], and pairs of close roots that hide inside one grid interval.

/// Roots in `[0, w]` of `g`, whose derivative is `dg`, found by sign changes on `n` sub-intervals.
/// Calls `found` with every root.
///
/// A sub-interval whose ends have the same sign can still hide a pair of close roots; where `dg`
/// changes sign inside it, the extremum of `g` there is located (bisection on `dg`) and, if `g`
/// changes sign at it, both roots are refined on either side.
pub fn grid_roots(w: f64, n: usize, gd: impl Fn(f64) -> (f64, f64), found: impl FnMut(f64)) {
    let h = w / n as f64;
    let grid = (0..=n).map(|i| {
        let t = if i == n { w } else { i as f64 * h };
        let (g, d) = gd(t);
        (t, g, d)
    });
    scan_roots(grid, &gd, found);
}

/// The scan of [`grid_roots`] over grid points `(t, g(t), g'(t))` that the caller has already evaluated
/// (ascending `t`, first at 0, last at the interval's width `w`), so one evaluation of all derivatives per
/// grid point serves several root searches.
pub fn scan_roots(
    mut grid: impl Iterator<Item = (f64, f64, f64)>,
    gd: &impl Fn(f64) -> (f64, f64),
    mut found: impl FnMut(f64),
) {
    let Some((mut t0, mut g0, mut d0)) = grid.next() else { return };
    for (t1, g1, d1) in grid {
        if g0 == 0.0 {
            found(t0);
        } else if g0.signum() != g1.signum() && g1 != 0.0 {
            found(refine(t0, t1, g0, gd));
        } else if g1 != 0.0 && d0.signum() != d1.signum() && d0 != 0.0 && d1 != 0.0 {
            // g has an extremum inside; if g changes sign there, two roots hide in this bracket.
            if let Some(tm) = sign_flip_at_extremum(t0, t1, g0, d0, d1, gd) {
                found(refine(t0, tm, g0, gd));
                found(refine(tm, t1, gd(tm).0, gd));
            }
        }
        (t0, g0, d0) = (t1, g1, d1);
    }
    if g0 == 0.0 {
        found(t0);
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
        // The extremum sits on an end of the bracket (g' there is rounding noise beside the other
        // end's, and the secant lands on it): g there is already known, of the sign of `glo`, so no
        // pair hides here. Without this, the search would creep to the end by halving.
        let at_end = |d_end: f64, d_far: f64, gap: f64| d_end.abs() <= 1e-9 * d_far.abs() && gap <= 1e-12 * width;
        if at_end(dhi, dlo, hi - t) || at_end(dlo, dhi, t - lo) {
            return None;
        }
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
    crate::refine_root(lo, hi, glo < 0.0, gd)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_close_pair_of_roots_inside_one_subinterval() {
        // g = (t − 0.5)² − 1e-6: roots 0.499 and 0.501, one sub-interval [0.25, 0.75] holds both.
        let mut got = Vec::new();
        grid_roots(1.0, 4, |t| ((t - 0.5) * (t - 0.5) - 1e-6, 2.0 * (t - 0.5)), |r| got.push(r));
        assert_eq!(got.len(), 2, "{got:?}");
        assert!((got[0] - 0.499).abs() < 1e-12 && (got[1] - 0.501).abs() < 1e-12, "{got:?}");
    }

    #[test]
    fn finds_simple_roots() {
        let mut got = Vec::new();
        grid_roots(4.0, 7, |t| (t.sin(), t.cos()), |r| got.push(r));
        assert_eq!(got.len(), 2, "{got:?}");
        assert_eq!(got[0], 0.0);
        assert!((got[1] - std::f64::consts::PI).abs() < 1e-14);
    }
}
