//! The grid a response's extremes are searched on. The search itself is the workspace's one peak
//! scan, [`loomkin_numeric::extremes_of`] (the derivative's sign changes bracketed and refined).

pub use loomkin_numeric::Extremes;

/// Number of grid intervals for a function on `[0, duration]` whose fastest oscillation is
/// `omega` (rad/s) and whose polynomial part has degree ≤ 7: three per half period plus six, at most 10⁵.
pub fn grid_size(duration: f64, omega: f64) -> usize {
    let n = 6.0 + 3.0 * omega * duration / std::f64::consts::PI;
    if n.is_finite() { n.min(1e5) as usize } else { 100_000 }
}
