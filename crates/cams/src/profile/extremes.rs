//! A span's extremes: the ends of a dwell (every quantity of the geometry is constant there), or
//! over a motion the workspace's one peak scan, [`loomkin_numeric::extremes`] (sign changes of the
//! exact derivative bracketed on the span's grid, refined where the grid does not resolve it, and
//! refined by Newton).

use super::lift::Span;
pub use loomkin_numeric::Extremes;

/// The extremes over a span of `f`, which returns `[q, q′, q″]` at a cam angle (rad).
pub(crate) fn extremes(sp: Span, f: impl Fn(f64) -> [f64; 3]) -> Extremes {
    if sp.dwell {
        let mut e = Extremes::EMPTY;
        e.take(f(sp.a)[0], sp.a);
        e.take(f(sp.b)[0], sp.b);
        return e;
    }
    loomkin_numeric::extremes(sp.a, sp.b, sp.grid, f)
}
