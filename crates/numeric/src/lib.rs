//! # loomkin-numeric — the one-dimensional searches of loomkin, written once
//!
//! Every crate of the workspace that brackets a root or a maximum and closes in on it calls this
//! crate: [`bisect`] (to adjacent doubles), [`refine_root`] (Newton kept inside a bracket),
//! [`illinois_root`] (regula falsi, no derivative needed),
//! [`golden_max`] (golden-section search keeping the best point), [`brent_max_from`] (parabolic
//! steps with golden-section fall-back), [`scan_max`] (a grid's local maxima, each refined;
//! [`periodic_scan_max`] over a period),
//! [`extremes_of`] (the least and greatest values of smooth functions known with two derivatives:
//! the derivatives' sign changes bracketed and refined) and
//! [`grid_roots`] / [`scan_roots`] (every root on an interval: sign changes of a grid, close pairs
//! inside one grid interval included, each refined); and one search in several dimensions,
//! [`compass_min`] (a compass search in a box under a constraint: the loom's stagger search).
//! Besides, [`WordMap`]: the hash map the studies key their repeated turns by (keys of 64-bit words).
//!
//! **The stop rule holds at any magnitude.** No search stops on an absolute width such as
//! `b − a ≤ 1e-10`: at an angle of 5·10⁵° the doubles are 1.2·10⁻¹⁰ apart, so such a bracket can
//! never get that narrow and the search never ends. Each search here stops when its bracket is no
//! wider than a tolerance *relative to the bracket it was given* (a fixed number of halvings or
//! golden steps, whatever the magnitude) or when it is down to a few units in the last place of
//! its ends ([`ulps`]), whichever comes first, and each has a cap on its steps besides. So the
//! number of evaluations is bounded by a constant, and the answer is as exact as the doubles
//! around it allow, at 10⁻⁹ as at 10⁹.
//!
//! ```
//! // A maximum at 10⁹ in a bracket 10⁻³ wide, and a root at 10⁻⁹.
//! let m = loomkin_numeric::golden_max(|x| -(x - 1e9 - 1e-4).powi(2), 1e9, 1e9 + 1e-3);
//! assert!((m.at - (1e9 + 1e-4)).abs() < 1e-6);
//! let r = loomkin_numeric::bisect(0.0, 1e-8, |x| x * x < 1e-18);
//! assert!((r - 1e-9).abs() <= 4.0 * f64::EPSILON * 1e-9);
//! ```
#![deny(missing_docs)]

mod bisect;
mod brent;
mod compass;
mod extremes;
mod golden;
mod linear;
mod root;
mod roots;
mod scan;
mod words;

pub use bisect::{MAX_HALVINGS, bisect, bisect_bracket, bisect_within, try_bisect_bracket, try_bisect_bracket_within};
pub use brent::brent_max_from;
pub use compass::{COMPASS_SWEEPS, compass_min};
pub use extremes::{Extremes, extremes, extremes_of};
pub use golden::{GOLDEN_REL, Max, golden_max, golden_max_from, try_golden_max};
pub use linear::{solve_cyclic_tridiagonal, solve_tridiagonal};
pub use root::{illinois_root, refine_root, refine_root_from, try_refine_root_from};
pub use roots::{grid_roots, scan_roots};
pub use scan::{GridPeak, PeriodicScan, grid_node, grid_peaks, periodic_scan_max, scan_max};
pub use words::{WordHasher, WordMap};

/// About `k` units in the last place of the larger of `|a|` and `|b|` (`k·ε·max(|a|, |b|)`, at
/// least the smallest normal double): the narrowest bracket worth refining between `a` and `b`.
/// A search whose bracket is this narrow has nothing left to find (its values are rounding noise).
pub fn ulps(a: f64, b: f64, k: f64) -> f64 {
    (k * f64::EPSILON * a.abs().max(b.abs())).max(f64::MIN_POSITIVE)
}
