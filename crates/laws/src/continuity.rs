//! Smoothness of a law at its joints and at its ends against the adjoining dwells.

use crate::{Kinematics, Law};
use serde::Serialize;

/// Absolute jump below which a quantity counts as continuous (for a unit-stroke law).
pub const CONTINUITY_TOL: f64 = 1e-9;

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
    /// `terms`: the magnitudes of the terms that make up s, v, a, j and the snap on either side
    /// ([`crate::Segment`]'s evaluation rounds to a few ulps of them). A jump of order k counts when
    /// it exceeds `CONTINUITY_TOL`·(1 + the larger of |left value| and 10⁻⁴ of its terms) plus the
    /// rounding of the joint's place, 8ε·x times the next order's terms (a joint sits at a rounded
    /// sum of widths, so each side is evaluated up to an ulp of x off its shape's end). Judged
    /// against 1 + |value| alone, narrow segments read as jumps: half-cosine ramps of width 1e-6
    /// end with j = 1.2e-9 where j = 0 (a law C3 by construction reported C2), and a sine arc of
    /// width 1e-6 ending at x = 1 has a = 2.8e-4 there, 1.8e-10 of its Ca (reported C1).
    fn new(x: f64, left_segment: Option<usize>, left: Kinematics, right: Kinematics, terms: [f64; 5]) -> Self {
        let d = [right.s - left.s, right.v - left.v, right.a - left.a, right.j - left.j];
        let value = [left.s, left.v, left.a, left.j];
        // s is judged absolutely (the law is normalised to a unit stroke), as before.
        let tol: [f64; 4] = std::array::from_fn(|k| {
            let scale = if k == 0 { 1.0 } else { 1.0 + value[k].abs().max(1e-4 * terms[k]) };
            CONTINUITY_TOL * scale + 8.0 * f64::EPSILON * x.abs() * terms[k + 1]
        });
        let continuous_up_to = d.iter().zip(tol).position(|(dk, t)| dk.abs() > t).map_or(3, |k| k as i32 - 1);
        Self { x, left_segment, ds: d[0], dv: d[1], da: d[2], dj: d[3], continuous_up_to }
    }

    /// Whether s, v, a, j are each continuous here.
    pub fn flags(&self) -> [bool; 4] {
        std::array::from_fn(|k| (k as i32) <= self.continuous_up_to)
    }
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
    /// The jumps of s, v, a, j at every joint and at both ends against dwells.
    pub fn continuity(&self) -> Continuity {
        let segs = self.segments();
        let dwell0 = Kinematics::default();
        let dwell1 = Kinematics { s: 1.0, ..Kinematics::default() };
        let at_start = |g: &crate::Segment| g.term_magnitudes(0.0);
        let at_end = |g: &crate::Segment| g.term_magnitudes(g.width());
        let both = |a: [f64; 5], b: [f64; 5]| -> [f64; 5] { std::array::from_fn(|k| a[k].max(b[k])) };
        let last = &segs[segs.len() - 1];
        let start = Joint::new(0.0, None, dwell0, segs[0].start(), at_start(&segs[0]));
        let end = Joint::new(1.0, Some(segs.len() - 1), last.end(), dwell1, at_end(last));
        let joints: Vec<Joint> = segs
            .windows(2)
            .enumerate()
            .map(|(i, w)| {
                Joint::new(w[1].x0(), Some(i), w[0].end(), w[1].start(), both(at_end(&w[0]), at_start(&w[1])))
            })
            .collect();
        let class = joints.iter().chain([&start, &end]).map(|j| j.continuous_up_to).min().unwrap_or(3);
        Continuity { start, joints, end, class }
    }
}
