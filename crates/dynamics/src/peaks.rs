//! Exact extremes of a smooth function on an interval: grid brackets of the derivative's sign
//! changes, refined by Newton inside the bracket ([`loomkin_laws::refine_root`]).

/// Smallest and largest value of a function on an interval, with where they occur.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Smallest value and its location.
    pub min: (f64, f64),
    /// Largest value and its location.
    pub max: (f64, f64),
}

impl Extremes {
    /// The empty set (to be merged into).
    pub const EMPTY: Extremes = Extremes { min: (f64::INFINITY, 0.0), max: (f64::NEG_INFINITY, 0.0) };

    /// Takes a candidate value `v` at `t`.
    pub fn take(&mut self, v: f64, t: f64) {
        if v < self.min.0 {
            self.min = (v, t);
        }
        if v > self.max.0 {
            self.max = (v, t);
        }
    }

    /// Merges another set, its locations shifted by `dt`.
    pub fn merge(&mut self, o: &Extremes, dt: f64) {
        self.take(o.min.0, o.min.1 + dt);
        self.take(o.max.0, o.max.1 + dt);
    }

    /// The largest magnitude `max(|min|, |max|)` and its location.
    pub fn peak_abs(&self) -> (f64, f64) {
        if self.max.0.abs() >= self.min.0.abs() {
            (self.max.0.abs(), self.max.1)
        } else {
            (self.min.0.abs(), self.min.1)
        }
    }

    /// True when nothing was taken.
    pub fn is_empty(&self) -> bool {
        !self.max.0.is_finite()
    }
}

/// Number of grid intervals for a function on `[0, duration]` whose fastest oscillation is
/// `omega` (rad/s) and whose polynomial part has degree ≤ 7: three per half period plus six, at most 10⁵.
pub fn grid_size(duration: f64, omega: f64) -> usize {
    let n = 6.0 + 3.0 * omega * duration / std::f64::consts::PI;
    if n.is_finite() { n.min(1e5) as usize } else { 100_000 }
}

/// The largest value of a function known by its values only (no derivative), on `[lo, hi]`, and
/// where it is: the function on a grid of `n` intervals, then every local maximum of the grid
/// (the ends included) refined by golden-section search in its two neighbouring intervals down to
/// 1e-12 of the interval. So the result is the function's maximum, not the grid's, whenever each
/// peak is resolved by the grid (one peak per bracket); a finer grid only finds the same peaks.
pub fn band_max(lo: f64, hi: f64, n: usize, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let n = n.max(2);
    let x = |j: usize| if j == n { hi } else { lo + (hi - lo) * j as f64 / n as f64 };
    let v: Vec<f64> = (0..=n).map(|j| f(x(j))).collect();
    let mut best = (f64::NEG_INFINITY, lo);
    for j in 0..=n {
        let left = if j > 0 { v[j - 1] } else { f64::NEG_INFINITY };
        let right = if j < n { v[j + 1] } else { f64::NEG_INFINITY };
        // A plateau is refined once, from its first point: on a flat stretch (a narrow band, where
        // neighbouring values round to the same number) every point is a local maximum, and each
        // search costs dozens of evaluations.
        let on_plateau = j > 0 && v[j] == left;
        if v[j] >= left && v[j] >= right && !on_plateau {
            let (a, b) = (x(j.saturating_sub(1)), x((j + 1).min(n)));
            let (at, val) = golden_max(&f, a, b, (x(j), v[j]));
            if val > best.0 {
                best = (val, at);
            }
        }
    }
    best
}

/// Golden-section search for the maximum of `f` on `[a, b]`, keeping the best point seen (`start`
/// included), to 1e-12 of the interval.
fn golden_max(f: &impl Fn(f64) -> f64, mut a: f64, mut b: f64, start: (f64, f64)) -> (f64, f64) {
    const INV_PHI: f64 = 0.618_033_988_749_894_8;
    // Not below a few ulps of the ends: a narrow interval far from 0 (a band of ±0.2 % around
    // 300 rpm) cannot shrink to 1e-12 of its width, and the search would never end. Capped too.
    let ulps = 4.0 * f64::EPSILON * a.abs().max(b.abs());
    let tol = (1e-12 * (b - a).abs()).max(ulps).max(f64::MIN_POSITIVE);
    let mut rounds = 0;
    let mut best = start;
    let mut c = b - INV_PHI * (b - a);
    let mut d = a + INV_PHI * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for (p, q) in [(c, fc), (d, fd)] {
        if q > best.1 {
            best = (p, q);
        }
    }
    while (b - a).abs() > tol && rounds < 200 {
        rounds += 1;
        if fc >= fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - INV_PHI * (b - a);
            fc = f(c);
            if fc > best.1 {
                best = (c, fc);
            }
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + INV_PHI * (b - a);
            fd = f(d);
            if fd > best.1 {
                best = (d, fd);
            }
        }
    }
    best
}

/// The extremes of `f` on `[0, duration]`; `f(t)` returns `[f, f', f'']`. Candidates: both ends and
/// every root of `f'` bracketed on an `n`-interval grid and refined by Newton.
pub fn extremes(duration: f64, n: usize, f: impl Fn(f64) -> [f64; 3]) -> Extremes {
    let [e] = extremes_of(duration, n, |t| [f(t)]);
    e
}

/// The extremes of `K` functions at once on one grid (each evaluation of `f` gives all of them):
/// `f(t)[i] = [f_i, f_i', f_i'']`.
pub fn extremes_of<const K: usize>(duration: f64, n: usize, f: impl Fn(f64) -> [[f64; 3]; K]) -> [Extremes; K] {
    let mut e = [Extremes::EMPTY; K];
    let n = n.max(1);
    let h = duration / n as f64;
    let mut prev = f(0.0);
    for i in 0..K {
        e[i].take(prev[i][0], 0.0);
    }
    for step in 1..=n {
        let t = if step == n { duration } else { step as f64 * h };
        let cur = f(t);
        for i in 0..K {
            e[i].take(cur[i][0], t);
            if prev[i][1] * cur[i][1] < 0.0 {
                let lo = (t - h).max(0.0);
                // Start from the secant point of f' at the grid's two ends (within O(h²) of the root).
                let (g0, g1) = (prev[i][1], cur[i][1]);
                let start = (lo * g1 - t * g0) / (g1 - g0);
                let r = loomkin_laws::refine_root_from(lo, t, start, prev[i][1] < 0.0, |x| {
                    let d = f(x)[i];
                    (d[1], d[2])
                });
                e[i].take(f(r)[i][0], r);
            }
        }
        prev = cur;
    }
    e
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_narrow_band_far_from_zero_ends() {
        // ±0.2 % around 300: the grid's intervals are 3e-2 wide, 1e-12 of that is below an ulp of 300.
        let (val, at) = band_max(299.4, 300.6, 40, |x| -(x - 300.1).powi(2));
        assert!((at - 300.1).abs() < 1e-6 && val <= 0.0, "{at} {val}");
    }

    #[test]
    fn a_flat_band_is_refined_once() {
        // Every grid point of a constant is a local maximum; one search, not 41.
        let calls = std::cell::Cell::new(0);
        let (val, at) = band_max(1.0, 2.0, 40, |_| {
            calls.set(calls.get() + 1);
            3.0
        });
        assert_eq!((val, at), (3.0, 1.0));
        assert!(calls.get() < 41 + 80, "{} evaluations", calls.get());
    }

    use super::*;

    #[test]
    fn finds_interior_extremes_exactly() {
        // sin(3t) + 0.1 t on [0, 4]: maxima where 3cos(3t) = −0.1.
        let e = extremes(4.0, grid_size(4.0, 3.0), |t| {
            [(3.0 * t).sin() + 0.1 * t, 3.0 * (3.0 * t).cos() + 0.1, -9.0 * (3.0 * t).sin()]
        });
        let tmax = (2.0 * std::f64::consts::PI + (-0.1f64 / 3.0).acos()) / 3.0;
        let tmax = if tmax > 4.0 { tmax - 2.0 * std::f64::consts::PI / 3.0 } else { tmax };
        let vmax = (3.0 * tmax).sin() + 0.1 * tmax;
        assert!((e.max.0 - vmax).abs() < 1e-15, "{:?} vs {vmax}", e.max);
        assert!((e.max.1 - tmax).abs() < 1e-9);
    }
}
