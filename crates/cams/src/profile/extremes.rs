//! Extremes of a smooth quantity over a span of cam angle, located exactly: sign changes of the
//! exact derivative bracketed on a grid and refined by `loomkin_laws::refine_root`.

use super::lift::Span;

/// The least and greatest value of a quantity and where (cam angle, rad).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremes {
    /// Least value.
    pub min: f64,
    /// Where it is least (rad).
    pub min_at: f64,
    /// Greatest value.
    pub max: f64,
    /// Where it is greatest (rad).
    pub max_at: f64,
}

impl Extremes {
    /// No values yet.
    pub fn empty() -> Self {
        Self { min: f64::INFINITY, min_at: f64::NAN, max: f64::NEG_INFINITY, max_at: f64::NAN }
    }

    /// Takes a value into account.
    pub fn push(&mut self, at: f64, v: f64) {
        if v < self.min {
            (self.min, self.min_at) = (v, at);
        }
        if v > self.max {
            (self.max, self.max_at) = (v, at);
        }
    }

    /// Takes another set of extremes into account.
    pub fn merge(&mut self, o: Extremes) {
        self.push(o.min_at, o.min);
        self.push(o.max_at, o.max);
    }
}

/// The extremes over a span of `f`, which returns `[q, q′, q″]` at a cam angle: the span's ends and
/// every root of `q′` (bracketed on the span's grid, refined by Newton inside the bracket). On a
/// dwell every quantity of the geometry is constant and only the ends are taken.
pub(crate) fn extremes(sp: Span, f: impl Fn(f64) -> [f64; 3]) -> Extremes {
    let mut ext = Extremes::empty();
    let fa = f(sp.a);
    let fb = f(sp.b);
    ext.push(sp.a, fa[0]);
    ext.push(sp.b, fb[0]);
    if sp.dwell {
        return ext;
    }
    let n = sp.grid.max(2);
    let h = (sp.b - sp.a) / n as f64;
    let (mut t0, mut d0) = (sp.a, fa[1]);
    for i in 1..=n {
        let t1 = if i == n { sp.b } else { sp.a + i as f64 * h };
        let f1 = if i == n { fb } else { f(t1) };
        ext.push(t1, f1[0]);
        let d1 = f1[1];
        if d0 != 0.0 && d1 != 0.0 && d0.signum() != d1.signum() {
            let t = loomkin_laws::refine_root(t0, t1, d0 < 0.0, |t| {
                let v = f(t);
                (v[1], v[2])
            });
            ext.push(t, f(t)[0]);
        }
        (t0, d0) = (t1, d1);
    }
    ext
}
