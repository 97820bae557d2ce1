//! The move planner: one heald frame's motion over the pattern repeat from its row of the lift plan.
//!
//! Pick `p` is inserted in the turn `[360p, 360(p + 1))` of the main shaft. A frame that keeps its
//! place from pick `p − 1` to pick `p` dwells; one that changes moves by the rise law (going up) or
//! the fall law (going down) over its motion angle `φ` (the rise's `φ_r` going up, the fall's `φ_f`
//! going down), centred on `360p + c`, `c` the frame's centre (the crossing angle taken into
//! `[−180°, 180°)` plus the frame's stagger) — the plan of the mechanical dobby, [`loomkin_laws`]
//! segments in closed form.
//!
//! **Pass-through.** Where the designer allows it, a frame that changes on consecutive picks (up on
//! pick `p`, down on `p + 1`, …) does not stop between: a run of `k + 1` consecutive changes, from
//! the start of its first move (`360p + c − φ_first/2`) to the end of its last (`360(p + k) + c +
//! φ_last/2`), is split into `k + 1` moves of equal length `(360k + φ_first/2 + φ_last/2)/(k + 1)`
//! (`(360k + φ)/(k + 1)` with one angle) laid end to end, each by the through law where one is given
//! ([`MoveLaws::through`]), else by the rise or fall law. With rest laws (velocity and acceleration zero at both ends) the frame turns
//! at the top or the bottom without a dwell, and the joint is as smooth as the law's ends (C² for
//! every law whose acceleration starts and ends at zero, [`crate::continuity`]). When every pick is
//! a change (a plain weave on this frame) the frame oscillates without a stop: every move 360°
//! long, centred on `360p + c`.

use crate::{EshedError, Result};
use loomkin_laws::{Cycle, CycleSegment, CycleSpec, Law, LawSpec, SegmentKind, SegmentSpec, StrokeUnit};

/// The laws of a frame's moves: a normalised rise (0 → 1 over `x ∈ [0, 1]`) for a frame going up
/// and one for a frame going down (`y = top − H·s(x)`), each with the catalogue form a cycle file
/// holds; and, where the designer gives one, the law of the moves that pass-through lays end to
/// end (both ways).
#[derive(Debug, Clone)]
pub struct MoveLaws {
    /// Going up: the spec and the built law.
    pub rise: (LawSpec, Law),
    /// Going down.
    pub fall: (LawSpec, Law),
    /// The moves of a run of consecutive changes laid end to end ([`PlannedMove::through`]), up
    /// and down; `None`: the rise or fall law by direction.
    pub through: Option<(LawSpec, Law)>,
    /// Where the rise, fall and through laws are given (the loom file's fields), named when a law
    /// is refused at a joint of the frame's motion.
    pub fields: [String; 3],
    /// The rise, fall and through laws' names in text ([`crate::GivenLaw::label`]; empty for a
    /// through law not given).
    pub labels: [String; 3],
}

impl MoveLaws {
    /// The laws up, down and laid end to end (`None`: none given), without their specs and names.
    pub(crate) fn law_values(&self) -> [Option<Law>; 3] {
        [Some(self.rise.1.clone()), Some(self.fall.1.clone()), self.through.as_ref().map(|t| t.1.clone())]
    }

    /// `rise` going up and `fall` going down, pass-through moves by the same (named `rise` and
    /// `fall` when refused).
    pub fn new(rise: (LawSpec, Law), fall: (LawSpec, Law)) -> Self {
        let labels = [rise.0.label(), fall.0.label(), String::new()];
        Self { rise, fall, through: None, fields: ["rise".into(), "fall".into(), "through".into()], labels }
    }

    /// How a frame moves by these laws, in words: each kind's law and motion angle (`motion_deg`:
    /// up, down; deg, in the number format of [`loomkin_units::compact`]) and the law of the moves
    /// laid end to end where one is given, e.g. `up by poly4567 over 260°, down by cycloidal over
    /// 300°, laid end to end by spline (5 points, clamped)`; `up and down by dobby preset over 280°`
    /// where both agree.
    pub fn describe(&self, motion_deg: [f64; 2]) -> String {
        let deg = |d: f64| format!("{}°", loomkin_units::compact(d));
        let mut text = if self.labels[0] == self.labels[1] && motion_deg[0] == motion_deg[1] {
            format!("up and down by {} over {}", self.labels[0], deg(motion_deg[0]))
        } else {
            format!(
                "up by {} over {}, down by {} over {}",
                self.labels[0],
                deg(motion_deg[0]),
                self.labels[1],
                deg(motion_deg[1])
            )
        };
        if self.through.is_some() {
            text.push_str(&format!(", laid end to end by {}", self.labels[2]));
        }
        text
    }

    /// The law going up (`rising`) or down.
    pub fn law(&self, rising: bool) -> &(LawSpec, Law) {
        if rising { &self.rise } else { &self.fall }
    }

    /// The law of a move going up (`rising`) or down, laid end to end with others (`through`) or not.
    pub fn of(&self, rising: bool, through: bool) -> &(LawSpec, Law) {
        match &self.through {
            Some(t) if through => t,
            _ => self.law(rising),
        }
    }

    /// The field the law of such a move is given in.
    pub fn field_of(&self, rising: bool, through: bool) -> &str {
        let k = if through && self.through.is_some() {
            2
        } else if rising {
            0
        } else {
            1
        };
        &self.fields[k]
    }
}

/// One move of a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedMove {
    /// The pick the frame moves into (0-based, within the repeat).
    pub pick: usize,
    /// Start, deg of the main shaft (may lie before 0 or past the repeat: the motion is periodic).
    pub start_deg: f64,
    /// Length, deg.
    pub length_deg: f64,
    /// Going up.
    pub rising: bool,
    /// Laid end to end with the moves before or after it, without a dwell (a run of consecutive
    /// changes with pass-through, or a frame that changes on every pick): moved by the through
    /// law when there is one.
    pub through: bool,
}

/// One segment of a plan: what [`FramePlan::cycle`] makes a segment of the cycle from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanSegment {
    /// Dwell, rise or return.
    pub kind: SegmentKind,
    /// Start, deg of the main shaft (the cycle's arithmetic: the plan's start plus the lengths before).
    pub start_deg: f64,
    /// Length, deg.
    pub length_deg: f64,
    /// Where it starts, m from the frame's place at the plan's start.
    pub base_m: f64,
    /// How far it goes, m (`±H`, 0 for a dwell).
    pub stroke_m: f64,
    /// A move laid end to end with others ([`PlannedMove::through`]).
    pub through: bool,
}

/// One frame's row of the lift plan and its timing.
#[derive(Debug, Clone, Copy)]
pub struct FrameInput<'a> {
    /// Up at pick `p`, for every pick of the repeat.
    pub up: &'a [bool],
    /// Full stroke, m (> 0).
    pub stroke_m: f64,
    /// Centre of the move into pick 0, deg (crossing offset plus stagger).
    pub centre_deg: f64,
    /// Motion angle of a move up, deg (0 < φ ≤ 360).
    pub motion_deg: f64,
    /// Motion angle of a move down, deg (0 < φ ≤ 360; `motion_deg` for one angle both ways).
    pub fall_motion_deg: f64,
}

/// A frame's moves over one repeat, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct FramePlan {
    /// The moves, in increasing angle; none when the frame keeps its place.
    pub moves: Vec<PlannedMove>,
    /// Where the plan starts, deg: the first move's start (0 without moves).
    pub start_deg: f64,
    /// The repeat, deg (`360 · picks`).
    pub period_deg: f64,
    /// Whether the frame is up at the start.
    pub start_up: bool,
    /// Full stroke, m.
    pub stroke_m: f64,
    /// The motion angle of a move up and of a move down, deg (before pass-through lengthens moves).
    pub motion_deg: [f64; 2],
    /// The centre of the move into pick 0, deg (crossing offset plus stagger): a move into pick
    /// `p` is centred on `360p + centre_deg`.
    pub centre_deg: f64,
}

impl FramePlan {
    /// Plans one frame; `pass_through` lays consecutive changes end to end (see the module).
    pub fn new(input: &FrameInput<'_>, pass_through: bool) -> Result<Self> {
        let picks = input.up.len();
        if picks == 0 {
            return Err(EshedError::field("pattern", "a lift plan needs at least one pick"));
        }
        for (name, phi) in [("motion_deg", input.motion_deg), ("fall_motion_deg", input.fall_motion_deg)] {
            if !(phi > 0.0 && phi <= 360.0) {
                return Err(EshedError::field(
                    name,
                    format!("{phi}°: a move must fit in one pick's turn (0 < {name} ≤ 360°)"),
                ));
            }
        }
        let up = |p: i64| input.up[p.rem_euclid(picks as i64) as usize];
        let change = |p: i64| up(p) != up(p - 1);
        // The motion angle of the move into pick `p` (up or down).
        let phi = |p: i64| if up(p) { input.motion_deg } else { input.fall_motion_deg };
        let c = input.centre_deg;
        let period_deg = 360.0 * picks as f64;
        let moves: Vec<PlannedMove> = if !pass_through {
            // The picks in order, each against the one before (the last before the first).
            let before = std::iter::once(input.up[picks - 1]).chain(input.up.iter().copied());
            input
                .up
                .iter()
                .zip(before)
                .enumerate()
                .filter(|&(_, (&now, was))| now != was)
                .map(|(p, (&rising, _))| {
                    let phi = if rising { input.motion_deg } else { input.fall_motion_deg };
                    PlannedMove {
                        pick: p,
                        start_deg: 360.0 * p as f64 + c - phi / 2.0,
                        length_deg: phi,
                        rising,
                        through: false,
                    }
                })
                .collect()
        } else if (0..picks as i64).all(change) {
            (0..picks as i64)
                .map(|p| PlannedMove {
                    pick: p as usize,
                    start_deg: 360.0 * p as f64 + c - 180.0,
                    length_deg: 360.0,
                    rising: up(p),
                    through: true,
                })
                .collect()
        } else {
            // Runs of consecutive changes, starting from a change whose previous pick is none.
            let first = (0..picks as i64).find(|&p| change(p) && !change(p - 1));
            let mut out = Vec::new();
            if let Some(p0) = first {
                let mut p = p0;
                while p < p0 + picks as i64 {
                    if !change(p) {
                        p += 1;
                        continue;
                    }
                    let mut k = 0;
                    while p + k + 1 < p0 + picks as i64 && change(p + k + 1) {
                        k += 1;
                    }
                    // From the first move's start to the last one's end (each by its own angle).
                    let s = 360.0 * p as f64 + c - phi(p) / 2.0;
                    let len = (360.0 * k as f64 + (phi(p) / 2.0 + phi(p + k) / 2.0)) / (k + 1) as f64;
                    for j in 0..=k {
                        out.push(PlannedMove {
                            pick: (p + j).rem_euclid(picks as i64) as usize,
                            start_deg: s + j as f64 * len,
                            length_deg: len,
                            rising: up(p + j),
                            through: k > 0,
                        });
                    }
                    p += k + 1;
                }
            }
            out
        };
        let start_deg = moves.first().map_or(0.0, |m| m.start_deg);
        let start_up = moves.first().map_or(input.up[0], |m| !m.rising);
        Ok(Self {
            moves,
            start_deg,
            period_deg,
            start_up,
            stroke_m: input.stroke_m,
            motion_deg: [input.motion_deg, input.fall_motion_deg],
            centre_deg: c,
        })
    }

    /// Per-segment values of the plan (`per_segment`, one for each of [`FramePlan::segments`], in
    /// order: integrals over the segments, e.g. `∫T² dt`) cut into the cells of the picks `picks`
    /// (increasing), one sum per pick. Pick `q`'s cell is the turn `[360q + c − 180°, 360q + c +
    /// 180°)` about its move centre `c` ([`FramePlan::centre_deg`]): the cells tile the repeat. A move
    /// counts whole in the cell of the pick it moves into (a move not laid end to end lies within
    /// that cell, `φ ≤ 360°`; a run laid end to end lies within its picks' cells, from its first
    /// move's start to its last one's end); a dwell counts by the part of it within the cell, in
    /// proportion to its length (the integrand is constant over a dwell). Over all picks of the
    /// repeat the cells' sums add up to the whole; each depends only on what the frame does in the
    /// cell: its lifts at picks `q − 1` and `q` and the run of changes through `q`.
    pub fn cell_sums(&self, per_segment: &[f64], picks: &[usize]) -> Vec<f64> {
        let parts = self.parts();
        let mut out = vec![0.0; picks.len()];
        let mut moves = self.moves.iter();
        for (&(kind, start, len, _), &v) in parts.iter().zip(per_segment) {
            if kind != SegmentKind::Dwell {
                if let Some(m) = moves.next()
                    && let Ok(k) = picks.binary_search(&m.pick)
                {
                    out[k] += v;
                }
                continue;
            }
            for (k, &q) in picks.iter().enumerate() {
                let (u, w) = (360.0 * q as f64 + self.centre_deg - 180.0, 360.0 * q as f64 + self.centre_deg + 180.0);
                // The dwell, and its repeats before and after, within the cell.
                let inside: f64 = [-self.period_deg, 0.0, self.period_deg]
                    .iter()
                    .map(|shift| ((start + len + shift).min(w) - (start + shift).max(u)).max(0.0))
                    .sum();
                if inside > 0.0 {
                    out[k] += v * (inside / len);
                }
            }
        }
        out
    }

    /// The segments of the plan as `(kind, start_deg, length_deg)`: dwells between the moves,
    /// gaps of 10⁻⁹° or less left out (as [`FramePlan::cycle_spec`] writes them).
    pub fn segments(&self) -> Vec<(SegmentKind, f64, f64)> {
        self.parts().into_iter().map(|(kind, start, len, _)| (kind, start, len)).collect()
    }

    /// [`FramePlan::segments`], each with whether it is a move laid end to end with others (which
    /// takes the through law: [`MoveLaws::of`]).
    pub fn parts(&self) -> Vec<(SegmentKind, f64, f64, bool)> {
        let mut out = Vec::with_capacity(2 * self.moves.len() + 1);
        let mut at = self.start_deg;
        for m in &self.moves {
            if m.start_deg > at + 1e-9 {
                out.push((SegmentKind::Dwell, at, m.start_deg - at, false));
            }
            let kind = if m.rising { SegmentKind::Rise } else { SegmentKind::Return };
            out.push((kind, m.start_deg, m.length_deg, m.through));
            at = m.start_deg + m.length_deg;
        }
        if self.start_deg + self.period_deg > at + 1e-9 {
            out.push((SegmentKind::Dwell, at, self.start_deg + self.period_deg - at, false));
        }
        out
    }

    /// The plan as a checked machine cycle of the law core (stroke unit mm, positions in m from
    /// the frame's place at the start: add `−H/2` when it starts down, `+H/2` up, to read the
    /// height over mid-stroke). Built segment by segment, so a repeat of any length is held (a
    /// cycle file is limited to 36 000°, 100 picks), with the arithmetic of
    /// [`Cycle::new`] on [`FramePlan::cycle_spec`]: where the cycle file can be written, the two
    /// cycles are the same bit for bit (so a cam table of either is the same file).
    pub fn cycle(&self, laws: &MoveLaws) -> Cycle {
        let deg = std::f64::consts::PI / 180.0;
        let segments = self
            .levels()
            .into_iter()
            .map(|l| CycleSegment {
                kind: l.kind,
                start_rad: l.start_deg * deg,
                length_rad: l.length_deg * deg,
                law: match l.kind {
                    SegmentKind::Dwell => None,
                    k => Some(laws.of(k == SegmentKind::Rise, l.through).clone()),
                },
                base_si: l.base_m,
                stroke_si: l.stroke_m,
            })
            .collect();
        Cycle { unit: StrokeUnit::Mm, period_rad: self.period_deg * deg, speed_rpm: None, segments }
    }

    /// The plan's segments ([`FramePlan::segments`]) with where each starts from and how far it
    /// goes, m from the frame's place at the plan's start: the numbers of [`FramePlan::cycle`]'s
    /// segments (one arithmetic for both).
    pub fn levels(&self) -> Vec<PlanSegment> {
        let h = self.stroke_mm() * StrokeUnit::Mm.to_si();
        let mut pos = 0.0;
        let mut at = self.start_deg;
        self.parts()
            .into_iter()
            .map(|(kind, _, len, through)| {
                let stroke = match kind {
                    SegmentKind::Dwell => 0.0,
                    SegmentKind::Rise => h,
                    SegmentKind::Return => -h,
                };
                let seg = PlanSegment { kind, start_deg: at, length_deg: len, base_m: pos, stroke_m: stroke, through };
                pos += stroke;
                at += len;
                seg
            })
            .collect()
    }

    /// The plan as a cycle file of the law core (strokes in mm; what the cam-table export and
    /// `loomkin cycle` read, within the cycle file's 36 000°).
    pub fn cycle_spec(&self, laws: &MoveLaws) -> CycleSpec {
        let mut segment: Vec<SegmentSpec> = self
            .parts()
            .into_iter()
            .map(|(kind, _, len, through)| match kind {
                SegmentKind::Dwell => SegmentSpec::dwell(len),
                k => SegmentSpec::moving(k, len, &laws.of(k == SegmentKind::Rise, through).0),
            })
            .collect();
        if let Some(first) = segment.first_mut() {
            first.from_deg = Some(self.start_deg);
        }
        CycleSpec {
            period_deg: self.period_deg,
            unit: StrokeUnit::Mm,
            stroke: Some(self.stroke_mm()),
            speed_rpm: None,
            segment,
        }
    }

    /// The full stroke in the cycle file's unit, mm, to 12 significant digits: the loom file's
    /// millimetres come back without the noise of their way through metres and the clean-lift
    /// ratio (`90`, not `89.99999999999999`; a change of 1e-14 relative at most). The plan's cycle
    /// ([`FramePlan::cycle`]) moves by this stroke too, so it stays the cycle file's bit for bit.
    pub fn stroke_mm(&self) -> f64 {
        loomkin_units::to_12_digits(loomkin_units::mm_from_m(self.stroke_m))
    }

    /// The height over mid-stroke at the plan's start, m.
    pub fn start_level_m(&self) -> f64 {
        if self.start_up { self.stroke_m / 2.0 } else { -self.stroke_m / 2.0 }
    }
}
