//! The smoothness of a frame's planned motion at every joint, in time, on the exact laws.
//!
//! A joint of the cycle (a dwell meeting a move, two moves laid end to end by pass-through) is
//! judged by the law core's one rule ([`loomkin_laws::DerivativeScale`], docs/design/continuity.md):
//! the derivative of order `k` jumps when its two sides differ by more than `1e-9` of the larger of
//! the two segments' own peaks of that derivative, plus the rounding of the two evaluations. The
//! joints inside a law are the law's own ([`loomkin_laws::Law::continuity`]).

use crate::MoveLaws;
use loomkin_laws::{Cycle, CycleSegment, DerivativeScale};

/// The least smoothness of a cycle's joints.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointClass {
    /// Highest derivative order continuous at every rest transition (a dwell meeting a move, or
    /// two moves meeting): −1 (position jumps), 0 (C0), 1 (C1), 2 (C2), 3 (jerk continuous too).
    pub rest: i32,
    /// Where the least smooth rest transition is, deg of the main shaft (`None` without joints).
    pub rest_at_deg: Option<f64>,
    /// The segment of the cycle that starts there (the joint is between it and the one before).
    pub rest_at_segment: Option<usize>,
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
    // A segment's scale by its kind, law (`law_id`'s number), length and stroke; a law that is
    // none of the frame's (3) is not remembered.
    let mut scales: crate::bus::WordMap<(u8, u64, u64, u64), DerivativeScale<4>> = Default::default();
    let mut scale = |s: &CycleSegment, id: u64| {
        let of = || {
            let base = CycleSegment { base_si: 0.0, ..s.clone() };
            DerivativeScale::of_piece(1.0, |x| kin(&base, x, omega))
        };
        if id == 3 {
            return of();
        }
        *scales.entry((s.kind as u8, id, s.length_rad.to_bits(), s.stroke_si.to_bits())).or_insert_with(of)
    };
    let mut rest = 3;
    let mut rest_at_deg = None;
    let mut rest_at_segment = None;
    // A joint between the same two segments (kind, law, length, stroke, base) as an earlier one
    // is the same joint: its class once.
    let law_id = |s: &CycleSegment| match &s.law {
        None => 0u64,
        Some((_, l)) if *l == laws.rise.1 => 1,
        Some((_, l)) if *l == laws.fall.1 => 2,
        Some((_, l)) if laws.through.as_ref().is_some_and(|t| *l == t.1) => 4,
        Some(_) => 3,
    };
    let ids: Vec<u64> = segs.iter().map(law_id).collect();
    let shape = |i: usize| {
        let s = &segs[i];
        [(s.kind as u64) << 8 | ids[i], s.length_rad.to_bits(), s.stroke_si.to_bits(), s.base_si.to_bits()]
    };
    let mut classes: crate::bus::WordMap<[u64; 8], i32> = Default::default();
    if segs.len() > 1 {
        for i in 0..segs.len() {
            let j = (i + 1) % segs.len();
            let (a, b) = (&segs[i], &segs[j]);
            let wrap = i + 1 == segs.len();
            let (ka, kb) = (shape(i), shape(j));
            let key = [ka[0], ka[1], ka[2], ka[3], kb[0], kb[1], kb[2], kb[3]];
            let known = if wrap || ids[i] == 3 || ids[j] == 3 { None } else { classes.get(&key).copied() };
            let class = match known {
                Some(c) => c,
                None => {
                    let mut l = kin(a, 1.0, omega);
                    let r = kin(b, 0.0, omega);
                    if wrap {
                        // Around the repeat: the position returns to the start.
                        l[0] -= segs.iter().map(|s| s.stroke_si).sum::<f64>();
                    }
                    let sc = scale(a, ids[i]).max(scale(b, ids[j]));
                    let rounding: [f64; 4] = std::array::from_fn(|k| 64.0 * f64::EPSILON * (l[k].abs() + r[k].abs()));
                    let c = sc.first_jump(&l, &r, &rounding).map_or(3, |k| k as i32 - 1);
                    if !wrap {
                        classes.insert(key, c);
                    }
                    c
                }
            };
            if class < rest {
                rest = class;
                rest_at_deg = Some((b.start_rad).to_degrees());
                rest_at_segment = Some(j);
            }
        }
    }
    let inner = |l: &loomkin_laws::Law| l.continuity().joints.iter().map(|j| j.continuous_up_to).min().unwrap_or(3);
    // Every law the cycle moves by, once.
    let mut seen = [false; 5];
    let mut law = 3;
    for (s, &id) in segs.iter().zip(&ids) {
        if let Some((_, l)) = &s.law
            && (id == 3 || !std::mem::replace(&mut seen[id as usize], true))
        {
            law = law.min(inner(l));
        }
    }
    JointClass { rest, rest_at_deg, rest_at_segment, law }
}
