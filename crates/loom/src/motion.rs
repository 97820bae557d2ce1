//! Every frame's motion over the pattern repeat (picks × 360° of the main shaft).
//!
//! Pick `p` is inserted in the turn `[360p, 360(p + 1))`, 0° being the beat-up of the previous
//! pick. A frame that keeps its place from pick `p − 1` to pick `p` dwells; one that changes
//! moves by the shedding law over the motion angle `φ`, centred on `360p + δ + σ_i`, where `δ`
//! is the crossing angle taken into `[−180°, 180°)` (a crossing at 300° is 60° before the
//! turn of pick `p` starts) and `σ_i` the frame's stagger.

use crate::{FrameLaw, Loom, Pattern, Result};
use loomkin_laws::{CycleSpec, Kinematics, LawSpec, SegmentKind, SegmentSpec, StrokeUnit};

/// A frame's height over mid-stroke and its derivatives with respect to the main-shaft angle.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FrameKin {
    /// Height over mid-stroke, m.
    pub y_m: f64,
    /// dy/dθ, m/rad.
    pub dy: f64,
    /// d²y/dθ², m/rad².
    pub d2y: f64,
    /// d³y/dθ³, m/rad³.
    pub d3y: f64,
}

/// One move of a frame: into pick `pick`, starting at `start_deg` (may be negative or past the
/// repeat's end: the motion is periodic), up or down.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    /// The pick the frame moves into.
    pub pick: usize,
    /// Start of the move, deg.
    pub start_deg: f64,
    /// Going up.
    pub rising: bool,
}

/// The motion of every frame of a loom weaving a pattern.
#[derive(Debug, Clone)]
pub struct Motion {
    law: FrameLaw,
    /// `up[i][p]`: frame `i` up at pick `p`.
    up: Vec<Vec<bool>>,
    stroke_m: Vec<f64>,
    /// Centre of the move into pick 0 for each frame, deg (`δ + σ_i`).
    centre0_deg: Vec<f64>,
    picks: usize,
}

/// The crossing angle taken into `[−180°, 180°)`.
pub fn crossing_offset_deg(crossing_deg: f64) -> f64 {
    if crossing_deg >= 180.0 { crossing_deg - 360.0 } else { crossing_deg }
}

impl Motion {
    /// The motion of `loom`'s frames weaving `pattern` (shaft `s` of the pattern on frame `s`,
    /// frames beyond the pattern's shafts staying down).
    pub fn new(loom: &Loom, pattern: &Pattern) -> Result<Self> {
        let n = loom.frame_count();
        crate::pattern::check_weavable(pattern, n)?;
        let picks = pattern.picks();
        // [`Pattern::is_up`] of every pick, read from the rows (frames beyond the shafts down).
        let rows = pattern.rows();
        let up = (0..n).map(|i| rows.iter().map(|r| r.get(i).copied().unwrap_or(false)).collect()).collect();
        let delta = crossing_offset_deg(loom.shedding.crossing_deg);
        Ok(Self {
            law: loom.shedding.law.clone(),
            up,
            stroke_m: loom.geometry.stroke_m.clone(),
            centre0_deg: loom.shedding.stagger_deg.iter().map(|s| delta + s).collect(),
            picks,
        })
    }

    /// Picks in the repeat.
    pub fn picks(&self) -> usize {
        self.picks
    }

    /// Frames.
    pub fn frames(&self) -> usize {
        self.up.len()
    }

    /// The repeat, deg (`360 · picks`).
    pub fn repeat_deg(&self) -> f64 {
        360.0 * self.picks as f64
    }

    /// Motion angle, deg.
    pub fn motion_deg(&self) -> f64 {
        self.law.motion_deg()
    }

    /// The law.
    pub fn law(&self) -> &FrameLaw {
        &self.law
    }

    /// Frame `i`'s stroke, m.
    pub fn stroke_m(&self, i: usize) -> f64 {
        self.stroke_m[i]
    }

    /// Whether frame `i` is up at pick `p` (wrapped into the repeat).
    pub fn is_up(&self, i: usize, p: i64) -> bool {
        self.up[i][p.rem_euclid(self.picks as i64) as usize]
    }

    /// Frame `i`'s lifts over the repeat: up at pick `p` ([`Motion::is_up`] of every pick, in order).
    pub fn lifts(&self, i: usize) -> &[bool] {
        &self.up[i]
    }

    /// Centre of frame `i`'s move into pick 0, deg.
    pub fn centre0_deg(&self, i: usize) -> f64 {
        self.centre0_deg[i]
    }

    /// Frame `i`'s moves over one repeat, in order.
    pub fn moves(&self, i: usize) -> Vec<Move> {
        let half = self.motion_deg() / 2.0;
        (0..self.picks)
            .filter(|&p| self.is_up(i, p as i64) != self.is_up(i, p as i64 - 1))
            .map(|p| Move {
                pick: p,
                start_deg: 360.0 * p as f64 + self.centre0_deg[i] - half,
                rising: self.is_up(i, p as i64),
            })
            .collect()
    }

    /// The number of frame `i`'s moves over one repeat ([`Motion::moves`] without the list).
    pub fn move_count(&self, i: usize) -> usize {
        (0..self.picks).filter(|&p| self.is_up(i, p as i64) != self.is_up(i, p as i64 - 1)).count()
    }

    /// The angles in `[from_deg, to_deg]` (any angles, not wrapped into the repeat) where some
    /// frame's motion is not smooth, as [`Motion::joints`] lists them over the repeat, sorted, with
    /// both ends (a joint within 1e-9° of an end is the end): the panels of exact quadrature over
    /// a part of the repeat.
    pub fn joints_between(&self, from_deg: f64, to_deg: f64) -> Vec<f64> {
        let phi = self.motion_deg();
        let mut out = vec![from_deg, to_deg];
        for i in 0..self.frames() {
            let c = self.centre0_deg[i];
            let first = ((from_deg - c - phi / 2.0) / 360.0).floor() as i64;
            let last = ((to_deg - c + phi / 2.0) / 360.0).ceil() as i64;
            for q in first..=last {
                let rising = self.is_up(i, q);
                if rising == self.is_up(i, q - 1) {
                    continue;
                }
                let start = 360.0 * q as f64 + c - phi / 2.0;
                let law = self.law.law(rising);
                let xs = std::iter::once(0.0).chain(law.joints()).chain(std::iter::once(1.0));
                out.extend(xs.map(|x| start + x * phi).filter(|&t| t > from_deg + 1e-9 && t < to_deg - 1e-9));
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
        out
    }

    /// The height of a frame at a state, m.
    fn level(&self, i: usize, up: bool) -> f64 {
        if up { self.stroke_m[i] / 2.0 } else { -self.stroke_m[i] / 2.0 }
    }

    /// Frame `i` at main-shaft angle `theta_deg` (any angle; the motion repeats every
    /// [`Motion::repeat_deg`]). At a joint between a dwell and a move the move's end value is taken.
    pub fn frame(&self, i: usize, theta_deg: f64) -> FrameKin {
        let q = ((theta_deg - self.centre0_deg[i]) / 360.0).round();
        self.frame_near(i, theta_deg, q, q as i64)
    }

    /// Frame `i` at angle `t_deg` of pick `p`'s turn (`θ = 360p + t`, worked out without the
    /// rounding of the absolute angle): the same motion as [`Motion::frame`] at `360p + t`, and a
    /// function of `t` and of the frame's lifts at the picks around `p` alone — two picks whose
    /// lifts agree there give the same bits (what the rows of a long repeat are made of: a
    /// frame's row over a span of the turn serves every pick whose lifts agree around it).
    pub fn frame_in_turn(&self, i: usize, p: usize, t_deg: f64) -> FrameKin {
        let q = self.move_in_turn(i, t_deg);
        self.frame_near(i, t_deg, q as f64, p as i64 + q)
    }

    /// The move nearest angle `t_deg` of a pick's turn for frame `i`, in picks from that pick
    /// (`0`: the move into the pick itself): [`Motion::frame_in_turn`] reads the lifts of that
    /// pick and of the one before. Non-decreasing in `t_deg`.
    pub fn move_in_turn(&self, i: usize, t_deg: f64) -> i64 {
        ((t_deg - self.centre0_deg[i]) / 360.0).round() as i64
    }

    /// Frame `i` at `theta_deg`, `q` whole turns from the move into pick 0 (the move nearest
    /// `theta_deg`), reading the lifts at picks `qi − 1` and `qi`.
    fn frame_near(&self, i: usize, theta_deg: f64, q: f64, qi: i64) -> FrameKin {
        let phi = self.motion_deg();
        let centre = self.centre0_deg[i] + 360.0 * q;
        let (before, after) = (self.is_up(i, qi - 1), self.is_up(i, qi));
        if before != after && (theta_deg - centre).abs() <= phi / 2.0 {
            let x = (theta_deg - centre + phi / 2.0) / phi;
            return self.moving(i, after, x);
        }
        let y_m = self.level(i, if theta_deg >= centre { after } else { before });
        FrameKin { y_m, ..FrameKin::default() }
    }

    /// Frame `i` moving up (`rising`) or down at fraction `x` of the motion.
    pub fn moving(&self, i: usize, rising: bool, x: f64) -> FrameKin {
        let k: Kinematics = self.law.law(rising).eval(x);
        let h = self.stroke_m[i];
        let r = 1.0 / self.motion_deg().to_radians();
        let sign = if rising { 1.0 } else { -1.0 };
        FrameKin {
            y_m: -sign * h / 2.0 + sign * h * k.s,
            dy: sign * h * k.v * r,
            d2y: sign * h * k.a * r * r,
            d3y: sign * h * k.j * r * r * r,
        }
    }

    /// Angles in `[0, repeat)` where some frame's motion is not smooth: the ends of every move and
    /// the joints of its law (the panels of exact quadrature), sorted, with 0 and the repeat's end.
    pub fn joints(&self) -> Vec<f64> {
        let period = self.repeat_deg();
        let phi = self.motion_deg();
        let mut out = vec![0.0, period];
        for i in 0..self.frames() {
            for m in self.moves(i) {
                let law = self.law.law(m.rising);
                let xs = std::iter::once(0.0).chain(law.joints()).chain(std::iter::once(1.0));
                out.extend(xs.map(|x| (m.start_deg + x * phi).rem_euclid(period)));
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup_by(|a, b| (*a - *b).abs() <= 1e-9);
        out
    }

    /// Frame `i`'s motion over the repeat as a machine cycle of the law core (period
    /// `360·picks` degrees, strokes in mm, starting at the first move's start, or at 0 when the
    /// frame never moves). Its position is relative to the frame's place before that start:
    /// add `−H/2` (down) or `+H/2` (up) to read the height over mid-stroke.
    pub fn cycle_spec(&self, i: usize) -> CycleSpec {
        let phi = self.motion_deg();
        let moves: Vec<(f64, f64, bool, &LawSpec)> =
            self.moves(i).iter().map(|m| (m.start_deg, phi, m.rising, self.law.spec(m.rising))).collect();
        machine_cycle(&moves, self.repeat_deg(), self.stroke_m[i] * 1e3, None)
    }
}

/// A frame's moves `(start, length, rising, law)` (deg, in order over one repeat) as a machine
/// cycle of the law core: dwells between them, period `period_deg`, strokes in mm, starting at the
/// first move (or at 0 when there is none).
pub(crate) fn machine_cycle(
    moves: &[(f64, f64, bool, &LawSpec)],
    period_deg: f64,
    stroke_mm: f64,
    speed_rpm: Option<f64>,
) -> CycleSpec {
    let mut segment = Vec::new();
    let start = moves.first().map_or(0.0, |m| m.0);
    let mut at = start;
    for &(s, l, rising, law) in moves {
        if s > at + 1e-9 {
            segment.push(SegmentSpec::dwell(s - at));
        }
        let kind = if rising { SegmentKind::Rise } else { SegmentKind::Return };
        segment.push(SegmentSpec::moving(kind, l, law));
        at = s + l;
    }
    if start + period_deg > at + 1e-9 {
        segment.push(SegmentSpec::dwell(start + period_deg - at));
    }
    if let Some(first) = segment.first_mut() {
        first.from_deg = Some(start);
    }
    CycleSpec { period_deg, unit: StrokeUnit::Mm, stroke: Some(stroke_mm), speed_rpm, segment }
}
