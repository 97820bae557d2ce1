//! Locating extrema of closed-form segment functions: bracket sign changes of the derivative on a
//! grid sized to the segment's polynomial degree and sine frequency, then refine by safeguarded Newton
//! ([`loomkin_numeric::grid_roots`], [`loomkin_numeric::scan_roots`]).

use crate::Segment;
use std::f64::consts::PI;

/// Number of bracketing sub-intervals for a function on `seg` whose derivative has polynomial
/// degree at most `deg`: enough to separate the roots of a degree-`deg` polynomial plus a sinusoid.
pub(crate) fn brackets(seg: &Segment, deg: usize) -> usize {
    let osc = seg.sine().map_or(0.0, |s| (s.omega.abs() * seg.width() / PI).ceil());
    2 * (deg + 1) + 3 * osc as usize
}
