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
    fn new(x: f64, left_segment: Option<usize>, left: Kinematics, right: Kinematics) -> Self {
        let d = [right.s - left.s, right.v - left.v, right.a - left.a, right.j - left.j];
        let scale = [1.0, 1.0 + left.v.abs(), 1.0 + left.a.abs(), 1.0 + left.j.abs()];
        let continuous_up_to =
            d.iter().zip(scale).position(|(dk, sc)| dk.abs() > CONTINUITY_TOL * sc).map_or(3, |k| k as i32 - 1);
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
        let start = Joint::new(0.0, None, dwell0, segs[0].start());
        let end = Joint::new(1.0, Some(segs.len() - 1), segs[segs.len() - 1].end(), dwell1);
        let joints: Vec<Joint> = segs
            .windows(2)
            .enumerate()
            .map(|(i, w)| Joint::new(w[1].x0(), Some(i), w[0].end(), w[1].start()))
            .collect();
        let class = joints.iter().chain([&start, &end]).map(|j| j.continuous_up_to).min().unwrap_or(3);
        Continuity { start, joints, end, class }
    }
}
