//! Exact extremes of a smooth function on an interval: grid brackets of the derivative's sign
//! changes, refined by Newton inside the bracket ([`loomkin_numeric::refine_root`]).

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
                let r = loomkin_numeric::refine_root_from(lo, t, start, prev[i][1] < 0.0, |x| {
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
