//! Smoothness of a law at its joints and at its ends against the adjoining dwells, and the one rule
//! that decides whether a derivative jumps at a joint ([`DerivativeScale`]), used for laws, cycles,
//! compensation and cam tables alike.

use crate::{Kinematics, Law};
use serde::Serialize;

/// Relative tolerance of the continuity judgement: a derivative of order `k` jumps at a joint when
/// its two sides differ by more than `CONTINUITY_TOL` times its scale, the peak `|d_k|` of the
/// motion it belongs to (see [`DerivativeScale`]), plus the rounding of the two evaluations.
///
/// Why 1e-9: the two sides of a joint that is continuous by construction differ by rounding, at
/// most ~1e-13 of the peak (Horner on degree ≤ 7 in local coordinates, a few ulps of the terms,
/// which are at most ~500 times the peak for the catalogue's polynomials); a joint's place is
/// rounded to an ulp of its position, which moves a side by `ε/w` of the peak for a segment of
/// width `w` (2.2e-10 at the narrowest catalogue ramp, `w` = 1e-6; narrower segments are covered
/// by the rounding term). So rounding stays well below the tolerance, and a real jump of 1e-6 of
/// the peak (far below anything a machine feels) is a thousand times above it and reported.
pub const CONTINUITY_TOL: f64 = 1e-9;

/// Points per piece (intervals) at which [`DerivativeScale::of_piece`] samples the peaks.
pub const SCALE_SAMPLES: usize = 32;

/// The scale of each derivative of a motion (a law, or one segment of a cycle in time), against
/// which the continuity judgement measures a jump: `peak[k]` is the largest `|d_k|` over the
/// motion, sampled at both ends and [`SCALE_SAMPLES`] − 1 inner points of every piece.
///
/// The sampled peak is within a few per cent of the exact one for the polynomials (degree ≤ 7) and
/// sinusoids laws are made of; it only sets the size of the tolerance, so that closeness is all it
/// needs. A jump at a joint between two motions (a law against a dwell, a return straight after a
/// rise) is judged against the larger of the two scales ([`DerivativeScale::max`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DerivativeScale<const N: usize> {
    /// Peak `|d_k|` for `k = 0 … N−1` (0 = position).
    pub peak: [f64; N],
}

impl<const N: usize> Default for DerivativeScale<N> {
    fn default() -> Self {
        Self { peak: [0.0; N] }
    }
}

impl<const N: usize> DerivativeScale<N> {
    /// The sampled peaks of one piece on `[0, width]`, `eval(t)` giving `d_0 … d_{N−1}` at local `t`.
    pub fn of_piece(width: f64, eval: impl Fn(f64) -> [f64; N]) -> Self {
        let mut peak = [0.0f64; N];
        for i in 0..=SCALE_SAMPLES {
            // The last point is the width itself (the end as the joint sees it).
            let t = if i == SCALE_SAMPLES { width } else { width * i as f64 / SCALE_SAMPLES as f64 };
            let d = eval(t);
            for k in 0..N {
                peak[k] = peak[k].max(d[k].abs());
            }
        }
        Self { peak }
    }

    /// The larger scale, order by order (of two pieces of one motion, or of two motions at a joint).
    pub fn max(self, other: Self) -> Self {
        Self { peak: std::array::from_fn(|k| self.peak[k].max(other.peak[k])) }
    }

    /// The largest difference of the two sides of order `k` that is no jump: `CONTINUITY_TOL` times
    /// the scale plus `rounding` (a bound on the rounding of the two sides' evaluation, given by the
    /// caller, who knows how they were evaluated).
    pub fn tolerance(&self, k: usize, rounding: f64) -> f64 {
        CONTINUITY_TOL * self.peak[k] + rounding
    }

    /// Whether the derivative of order `k` jumps from `left` to `right`.
    pub fn jumps(&self, k: usize, left: f64, right: f64, rounding: f64) -> bool {
        (right - left).abs() > self.tolerance(k, rounding)
    }

    /// The lowest order that jumps from `left` to `right` (`None`: all `N` are continuous).
    pub fn first_jump(&self, left: &[f64; N], right: &[f64; N], rounding: &[f64; N]) -> Option<usize> {
        (0..N).find(|&k| self.jumps(k, left[k], right[k], rounding[k]))
    }
}

/// The jumps of s, v, a, j at one point (right value minus left value).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Joint {
    /// Position of the joint (0 and 1 for the ends against the dwells).
    pub x: f64,
    /// Index of the segment on the left (`None` for the dwell before the rise).
    pub left_segment: Option<usize>,
    /// Jump in displacement.
    pub ds: f64,
    /// Jump in velocity.
    pub dv: f64,
    /// Jump in acceleration.
    pub da: f64,
    /// Jump in jerk.
    pub dj: f64,
    /// Highest derivative order up to which the law is continuous here: −1 (s jumps), 0 (C0: s
    /// continuous), 1 (C1: s, v), 2 (C2: s, v, a), 3 (s, v, a, j).
    pub continuous_up_to: i32,
}

impl Joint {
    /// Judged by [`DerivativeScale::first_jump`] against the law's `scale`. `terms`: the magnitudes
    /// of the terms that make up s, v, a, j and the snap on either side ([`crate::Segment`]'s
    /// evaluation rounds to a few ulps of them). The rounding allowed for order k is 32ε times its
    /// terms plus 8ε·x times the next order's terms: a joint sits at a rounded sum of widths, so
    /// each side is evaluated up to an ulp of x off its shape's end, which matters where a segment
    /// is narrow (half-cosine ramps of width 1e-8 move `a` by 1e-8 of its peak that way).
    /// (32ε bounds Horner's rounding on degree ≤ 7 for the two sides together.)
    fn new(
        x: f64,
        left_segment: Option<usize>,
        left: Kinematics,
        right: Kinematics,
        scale: &Scale4,
        terms: [f64; 5],
    ) -> Self {
        let (l, r) = ([left.s, left.v, left.a, left.j], [right.s, right.v, right.a, right.j]);
        let rounding: [f64; 4] = std::array::from_fn(|k| joint_rounding(x, &terms, k));
        let continuous_up_to = scale.first_jump(&l, &r, &rounding).map_or(3, |k| k as i32 - 1);
        let d: [f64; 4] = std::array::from_fn(|k| r[k] - l[k]);
        Self { x, left_segment, ds: d[0], dv: d[1], da: d[2], dj: d[3], continuous_up_to }
    }

    /// Whether s, v, a, j are each continuous here.
    pub fn flags(&self) -> [bool; 4] {
        std::array::from_fn(|k| (k as i32) <= self.continuous_up_to)
    }
}

type Scale4 = DerivativeScale<4>;

/// The rounding allowed for order `k` at a law's joint at `x`, `terms` the magnitudes of the terms
/// of orders 0…4 on the two sides ([`Joint::new`] says why).
pub(crate) fn joint_rounding(x: f64, terms: &[f64; 5], k: usize) -> f64 {
    f64::EPSILON * (32.0 * terms[k] + 8.0 * x.abs() * terms[k + 1])
}

/// The scale of s, v, a, j and the snap over `segments` (a law's, [`Law::derivative_scale`]).
pub(crate) fn segments_scale(segments: &[crate::Segment]) -> DerivativeScale<5> {
    segments.iter().fold(DerivativeScale::default(), |acc, g| {
        acc.max(DerivativeScale::of_piece(g.width(), |t| {
            let d = g.derivs_local(t);
            [d[0], d[1], d[2], d[3], d[4]]
        }))
    })
}

/// The smoothness report of a law.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Continuity {
    /// At x = 0 against a dwell at s = 0.
    pub start: Joint,
    /// At each joint between segments.
    pub joints: Vec<Joint>,
    /// At x = 1 against a dwell at s = 1.
    pub end: Joint,
    /// The smallest `continuous_up_to` over all joints and ends (2 means the law is C2 in a
    /// dwell-rise-dwell cycle).
    pub class: i32,
}

impl Law {
    /// The scale of s, v, a, j and the snap over the law ([`DerivativeScale`]).
    pub fn derivative_scale(&self) -> DerivativeScale<5> {
        segments_scale(self.segments())
    }

    /// The jumps of s, v, a, j at every joint and at both ends against dwells, judged against the
    /// law's own [`Law::derivative_scale`] (the dwells' scale is zero).
    pub fn continuity(&self) -> Continuity {
        let segs = self.segments();
        let full = self.derivative_scale().peak;
        let scale = Scale4 { peak: [full[0], full[1], full[2], full[3]] };
        let dwell0 = Kinematics::default();
        let dwell1 = Kinematics { s: 1.0, ..Kinematics::default() };
        let at_start = |g: &crate::Segment| g.term_magnitudes(0.0);
        let at_end = |g: &crate::Segment| g.term_magnitudes(g.width());
        let both = |a: [f64; 5], b: [f64; 5]| -> [f64; 5] { std::array::from_fn(|k| a[k].max(b[k])) };
        let last = &segs[segs.len() - 1];
        let start = Joint::new(0.0, None, dwell0, segs[0].start(), &scale, at_start(&segs[0]));
        let end = Joint::new(1.0, Some(segs.len() - 1), last.end(), dwell1, &scale, at_end(last));
        let joints: Vec<Joint> = segs
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                let terms = both(at_end(&w[0]), at_start(&w[1]));
                Joint::new(w[1].x0(), Some(i), w[0].end(), w[1].start(), &scale, terms)
            })
            .collect();
        let class = joints.iter().chain([&start, &end]).map(|j| j.continuous_up_to).min().unwrap_or(3);
        Continuity { start, joints, end, class }
    }
}
