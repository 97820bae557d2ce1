//! The smoothness of a frame's planned motion at every joint, in time, on the exact laws.
//!
//! A joint of the cycle (a dwell meeting a move, two moves laid end to end by pass-through) is
//! judged by the law core's one rule ([`loomkin_laws::DerivativeScale`], docs/design/continuity.md):
//! the derivative of order `k` jumps when its two sides differ by more than `1e-9` of the larger of
//! the two segments' own peaks of that derivative, plus the rounding of the two evaluations. The
//! joints inside a law are the law's own ([`loomkin_laws::Law::continuity`]).

use crate::MoveLaws;
use loomkin_laws::{Cycle, CycleSegment, DerivativeScale};
use std::collections::HashMap;

/// The least smoothness of a cycle's joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointClass {
    /// Highest derivative order continuous at every rest transition (a dwell meeting a move, or
    /// two moves meeting): −1 (position jumps), 0 (C0), 1 (C1), 2 (C2), 3 (jerk continuous too).
    pub rest: i32,
    /// Where the least smooth rest transition is, deg of the main shaft (`None` without joints).
    pub rest_at_deg: Option<f64>,
    /// The same over the joints inside the laws of the moves.
    pub law: i32,
}

/// Position, velocity, acceleration and jerk of a segment at its fraction `x`, the shaft turning
/// at `omega` rad/s (SI).
pub(crate) fn kin(seg: &CycleSegment, x: f64, omega: f64) -> [f64; 4] {
    match &seg.law {
        None => [seg.base_si, 0.0, 0.0, 0.0],
        Some((_, law)) => {
            let k = law.eval(x);
            let r = omega / seg.length_rad;
            let h = seg.stroke_si;
            [seg.base_si + h * k.s, h * k.v * r, h * k.a * r * r, h * k.j * r * r * r]
        }
    }
}

/// The classes of `cycle`'s joints at `omega` rad/s (the class does not depend on the speed; the
/// values are in time so that two moves of different lengths compare).
pub fn joint_class(cycle: &Cycle, laws: &MoveLaws, omega: f64) -> JointClass {
    let segs = &cycle.segments;
    let mut scales: HashMap<(u8, u64, u64), DerivativeScale<4>> = HashMap::new();
    let mut scale = |s: &CycleSegment| {
        let key = (s.kind as u8, s.length_rad.to_bits(), s.stroke_si.to_bits());
        *scales.entry(key).or_insert_with(|| {
            let base = CycleSegment { base_si: 0.0, ..s.clone() };
            DerivativeScale::of_piece(1.0, |x| kin(&base, x, omega))
        })
    };
    let mut rest = 3;
    let mut rest_at_deg = None;
    if segs.len() > 1 {
        for i in 0..segs.len() {
            let (a, b) = (&segs[i], &segs[(i + 1) % segs.len()]);
            let mut l = kin(a, 1.0, omega);
            let r = kin(b, 0.0, omega);
            if i + 1 == segs.len() {
                // Around the repeat: the position returns to the start.
                l[0] -= segs.iter().map(|s| s.stroke_si).sum::<f64>();
            }
            let sc = scale(a).max(scale(b));
            let rounding: [f64; 4] = std::array::from_fn(|k| 64.0 * f64::EPSILON * (l[k].abs() + r[k].abs()));
            let class = sc.first_jump(&l, &r, &rounding).map_or(3, |k| k as i32 - 1);
            if class < rest {
                rest = class;
                rest_at_deg = Some((b.start_rad).to_degrees());
            }
        }
    }
    let inner = |l: &loomkin_laws::Law| l.continuity().joints.iter().map(|j| j.continuous_up_to).min().unwrap_or(3);
    let moves = segs.iter().any(|s| s.law.is_some());
    let law = if moves { inner(&laws.rise.1).min(inner(&laws.fall.1)) } else { 3 };
    JointClass { rest, rest_at_deg, law }
}
