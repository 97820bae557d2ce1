//! A frame's height along its plan at any angle of the main shaft: what the shed geometry reads
//! (the clear shed, the clearance to the carrier) for frames that each move by their own plan.

use crate::{FramePlan, MoveLaws, PlanSegment};
use loomkin_laws::{Law, SegmentKind};
use std::sync::atomic::{AtomicUsize, Ordering};

/// One frame's height over mid-stroke along its [`FramePlan`]: the numbers of the exact cycle
/// ([`FramePlan::cycle`], [`FramePlan::levels`]), looked up by angle. The segment found last is
/// tried first (the timing reads angles in order: a scan of a turn, the picks one after another),
/// then its successor, then a binary search: the same segment, whichever finds it.
#[derive(Debug)]
pub struct FramePath {
    segments: Vec<PlanSegment>,
    /// Per segment: an identity of its shape (kind, length, base, stroke): equal shapes, equal ids.
    shapes: Vec<u64>,
    /// The laws of a move up, down, up laid end to end, down laid end to end.
    laws: [Law; 4],
    start_deg: f64,
    period_deg: f64,
    level0_m: f64,
    /// The segment found last (a hint only: any value gives the same answers).
    last: AtomicUsize,
}

impl Clone for FramePath {
    fn clone(&self) -> Self {
        Self {
            segments: self.segments.clone(),
            shapes: self.shapes.clone(),
            laws: self.laws.clone(),
            start_deg: self.start_deg,
            period_deg: self.period_deg,
            level0_m: self.level0_m,
            last: AtomicUsize::new(self.last.load(Ordering::Relaxed)),
        }
    }
}

/// Path keys round offsets to 2⁻³⁰ degree (as the bus's window keys do).
const KEY_SCALE: f64 = (1u64 << 30) as f64;

/// `x` to the nearest 2⁻³⁰ (half away from zero), as a key word.
fn key_word(x: f64) -> u64 {
    let y = x * KEY_SCALE;
    (y + 0.5f64.copysign(y)) as i64 as u64
}

impl FramePath {
    /// The path of `plan` moving by `laws`.
    pub fn new(plan: &FramePlan, laws: &MoveLaws) -> Self {
        let segments = plan.levels();
        let mut ids: loomkin_numeric::WordMap<[u64; 4], u64> = Default::default();
        let shapes = segments
            .iter()
            .map(|s| {
                let k = [
                    s.kind as u64 | u64::from(s.through) << 8,
                    key_word(s.length_deg),
                    s.base_m.to_bits(),
                    s.stroke_m.to_bits(),
                ];
                let n = ids.len() as u64;
                *ids.entry(k).or_insert(n)
            })
            .collect();
        Self {
            segments,
            shapes,
            laws: [
                laws.of(true, false).1.clone(),
                laws.of(false, false).1.clone(),
                laws.of(true, true).1.clone(),
                laws.of(false, true).1.clone(),
            ],
            start_deg: plan.start_deg,
            period_deg: plan.period_deg,
            level0_m: plan.start_level_m(),
            last: AtomicUsize::new(0),
        }
    }

    /// The segment holding absolute angle `theta_deg` (wrapped into the repeat), and the angle
    /// moved into the plan's span `[start, start + period)`.
    #[inline]
    fn locate(&self, theta_deg: f64) -> (usize, f64) {
        // `start + (θ − start) mod period`; without the remainder's call when θ − start already
        // lies in [0, period) (the remainder is then that number itself, bit for bit).
        let d = theta_deg - self.start_deg;
        let th = if d >= 0.0 && d < self.period_deg {
            self.start_deg + d
        } else {
            self.start_deg + d.rem_euclid(self.period_deg)
        };
        // The last segment starting at or before `th` (the first when none does).
        let holds = |j: usize| {
            self.segments.get(j).is_some_and(|s| s.start_deg <= th)
                && self.segments.get(j + 1).is_none_or(|s| s.start_deg > th)
        };
        let hint = self.last.load(Ordering::Relaxed);
        let j = if holds(hint) {
            hint
        } else if holds(hint + 1) {
            hint + 1
        } else {
            self.segments.partition_point(|s| s.start_deg <= th).saturating_sub(1)
        };
        self.last.store(j, Ordering::Relaxed);
        (j, th)
    }

    /// The height over mid-stroke at main-shaft angle `theta_deg` (any angle: the plan repeats),
    /// m. At a joint the later segment's start is taken (the position is continuous there).
    #[inline]
    pub fn y_m(&self, theta_deg: f64) -> f64 {
        if self.segments.is_empty() {
            return self.level0_m;
        }
        let (j, th) = self.locate(theta_deg);
        let s = &self.segments[j];
        let law = match s.kind {
            SegmentKind::Dwell => return self.level0_m + s.base_m,
            SegmentKind::Rise => &self.laws[2 * usize::from(s.through)],
            SegmentKind::Return => &self.laws[1 + 2 * usize::from(s.through)],
        };
        let x = ((th - s.start_deg) / s.length_deg).clamp(0.0, 1.0);
        self.level0_m + (s.base_m + s.stroke_m * law.eval(x).s)
    }

    /// The height over mid-stroke where the frame rests over all of `[from_deg, to_deg]` (main-shaft
    /// angles, `from_deg ≤ to_deg`), m: [`FramePath::y_m`] at every angle of the span, bit for bit
    /// (a dwell's height does not depend on the angle). `None` when the frame moves there, or
    /// when the span comes within [`FramePath::REST_MARGIN_DEG`] of a move (so that no rounding
    /// of an angle in the span can reach it).
    #[inline]
    pub fn rest_m(&self, from_deg: f64, to_deg: f64) -> Option<f64> {
        let n = self.segments.len();
        if n == 0 || (n == 1 && self.segments[0].kind == SegmentKind::Dwell) {
            // `y_m` of a frame that never moves: its one level everywhere.
            return Some(if n == 0 { self.level0_m } else { self.level0_m + self.segments[0].base_m });
        }
        let (j, th) = self.locate(from_deg);
        let s = &self.segments[j];
        // The dwell's end: the next segment's start, or the plan's end (a move starts it again).
        let end = self.segments.get(j + 1).map_or(self.start_deg + self.period_deg, |next| next.start_deg);
        (s.kind == SegmentKind::Dwell
            && th - s.start_deg >= Self::REST_MARGIN_DEG
            && end - th > (to_deg - from_deg) + Self::REST_MARGIN_DEG)
            .then_some(self.level0_m + s.base_m)
    }

    /// How far from a move's ends a span must keep for [`FramePath::rest_m`], deg: far above the
    /// rounding of an angle of the longest repeat (10⁵ picks: 3.6·10⁷°, 7.5·10⁻⁹° a unit in the
    /// last place).
    pub const REST_MARGIN_DEG: f64 = 1e-6;

    /// Appends to `key` words naming what the frame does over `[origin + from_deg, origin +
    /// to_deg]` relative to `origin_deg`: every segment that meets the span, its shape (kind,
    /// length, level) and its place (to 2⁻³⁰°). Two origins with equal words see the same heights
    /// over the span (shifted by the difference of the origins, to that rounding).
    #[inline]
    pub fn key_words(&self, origin_deg: f64, from_deg: f64, to_deg: f64, key: &mut Vec<u64>) {
        let n = self.segments.len();
        if n == 0 {
            return;
        }
        let (a, b) = (origin_deg + from_deg, origin_deg + to_deg);
        let (mut j, th) = self.locate(a);
        // Whole repeats between the plan's span and the span's start (none when the span starts
        // within the plan's span: `a − th` is then rounding only, and the rounding call is skipped).
        let d = a - self.start_deg;
        let mut shift =
            if d >= 0.0 && d < self.period_deg { 0.0 } else { ((a - th) / self.period_deg).round() * self.period_deg };
        loop {
            let s = &self.segments[j];
            let start = s.start_deg + shift;
            key.extend([self.shapes[j], key_word(start - origin_deg)]);
            if start + s.length_deg >= b {
                break;
            }
            j += 1;
            if j == n {
                j = 0;
                shift += self.period_deg;
            }
        }
    }
}
